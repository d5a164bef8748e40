/* The dda_card driver's unload: its exit waits until no servo thread is
 * inside its functions.  Included by dda_card.c.
 *
 * `halcmd stop` only keeps a thread from starting its next pass: a pass
 * already inside read or write goes on while `unload` runs rtapi_app_exit.
 * Left alone, the exit used a card's transport beside the thread (on the
 * simulated card two requests crossed on the socket) and freed the functions
 * while the thread was still in them; rtapi_app then crashed, which halrun
 * shows as "Waited 3 seconds for master".  A pass on the simulated card
 * waits for the card server's answers, so on a loaded machine the window is
 * wide (tests/linuxcnc/test_unload.py).  So every function runs its pass
 * through dda_guarded (refused once the exit began), and the exit waits in
 * dda_wait_outside before it touches a card.
 *
 * Copyright the PCI DDA card authors.  GPL-2.0-or-later (see COPYING here).
 */
#ifndef DDA_UNLOAD_H
#define DDA_UNLOAD_H

#include <time.h>

static int dda_unloading;  /* set once, by the exit */
static int dda_inside;     /* passes inside read or write now */

/* pass(arg, period), unless the exit has begun; counted in dda_inside while it runs. */
static void dda_guarded(void (*pass)(void *, long), void *arg, long period)
{
    __atomic_add_fetch(&dda_inside, 1, __ATOMIC_SEQ_CST);
    if (!__atomic_load_n(&dda_unloading, __ATOMIC_SEQ_CST))
        pass(arg, period);
    __atomic_sub_fetch(&dda_inside, 1, __ATOMIC_SEQ_CST);
}

/* Refuse every further pass, then wait until the passes inside have left, at most
 * `limit_ms` (a request waits at most the transport's timeout): 0, or -1. */
static int dda_wait_outside(int limit_ms)
{
    const struct timespec tick = {0, 1000000};
    int waited;
    __atomic_store_n(&dda_unloading, 1, __ATOMIC_SEQ_CST);
    for (waited = 0; __atomic_load_n(&dda_inside, __ATOMIC_SEQ_CST) && waited < limit_ms; waited++)
        nanosleep(&tick, NULL);
    return __atomic_load_n(&dda_inside, __ATOMIC_SEQ_CST) ? -1 : 0;
}

#endif /* DDA_UNLOAD_H */
