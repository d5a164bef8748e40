/* One axis of the dda_card driver in a period: from position-cmd (or
 * velocity-cmd, control-type 1) to the steps it is to make, as hostmot2's
 * stepgen takes them: its own `enable`, `position-reset`, maxvel and
 * maxaccel (dda_follow).  Included by dda_card.c.
 *
 * Copyright the PCI DDA card authors.  GPL-2.0-or-later (see COPYING here).
 */
#ifndef DDA_AXIS_H
#define DDA_AXIS_H

#include "dda_state.h"

/* An axis enabled while the queue runs starts from where it stands: in position
 * mode its command is taken as its present position (the driver's coordinates move,
 * position-fb follows; LinuxCNC holds the command at the feedback while disabled). */
static void take_up(struct stepgen *s)
{
    int64_t target;
    s->queued = 1;
    s->refused = 0;
    if (!*s->control_type && dda_steps_of(*s->position_cmd, s->position_scale, &target) == 0) {
        s->offset += target - s->sent;
        s->sent = target;
        s->follow.position = s->last_target = *s->position_cmd;
    } else {
        s->follow.position = s->last_target = (double)s->sent / s->position_scale;
    }
    s->follow.velocity = 0.0;
}

/* position-reset: the axis's coordinates move so that it stands at 0 (counts and
 * position-fb 0 once what it has queued is made); it holds meanwhile. */
static void reset_position(struct stepgen *s)
{
    s->offset -= s->sent;
    s->sent = 0;
    s->follow.position = s->follow.velocity = s->last_target = 0.0;
}

/* A command that is no position (not a number, or beyond 2^53 steps): error
 * FAULT_BAD_COMMAND and the axis holds its last good target; said once. */
static int64_t refuse_command(struct card *c, struct stepgen *s, int i, double command)
{
    if (!s->refused)
        rtapi_print_msg(RTAPI_MSG_ERR, "dda_card: dda-card.%d.stepgen.%02d.%s %g at position-scale %g is no "
                        "position in steps: the axis holds at %g\n", c->index, i,
                        *s->control_type ? "velocity-cmd" : "position-cmd", command, s->position_scale,
                        (double)s->sent / s->position_scale);
    s->refused = 1;
    *c->error = 1;
    *c->error_code = FAULT_BAD_COMMAND;
    return 0;
}

/* The steps axis i is to make this period (dt seconds); 0 while it is not enabled. */
static int64_t axis_delta(struct card *c, int i, double dt)
{
    struct stepgen *s = &c->axis[i];
    struct dda_follower next;
    double command = *s->control_type ? *s->velocity_cmd : *s->position_cmd;
    int64_t target;
    if (!*s->enable) {
        s->queued = 0;
        return 0;
    }
    if (!s->queued)
        take_up(s);
    if (*s->position_reset) {
        reset_position(s);
        return 0;
    }
    if (!isfinite(command) || (!*s->control_type && dda_steps_of(command, s->position_scale, &target) < 0))
        return refuse_command(c, s, i, command);
    next = s->follow;
    if (*s->control_type)
        dda_follow_velocity(&next, command, s->maxvel, s->maxaccel, dt);
    else
        dda_follow(&next, command, (command - s->last_target) / dt, s->maxvel, s->maxaccel, dt);
    if (dda_steps_of(next.position, s->position_scale, &target) < 0)
        return refuse_command(c, s, i, command);
    s->follow = next;
    s->last_target = *s->control_type ? next.position : command;
    s->refused = 0;
    return target - s->sent;
}

#endif /* DDA_AXIS_H */
