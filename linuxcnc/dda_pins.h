/* The dda_card driver's per-axis pins and parameters, named as hostmot2's
 * stepgen names them (docs/linuxcnc.md), with their defaults.
 *
 * Copyright the PCI DDA card authors.  GPL-2.0-or-later (see COPYING here).
 */
#ifndef DDA_PINS_H
#define DDA_PINS_H

#include "hal.h"
#include "dda_state.h"

static int dda_export_axis(int comp_id, struct stepgen *s, int i)
{
    const char *p = "dda-card.0.stepgen";
    int r = 0;
    r |= hal_pin_float_newf(HAL_IN, &s->position_cmd, comp_id, "%s.%02d.position-cmd", p, i);
    r |= hal_pin_float_newf(HAL_IN, &s->velocity_cmd, comp_id, "%s.%02d.velocity-cmd", p, i);
    r |= hal_pin_float_newf(HAL_OUT, &s->position_fb, comp_id, "%s.%02d.position-fb", p, i);
    r |= hal_pin_float_newf(HAL_OUT, &s->velocity_fb, comp_id, "%s.%02d.velocity-fb", p, i);
    r |= hal_pin_s32_newf(HAL_OUT, &s->counts, comp_id, "%s.%02d.counts", p, i);
    r |= hal_pin_bit_newf(HAL_IN, &s->enable, comp_id, "%s.%02d.enable", p, i);
    r |= hal_param_float_newf(HAL_RW, &s->position_scale, comp_id, "%s.%02d.position-scale", p, i);
    r |= hal_param_float_newf(HAL_RW, &s->maxvel, comp_id, "%s.%02d.maxvel", p, i);
    r |= hal_param_float_newf(HAL_RW, &s->maxaccel, comp_id, "%s.%02d.maxaccel", p, i);
    r |= hal_param_u32_newf(HAL_RW, &s->steplen, comp_id, "%s.%02d.steplen", p, i);
    r |= hal_param_u32_newf(HAL_RW, &s->stepspace, comp_id, "%s.%02d.stepspace", p, i);
    r |= hal_param_u32_newf(HAL_RW, &s->dirsetup, comp_id, "%s.%02d.dirsetup", p, i);
    r |= hal_param_u32_newf(HAL_RW, &s->dirhold, comp_id, "%s.%02d.dirhold", p, i);
    s->position_scale = 1.0;
    s->steplen = s->stepspace = s->dirsetup = s->dirhold = 1000;
    return r;
}

#endif /* DDA_PINS_H */
