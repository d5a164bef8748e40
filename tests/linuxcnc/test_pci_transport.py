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

static struct rtapi_pci_dev dev;
static int preads;

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
    return driver->probe(&dev, driver->id_table);
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

int main(int argc, char **argv)
{
    struct dda_transport t;
    uint32_t id = 0;
    int i;
    memset(&t, 0, sizeof t);
    snprintf(dev.sys_path, sizeof dev.sys_path, "%s", argv[1]);
    snprintf(dev.dev_name, sizeof dev.dev_name, "0000:03:00.0");
    for (i = 2; i + 2 < argc; i += 3) {
        int bar = atoi(argv[i]);
        dev.resource[bar].start = 0x1000;
        dev.resource[bar].end = 0x1000 + strtol(argv[i + 1], NULL, 0) - 1;
        dev.resource[bar].flags = strtoul(argv[i + 2], NULL, 0);
    }
    if (dda_pci_open(&t) < 0) { printf("refused\n"); return 0; }
    preads = 0;
    if (dda_read32(&t, DDA_ID, &id) < 0 || dda_write32(&t, DDA_LOW_WATER, 0x1234u) < 0) { printf("failed\n"); return 0; }
    printf("id %08x mapped %d system-calls %d\n", id, t.regs != NULL, preads);
    dda_transport_close(&t);
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
