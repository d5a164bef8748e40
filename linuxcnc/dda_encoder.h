/* The dda_card driver's encoders: on a card built with encoders
 * (BUILD.ENCODERS, docs/encoders.md), each axis's quadrature input served
 * as hostmot2's encoder, `dda-card.K.encoder.NN.*` (docs/linuxcnc.md).
 * Included by dda_card.c.
 *
 * Each `read`: TIMESTAMP once, every axis's ENC_COUNT (one read an axis,
 * unwrapped into 64 bits), its ENC_TIME and ENC_COUNT again only in a period
 * its count moved (encoder_edge_time: the pair taken together; the
 * time-stamped velocity, as hostmot2's: counts over the clocks between
 * the last count edges; with no count since, at most one count in the
 * clocks since the last, so the last speed bounded by that, 0 beyond
 * vel-timeout), one axis's ENC_STATUS in turn (QUAD_ERROR is sticky on the
 * card; cleared, ENC_STATUS written, when quad-error-enable rises), and
 * ENC_CONTROL / PROBE_CONTROL only while an index or the probe is armed.  `count` is the unwrapped count less `zero`: the count at the
 * last `reset` or index; the card's count itself runs on (rawcounts), so its
 * following error keeps its alignment.  Each `write`: ENC_CONTROL when
 * counter-mode, filter or index-invert changed, or (in a later period: a
 * polarity change is an index edge) when index-enable arms it, PROBE_CONTROL
 * when a probe-enable arms it.
 *
 * Copyright the PCI DDA card authors.  GPL-2.0-or-later (see COPYING here).
 */
#ifndef DDA_ENCODER_H
#define DDA_ENCODER_H

#include "dda_checks.h"
#include "dda_state.h"
#include "dda_transport.h"

#define ENC_FILTER_ON 14u   /* filter TRUE: a level after 15 clocks, as hostmot2's */
#define ENC_FILTER_OFF 2u   /* filter FALSE: after 3 clocks (the card's reset value) */
#define ENC_POLARITY_INDEX 4u /* ENC_CONTROL.POLARITY's index bit */
#define PROBE_FILTER 2u     /* PROBE_CONTROL.FILTER: the reset value */

/* ENC_CONTROL for an encoder's parameters (INDEX_ARM and INDEX_ZERO clear).  index-invert
 * as hostmot2's: TRUE, the index's rising edge latches; FALSE, its falling edge. */
static uint32_t encoder_control(const struct encoder *e)
{
    uint32_t polarity = e->index_invert ? 0u : ENC_POLARITY_INDEX;
    return ((e->counter_mode ? 1u : 0u) << DDA_AXIS_ENC_CONTROL_MODE_SHIFT)
           | (polarity << DDA_AXIS_ENC_CONTROL_POLARITY_SHIFT)
           | ((e->filter ? ENC_FILTER_ON : ENC_FILTER_OFF) << DDA_AXIS_ENC_CONTROL_FILTER_SHIFT);
}

/* scale 0 would make every position infinite: forced to 1 and said, as the stepgen's. */
static void check_encoder_scale(struct card *c, int i)
{
    struct encoder *e = &c->encoder[i];
    if (e->scale != 0.0 && isfinite(e->scale))
        return;
    rtapi_print_msg(RTAPI_MSG_ERR, "dda_card: dda-card.%d.encoder.%02d.scale %g is no scale (counts per "
                    "position unit): set to 1\n", c->index, i, e->scale);
    e->scale = 1.0;
}

