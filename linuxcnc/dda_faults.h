/* The dda_card driver's fault checks: the faults that stand whatever
 * enable does, a card gone from the bus, why the card stopped itself, a
 * position-scale of 0; and what a fault does: the queue halted, error and
 * error-code set, why the card stopped itself on stop-reason.
 * error-code values: dda_state.h.  Included by dda_card.c.
 *
 * Copyright the PCI DDA card authors.  GPL-2.0-or-later (see COPYING here).
 */
#ifndef DDA_FAULTS_H
#define DDA_FAULTS_H

#include "dda_checks.h"
#include "dda_state.h"
#include "dda_transport.h"

/* A fault that stands whatever enable does: the transport failed, the card gone, a
 * watchdog stop held by has_bit; else 0. */
static int standing_fault(struct card *c)
{
    if (c->transport.failed)
        return FAULT_TRANSPORT;
    if (c->gone)
        return FAULT_CARD_GONE;
    return *c->watchdog_has_bit ? FAULT_CARD_STOPPED : 0;
}

/* STOP_REASON.REASON in words. */
static const char *reason_name(int reason)
{
    switch (reason) {
    case DDA_STOP_ESTOP: return "its E-stop input";
    case DDA_STOP_WATCHDOG: return "its watchdog (the servo thread stopped writing it in time)";
    case DDA_STOP_LIMIT: return "a limit switch";
    case DDA_STOP_FOLLOWING_ERROR: return "a following error beyond FERROR_LIMIT (STOP_REASON.AXIS names the axis)";
    default: return "an unknown reason";
    }
}

/* A card gone from the bus (pulled, its slot unpowered) reads all-ones, which STATUS
 * (reserved bits 0) never does; ID reading all-ones too confirms it. */
static int card_gone(struct card *c, uint32_t status)
{
    uint32_t id = 0;
    return status == 0xFFFFFFFFu && (dda_read32(&c->transport, DDA_ID, &id) < 0 || id == 0xFFFFFFFFu);
}

/* position-scale 0 would put every target at step 0: forced to 1, as hostmot2 does. */
static void check_scale(struct card *c, int i)
{
    struct stepgen *s = &c->axis[i];
    if (s->position_scale != 0.0)
        return;
    s->position_scale = 1.0;
    rtapi_print_msg(RTAPI_MSG_ERR, "dda_card: dda-card.%d.stepgen.%02d.position-scale 0 is no scale: set to 1\n",
                    c->index, i);
}

/* The queue stops now: nothing more leaves the FIFO, the watchdog is off. */
static void halt_card(struct card *c)
{
    c->running = 0;
    *c->drift_trim = 0;
    dda_write32(&c->transport, DDA_CONTROL, 0);
    dda_write32(&c->transport, DDA_COMMAND, DDA_COMMAND_SOFT_RESET_MASK);
    dda_write32(&c->transport, DDA_WATCHDOG, 0);
}

static void stop(struct card *c, int code)
{
    *c->error = 1;
    *c->error_code = code;
    halt_card(c);
}

/* The card's guard holds it stopped (STATUS.STOPPED): why, on stop-reason.  When that
 * stops the machine (`stopping`): error -3, and a watchdog stop sets has_bit. */
static void card_stopped(struct card *c, int stopping)
{
    uint32_t why = 0;
    dda_read32(&c->transport, DDA_STOP_REASON, &why);
    *c->stop_reason = (int32_t)FIELD(why, DDA_STOP_REASON_REASON);
    if (!stopping)
        return;
    if (*c->stop_reason == DDA_STOP_WATCHDOG)
        *c->watchdog_has_bit = 1;
    stop(c, FAULT_CARD_STOPPED);
    rtapi_print_msg(RTAPI_MSG_ERR, "dda_card: %s: the card stopped the machine: %s (STOP_REASON.AXIS %u)\n",
                    c->transport.name, reason_name(*c->stop_reason), (unsigned)FIELD(why, DDA_STOP_REASON_AXIS));
}

#endif /* DDA_FAULTS_H */
