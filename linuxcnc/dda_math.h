/* The dda_card driver's arithmetic, apart from HAL and the card so that a
 * plain C program can test it (tests/linuxcnc/test_driver_math.py):
 * nanoseconds to card clocks, the step timing the card can hold and the
 * iteration period it gives, the card's 32-bit step counters unwrapped
 * into 64 bits, a position in whole steps (or why not), and an axis
 * following its command within maxvel and maxaccel.
 *
 * Copyright the PCI DDA card authors.  GPL-2.0-or-later (see COPYING here).
 */
#ifndef DDA_MATH_H
#define DDA_MATH_H

#include <stdint.h>

#include "../gen/dda_card.h"  /* the registers' ranges */
#ifdef RTAPI
#include "rtapi_math.h"
#else
#include <math.h>
#endif

#define DDA_TIMING_MIN ((uint32_t)DDA_STEP_WIDTH_MIN) /* STEP_WIDTH, DIR_SETUP, DIR_HOLD, STEP_SPACE: */
#define DDA_TIMING_MAX ((uint32_t)DDA_STEP_WIDTH_MAX) /* one range, in clocks */
#define DDA_FASTEST_ITERATION 2u   /* clocks: the DDA iterates at most every other clock */
#define DDA_SLOWEST_ITERATION 65536u /* FEED_RATE 1 */
#define DDA_MAX_STEPS 9007199254740992.0 /* 2^53: beyond it a double no longer holds every step */

/* ns in whole card clocks at hz, rounded up (a time asked for is a minimum). */
static inline uint64_t dda_clocks_of_ns(uint64_t ns, uint32_t hz)
{
    return (ns * hz + 999999999u) / 1000000000u;
}

/* A step timing parameter in the clocks the card's register holds: 0 when it fits
 * (*clocks set; less than the card's 1 clock is 1), -1 when it is more than 255 clocks. */
static inline int dda_timing_clocks(uint32_t ns, uint32_t hz, uint32_t *clocks)
{
    uint64_t c = dda_clocks_of_ns(ns, hz);
    if (c > DDA_TIMING_MAX)
        return -1;
    *clocks = c < DDA_TIMING_MIN ? DDA_TIMING_MIN : (uint32_t)c;
    return 0;
}

/* Longest time (ns) a timing register holds at hz: the limit a refusal names. */
static inline uint64_t dda_timing_max_ns(uint32_t hz)
{
    return (uint64_t)DDA_TIMING_MAX * 1000000000u / hz;
}

/* Card clocks from one STEP rise to the next when steps come as fast as the
 * timing allows.  STEP is high steplen clocks (STEP_WIDTH).  With a STEP_SPACE
 * register of its own the low time is stepspace; without one the card holds
 * STEP low at least STEP_WIDTH clocks too, so the low time is the longer of
 * the two. */
static inline uint32_t dda_step_cycle(uint32_t steplen, uint32_t stepspace, int has_step_space)
{
    if (has_step_space)
        return steplen + stepspace;
    return steplen + (stepspace > steplen ? stepspace : steplen);
}

/* Clocks per DDA iteration: the power of two (2..65536) that covers cycle
 * clocks, so that FEED_RATE = 65536 / it is exact. */
static inline uint32_t dda_iteration_clocks(uint32_t cycle)
{
    uint32_t it = DDA_FASTEST_ITERATION;
    while (it < DDA_SLOWEST_ITERATION && it < cycle)
        it *= 2;
    return it;
}

/* The card's 32-bit counter read as `raw`, carried on from `previous` (the last
 * value unwrapped): it moves less than 2^31 steps between two reads. */
static inline int64_t dda_unwrap(int64_t previous, uint32_t raw)
{
    uint32_t change = raw - (uint32_t)previous;
    return previous + (change & 0x80000000u ? (int64_t)change - 4294967296LL : (int64_t)change);
}

/* round(position * scale), half up: 0, or -1 when that is not a number or
 * more than 2^53 steps either way (*steps untouched). */
static inline int dda_steps_of(double position, double scale, int64_t *steps)
{
    double x = position * scale;
    if (!isfinite(x) || x > DDA_MAX_STEPS || x < -DDA_MAX_STEPS)
        return -1;
    *steps = (int64_t)floor(x + 0.5);
    return 0;
}

/* An axis following its command: where it is commanded to (machine units) and
 * at what velocity (units/s) it moved there in the last period. */
struct dda_follower {
    double position, velocity;
};

/* Move f one period of dt seconds towards target, which moves at
 * target_velocity.  The target is reached at once when that needs no more
 * than maxvel and changes the velocity by no more than maxaccel (0: no
 * limit); else the axis closes the gap as fast as those limits allow and
 * it can still match the target's velocity on reaching it (the braking
 * distance of a period-by-period deceleration). */
static inline void dda_follow(struct dda_follower *f, double target, double target_velocity,
                              double maxvel, double maxaccel, double dt)
{
    double reach = (target - f->position) / dt;
    double dv = maxaccel > 0.0 ? maxaccel * dt : INFINITY;
    double vmax = maxvel > 0.0 ? maxvel : INFINITY;
    double gap, closing, v;
    /* reached at once when the limits allow it, and the axis can go on at the target's velocity */
    if (fabs(reach) <= vmax && fabs(reach - f->velocity) <= dv && fabs(reach - target_velocity) <= dv) {
        f->position = target;
        f->velocity = reach;
        return;
    }
    gap = target - f->position - target_velocity * dt;  /* left after moving with the target */
    closing = fabs(gap) / dt;
    if (maxaccel > 0.0) {
        double braking = -dv + sqrt(dv * dv + 2.0 * maxaccel * fabs(gap));
        closing = braking < closing ? braking : closing;
    }
    v = target_velocity + (gap < 0.0 ? -closing : closing);
    v = v > f->velocity + dv ? f->velocity + dv : v < f->velocity - dv ? f->velocity - dv : v;
    v = v > vmax ? vmax : v < -vmax ? -vmax : v;
    f->position += v * dt;
    f->velocity = v;
}

/* Velocity mode: the target runs ahead of the axis by velocity_cmd each period. */
static inline void dda_follow_velocity(struct dda_follower *f, double velocity_cmd, double maxvel, double maxaccel,
                                       double dt)
{
    dda_follow(f, f->position + velocity_cmd * dt, velocity_cmd, maxvel, maxaccel, dt);
}

#endif /* DDA_MATH_H */