static int dda_export_encoder(int comp_id, struct encoder *e, int card, int i)
{
    char p[HAL_NAME_LEN];
    int r = 0;
    rtapi_snprintf(p, sizeof p, "dda-card.%d.encoder.%02d", card, i);
    r |= hal_pin_s32_newf(HAL_OUT, &e->count, comp_id, "%s.count", p);
    r |= hal_pin_s32_newf(HAL_OUT, &e->rawcounts, comp_id, "%s.rawcounts", p);
    r |= hal_pin_float_newf(HAL_OUT, &e->position, comp_id, "%s.position", p);
    r |= hal_pin_float_newf(HAL_OUT, &e->velocity, comp_id, "%s.velocity", p);
    r |= hal_pin_bit_newf(HAL_IN, &e->reset, comp_id, "%s.reset", p);
    r |= hal_pin_bit_newf(HAL_IO, &e->index_enable, comp_id, "%s.index-enable", p);
    r |= hal_pin_bit_newf(HAL_IO, &e->probe_enable, comp_id, "%s.probe-enable", p);
    r |= hal_pin_s32_newf(HAL_OUT, &e->count_latched, comp_id, "%s.count-latched", p);
    r |= hal_pin_float_newf(HAL_OUT, &e->position_latched, comp_id, "%s.position-latched", p);
    r |= hal_pin_bit_newf(HAL_IN, &e->quad_error_enable, comp_id, "%s.quad-error-enable", p);
    r |= hal_pin_bit_newf(HAL_OUT, &e->quad_error, comp_id, "%s.quad-error", p);
    r |= hal_param_float_newf(HAL_RW, &e->scale, comp_id, "%s.scale", p);
    r |= hal_param_float_newf(HAL_RW, &e->vel_timeout, comp_id, "%s.vel-timeout", p);
    r |= hal_param_float_newf(HAL_RW, &e->ferror_limit, comp_id, "%s.ferror-limit", p);
    r |= hal_param_bit_newf(HAL_RW, &e->filter, comp_id, "%s.filter", p);
    r |= hal_param_bit_newf(HAL_RW, &e->counter_mode, comp_id, "%s.counter-mode", p);
    r |= hal_param_bit_newf(HAL_RW, &e->index_invert, comp_id, "%s.index-invert", p);
    e->scale = 1.0;
    e->vel_timeout = 0.5;
    e->filter = 1;
    return r;
}

/* Every axis's encoder pins, and where the card's counts stand now (count reads 0 at load):
 * 0, or -EINVAL / -ENODEV. */
static int dda_export_encoders(int comp_id, struct card *c)
{
    struct dda_transport *t = &c->transport;
    char name[HAL_NAME_LEN];
    int i, r = 0;
    rtapi_snprintf(name, sizeof name, "dda-card.%d.encoder.probe-invert", c->index);
    r |= hal_param_bit_newf(HAL_RW, &c->probe_invert, comp_id, "%s", name);
    for (i = 0; i < c->axes && r == 0; i++) {
        struct encoder *e = &c->encoder[i];
        uint32_t raw = 0, time = 0;
        r |= dda_export_encoder(comp_id, e, c->index, i);
        if (dda_read32(t, DDA_AXIS_ENC_COUNT_OFFSET(i), &raw) < 0 || dda_read32(t, DDA_AXIS_ENC_TIME_OFFSET(i), &time) < 0)
            return -ENODEV;
        e->raw = e->zero = (int32_t)raw;
        e->time = time;
        e->control = ~0u;  /* written at the first `write` */
    }
    c->probe_control = ~0u;
    return r ? -EINVAL : 0;
}

/* The card's following error for each axis, at enable (before CLEAR_STOP: the write of ENC_SCALE
 * re-aligns it): ENC_SCALE = encoder scale / stepgen position-scale (counts per step), FERROR_LIMIT =
 * ferror-limit (position units, 0 off) in counts.  0, or FAULT_SETTING with the parameter named. */
static int dda_align_encoders(struct card *c)
{
    int i;
    for (i = 0; i < c->axes && c->encoders; i++) {
        struct encoder *e = &c->encoder[i];
        double per_step, limit = e->ferror_limit;
        check_encoder_scale(c, i);
        per_step = e->scale / c->axis[i].position_scale;
        if (limit == 0.0) {
            if (dda_write32(&c->transport, DDA_AXIS_FERROR_LIMIT_OFFSET(i), 0) < 0)
                return FAULT_TRANSPORT;
            continue;
        }
        limit *= fabs(e->scale);
        if (!(per_step > 0.0) || per_step * 65536.0 > (double)DDA_AXIS_ENC_SCALE_MAX || !(limit > 0.0)
            || limit >= (double)DDA_AXIS_FERROR_LIMIT_MAX) {
            rtapi_print_msg(RTAPI_MSG_ERR, "dda_card: dda-card.%d.encoder.%02d: scale %g over the stepgen's "
                            "position-scale %g is %g counts a step and ferror-limit %g is %g counts: the card "
                            "checks 0 < counts a step < 65536 (both scales the same sign) and 0 < limit < 2^32\n",
                            c->index, i, e->scale, c->axis[i].position_scale, per_step, e->ferror_limit, limit);
            return FAULT_SETTING;
        }
        if (dda_write32(&c->transport, DDA_AXIS_ENC_SCALE_OFFSET(i), (uint32_t)(per_step * 65536.0 + 0.5)) < 0
            || dda_write32(&c->transport, DDA_AXIS_FERROR_LIMIT_OFFSET(i), (uint32_t)ceil(limit)) < 0)
            return FAULT_TRANSPORT;
    }
    return 0;
}

