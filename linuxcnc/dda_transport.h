/* Transports of the dda_card HAL driver: the real card on PCI
 * (dda_pci.h), or the simulated card served by
 * `python -m sim.card.card_server` on a Unix socket (dda_sim.h).
 *
 * Copyright the PCI DDA card authors.  GPL-2.0-or-later (see COPYING here).
 *
 * Both offer read32/write32 of the function registers and fifo_write (one
 * burst into BAR1, the command FIFO window).  On the real card the
 * registers are reached through a mapping when a memory BAR maps them
 * (`regs`: one load or store per access, no system call), else by
 * pread/pwrite of BAR0's sysfs file; the FIFO window is always mapped.
 * The socket transport adds advance(): the simulated card runs only when
 * told to, one servo period of card clocks at a time (lock-step).  A failed
 * access is said once and marks the transport failed: every later call
 * fails at once, without a system call.  Register offsets come from
 * gen/dda_card.h.
 */
#ifndef DDA_TRANSPORT_H
#define DDA_TRANSPORT_H

#include "dda_transport_state.h"
#include "dda_sim.h"
#include "dda_pci.h"

/* ---- the calls the driver makes ---- */

static int dda_read32(struct dda_transport *t, uint32_t offset, uint32_t *value)
{
    if (t->failed)
        return -EIO;
    if (t->regs) {
        *value = t->regs[offset / 4];
        return 0;
    }
    if (t->sock >= 0)
        return dda_sim_exchange(t, DDA_SIM_READ, offset, 0, NULL, value);
    return dda_pci_io(t, offset, value, 0);
}

static int dda_write32(struct dda_transport *t, uint32_t offset, uint32_t value)
{
    if (t->failed)
        return -EIO;
    if (t->regs) {
        t->regs[offset / 4] = value;
        return 0;
    }
    if (t->sock >= 0)
        return dda_sim_exchange(t, DDA_SIM_WRITE, offset, value, NULL, NULL);
    return dda_pci_io(t, offset, &value, 1);
}

/* One burst of `count` words into the FIFO window.  The caller has made sure
 * that the FIFO has room for them (STATUS.FIFO_LEVEL against FIFO_SIZE), so
 * the card never has to retry the bus. */
static int dda_fifo_write(struct dda_transport *t, const uint32_t *words, unsigned count)
{
    unsigned i;
    if (t->failed)
        return -EIO;
    if (count > DDA_MAX_BURST)
        return -EINVAL;
    if (t->sock >= 0)
        return dda_sim_exchange(t, DDA_SIM_FIFO, count, 0, words, NULL);
    for (i = 0; i < count; i++)
        t->fifo[i] = words[i];  /* one aligned 32-bit store each: the card takes every one */
    return 0;
}

/* The simulated card runs `clocks` clocks; `now`: its clocks since reset (low 32 bits).
 * The real card runs on its own: nothing to do. */
static int dda_advance(struct dda_transport *t, uint32_t clocks, uint32_t *now)
{
    if (t->failed)
        return -EIO;
    if (t->sock >= 0)
        return dda_sim_exchange(t, DDA_SIM_ADVANCE, clocks, 0, NULL, now);
    return 0;
}

static void dda_transport_close(struct dda_transport *t)
{
    if (t->sock >= 0)
        dda_sim_close(t);
    else
        dda_pci_close(t);
}

#endif /* DDA_TRANSPORT_H */
