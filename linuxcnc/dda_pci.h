/* The dda_card driver's real-card transport: rtapi_pci finds the card and
 * maps its memory BARs (uspace: the sysfs resource files).  The FIFO
 * window is BAR1.  The registers are reached through a memory BAR that
 * aliases them when the card has one (BAR2 on cards that do; mapped
 * once, every access then one load or store, no system call), else
 * through BAR0, the I/O BAR, by a 4-byte pread/pwrite of its sysfs file
 * (I/O BARs cannot be mapped; each access is a system call).  A card
 * reachable by neither is refused with both reasons.  Every card present is
 * served, numbered by PCI address.  Included by
 * dda_transport.h.
 *
 * Copyright the PCI DDA card authors.  GPL-2.0-or-later (see COPYING here).
 */
#ifndef DDA_PCI_H
#define DDA_PCI_H

#include <fcntl.h>
#include <unistd.h>

#include "rtapi_pci.h"

#include "dda_transport_state.h"

#define DDA_FIFO_BAR 1
#define DDA_REGS_BAR 2              /* the memory BAR aliasing the registers, on cards that have it */
#define DDA_RESOURCE_MEM 0x200ul    /* a BAR's flags in sysfs `resource`: memory (the kernel's IORESOURCE_MEM) */

static const struct rtapi_pci_device_id dda_pci_ids[] = {
    {DDA_PCI_VENDOR_ID, DDA_PCI_DEVICE_ID, DDA_PCI_SUBSYSTEM_VENDOR_ID, DDA_PCI_SUBSYSTEM_ID, 0, 0},
    {0, 0, 0, 0, 0, 0},
};
#define DDA_PCI_FOUND_MAX 8
static struct rtapi_pci_dev *dda_pci_found[DDA_PCI_FOUND_MAX];
static int dda_pci_count;
static int dda_pci_registered;

