"""A real card on Linux, from user space: sysfs for the BARs, ``uio_pci_generic``
for the interrupt.  No kernel module of our own.

* The card is found by its vendor and device ID under
  ``/sys/bus/pci/devices`` (``--card pci``), or named
  (``--card pci:DDDD:BB:DD.F``); its decoders are turned on by writing 1
  to ``enable``.
* The registers: through a memory BAR that aliases them when the card has
  one (BAR2 on cards that do: ``resource2`` mapped, every access a single
  aligned load or store of its size, no system call), else through BAR0
  (I/O): ``pread`` / ``pwrite`` of exactly 1, 2 or 4 bytes at the
  register's offset in ``resource0``; the kernel turns each into one
  in/out instruction (I/O BARs cannot be mapped on x86).  A memory BAR
  whose ID differs from BAR0's is no alias and is not used; a card whose
  registers are reachable neither way is refused with both reasons.
* BAR1 (memory, the FIFO window): ``resource1`` mapped with ``mmap``
  (``O_SYNC``, not the write-combining ``resource1_wc``); every word is one
  aligned 32-bit store through a ``memoryview`` cast to ``I``, never a
  slice copy that might split into byte stores.
* Interrupts: ``uio_pci_generic`` bound to the card gives ``/dev/uioN``; a
  4-byte read returns when INTx fires.  The driver masks INTx each time, so
  before each wait the host clears Command bit 10 (Interrupt Disable)
  through the ``config`` file.
* Configuration space: ``pread`` of ``config``.

Clear errors (``TransportError``): no card, several cards (with their
addresses), a named address that is missing or another device, no
permission (which file, and the udev rule or group that fixes it), kernel
lockdown, ``uio_pci_generic`` not bound (and how to bind it).

``sysfs`` and ``dev`` name the roots, so the tests run all of it on a fake
tree built from ordinary files.
"""
import errno
import mmap
import os
import re
import select
import time
from pathlib import Path

from host.transports.base import Transport, TransportError
from models import registers as regmap
from models.parameters import PARAMETERS
from models.pci import check_access, check_value

VENDOR_ID = PARAMETERS["vendor_id"].default
DEVICE_ID = PARAMETERS["device_id"].default
COMMAND = 0x04
INTERRUPT_DISABLE = 1 << 10
IORESOURCE_IO = 0x100
IORESOURCE_MEM = 0x200
REGS_BAR = 2  # the memory BAR that aliases the registers, on cards that have one
REGISTER_BYTES = 1 << regmap.IO_BAR_BITS
ADDRESS = re.compile(r"^(?:[0-9a-f]{4}:)?[0-9a-f]{2}:[0-1][0-9a-f]\.[0-7]$")
DOCS = "docs/host.md, 'A real card'"
open_file = os.open  # every file is opened through here (the tests stand in for the kernel's refusals)


def _ids(path):
    try:
        return int((path / "vendor").read_text(), 16), int((path / "device").read_text(), 16)
    except (OSError, ValueError):
        return None


def find_cards(sysfs="/sys", vendor_id=VENDOR_ID, device_id=DEVICE_ID):
    """Addresses (``DDDD:BB:DD.F``) of every card with these IDs, sorted."""
    devices = Path(sysfs) / "bus" / "pci" / "devices"
    if not devices.is_dir():
        return []
    return sorted(entry.name for entry in devices.iterdir() if _ids(entry) == (vendor_id, device_id))


def find_card(address=None, sysfs="/sys", vendor_id=VENDOR_ID, device_id=DEVICE_ID):
    """The sysfs folder of the card at ``address``, or of the one card present."""
    devices = Path(sysfs) / "bus" / "pci" / "devices"
    wanted = f"{vendor_id:04x}:{device_id:04x}"
    if address is not None:
        address = address.lower()
        if not ADDRESS.match(address):
            raise ValueError(f"pci:{address}: give the address as pci:DDDD:BB:DD.F (lspci -D shows it)")
        if address.count(":") == 1:
            address = f"0000:{address}"
        path = devices / address
        ids = _ids(path)
        if ids is None:
            raise TransportError(f"no PCI device at {address} ({devices})")
        if ids != (vendor_id, device_id):
            raise TransportError(f"{address} is {ids[0]:04x}:{ids[1]:04x}, not the DDA card ({wanted})")
        return path
    found = find_cards(sysfs, vendor_id, device_id)
    if not found:
        raise TransportError(f"no DDA card ({wanted}) under {devices}: is it seated? (lspci -d {wanted})")
    if len(found) > 1:
        raise TransportError(f"{len(found)} DDA cards: {', '.join(found)}; choose one with --card pci:"
                             f"{found[0]}")
    return devices / found[0]


