"""The driver's real-card transport (``linuxcnc/dda_pci.h``) on files standing in for sysfs.

A C program built against LinuxCNC's ``rtapi_pci.h`` and the driver's headers
supplies rtapi_pci itself: its "card" is a folder with ``resource0`` (BAR0,
the registers, read by pread/pwrite), ``resource1`` (the FIFO window) and,
where the card has it, ``resource2`` (a memory BAR aliasing the registers);
``rtapi_pci_ioremap_bar`` maps those files.  pread and pwrite are wrapped
(``-Wl,--wrap``) to count the system calls of register accesses.  Skipped
without LinuxCNC's headers.
"""
import shutil
import subprocess
from pathlib import Path

import pytest

from models import registers as regmap

ROOT = Path(__file__).resolve().parents[2]
HEADERS = Path("/usr/include/linuxcnc")
IO, MEM = 0x100, 0x200  # resource flags: the kernel's IORESOURCE_IO, IORESOURCE_MEM
REGISTERS = 1 << regmap.IO_BAR_BITS
ID = regmap.register("ID").reset

PROBE = r"""#include <stdarg.h>
#include <stdlib.h>
#include <sys/mman.h>
#include "dda_transport.h"
#include "dda_state.h"

static struct rtapi_pci_dev dev, several[8];
static int preads, cards = 1;

ssize_t __real_pread(int fd, void *buf, size_t n, off_t off);
ssize_t __wrap_pread(int fd, void *buf, size_t n, off_t off) { preads++; return __real_pread(fd, buf, n, off); }
ssize_t __real_pwrite(int fd, const void *buf, size_t n, off_t off);
ssize_t __wrap_pwrite(int fd, const void *buf, size_t n, off_t off) { preads++; return __real_pwrite(fd, buf, n, off); }

void rtapi_print_msg(msg_level_t level, const char *fmt, ...)
{
    va_list args;
    (void)level;
    va_start(args, fmt);
    vprintf(fmt, args);
    va_end(args);
}
int rtapi_pci_register_driver(struct rtapi_pci_driver *driver)
{
    int i;
    if (cards == 1)
        return driver->probe(&dev, driver->id_table);
    for (i = 0; i < cards; i++)  /* as the kernel may list them: not by address */
        if (driver->probe(&several[i], driver->id_table) < 0)
            return -1;
    return 0;
}
void rtapi_pci_unregister_driver(struct rtapi_pci_driver *driver) { (void)driver; }
int rtapi_pci_enable_device(struct rtapi_pci_dev *d) { (void)d; return 0; }
void *rtapi_pci_ioremap_bar(struct rtapi_pci_dev *d, int bar)
{
    char path[300];
    int fd;
    void *p;
    snprintf(path, sizeof path, "%s/resource%d", d->sys_path, bar);
    fd = open(path, O_RDWR);
    if (fd < 0) return NULL;
    p = mmap(NULL, (size_t)rtapi_pci_resource_len(d, bar), PROT_READ | PROT_WRITE, MAP_SHARED, fd, 0);
    close(fd);
    return p == MAP_FAILED ? NULL : p;
}

/* --several N: N cards on the bus, the order dda_pci_find numbers them in */
static int number_several(int count)
{
    int i, found;
    cards = count;
    for (i = 0; i < cards; i++)
        snprintf(several[i].dev_name, sizeof several[i].dev_name, "0000:%02x:00.0", (7 * i + 3) % 16);
    found = dda_pci_find(CARDS_MAX);
    for (i = 0; i < found; i++)
        printf("dda-card.%d %s\n", i, rtapi_pci_name(dda_pci_found[i]));
    printf("found %d\n", found);
    dda_pci_release();
    return 0;
}

int main(int argc, char **argv)
{
    struct dda_transport t;
    uint32_t id = 0;
    int i;
    if (argc == 3 && strcmp(argv[1], "--several") == 0)
        return number_several(atoi(argv[2]));
    memset(&t, 0, sizeof t);
    snprintf(dev.sys_path, sizeof dev.sys_path, "%s", argv[1]);
    snprintf(dev.dev_name, sizeof dev.dev_name, "0000:03:00.0");
    for (i = 2; i + 2 < argc; i += 3) {
        int bar = atoi(argv[i]);
        dev.resource[bar].start = 0x1000;
        dev.resource[bar].end = 0x1000 + strtol(argv[i + 1], NULL, 0) - 1;
        dev.resource[bar].flags = strtoul(argv[i + 2], NULL, 0);
    }
    if (dda_pci_find(CARDS_MAX) != 1 || dda_pci_open(&t, 0) < 0) { printf("refused\n"); return 0; }
    preads = 0;
    if (dda_read32(&t, DDA_ID, &id) < 0 || dda_write32(&t, DDA_LOW_WATER, 0x1234u) < 0) { printf("failed\n"); return 0; }
    printf("id %08x mapped %d system-calls %d\n", id, t.regs != NULL, preads);
    dda_transport_close(&t);
    dda_pci_release();
    return 0;
}
"""


