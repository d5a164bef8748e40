/* The dda_card driver's state: its pins and parameters, and what it keeps
 * between servo periods (see dda_card.c and docs/linuxcnc.md).
 *
 * Copyright the PCI DDA card authors.  GPL-2.0-or-later (see COPYING here).
 */
#ifndef DDA_STATE_H
#define DDA_STATE_H

#include "hal.h"
#include "dda_math.h"
#include "dda_transport.h"

#define CARDS_MAX 4          /* cards one driver serves: dda-card.0 .. dda-card.3 */
#define TRIM_RING 64         /* periods of FIFO words remembered: more than keep_ahead can be */
#define TRIM_SHIFT 8         /* the drift loop's step: a period's clocks / 256 (at least 1) */
#define DDA_INPUTS_MAX (1 + 3 * (int)DDA_AXES_MAX) /* INPUT_ACTIVE's bits: E-stop, each axis's limits and home */
#define START_WORDS (6 * DDA_CMD_SET_WORDS) /* the SETs of a start, at most */
#define PERIOD_WORDS (DDA_CMD_LINE_MAX_WORDS + DDA_CMD_DWELL_WORDS) /* a period's burst on any card, at most */

/* Axis i's step counter (gen/dda_card.h): X's and Y's in BAR0 (POS_X, POS_Y: every transport
 * reaches them), the others in their BAR2 block (DDA_AXIS_POS_OFFSET).  A read of X's captures
 * the others' in the same card clock, so X's is read first. */
#define BAR0_AXES 2
static inline uint32_t pos_reg(int axis)
{
    return axis == 0 ? DDA_POS_X : axis == 1 ? DDA_POS_Y : DDA_AXIS_POS_OFFSET(axis);
}

/* error-code: the card's STATUS.ERROR (1..4, docs/instructions.md), or the driver's own */
enum dda_fault {
    FAULT_FIFO_DRY = -1,       /* the FIFO ran dry while running: the servo thread fell behind */
    FAULT_TOO_FAST = -2,       /* a period with more steps than the card makes in it */
    FAULT_CARD_STOPPED = -3,   /* the card stopped itself (stop-reason says why) */
    FAULT_TRANSPORT = -4,      /* the transport failed (a sysfs file gone, the card server gone or stalled) */
    FAULT_CARD_GONE = -5,      /* the card reads all-ones: it left the bus */
    FAULT_BAD_COMMAND = -6,    /* position-cmd is not a number, or beyond 2^53 steps: the axis holds */
    FAULT_FIFO_FULL = -7,      /* no room in the FIFO for a period: the card is not taking commands */
    FAULT_SETTING = -8,        /* a step timing or step_type the card cannot do (said at enable) */
};

/* Timing parameters (ns) in the order the card's registers take them. */
enum dda_timing { STEPLEN, STEPSPACE, DIRSETUP, DIRHOLD, TIMINGS };

struct stepgen {
    hal_float_t *position_cmd, *velocity_cmd, *position_fb, *velocity_fb;
    hal_s32_t *counts;
    hal_bit_t *enable, *position_reset, *control_type;
    hal_float_t position_scale, maxvel, maxaccel;
    hal_u32_t timing[TIMINGS];     /* steplen, stepspace, dirsetup, dirhold (ns) */
    hal_u32_t step_type;
    int64_t sent;                  /* steps queued so far (driver's coordinates) */
    int64_t offset;                /* driver's steps minus the card's counter, unwrapped */
    int64_t card;                  /* the card's step counter unwrapped into 64 bits (last good read) */
    struct dda_follower follow;    /* the commanded position within maxvel / maxaccel (machine units) */
    double last_target;            /* position mode: the last period's position-cmd */
    int queued;                    /* the axis is being queued (enabled while the queue runs) */
    int refused;                   /* its position-cmd was refused (said once) */
    int dir;                       /* its DIR level: 1 forward, 0 backward, -1 not known (after load) */
};

