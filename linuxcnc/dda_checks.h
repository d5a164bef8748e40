/* The dda_card driver's checks: at load, that the card is one this driver
 * was built for and that its FIFO holds the queue; at enable, that the
 * card can make the step timing and step type asked for.  Each refusal
 * says which value, and what the card holds.
 *
 * Copyright the PCI DDA card authors.  GPL-2.0-or-later (see COPYING here).
 */
#ifndef DDA_CHECKS_H
#define DDA_CHECKS_H

#include "dda_pins.h"
#include "dda_state.h"

#ifdef DDA_STEP_SPACE_SET_INDEX
#define HAS_STEP_SPACE 1  /* the card holds STEP low for STEP_SPACE clocks (a register of its own) */
#else
#define HAS_STEP_SPACE 0  /* the card holds STEP low at least STEP_WIDTH clocks */
#endif

#define FIELD(value, name) (((value) & name##_MASK) >> name##_SHIFT)
#define MAJOR(id) (FIELD(id, DDA_ID_VERSION) >> 8)

/* keep_ahead periods of the queue: within the drift loop's ring, and at least one. */
static int dda_check_keep_ahead(int keep_ahead)
{
    if (keep_ahead >= 1 && keep_ahead < TRIM_RING)
        return 0;
    rtapi_print_msg(RTAPI_MSG_ERR, "dda_card: keep_ahead=%d: give 1..%d periods queued ahead (default 4)\n",
                    keep_ahead, TRIM_RING - 1);
    return -EINVAL;
}

/* The card at load: ID (magic, major version), CLOCK_HZ, BUILD (its axes, as many as the
 * driver drives; coordinate width)
 * and FIFO_SIZE (the start and keep_ahead periods fit).  0, or -ENODEV with the reason said. */
static int dda_check_card(struct card *c, int keep_ahead)
{
    struct dda_transport *t = &c->transport;
    uint32_t id = 0, build = 0, fifo = 0, width, needed;
    if (dda_read32(t, DDA_ID, &id) < 0 || dda_read32(t, DDA_CLOCK_HZ, &c->clock_hz) < 0
        || dda_read32(t, DDA_BUILD, &build) < 0 || dda_read32(t, DDA_FIFO_SIZE, &fifo) < 0)
        return -ENODEV;
    if (FIELD(id, DDA_ID_MAGIC) != FIELD(DDA_ID_RESET, DDA_ID_MAGIC) || c->clock_hz == 0) {
        rtapi_print_msg(RTAPI_MSG_ERR, "dda_card: %s does not identify as the DDA card (ID %08x)\n", t->name, id);
        return -ENODEV;
    }
    if (MAJOR(id) != MAJOR(DDA_ID_RESET)) {
        rtapi_print_msg(RTAPI_MSG_ERR, "dda_card: %s is version %u.%u; this driver was built for %u.x "
                        "(gen/dda_card.h): build the driver from the checkout of the card's bitstream\n",
                        t->name, MAJOR(id), FIELD(id, DDA_ID_VERSION) & 0xFFu, MAJOR(DDA_ID_RESET));
        return -ENODEV;
    }
    width = FIELD(build, DDA_BUILD_COORD_WIDTH);
    c->axes = (int)FIELD(build, DDA_BUILD_AXES);
    if (c->axes < 2 || c->axes > (int)DDA_AXES_MAX || width < 2 || width > 32) {
        rtapi_print_msg(RTAPI_MSG_ERR, "dda_card: %s reports %d axes and %u-bit coordinates (BUILD %08x): "
                        "no card of this design\n", t->name, c->axes, width, build);
        return -ENODEV;
    }
    if (c->axes > BAR0_AXES && t->sock < 0 && !t->regs) {
        /* the step counters of Z and up live in BAR2's per-axis blocks only */
        rtapi_print_msg(RTAPI_MSG_ERR, "dda_card: %s has %d axes (BUILD.AXES), and the registers of axes %d and "
                        "up are in BAR2, which this host does not map (the registers go through BAR0): "
                        "docs/linuxcnc.md\n", t->name, c->axes, BAR0_AXES);
        return -ENODEV;
    }
    c->inputs_count = 1 + 3 * c->axes;
    c->encoders = FIELD(build, DDA_BUILD_ENCODERS) != 0;
    if (c->encoders && t->sock < 0 && !t->regs) {
        /* the encoders' registers are in the per-axis blocks: BAR2 only */
        rtapi_print_msg(RTAPI_MSG_ERR, "dda_card: %s has encoders (BUILD.ENCODERS), whose registers are in BAR2, "
                        "which this host does not map: no encoder pins (docs/linuxcnc.md)\n", t->name);
        c->encoders = 0;
    }
    /* LINE's AXES = 0 is X and Y (the form every card takes); more axes are named */
    c->line_axes = c->axes == 2 ? 0u : (1u << c->axes) - 1u;
    c->burst_words = (c->axes == 2 ? DDA_CMD_LINE_WORDS : 1u + (unsigned)c->axes) + DDA_CMD_DWELL_WORDS;
    c->max_delta = (int32_t)((1ull << (width - 1)) - 1);
    c->fifo_size = FIELD(fifo, DDA_FIFO_SIZE_WORDS);
    needed = START_WORDS + (uint32_t)keep_ahead * c->burst_words;
    if (c->fifo_size < needed) {
        rtapi_print_msg(RTAPI_MSG_ERR, "dda_card: %s: its FIFO holds %u words, keep_ahead=%d needs %u: "
                        "give at most %u\n", t->name, c->fifo_size, keep_ahead, needed,
                        c->fifo_size < START_WORDS ? 0 : (c->fifo_size - START_WORDS) / c->burst_words);
        return -ENODEV;
    }
    return 0;
}