@pytest.fixture(scope="module")
def probe(tmp_path_factory):
    compiler = shutil.which("gcc") or shutil.which("cc")
    if compiler is None or not (HEADERS / "rtapi_pci.h").exists():
        pytest.skip("no C compiler or no LinuxCNC headers (linuxcnc-uspace-dev)")
    folder = tmp_path_factory.mktemp("pci_probe")
    (folder / "probe.c").write_text(PROBE)
    built = subprocess.run([compiler, "-std=gnu99", "-DRTAPI", "-I", str(HEADERS), "-I", str(ROOT / "linuxcnc"),
                            "-Wall", "-Wextra", "-Werror", "-Wno-unused-function", str(folder / "probe.c"),
                            "-o", str(folder / "probe"), "-Wl,--wrap=pread,--wrap=pwrite"],
                           capture_output=True, text=True)
    assert built.returncode == 0, built.stderr
    return folder / "probe"


def card_files(folder, bar0=True, bar2=None):
    """The card's resource files; bar2: None (no BAR2) or the ID its registers read."""
    registers = bytearray(REGISTERS)
    registers[0:4] = ID.to_bytes(4, "little")
    if bar0:
        (folder / "resource0").write_bytes(bytes(registers))
    (folder / "resource1").write_bytes(bytes(4096))
    if bar2 is not None:
        registers[0:4] = bar2.to_bytes(4, "little")
        (folder / "resource2").write_bytes(bytes(registers))


def run(probe, folder, bars):
    arguments = [str(a) for bar, size, flags in bars for a in (bar, size, flags)]
    return subprocess.run([str(probe), str(folder), *arguments], capture_output=True, text=True,
                          check=True).stdout


BAR0, BAR1, BAR2 = (0, REGISTERS, IO), (1, 4096, MEM), (2, REGISTERS, MEM)


def test_registers_through_bar2_take_no_system_call(probe, tmp_path):
    card_files(tmp_path, bar2=ID)
    output = run(probe, tmp_path, [BAR0, BAR1, BAR2])
    assert output.splitlines()[-1] == f"id {ID:08x} mapped 1 system-calls 0"
    low_water = regmap.offset("LOW_WATER")
    assert (tmp_path / "resource2").read_bytes()[low_water:low_water + 4] == (0x1234).to_bytes(4, "little")


def test_without_bar2_the_registers_are_pread_and_pwrite_of_bar0(probe, tmp_path):
    card_files(tmp_path)
    assert run(probe, tmp_path, [BAR0, BAR1]).splitlines()[-1] == f"id {ID:08x} mapped 0 system-calls 2"


def test_a_host_without_io_space_reaches_the_registers_through_bar2(probe, tmp_path):
    card_files(tmp_path, bar0=False, bar2=ID)
    assert run(probe, tmp_path, [BAR1, BAR2]).splitlines()[-1] == f"id {ID:08x} mapped 1 system-calls 0"


def test_a_bar2_that_reads_another_id_is_not_used(probe, tmp_path):
    card_files(tmp_path, bar2=0)
    output = run(probe, tmp_path, [BAR0, BAR1, BAR2])
    assert "BAR2 reads ID 00000000 where BAR0 reads" in output
    assert output.splitlines()[-1] == f"id {ID:08x} mapped 0 system-calls 2"


def test_registers_reachable_neither_way_are_refused(probe, tmp_path):
    card_files(tmp_path, bar0=False)
    output = run(probe, tmp_path, [BAR1])
    assert "the registers are reachable neither through a memory BAR (BAR2: none that maps them) nor " \
           "through BAR0" in output
    assert "resource0: No such file or directory" in output and output.splitlines()[-1] == "refused"


def test_several_cards_are_numbered_by_pci_address(probe):
    """Cards probed out of address order: dda-card.0 is the lowest address, the same at every boot."""
    output = subprocess.run([str(probe), "--several", "3"], capture_output=True, text=True, check=True).stdout
    # probed as 03, 0a, 01 (7 i + 3 mod 16)
    assert output.splitlines() == ["dda-card.0 0000:01:00.0", "dda-card.1 0000:03:00.0", "dda-card.2 0000:0a:00.0",
                                   "found 3"]


def test_more_cards_than_the_driver_serves_are_refused_naming_them(probe):
    output = subprocess.run([str(probe), "--several", "5"], capture_output=True, text=True, check=True).stdout
    assert "dda_card: 5 DDA cards: 0000:03:00.0 0000:0a:00.0 0000:01:00.0 0000:08:00.0 0000:0f:00.0; " \
           "this driver serves at most 4" in output
    assert output.splitlines()[-1] == "found -19"