static int dda_pci_probe(struct rtapi_pci_dev *dev, const struct rtapi_pci_device_id *id)
{
    (void)id;
    if (dda_pci_count < DDA_PCI_FOUND_MAX)
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

/* BAR0 by pread/pwrite of 4 bytes (`write`: 1 writes *value). */
static int dda_pci_io(struct dda_transport *t, uint32_t offset, uint32_t *value, int write)
{
    ssize_t done = write ? pwrite(t->io_fd, value, 4, offset) : pread(t->io_fd, value, 4, offset);
    if (done != 4)
        return dda_transport_fail(t, "BAR0 %s at 0x%02x failed (%s)", write ? "write" : "read", offset,
                                  done < 0 ? strerror(errno) : "cut short");
    return 0;
}

/* The registers through memory BAR `bar` when the card has it (a memory BAR of at least
 * the register block): 0 with t->regs set, else -1 (BAR0 stays the way).  Where BAR0 is
 * open too, ID read both ways must agree: a BAR that is no alias is not used. */
static int dda_pci_map_registers(struct dda_transport *t, struct rtapi_pci_dev *dev, int bar)
{
    uint32_t id = 0;
    volatile uint32_t *regs;
    if (!(rtapi_pci_resource_flags(dev, bar) & DDA_RESOURCE_MEM)
        || rtapi_pci_resource_len(dev, bar) < DDA_IO_BAR_SIZE)
        return -1;
    regs = rtapi_pci_ioremap_bar(dev, bar);
    if (!regs)
        return -1;
    if (t->io_fd >= 0 && (pread(t->io_fd, &id, 4, DDA_ID) != 4 || id != regs[DDA_ID / 4])) {
        rtapi_print_msg(RTAPI_MSG_ERR, "dda_card: %s: BAR%d reads ID %08x where BAR0 reads %08x: "
                        "not the registers, BAR0 is used\n", t->name, bar, regs[DDA_ID / 4], id);
        return -1;
    }
    t->regs = regs;
    return 0;
}

/* Every card present, in the order of their PCI addresses (dda-card.0 the lowest), as
 * many as the driver serves: their count, or -ENODEV with the reason said. */
static int dda_pci_find(int most)
{
    int i, j;
    dda_pci_count = 0;
    if (rtapi_pci_register_driver(&dda_pci_driver) < 0 || dda_pci_count == 0) {
        rtapi_print_msg(RTAPI_MSG_ERR, "dda_card: no DDA card (%04x:%04x) under /sys/bus/pci/devices: "
                        "is it seated? (lspci -d %04x:%04x)\n", DDA_PCI_VENDOR_ID, DDA_PCI_DEVICE_ID,
                        DDA_PCI_VENDOR_ID, DDA_PCI_DEVICE_ID);
        rtapi_pci_unregister_driver(&dda_pci_driver);
        return -ENODEV;
    }
    dda_pci_registered = 1;
    if (dda_pci_count > most) {
        rtapi_print_msg(RTAPI_MSG_ERR, "dda_card: %d DDA cards:", dda_pci_count);
        for (i = 0; i < dda_pci_count && i < DDA_PCI_FOUND_MAX; i++)
            rtapi_print_msg(RTAPI_MSG_ERR, " %s", rtapi_pci_name(dda_pci_found[i]));
        rtapi_print_msg(RTAPI_MSG_ERR, "; this driver serves at most %d\n", most);
        return -ENODEV;
    }
    for (i = 1; i < dda_pci_count; i++)  /* by address: the same numbering at every boot */
        for (j = i; j > 0 && strcmp(rtapi_pci_name(dda_pci_found[j - 1]), rtapi_pci_name(dda_pci_found[j])) > 0; j--) {
            struct rtapi_pci_dev *swap = dda_pci_found[j];
            dda_pci_found[j] = dda_pci_found[j - 1];
            dda_pci_found[j - 1] = swap;
        }
    return dda_pci_count;
}

/* This card's files; the driver registration stays (dda_pci_release). */
static void dda_pci_close(struct dda_transport *t)
{
    if (t->io_fd >= 0)
        close(t->io_fd);
    t->io_fd = -1;
    t->regs = NULL;
}

/* The driver registration, once every card is closed. */
static void dda_pci_release(void)
{
    if (dda_pci_registered)
        rtapi_pci_unregister_driver(&dda_pci_driver);
    dda_pci_registered = 0;
}

/* Card `index` of those dda_pci_find found. */
static int dda_pci_open(struct dda_transport *t, int index)
{
    char path[300];
    int bar0_errno;
    struct rtapi_pci_dev *dev = dda_pci_found[index];
    t->sock = -1;
    t->io_fd = -1;
    t->regs = NULL;
    snprintf(t->name, sizeof t->name, "dda-card.%d, PCI card %s", t->card, rtapi_pci_name(dev));
    if (rtapi_pci_enable_device(dev) < 0) {
        snprintf(path, sizeof path, "%s/enable", dev->sys_path);
        dda_pci_close(t);
        return dda_pci_refused(path);
    }
    t->fifo = rtapi_pci_ioremap_bar(dev, DDA_FIFO_BAR);
    if (!t->fifo) {
        snprintf(path, sizeof path, "%s/resource%d", dev->sys_path, DDA_FIFO_BAR);
        dda_pci_close(t);
        return dda_pci_refused(path);
    }
    snprintf(path, sizeof path, "%s/resource0", dev->sys_path);
    t->io_fd = open(path, O_RDWR);
    bar0_errno = t->io_fd < 0 ? errno : 0;
    if (dda_pci_map_registers(t, dev, DDA_REGS_BAR) == 0 && t->io_fd >= 0) {
        close(t->io_fd);  /* every access goes through the mapping */
        t->io_fd = -1;
    }
    if (!t->regs && t->io_fd < 0) {
        errno = bar0_errno;
        rtapi_print_msg(RTAPI_MSG_ERR, "dda_card: %s: the registers are reachable neither through a memory "
                        "BAR (BAR%d: none that maps them) nor through BAR0:\n", t->name, DDA_REGS_BAR);
        dda_pci_close(t);
        return dda_pci_refused(path);
    }
    return 0;
}

#endif /* DDA_PCI_H */