/* At enable: each timing register takes the largest of the axes' values (the card's
 * step timing is shared), in clocks; every axis's step_type the card can make.
 * 0, or FAULT_SETTING with the parameter named. */
static int dda_check_settings(struct card *c)
{
    const struct stepgen *a = c->axis;
    int k, i;
    for (k = 0; k < TIMINGS; k++) {
        int largest = 0, differ = 0;
        uint32_t ns;
        for (i = 1; i < c->axes; i++) {
            largest = a[i].timing[k] > a[largest].timing[k] ? i : largest;
            differ |= a[i].timing[k] != a[0].timing[k];
        }
        ns = a[largest].timing[k];
        if (dda_timing_clocks(ns, c->clock_hz, &c->timing_clocks[k]) < 0) {
            rtapi_print_msg(RTAPI_MSG_ERR, "dda_card: dda-card.%d.stepgen.%02d.%s %u ns is %llu clocks at %u Hz; "
                            "the card's timing registers hold 1..%u clocks (at most %llu ns)\n", c->index, largest,
                            TIMING_NAMES[k], ns, (unsigned long long)dda_clocks_of_ns(ns, c->clock_hz), c->clock_hz,
                            DDA_TIMING_MAX, (unsigned long long)dda_timing_max_ns(c->clock_hz));
            return FAULT_SETTING;
        }
        if (differ)
            rtapi_print_msg(RTAPI_MSG_INFO, "dda_card: dda-card.%d: the axes' %s differ; the card's is shared: "
                            "%u ns for all\n", c->index, TIMING_NAMES[k], ns);
    }
#ifdef DDA_STEP_MODE
    /* STEP_MODE is one register for every axis (the pins of all change alike) and
     * its codes are hostmot2's step_type: 0 step/dir, 1 up/down, 2 quadrature */
    for (i = 0; i < c->axes; i++)
        if (a[i].step_type > DDA_STEP_MODE_MAX || a[i].step_type != a[0].step_type) {
            rtapi_print_msg(RTAPI_MSG_ERR, "dda_card: dda-card.%d.stepgen.%02d.step_type %u: the card makes "
                            "0 step/dir, 1 up/down or 2 quadrature, one for all its axes (stepgen.00.step_type "
                            "is %u)\n", c->index, i, a[i].step_type, a[0].step_type);
            return FAULT_SETTING;
        }
#else
    for (i = 0; i < c->axes; i++)
        if (a[i].step_type != 0) {
            rtapi_print_msg(RTAPI_MSG_ERR, "dda_card: dda-card.%d.stepgen.%02d.step_type %u: this card makes "
                            "step/dir only (step_type 0); up/down and quadrature need its STEP_MODE register\n",
                            c->index, i, a[i].step_type);
            return FAULT_SETTING;
        }
#endif
    return 0;
}

#endif /* DDA_CHECKS_H */
