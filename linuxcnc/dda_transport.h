/* Transports of the dda_card HAL driver: the real card on PCI, or the
 * simulated card served by `python -m sim.card.card_server` on a Unix socket.
 *
 * Copyright the PCI DDA card authors.  GPL-2.0-or-later (see COPYING here).
 *
 * Both offer read32/write32 of the function registers (BAR0, I/O) and
 * fifo_write (one burst into BAR1, the command FIFO window).  The socket
 * transport adds advance(): the simulated card runs only when told to, one
 * servo period of card clocks at a time (lock-step).  Register offsets come
 * from gen/dda_card.h.
 */
#ifndef DDA_TRANSPORT_H
#define DDA_TRANSPORT_H

#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <string.h>
#include <sys/socket.h>
#include <sys/un.h>
#include <unistd.h>

#include "rtapi.h"
#include "rtapi_pci.h"
#include "../gen/dda_card.h"  /* via -I of this folder: the generated header, never retyped */

#define DDA_MAX_BURST 64u /* words one period writes at most */

struct dda_transport {
    int sock;                     /* simulation: the server's socket, else -1 */
    int io_fd;                    /* PCI: BAR0's sysfs resource file (pread/pwrite of 4 bytes) */
    volatile uint32_t *fifo;      /* PCI: BAR1 mapped */
    char name[64];
};

/* ---- simulation: three-word requests, two-word answers (sim/card/card_server.py) ---- */

static int dda_sim_exchange(struct dda_transport *t, uint32_t op, uint32_t a, uint32_t b,
                            const uint32_t *words, uint32_t *value)
{
    uint32_t request[3 + DDA_MAX_BURST] = {op, a, b};
    size_t length = 3;
    uint32_t answer[2];
    char message[256];
    if (op == DDA_SIM_FIFO) {
        memcpy(&request[3], words, a * sizeof(uint32_t));
        length += a;
    }
    if (send(t->sock, request, length * sizeof(uint32_t), MSG_NOSIGNAL) != (ssize_t)(length * sizeof(uint32_t))
        || recv(t->sock, answer, sizeof answer, MSG_WAITALL) != (ssize_t)sizeof answer) {
        rtapi_print_msg(RTAPI_MSG_ERR, "dda_card: %s: the card server went away\n", t->name);
        return -EIO;
    }
    if (answer[0] != 0) {
        size_t size = answer[1] < sizeof message - 1 ? answer[1] : sizeof message - 1;
        ssize_t got = recv(t->sock, message, size, MSG_WAITALL);
        message[got > 0 ? got : 0] = 0;
        rtapi_print_msg(RTAPI_MSG_ERR, "dda_card: %s: %s\n", t->name, message);
        return -EIO;
    }
    if (value)
        *value = answer[1];
    return 0;
}

static int dda_sim_open(struct dda_transport *t, const char *path)
{
    struct sockaddr_un address = {.sun_family = AF_UNIX};
    if (strlen(path) >= sizeof address.sun_path) {
        rtapi_print_msg(RTAPI_MSG_ERR, "dda_card: sim=%s: the socket path is too long\n", path);
        return -EINVAL;
    }
    strcpy(address.sun_path, path);
    t->sock = socket(AF_UNIX, SOCK_STREAM, 0);
    t->io_fd = -1;
    snprintf(t->name, sizeof t->name, "simulated card at %s", path);
    if (t->sock < 0 || connect(t->sock, (struct sockaddr *)&address, sizeof address) < 0) {
        rtapi_print_msg(RTAPI_MSG_ERR, "dda_card: sim=%s: no card server (%s): start "
                        "python -m sim.card.card_server --socket %s first\n", path, strerror(errno), path);
        if (t->sock >= 0)
            close(t->sock);
        t->sock = -1;
        return -ENODEV;
    }
    return 0;
}

/* ---- the real card: rtapi_pci finds it and maps BAR1; BAR0 (I/O) through sysfs ---- */

static const struct rtapi_pci_device_id dda_pci_ids[] = {
    {DDA_PCI_VENDOR_ID, DDA_PCI_DEVICE_ID, DDA_PCI_SUBSYSTEM_VENDOR_ID, DDA_PCI_SUBSYSTEM_ID, 0, 0},
    {0, 0, 0, 0, 0, 0},
};
static struct rtapi_pci_dev *dda_pci_found[8];
static int dda_pci_count;