class SysfsTransport(Transport):
    """The card at ``address`` (``DDDD:BB:DD.F``; None: the one present)."""

    def __init__(self, address=None, sysfs="/sys", dev="/dev", vendor_id=VENDOR_ID, device_id=DEVICE_ID):
        self.sysfs, self.dev = Path(sysfs), Path(dev)
        self.path = find_card(address, sysfs, vendor_id, device_id)
        self.address = self.path.name
        self.name = f"PCI card {self.address}"
        self.ids = (vendor_id, device_id)
        self._fds, self._map, self._regs_map, self._regs = [], None, None, None
        try:
            self._open()
        except BaseException:
            self.close()
            raise
        self._start = time.monotonic()

    def _open(self):
        self._write_file(self.path / "enable", b"1")
        bars = self._bars()
        self._check_io_bar(bars)
        self._open_registers(bars)
        mem_fd = self._fd(self.path / "resource1", os.O_RDWR | os.O_SYNC)
        self.mem_size = os.fstat(mem_fd).st_size
        self._map = mmap.mmap(mem_fd, self.mem_size, mmap.MAP_SHARED, mmap.PROT_READ | mmap.PROT_WRITE)
        self.fifo = memoryview(self._map).cast("I")
        self.config_fd = self._fd(self.path / "config", os.O_RDWR)
        self.uio_fd = self._fd(self._uio(), os.O_RDONLY | os.O_NONBLOCK)

    def _bars(self):
        """(start, end, flags) per BAR from ``resource``, or None when it cannot be read."""
        try:
            lines = (self.path / "resource").read_text().splitlines()
        except OSError:
            return None
        return [tuple(int(v, 16) for v in line.split()) for line in lines if len(line.split()) == 3]

    def _check_io_bar(self, bars):
        """BAR0 must be I/O, or unassigned (a host or bridge without I/O space)."""
        if bars and bars[0][2] and not bars[0][2] & IORESOURCE_IO:
            raise TransportError(f"{self.address}: BAR0 is not an I/O BAR: another bitstream?")

    def _open_registers(self, bars):
        """The registers through the memory BAR that aliases them, else BAR0's pread/pwrite."""
        self.io_fd, refused = None, None
        try:
            self.io_fd = self._fd(self.path / "resource0", os.O_RDWR)
            self.io_size = os.fstat(self.io_fd).st_size
        except TransportError as error:
            refused = error
        why = self._map_registers(bars)
        if why is None:
            return
        if self.io_fd is None:
            raise TransportError(f"{self.address}: the registers are reachable neither through a memory BAR "
                                 f"(BAR{REGS_BAR}: {why}) nor through BAR0 ({refused})")

    def _map_registers(self, bars):
        """Map BAR2 when it is a memory BAR holding the registers and reads BAR0's ID: None
        (``_regs`` set), else why not."""
        if not bars or len(bars) <= REGS_BAR or not bars[REGS_BAR][2] & IORESOURCE_MEM:
            return "the card has none"
        start, end, _ = bars[REGS_BAR]
        if end - start + 1 < REGISTER_BYTES:
            return f"{end - start + 1} bytes, fewer than the registers' {REGISTER_BYTES}"
        fd = self._fd(self.path / f"resource{REGS_BAR}", os.O_RDWR | os.O_SYNC)
        size = os.fstat(fd).st_size
        self._regs_map = mmap.mmap(fd, size, mmap.MAP_SHARED, mmap.PROT_READ | mmap.PROT_WRITE)
        view = memoryview(self._regs_map)
        regs = {4: view.cast("I"), 2: view.cast("H"), 1: view}  # released in this order
        if self.io_fd is not None:
            identity = int.from_bytes(os.pread(self.io_fd, 4, regmap.offset("ID")), "little")
            if regs[4][regmap.offset("ID") // 4] != identity:
                for item in regs.values():
                    item.release()
                return "it reads another ID than BAR0: no alias of the registers"
            os.close(self.io_fd)  # every access goes through the mapping
            self._fds.remove(self.io_fd)
            self.io_fd = None
        self._regs, self.io_size = regs, size
        return None

    def _uio(self):
        """``/dev/uioN`` of the card, or how to bind ``uio_pci_generic``."""
        folder = self.path / "uio"
        names = sorted(p.name for p in folder.iterdir()) if folder.is_dir() else []
        if not names:
            driver = self.path / "driver"
            bound = f" (bound to {os.path.basename(os.readlink(driver))})" if driver.is_symlink() else ""
            ids = f"{self.ids[0]:04x} {self.ids[1]:04x}"
            raise TransportError(
                f"{self.address}: uio_pci_generic is not bound{bound}, so interrupts cannot reach user "
                f"space: modprobe uio_pci_generic; echo '{ids}' > /sys/bus/pci/drivers/uio_pci_generic/new_id "
                f"({DOCS})")
        return self.dev / names[0]

    def _refused(self, path, error):
        if error.errno == errno.EPERM:
            mode = self._lockdown()
            if mode:
                return TransportError(f"{path}: kernel lockdown ({mode}) forbids user-space access to PCI "
                                      f"resources; it follows Secure Boot: turn lockdown off ({DOCS})")
        if error.errno in (errno.EACCES, errno.EPERM):
            return TransportError(f"{path}: no permission ({error.strerror}): run as root, or install the "
                                  f"udev rule that gives the group 'dda' the card's files and join that group "
                                  f"({DOCS})")
        return TransportError(f"{path}: {error.strerror}")

    def _lockdown(self):
        """The kernel's lockdown mode when it is not ``none``, else None."""
        try:
            text = (self.sysfs / "kernel" / "security" / "lockdown").read_text()
        except OSError:
            return None
        match = re.search(r"\[(\w+)\]", text)
        return match.group(1) if match and match.group(1) != "none" else None

    def _fd(self, path, flags):
        try:
            fd = open_file(str(path), flags)
        except OSError as error:
            raise self._refused(path, error) from None
        self._fds.append(fd)
        return fd

    def _write_file(self, path, data):
        fd = self._fd(path, os.O_WRONLY)
        os.write(fd, data)
        os.close(fd)
        self._fds.remove(fd)

    # ----- the interface -----------------------------------------------------------
    @property
    def registers_mapped(self):
        """True when the registers are reached through a mapped memory BAR (no system call)."""
        return self._regs is not None

    def _unmapped_block(self, offset):
        """TransportError for a per-axis block offset when only BAR0 reaches the registers."""
        if self._regs is None and offset >= self.io_size:
            raise TransportError(f"{self.address}: offset {offset:#x} is in BAR2's per-axis register blocks, "
                                 "and BAR2 is not mapped (the registers go through BAR0, which has BAR0's "
                                 f"{self.io_size} bytes only)")

    def read(self, offset, size=4):
        self._unmapped_block(offset)
        check_access(offset, size, self.io_size)
        if self._regs is not None:
            return self._regs[size][offset // size]  # one aligned load of that size
        data = os.pread(self.io_fd, size, offset)
        if len(data) != size:
            raise TransportError(f"{self.address}: BAR0 read at {offset:#x} gave {len(data)} of {size} bytes")
        return int.from_bytes(data, "little")

    def write(self, offset, value, size=4):
        self._unmapped_block(offset)
        check_access(offset, size, self.io_size)
        check_value(value, size)
        if self._regs is not None:
            self._regs[size][offset // size] = value  # one aligned store of that size
            return
        if os.pwrite(self.io_fd, value.to_bytes(size, "little"), offset) != size:
            raise TransportError(f"{self.address}: BAR0 write at {offset:#x} was cut short")

    def fifo_write(self, words):
        """One aligned 32-bit store per word, at successive addresses of the window
        (a full FIFO holds the store on the bus: the card retries it)."""
        slots = len(self.fifo)
        for index, word in enumerate(words):
            check_value(word, 4)
            self.fifo[index % slots] = word

    def mem_read(self, offset, count=1):
        check_access(offset, 4, self.mem_size, "BAR1")
        first = offset // 4
        return [self.fifo[i] for i in range(first, min(first + count, len(self.fifo)))]

    def config_read(self, register, size=4):
        check_access(register, size, 256, "configuration space")
        return int.from_bytes(os.pread(self.config_fd, size, register), "little")

    def _unmask(self):
        command = self.config_read(COMMAND, 2)
        if command & INTERRUPT_DISABLE:
            os.pwrite(self.config_fd, (command & ~INTERRUPT_DISABLE).to_bytes(2, "little"), COMMAND)

    def wait_interrupt(self, seconds):
        """Unmask INTx, then wait up to ``seconds`` for ``/dev/uioN``."""
        self._unmask()
        ready, _, _ = select.select([self.uio_fd], [], [], max(0.0, seconds))
        if not ready:
            return False
        try:
            data = os.read(self.uio_fd, 4)
        except BlockingIOError:
            return False
        if len(data) != 4:
            raise TransportError(f"{self.address}: the uio device closed")
        return True

    def sleep(self, seconds):
        time.sleep(seconds)

    def now(self):
        return time.monotonic() - self._start

    def close(self):
        if getattr(self, "fifo", None) is not None:
            self.fifo.release()
            self.fifo = None
        if self._map is not None:
            self._map.close()
            self._map = None
        for view in (self._regs or {}).values():
            view.release()
        self._regs = None
        if self._regs_map is not None:
            self._regs_map.close()
            self._regs_map = None
        for fd in self._fds:
            os.close(fd)
        self._fds = []