/* Axis i's count moved since the last read (`word`, ENC_COUNT just read): ENC_TIME, the time of the
 * count's last edge.  The two are separate reads, so ENC_COUNT is read again after ENC_TIME: an edge
 * between them moved the time past the count read first, and the pair is taken again (the count
 * then, ENC_TIME after it).  0, or -1 (transport). */
static int encoder_edge_time(struct card *c, int i, uint32_t *word, uint32_t *time)
{
    uint32_t again = 0;
    if (dda_read32(&c->transport, DDA_AXIS_ENC_TIME_OFFSET(i), time) < 0
        || dda_read32(&c->transport, DDA_AXIS_ENC_COUNT_OFFSET(i), &again) < 0)
        return -1;
    if (again == *word)
        return 0;
    *word = again;
    return dda_read32(&c->transport, DDA_AXIS_ENC_TIME_OFFSET(i), time);
}

/* Counts per second of axis i's encoder (module comment), its count now `raw`, `time` its ENC_TIME
 * when it moved, `stamp` TIMESTAMP. */
static void encoder_rate(struct card *c, int i, int64_t raw, uint32_t time, uint32_t stamp)
{
    struct encoder *e = &c->encoder[i];
    uint32_t clocks;
    double bound;
    if (raw != e->raw) {
        clocks = time - e->time;
        e->rate = (double)(raw - e->raw) * c->clock_hz / (clocks ? clocks : 1);
        e->time = time;
        return;
    }
    clocks = stamp - e->time;
    bound = (double)c->clock_hz / (clocks ? clocks : 1);
    if (clocks > e->vel_timeout * c->clock_hz)
        e->rate = 0.0;
    else if (e->rate > bound || e->rate < -bound)
        e->rate = e->rate > 0 ? bound : -bound;
}

/* An index armed for index-enable that has come: count reads 0 from the count at the index on,
 * index-enable falls.  `raw` is the count just read.  0, or -1 (transport). */
static int encoder_index(struct card *c, int i, int64_t raw)
{
    struct encoder *e = &c->encoder[i];
    uint32_t control = 0, latch = 0;
    if (!e->armed)
        return 0;
    if (dda_read32(&c->transport, DDA_AXIS_ENC_CONTROL_OFFSET(i), &control) < 0)
        return -1;
    if (control & DDA_AXIS_ENC_CONTROL_INDEX_ARM_MASK)
        return 0;
    if (dda_read32(&c->transport, DDA_AXIS_ENC_INDEX_LATCH_OFFSET(i), &latch) < 0)
        return -1;
    e->zero = dda_unwrap(raw, latch);
    e->armed = 0;
    *e->index_enable = 0;
    return 0;
}

/* The probe armed for probe-enable that has come: each such axis's count at the probe edge. */
static int encoder_probe(struct card *c)
{
    uint32_t control = 0, latch = 0;
    int i;
    if (!c->probe_armed)
        return 0;
    if (dda_read32(&c->transport, DDA_PROBE_CONTROL, &control) < 0)
        return -1;
    if (control & DDA_PROBE_CONTROL_ARM_MASK)
        return 0;
    c->probe_armed = 0;
    for (i = 0; i < c->axes; i++) {
        struct encoder *e = &c->encoder[i];
        int64_t at;
        if (!*e->probe_enable)
            continue;
        if (dda_read32(&c->transport, DDA_AXIS_PROBE_ENC_OFFSET(i), &latch) < 0)
            return -1;
        at = dda_unwrap(e->raw, latch) - e->zero;
        *e->count_latched = (int32_t)(uint32_t)(uint64_t)at;
        *e->position_latched = (double)at / e->scale;
        *e->probe_enable = 0;
    }
    return 0;
}

/* quad-error-enable of axis i, every period: at its rise the card's sticky QUAD_ERROR (and ERROR_COUNT)
 * is cleared first, so only errors after it are reported, as hostmot2's (an illegal transition while
 * it was FALSE, or before the driver loaded, is not); while it is FALSE `quad-error` is FALSE.
 * 0, or -1 (transport: tried again next period). */
static int encoder_quad_enable(struct card *c, int i)
{
    struct encoder *e = &c->encoder[i];
    int enabled = *e->quad_error_enable != 0;
    if (enabled && !e->quad_enabled
        && dda_write32(&c->transport, DDA_AXIS_ENC_STATUS_OFFSET(i), DDA_AXIS_ENC_STATUS_QUAD_ERROR_MASK) < 0)
        return -1;
    e->quad_enabled = enabled;
    if (!enabled)
        *e->quad_error = 0;
    return 0;
}

/* ENC_STATUS of one axis a period, in turn: `quad-error` is the card's sticky QUAD_ERROR while
 * quad-error-enable is TRUE, said once when it rises (as hostmot2's "quadrature count error"; the
 * encoder counts on: what to do is the HAL's, e.g. quad-error into the E-stop chain). */