static int dda_pci_probe(struct rtapi_pci_dev *dev, const struct rtapi_pci_device_id *id)
{
    (void)id;
    if (dda_pci_count < (int)(sizeof dda_pci_found / sizeof dda_pci_found[0]))
        dda_pci_found[dda_pci_count] = dev;
    dda_pci_count++;
    return 0;
}

static struct rtapi_pci_driver dda_pci_driver = {
    .name = "dda_card",
    .id_table = dda_pci_ids,
    .probe = dda_pci_probe,
};

static int dda_pci_refused(const char *path)
{
    if (errno == EACCES || errno == EPERM)
        rtapi_print_msg(RTAPI_MSG_ERR, "dda_card: %s: no permission (%s): install the udev rule that gives "
                        "the group 'dda' the card's files and join that group (docs/linuxcnc.md)\n",
                        path, strerror(errno));
    else
        rtapi_print_msg(RTAPI_MSG_ERR, "dda_card: %s: %s\n", path, strerror(errno));
    return -errno;
}

static int dda_pci_open(struct dda_transport *t)
{
    char path[300];
    struct rtapi_pci_dev *dev;
    int i;
    t->sock = -1;
    t->io_fd = -1;
    dda_pci_count = 0;
    if (rtapi_pci_register_driver(&dda_pci_driver) < 0 || dda_pci_count == 0) {
        rtapi_print_msg(RTAPI_MSG_ERR, "dda_card: no DDA card (%04x:%04x) under /sys/bus/pci/devices: "
                        "is it seated? (lspci -d %04x:%04x)\n", DDA_PCI_VENDOR_ID, DDA_PCI_DEVICE_ID,
                        DDA_PCI_VENDOR_ID, DDA_PCI_DEVICE_ID);
        rtapi_pci_unregister_driver(&dda_pci_driver);
        return -ENODEV;
    }
    if (dda_pci_count > 1) {
        rtapi_print_msg(RTAPI_MSG_ERR, "dda_card: %d DDA cards:", dda_pci_count);
        for (i = 0; i < dda_pci_count && i < 8; i++)
            rtapi_print_msg(RTAPI_MSG_ERR, " %s", rtapi_pci_name(dda_pci_found[i]));
        rtapi_print_msg(RTAPI_MSG_ERR, "; this driver runs one card per machine\n");
        rtapi_pci_unregister_driver(&dda_pci_driver);
        return -EBUSY;
    }
    dev = dda_pci_found[0];
    snprintf(t->name, sizeof t->name, "PCI card %s", rtapi_pci_name(dev));
    if (rtapi_pci_enable_device(dev) < 0) {
        snprintf(path, sizeof path, "%s/enable", dev->sys_path);
        return dda_pci_refused(path);
    }
    snprintf(path, sizeof path, "%s/resource0", dev->sys_path);
    t->io_fd = open(path, O_RDWR);
    if (t->io_fd < 0)
        return dda_pci_refused(path);
    t->fifo = rtapi_pci_ioremap_bar(dev, 1);
    if (!t->fifo) {
        snprintf(path, sizeof path, "%s/resource1", dev->sys_path);
        return dda_pci_refused(path);
    }
    return 0;
}

/* ---- the calls the driver makes ---- */

static int dda_read32(struct dda_transport *t, uint32_t offset, uint32_t *value)
{
    if (t->sock >= 0)
        return dda_sim_exchange(t, DDA_SIM_READ, offset, 0, NULL, value);
    return pread(t->io_fd, value, 4, offset) == 4 ? 0 : -EIO;
}

static int dda_write32(struct dda_transport *t, uint32_t offset, uint32_t value)
{
    if (t->sock >= 0)
        return dda_sim_exchange(t, DDA_SIM_WRITE, offset, value, NULL, NULL);
    return pwrite(t->io_fd, &value, 4, offset) == 4 ? 0 : -EIO;
}

static int dda_fifo_write(struct dda_transport *t, const uint32_t *words, unsigned count)
{
    unsigned i;
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
    if (t->sock >= 0)
        return dda_sim_exchange(t, DDA_SIM_ADVANCE, clocks, 0, NULL, now);
    return 0;
}

static void dda_transport_close(struct dda_transport *t)
{
    if (t->sock >= 0)
        close(t->sock);
    if (t->io_fd >= 0) {
        close(t->io_fd);
        rtapi_pci_unregister_driver(&dda_pci_driver);
    }
    t->sock = t->io_fd = -1;
}

#endif /* DDA_TRANSPORT_H */
