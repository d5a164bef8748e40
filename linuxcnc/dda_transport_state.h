/* The dda_card driver's transport state: what the real card's (dda_pci.h)
 * and the simulated card's (dda_sim.h) transports share, and the one way
 * either fails.  dda_transport.h puts them together behind the calls the
 * driver makes.
 *
 * Copyright the PCI DDA card authors.  GPL-2.0-or-later (see COPYING here).
 */
#ifndef DDA_TRANSPORT_STATE_H
#define DDA_TRANSPORT_STATE_H

#include <errno.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#include "rtapi.h"
#include "../gen/dda_card.h"  /* via -I of this folder: the generated header, never retyped */

#define DDA_MAX_BURST 64u /* words one period writes at most */

struct dda_transport {
    int sock;                     /* simulation: the server's socket, else -1 */
    int timeout_ms;               /* simulation: the longest wait for an answer */
    int io_fd;                    /* PCI: BAR0's sysfs file (pread/pwrite of 4 bytes) when no BAR maps the registers */
    volatile uint32_t *regs;      /* PCI: the registers mapped (a memory BAR aliasing BAR0), else NULL */
    volatile uint32_t *fifo;      /* PCI: BAR1 mapped */
    int failed;                   /* an access failed: said once, every call fails from then on */
    int card;                     /* K of dda-card.K, set before open: the name says it */
    char name[112];               /* "dda-card.K, <which card>": every message of the card says it */
};

/* The transport fails: say why, once. */
static int dda_transport_fail(struct dda_transport *t, const char *format, ...)
{
    char why[200];
    va_list args;
    if (!t->failed) {
        va_start(args, format);
        vsnprintf(why, sizeof why, format, args);
        va_end(args);
        rtapi_print_msg(RTAPI_MSG_ERR, "dda_card: %s: %s; the driver stops using the card\n", t->name, why);
    }
    t->failed = 1;
    return -EIO;
}

#endif /* DDA_TRANSPORT_STATE_H */