static int encoder_quad_error(struct card *c)
{
    unsigned i = c->quad_axis++ % (unsigned)c->axes;
    struct encoder *e = &c->encoder[i];
    uint32_t status = 0;
    if (dda_read32(&c->transport, DDA_AXIS_ENC_STATUS_OFFSET(i), &status) < 0)
        return -1;
    if (!e->quad_enabled)
        return 0;
    if ((status & DDA_AXIS_ENC_STATUS_QUAD_ERROR_MASK) && !*e->quad_error)
        rtapi_print_msg(RTAPI_MSG_ERR, "dda_card: dda-card.%d.encoder.%02d: quadrature error (A and B changed "
                        "in the same sample, not counted; %u since quad-error-enable)\n", c->index, (int)i,
                        (unsigned)((status & DDA_AXIS_ENC_STATUS_ERROR_COUNT_MASK) >> DDA_AXIS_ENC_STATUS_ERROR_COUNT_SHIFT));
    *e->quad_error = (status & DDA_AXIS_ENC_STATUS_QUAD_ERROR_MASK) != 0;
    return 0;
}

/* `read`'s part: every encoder's pins.  0, or -1 (the transport failed: pins keep their values). */
static int dda_read_encoders(struct card *c)
{
    uint32_t stamp = 0, word = 0;
    int i;
    if (!c->encoders)
        return 0;
    if (dda_read32(&c->transport, DDA_TIMESTAMP, &stamp) < 0)
        return -1;
    for (i = 0; i < c->axes; i++) {
        struct encoder *e = &c->encoder[i];
        uint32_t time = 0;
        int64_t raw;
        if (dda_read32(&c->transport, DDA_AXIS_ENC_COUNT_OFFSET(i), &word) < 0
            || ((uint32_t)e->raw != word && encoder_edge_time(c, i, &word, &time) < 0))
            return -1;
        raw = dda_unwrap(e->raw, word);
        check_encoder_scale(c, i);
        encoder_rate(c, i, raw, time, stamp);
        if (encoder_index(c, i, raw) < 0 || encoder_quad_enable(c, i) < 0)
            return -1;
        e->raw = raw;
        if (*e->reset)
            e->zero = raw;
        *e->rawcounts = (int32_t)word;
        *e->count = (int32_t)(uint32_t)(uint64_t)(raw - e->zero);
        *e->position = (double)(raw - e->zero) / e->scale;
        *e->velocity = e->rate / e->scale;
    }
    return encoder_probe(c) < 0 || encoder_quad_error(c) < 0 ? -1 : 0;
}

/* `write`'s part: ENC_CONTROL and PROBE_CONTROL when a parameter changed or an enable arms. */
static void dda_write_encoders(struct card *c)
{
    uint32_t probe = PROBE_FILTER << DDA_PROBE_CONTROL_FILTER_SHIFT | (c->probe_invert ? 0 : DDA_PROBE_CONTROL_INVERT_MASK);
    int i, probing = 0;
    if (!c->encoders)
        return;
    for (i = 0; i < c->axes; i++) {
        struct encoder *e = &c->encoder[i];
        uint32_t control = encoder_control(e);
        int arm = *e->index_enable && !e->armed;
        if (!*e->index_enable)
            e->armed = 0;  /* given up before the index came: its latch is not taken */
        probing |= *e->probe_enable != 0;
        if (control != e->control) {
            /* a new index polarity flips the filtered index: an edge the latch must not take,
             * so the arm waits for the next period (the edge has passed the filter by then) */
            if (dda_write32(&c->transport, DDA_AXIS_ENC_CONTROL_OFFSET(i), control) == 0)
                e->control = control;
        } else if (arm && dda_write32(&c->transport, DDA_AXIS_ENC_CONTROL_OFFSET(i),
                                      control | DDA_AXIS_ENC_CONTROL_INDEX_ARM_MASK) == 0) {
            e->armed = 1;
        }
    }
    if (!probing)
        c->probe_armed = 0;
    if (probe != c->probe_control) {
        /* as the index: the arm waits a period after a polarity change */
        if (dda_write32(&c->transport, DDA_PROBE_CONTROL, probe) == 0)
            c->probe_control = probe;
    } else if (probing && !c->probe_armed
               && dda_write32(&c->transport, DDA_PROBE_CONTROL, probe | DDA_PROBE_CONTROL_ARM_MASK) == 0) {
        c->probe_armed = 1;
    }
}

#endif /* DDA_ENCODER_H */
