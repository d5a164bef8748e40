/* The dda_card driver's state: its pins and parameters, and what it keeps
 * between servo periods (see dda_card.c and docs/linuxcnc.md).
 *
 * Copyright the PCI DDA card authors.  GPL-2.0-or-later (see COPYING here).
 */
#ifndef DDA_STATE_H
#define DDA_STATE_H

#include "hal.h"
#include "dda_transport.h"

#define AXES 2
#define FASTEST_ITERATION 2  /* clocks: the DDA iterates at most every other clock */
#define TRIM_RING 64         /* periods of FIFO words remembered: more than keep_ahead can be */
#define TRIM_SHIFT 8         /* the drift loop's step: a period's clocks / 256 (at least 1) */
#define DDA_INPUTS 7         /* MACHINE_STATUS.ACTIVE's bits: E-stop, limits, home switches */

struct stepgen {
    hal_float_t *position_cmd, *velocity_cmd, *position_fb, *velocity_fb;
    hal_s32_t *counts;
    hal_bit_t *enable;
    hal_float_t position_scale, maxvel, maxaccel;
    hal_u32_t steplen, stepspace, dirsetup, dirhold;
    int32_t sent;          /* steps queued so far (driver's coordinates) */
    int32_t offset;        /* driver's steps minus the card's counter */
    int32_t last_counts;
    int forward;           /* the DIR pin's side: the last move's direction (reset: backward) */
};

struct card {
    struct stepgen axis[AXES];
    hal_s32_t *fifo_level;
    hal_u32_t *underruns;
    hal_bit_t *error;
    hal_s32_t *error_code;
    hal_u32_t *clock;              /* simulation: card clocks at the end of this period */
    hal_bit_t *estop_in;           /* low: the queue stops (LinuxCNC's E-stop chain) */
    hal_bit_t *drive_enable;       /* MACHINE_CONTROL.DRIVE_ENABLE */
    hal_bit_t *estop_active;       /* the card's E-stop input (MACHINE_STATUS.ACTIVE) */
    hal_bit_t *inputs[DDA_INPUTS]; /* the card's filtered inputs (MACHINE_STATUS.ACTIVE): input.<name> */
    hal_s32_t *stop_reason;        /* STOP_REASON.REASON: why the card holds itself stopped */
    hal_bit_t *watchdog_has_bit;   /* the card's watchdog stopped it; written false to go on */
    hal_u32_t watchdog_timeout_ns;
    int drive_written;             /* DRIVE_ENABLE as last written */
    uint32_t clock_hz;
    uint32_t iteration;            /* clocks per DDA iteration, a power of two: FEED_RATE 65536 / it */
    uint64_t fraction;             /* ns x Hz carried between periods (below 1e9) */
    hal_s32_t *drift_trim;         /* clocks added to this period's DWELL (the clock-drift loop) */
    uint8_t period_words[TRIM_RING]; /* FIFO words of the last periods queued, by period number */
    uint32_t periods_queued;
    int depth_start;               /* whole periods in the FIFO at the first read after start, -1 before */
    int trim_sign;                 /* +1 lengthen, -1 shorten, 0 keep this period's DWELL */
    int running;
    struct dda_transport transport;
};

#endif /* DDA_STATE_H */