/* hostmot2's encoder of one axis on a card built with encoders (dda_encoder.h) */
struct encoder {
    hal_s32_t *count, *rawcounts, *count_latched;
    hal_float_t *position, *velocity, *position_latched;
    hal_bit_t *reset, *index_enable, *probe_enable, *quad_error, *quad_error_enable;
    hal_float_t scale, vel_timeout, ferror_limit;
    hal_bit_t filter, counter_mode, index_invert;
    int64_t raw;                   /* ENC_COUNT unwrapped into 64 bits (last good read) */
    int64_t zero;                  /* the unwrapped count at which `count` reads 0 (reset, index) */
    uint32_t time;                 /* ENC_TIME at the last read */
    double rate;                   /* counts per second at the last read */
    uint32_t control;              /* ENC_CONTROL as last written, INDEX_ARM aside; ~0: not yet */
    int armed;                     /* the index latch armed for index-enable, not yet seen to fire */
    int quad_enabled;              /* quad-error-enable as `read` last saw it (its rise clears QUAD_ERROR) */
};

struct card {
    int index;                     /* K of dda-card.K: its place in the card list */
    int axes;                      /* BUILD.AXES: stepgen.00 .. stepgen.(axes - 1) */
    uint32_t line_axes;            /* LINE's AXES field: 0 (X and Y, today's form) on a two-axis card */
    unsigned burst_words;          /* a period's burst at most: its LINE and DWELL */
    struct stepgen axis[DDA_AXES_MAX];
    hal_s32_t *fifo_level;
    hal_u32_t *underruns;
    hal_bit_t *error;
    hal_s32_t *error_code;
    hal_u32_t *clock;              /* simulation: card clocks at the end of this period */
    hal_bit_t *estop_in;           /* low: the queue stops (LinuxCNC's E-stop chain) */
    hal_bit_t *drive_enable;       /* MACHINE_CONTROL.DRIVE_ENABLE */
    hal_bit_t *estop_active;       /* the card's E-stop input (MACHINE_STATUS.ACTIVE) */
    int inputs_count;              /* 1 + 3 * axes: INPUT_ACTIVE's bits of this card */
    hal_bit_t *inputs[DDA_INPUTS_MAX]; /* the card's filtered inputs (INPUT_ACTIVE): input.<name> */
    int encoders;                  /* BUILD.ENCODERS: encoder.NN per axis (dda_encoder.h) */
    struct encoder encoder[DDA_AXES_MAX];
    hal_bit_t probe_invert;        /* encoder.probe-invert: 1 the probe's rising edge latches, 0 its falling */
    int probe_armed;               /* PROBE_CONTROL.ARM written for probe-enable, not yet seen to fire */
    uint32_t probe_control;        /* PROBE_CONTROL as last written, ARM aside; ~0: not yet */
    unsigned quad_axis;            /* the axis whose ENC_STATUS this period reads (one a period, in turn) */
    hal_s32_t *stop_reason;        /* STOP_REASON.REASON: why the card holds itself stopped */
    hal_bit_t *watchdog_has_bit;   /* the card's watchdog stopped it; written false to go on */
    hal_u32_t watchdog_timeout_ns;
    int drive_written;             /* DRIVE_ENABLE as last written */
    uint32_t clock_hz;
    uint32_t fifo_size;            /* FIFO_SIZE: words the FIFO holds */
    int32_t max_delta;             /* steps a LINE takes per axis (BUILD.COORD_WIDTH, signed) */
    uint32_t timing_clocks[TIMINGS]; /* what the card was set to at the last start */
    uint32_t iteration;            /* clocks per DDA iteration, a power of two: FEED_RATE 65536 / it */
    uint64_t fraction;             /* ns x Hz carried between periods (below 1e9) */
    uint32_t room;                 /* FIFO words free: at the read, less what was written since */
    hal_s32_t *drift_trim;         /* clocks added to this period's DWELL (the clock-drift loop) */
    uint8_t period_words[TRIM_RING]; /* FIFO words of the last periods queued, by period number */
    uint32_t periods_queued;
    int depth_start;               /* whole periods in the FIFO at the first read after start, -1 before */
    int trim_sign;                 /* +1 lengthen, -1 shorten, 0 keep this period's DWELL */
    int running;
    int gone;                      /* the last read found the card all-ones */
    struct dda_transport transport;
};

#endif /* DDA_STATE_H */
