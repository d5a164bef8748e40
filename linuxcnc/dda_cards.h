/* The dda_card driver's cards: the list it is loaded with, each card opened
 * and checked, all or none.  `sim` names the simulated cards' sockets,
 * separated by commas (dda-card.0 the first); empty, the driver serves every
 * DDA card on the PCI bus, numbered by PCI address (dda_pci.h).  A list it
 * cannot take (empty items, a socket twice, more than CARDS_MAX) is refused
 * before any card is opened; a card that fails to open or to pass its checks
 * closes those opened before it.  Included by dda_card.c.
 *
 * Copyright the PCI DDA card authors.  GPL-2.0-or-later (see COPYING here).
 */
#ifndef DDA_CARDS_H
#define DDA_CARDS_H

#include <sys/un.h>

#include "hal.h"
#include "dda_checks.h"
#include "dda_state.h"
#include "dda_transport.h"

#define SOCKET_PATH_MAX ((int)sizeof(((struct sockaddr_un *)0)->sun_path))

/* The sockets of `list` (comma-separated) into paths[]: how many, or -EINVAL with the
 * reason said. */
static int dda_parse_sockets(const char *list, char paths[CARDS_MAX][SOCKET_PATH_MAX])
{
    const char *item = list;
    int count = 0, i;
    for (;;) {
        const char *end = strchr(item, ',');
        int length = end ? (int)(end - item) : (int)strlen(item);
        if (length == 0) {
            rtapi_print_msg(RTAPI_MSG_ERR, "dda_card: sim=%s: socket %d of the list is empty: give the card "
                            "servers' sockets separated by commas (sim=/run/a.sock,/run/b.sock)\n", list, count);
            return -EINVAL;
        }
        if (count == CARDS_MAX) {
            rtapi_print_msg(RTAPI_MSG_ERR, "dda_card: sim=%s: more than %d cards; this driver serves at most %d\n",
                            list, CARDS_MAX, CARDS_MAX);
            return -EINVAL;
        }
        if (length >= SOCKET_PATH_MAX) {
            rtapi_print_msg(RTAPI_MSG_ERR, "dda_card: sim=%s: socket %d of the list is %d characters, a socket "
                            "path holds at most %d\n", list, count, length, SOCKET_PATH_MAX - 1);
            return -EINVAL;
        }
        memcpy(paths[count], item, (size_t)length);
        paths[count][length] = 0;
        for (i = 0; i < count; i++)
            if (strcmp(paths[i], paths[count]) == 0) {
                rtapi_print_msg(RTAPI_MSG_ERR, "dda_card: sim=%s: %s is given for dda-card.%d and dda-card.%d: "
                                "each card has a server of its own\n", list, paths[i], i, count);
                return -EINVAL;
            }
        count++;
        if (!end)
            return count;
        item = end + 1;
    }
}

/* Whatever a previous session left queued on the card stops here, its drives off. */
static int dda_reset_card(struct card *c)
{
    struct dda_transport *t = &c->transport;
    if (dda_write32(t, DDA_CONTROL, 0) < 0 || dda_write32(t, DDA_COMMAND, DDA_COMMAND_SOFT_RESET_MASK) < 0
        || dda_write32(t, DDA_WATCHDOG, 0) < 0 || dda_write32(t, DDA_MACHINE_CONTROL, 0) < 0)
        return -ENODEV;
    return 0;
}

/* Card `index` in HAL's memory, opened (on `socket`, or the PCI card found at `index`
 * when socket is NULL), checked and reset: 0, or the reason (said) it is not. */
static int dda_open_card(struct card **made, int index, const char *socket, int timeout_ms, int keep_ahead)
{
    struct card *c = hal_malloc(sizeof *c);
    int problem;
    *made = c;
    if (!c)
        return -ENOMEM;
    memset(c, 0, sizeof *c);
    c->index = index;
    c->transport.card = index;
    c->transport.sock = -1;
    c->transport.io_fd = -1;
    problem = socket ? dda_sim_open(&c->transport, socket, timeout_ms) : dda_pci_open(&c->transport, index);
    if (problem < 0) {
        *made = NULL;  /* nothing open to close */
        return problem;
    }
    problem = dda_check_card(c, keep_ahead);
    return problem ? problem : dda_reset_card(c);
}

/* Close every card opened (cards[i] NULL: not opened), then let go of the PCI bus. */
static void dda_close_cards(struct card **cards, int count)
{
    int i;
    for (i = 0; i < count; i++)
        if (cards[i])
            dda_transport_close(&cards[i]->transport);
    dda_pci_release();
}

/* The cards of the list (`sim`, or every PCI card), each opened, checked and reset:
 * how many, or the reason (said) for none, with nothing left open. */
static int dda_open_cards(struct card **cards, const char *sim, int timeout_ms, int keep_ahead)
{
    char paths[CARDS_MAX][SOCKET_PATH_MAX];
    int count = sim[0] ? dda_parse_sockets(sim, paths) : dda_pci_find(CARDS_MAX);
    int k, problem = 0;
    if (count < 0) {
        dda_pci_release();
        return count;
    }
    for (k = 0; k < count && problem == 0; k++)
        problem = dda_open_card(&cards[k], k, sim[0] ? paths[k] : NULL, timeout_ms, keep_ahead);
    if (problem) {
        dda_close_cards(cards, k);
        return problem;
    }
    return count;
}

#endif /* DDA_CARDS_H */
