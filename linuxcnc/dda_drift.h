/* The dda_card driver's clock-drift loop: each period's DWELL is trimmed
 * from the card's FIFO level so that the card's crystal, some ppm off the
 * PC's timer, neither drains nor fills the queue (docs/linuxcnc.md, "Clock
 * drift").  Included by dda_card.c.
 *
 * Copyright the PCI DDA card authors.  GPL-2.0-or-later (see COPYING here).
 */
#ifndef DDA_DRIFT_H
#define DDA_DRIFT_H

#include "dda_state.h"

/* The card's crystal and the PC's timer differ (~100 ppm): left alone the queue
 * would slowly drain or fill.  The whole periods still in the FIFO at the read
 * (its level against the words of each period queued, newest first) are held
 * where they stood at the first read after start: fewer, the card runs fast and
 * each DWELL is lengthened by a step; more, it runs slow and each is shortened.
 * The count moves only when the card's period boundary crosses the read, so the
 * queue stays within a period of where it started.  */
static void trim_drift(struct card *c, int32_t level)
{
    int32_t words = 0;
    int depth = 0;
    while (depth < TRIM_RING && (uint32_t)depth < c->periods_queued) {
        words += c->period_words[(c->periods_queued - 1 - depth) % TRIM_RING];
        if (words > level)
            break;
        depth++;
    }
    if (c->depth_start < 0)
        c->depth_start = depth;
    c->trim_sign = depth < c->depth_start ? 1 : depth > c->depth_start ? -1 : 0;
}

#endif /* DDA_DRIFT_H */
