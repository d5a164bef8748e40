/* The dda_card driver's simulation transport: the card server
 * (sim/card/card_server.py) on a Unix socket.  Every request is three
 * words (FIFO: and its data), every answer two (models/card_socket.py,
 * DDA_SIM_* in gen/dda_card.h).  Every send and receive waits at most
 * `timeout_ms` (SO_SNDTIMEO / SO_RCVTIMEO, set once at open): a server that
 * stalls or goes fails the transport, said once.  Included by
 * dda_transport.h.
 *
 * Copyright the PCI DDA card authors.  GPL-2.0-or-later (see COPYING here).
 */
#ifndef DDA_SIM_H
#define DDA_SIM_H

#include <sys/socket.h>
#include <sys/time.h>
#include <sys/un.h>
#include <unistd.h>

#include "dda_transport_state.h"

/* Why a send or receive of `wanted` bytes gave `got`. */
static int dda_sim_broken(struct dda_transport *t, ssize_t got, size_t wanted, const char *what)
{
    if (got < 0 && (errno == EAGAIN || errno == EWOULDBLOCK))
        return dda_transport_fail(t, "no %s within %d ms: the card server stalled", what, t->timeout_ms);
    if (got < 0)
        return dda_transport_fail(t, "the card server went away (%s)", strerror(errno));
    return dda_transport_fail(t, "the card server went away (%zd of %zu bytes of %s)", got, wanted, what);
}

static int dda_sim_exchange(struct dda_transport *t, uint32_t op, uint32_t a, uint32_t b,
                            const uint32_t *words, uint32_t *value)
{
    uint32_t request[DDA_SIM_REQUEST_WORDS + DDA_MAX_BURST] = {op, a, b};
    size_t length = DDA_SIM_REQUEST_WORDS * sizeof(uint32_t);
    uint32_t answer[DDA_SIM_ANSWER_WORDS];
    char message[256];
    ssize_t got;
    if (op == DDA_SIM_FIFO) {
        memcpy(&request[DDA_SIM_REQUEST_WORDS], words, a * sizeof(uint32_t));
        length += a * sizeof(uint32_t);
    }
    got = send(t->sock, request, length, MSG_NOSIGNAL);
    if (got != (ssize_t)length)
        return dda_sim_broken(t, got, length, "room to send a request");
    got = recv(t->sock, answer, sizeof answer, MSG_WAITALL);
    if (got != (ssize_t)sizeof answer)
        return dda_sim_broken(t, got, sizeof answer, "answer");
    if (answer[0] != 0) {
        size_t size = answer[1] < sizeof message - 1 ? answer[1] : sizeof message - 1;
        got = recv(t->sock, message, size, MSG_WAITALL);
        message[got > 0 ? got : 0] = 0;
        return dda_transport_fail(t, "the card server refused a request: %s", message);
    }
    if (value)
        *value = answer[1];
    return 0;
}

static int dda_sim_open(struct dda_transport *t, const char *path, int timeout_ms)
{
    struct sockaddr_un address = {.sun_family = AF_UNIX};
    struct timeval limit = {.tv_sec = timeout_ms / 1000, .tv_usec = (timeout_ms % 1000) * 1000};
    t->io_fd = -1;
    t->timeout_ms = timeout_ms;
    snprintf(t->name, sizeof t->name, "dda-card.%d, simulated card at %.80s", t->card, path);
    if (strlen(path) >= sizeof address.sun_path) {
        rtapi_print_msg(RTAPI_MSG_ERR, "dda_card: dda-card.%d: sim %s: the socket path is too long\n", t->card, path);
        return -EINVAL;
    }
    strcpy(address.sun_path, path);
    t->sock = socket(AF_UNIX, SOCK_STREAM, 0);
    if (t->sock < 0 || setsockopt(t->sock, SOL_SOCKET, SO_RCVTIMEO, &limit, sizeof limit) < 0
        || setsockopt(t->sock, SOL_SOCKET, SO_SNDTIMEO, &limit, sizeof limit) < 0
        || connect(t->sock, (struct sockaddr *)&address, sizeof address) < 0) {
        rtapi_print_msg(RTAPI_MSG_ERR, "dda_card: dda-card.%d: sim %s: no card server (%s): start "
                        "python -m sim.card.card_server --socket %s first\n", t->card, path, strerror(errno), path);
        if (t->sock >= 0)
            close(t->sock);
        t->sock = -1;
        return -ENODEV;
    }
    return 0;
}

static void dda_sim_close(struct dda_transport *t)
{
    close(t->sock);
    t->sock = -1;
}

#endif /* DDA_SIM_H */
