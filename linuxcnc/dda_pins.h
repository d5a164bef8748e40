/* The dda_card driver's pins and parameters, named as hostmot2's stepgen
 * and watchdog name them (docs/linuxcnc.md), with their defaults.
 *
 * Copyright the PCI DDA card authors.  GPL-2.0-or-later (see COPYING here).
 */
#ifndef DDA_PINS_H
#define DDA_PINS_H

#include "hal.h"
#include "dda_state.h"

static const char *const TIMING_NAMES[TIMINGS] = {"steplen", "stepspace", "dirsetup", "dirhold"};
/* the input.<name> pins, bit n of INPUT_ACTIVE (INPUT_POLARITY's order): E-stop, X's and Y's, then
 * each further axis's three; a card of N axes has the first 1 + 3 N */
static const char *const INPUT_PINS[DDA_INPUTS_MAX] = {
    "estop", "limit-pos-x", "limit-neg-x", "limit-pos-y", "limit-neg-y", "home-x", "home-y",
    "limit-pos-z", "limit-neg-z", "home-z", "limit-pos-a", "limit-neg-a", "home-a",
    "limit-pos-b", "limit-neg-b", "home-b", "limit-pos-c", "limit-neg-c", "home-c"};

static int dda_export_axis(int comp_id, struct stepgen *s, int card, int i)
{
    char p[HAL_NAME_LEN];
    int r = 0, k;
    rtapi_snprintf(p, sizeof p, "dda-card.%d.stepgen", card);
    r |= hal_pin_float_newf(HAL_IN, &s->position_cmd, comp_id, "%s.%02d.position-cmd", p, i);
    r |= hal_pin_float_newf(HAL_IN, &s->velocity_cmd, comp_id, "%s.%02d.velocity-cmd", p, i);
    r |= hal_pin_float_newf(HAL_OUT, &s->position_fb, comp_id, "%s.%02d.position-fb", p, i);
    r |= hal_pin_float_newf(HAL_OUT, &s->velocity_fb, comp_id, "%s.%02d.velocity-fb", p, i);
    r |= hal_pin_s32_newf(HAL_OUT, &s->counts, comp_id, "%s.%02d.counts", p, i);
    r |= hal_pin_bit_newf(HAL_IN, &s->enable, comp_id, "%s.%02d.enable", p, i);
    r |= hal_pin_bit_newf(HAL_IN, &s->position_reset, comp_id, "%s.%02d.position-reset", p, i);
    r |= hal_pin_bit_newf(HAL_IN, &s->control_type, comp_id, "%s.%02d.control-type", p, i);
    r |= hal_param_float_newf(HAL_RW, &s->position_scale, comp_id, "%s.%02d.position-scale", p, i);
    r |= hal_param_float_newf(HAL_RW, &s->maxvel, comp_id, "%s.%02d.maxvel", p, i);
    r |= hal_param_float_newf(HAL_RW, &s->maxaccel, comp_id, "%s.%02d.maxaccel", p, i);
    for (k = 0; k < TIMINGS; k++)
        r |= hal_param_u32_newf(HAL_RW, &s->timing[k], comp_id, "%s.%02d.%s", p, i, TIMING_NAMES[k]);
    r |= hal_param_u32_newf(HAL_RW, &s->step_type, comp_id, "%s.%02d.step_type", p, i);
    s->position_scale = 1.0;
    for (k = 0; k < TIMINGS; k++)
        s->timing[k] = 1000;
    s->dir = -1;
    return r;
}

/* dda-card.K's pins and parameters, stepgen.00 .. stepgen.(axes - 1) */
static int dda_export_card(int comp_id, struct card *c)
{
    char p[HAL_NAME_LEN];
    int r = 0, i;
    rtapi_snprintf(p, sizeof p, "dda-card.%d", c->index);
    for (i = 0; i < c->axes; i++)
        r |= dda_export_axis(comp_id, &c->axis[i], c->index, i);
    r |= hal_pin_s32_newf(HAL_OUT, &c->fifo_level, comp_id, "%s.fifo-level", p);
    r |= hal_pin_u32_newf(HAL_OUT, &c->underruns, comp_id, "%s.underruns", p);
    r |= hal_pin_bit_newf(HAL_OUT, &c->error, comp_id, "%s.error", p);
    r |= hal_pin_s32_newf(HAL_OUT, &c->error_code, comp_id, "%s.error-code", p);
    r |= hal_pin_u32_newf(HAL_OUT, &c->clock, comp_id, "%s.clock", p);
    r |= hal_pin_s32_newf(HAL_OUT, &c->drift_trim, comp_id, "%s.drift-trim", p);
    r |= hal_pin_bit_newf(HAL_IN, &c->estop_in, comp_id, "%s.estop-in", p);
    r |= hal_pin_bit_newf(HAL_IN, &c->drive_enable, comp_id, "%s.drive-enable", p);
    r |= hal_pin_bit_newf(HAL_OUT, &c->estop_active, comp_id, "%s.estop-active", p);
    for (i = 0; i < c->inputs_count; i++)
        r |= hal_pin_bit_newf(HAL_OUT, &c->inputs[i], comp_id, "%s.input.%s", p, INPUT_PINS[i]);
    r |= hal_pin_s32_newf(HAL_OUT, &c->stop_reason, comp_id, "%s.stop-reason", p);
    r |= hal_pin_bit_newf(HAL_IO, &c->watchdog_has_bit, comp_id, "%s.watchdog.has_bit", p);
    r |= hal_param_u32_newf(HAL_RW, &c->watchdog_timeout_ns, comp_id, "%s.watchdog.timeout_ns", p);
    c->watchdog_timeout_ns = 5000000;
    *c->estop_in = 1;
    return r;
}

#endif /* DDA_PINS_H */
