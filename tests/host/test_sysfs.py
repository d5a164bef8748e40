"""The real-card transport on a fake sysfs tree made of ordinary files: a
file for each BAR and for configuration space, a named pipe for /dev/uio0.
What the kernel would refuse (permission, lockdown) is stood in for at
the one place files are opened.  A run on a real card is marked
``hardware`` and skipped without one."""
import errno
import os

import pytest

from host.card import Card, IdentityError
from host.transports import TransportError, open_transport, sysfs
from host.transports.sysfs import DEVICE_ID, VENDOR_ID, SysfsTransport, find_cards
from models import registers as regmap
from models.instructions import encode

ADDRESS = "0000:03:00.0"


def register_bytes(registers=True, size=1 << regmap.IO_BAR_BITS):
    """The card's register block after reset (zeros: another bitstream), ``size`` bytes."""
    bar0 = bytearray(size)
    if registers:
        for reg in regmap.REGISTERS:
            bar0[reg.offset:reg.offset + 4] = reg.reset.to_bytes(4, "little")
    return bar0


def fake_card(root, address=ADDRESS, ids=(VENDOR_ID, DEVICE_ID), uio="uio0", registers=True, bar2=False, bar0=True):
    """A card's sysfs folder (and /dev/uioN, a named pipe) under ``root``; the folder.
    ``bar2``: the memory BAR aliasing the registers; ``bar0`` False: BAR0 unassigned
    (a host without I/O space), no ``resource0``."""
    folder = root / "sys" / "bus" / "pci" / "devices" / address
    folder.mkdir(parents=True)
    (folder / "vendor").write_text(f"0x{ids[0]:04x}\n")
    (folder / "device").write_text(f"0x{ids[1]:04x}\n")
    (folder / "enable").write_text("0\n")
    lines = ["0x0000000000001000 0x00000000000010ff 0x0000000000040101" if bar0 else
             "0x0000000000000000 0x0000000000000000 0x0000000000000000",
             "0x00000000fe000000 0x00000000fe000fff 0x0000000000040200"]
    if bar2:   # 4 KiB: BAR0's registers, then the per-axis blocks (docs/pci.md)
        lines.append("0x00000000fe001000 0x00000000fe001fff 0x0000000000040200")
    (folder / "resource").write_text("\n".join(lines) + "\n")
    if bar0:
        (folder / "resource0").write_bytes(bytes(register_bytes(registers)))
    if bar2:
        (folder / "resource2").write_bytes(bytes(register_bytes(registers, 4096)))
    (folder / "resource1").write_bytes(bytes(4096))
    config = bytearray(256)
    config[0:4] = (ids[1] << 16 | ids[0]).to_bytes(4, "little")
    config[4:6] = (0x0003 | 1 << 10).to_bytes(2, "little")  # I/O and memory on, INTx masked by uio
    config[0x3D] = 1
    (folder / "config").write_bytes(bytes(config))
    if uio:
        (folder / "uio" / uio).mkdir(parents=True)
        (root / "dev").mkdir(exist_ok=True)
        os.mkfifo(root / "dev" / uio)
    return folder


@pytest.fixture
def tree(tmp_path):
    folder = fake_card(tmp_path)
    writer = os.open(tmp_path / "dev" / "uio0", os.O_RDWR)  # the kernel's end of /dev/uio0
    yield tmp_path, folder, writer
    os.close(writer)


def opened(root, address=None):
    return SysfsTransport(address, sysfs=root / "sys", dev=root / "dev")


def test_registers_are_1_2_4_byte_accesses_of_resource0(tree):
    root, folder, _ = tree
    with opened(root) as transport:
        assert not transport.registers_mapped
        assert (folder / "enable").read_text().strip() == "1"
        assert transport.read(regmap.offset("ID")) == regmap.ID_MAGIC << 16 | regmap.VERSION
        assert transport.read(regmap.offset("ID") + 2, 2) == regmap.ID_MAGIC
        transport.write(regmap.offset("LOW_WATER"), 0x1234)
        transport.write(regmap.offset("LOW_WATER") + 1, 0xAB, 1)
        data = (folder / "resource0").read_bytes()
        assert data[0x18:0x1C] == bytes([0x34, 0xAB, 0, 0])
        with pytest.raises(ValueError):
            transport.read(2)


def no_system_calls(monkeypatch):
    """pread/pwrite refused from here on: an access that makes one fails the test."""
    def refused(*args):
        raise AssertionError("a register access made a system call")
    monkeypatch.setattr(sysfs.os, "pread", refused)
    monkeypatch.setattr(sysfs.os, "pwrite", refused)


@pytest.mark.parametrize("bar0", [True, False])
def test_registers_through_the_mapped_memory_bar_without_system_calls(tmp_path, monkeypatch, bar0):
    """A card with BAR2 aliasing the registers (and BAR0 as well, or none: a host without
    I/O space): every register access is one load or store in the mapping of resource2."""
    folder = fake_card(tmp_path, bar2=True, bar0=bar0)
    writer = os.open(tmp_path / "dev" / "uio0", os.O_RDWR)
    try:
        with opened(tmp_path) as transport:
            assert transport.registers_mapped
            no_system_calls(monkeypatch)
            assert transport.read(regmap.offset("ID")) == regmap.ID_MAGIC << 16 | regmap.VERSION
            assert transport.read(regmap.offset("ID") + 2, 2) == regmap.ID_MAGIC
            transport.write(regmap.offset("LOW_WATER"), 0x1234)
            transport.write(regmap.offset("LOW_WATER") + 1, 0xAB, 1)
            assert transport.read(regmap.offset("LOW_WATER")) == 0xAB34
            with pytest.raises(ValueError):
                transport.read(2)
            monkeypatch.undo()
            data = (folder / "resource2").read_bytes()
            assert data[0x18:0x1C] == bytes([0x34, 0xAB, 0, 0])
            identity = Card(transport).identity
            assert identity.fifo_words == regmap.register("FIFO_SIZE").reset
    finally:
        os.close(writer)


def test_per_axis_blocks_are_reached_through_the_mapped_bar2_only(tmp_path):
    """Z's block (0x180 + 0x40 * ... docs/registers.md: POS_Z at 0x180, PULSE_COUNT_Z at
    0x188) lies beyond BAR0: loads and stores in resource2's mapping; with BAR0 alone
    the host is told why it cannot reach it."""
    folder = fake_card(tmp_path / "mapped", bar2=True)
    image = bytearray((folder / "resource2").read_bytes())
    image[0x180:0x184] = (0xFFFFFFFB).to_bytes(4, "little")
    (folder / "resource2").write_bytes(bytes(image))
    writer = os.open(tmp_path / "mapped" / "dev" / "uio0", os.O_RDWR)
    try:
        with opened(tmp_path / "mapped") as transport:
            assert transport.read(0x180) == 0xFFFFFFFB
            transport.write(0x188, 12)
            assert (folder / "resource2").read_bytes()[0x188:0x18C] == bytes([12, 0, 0, 0])
            with pytest.raises(ValueError, match="0x1000"):
                transport.read(0x1000)
    finally:
        os.close(writer)
    fake_card(tmp_path / "io", bar2=False)
    writer = os.open(tmp_path / "io" / "dev" / "uio0", os.O_RDWR)
    try:
        with opened(tmp_path / "io") as transport:
            with pytest.raises(TransportError, match="BAR2 is not mapped"):
                transport.read(0x180)
            with pytest.raises(TransportError, match="BAR2 is not mapped"):
                transport.write(0x188, 1)
    finally:
        os.close(writer)


def test_a_memory_bar_that_reads_another_id_is_not_used(tmp_path):
    folder = fake_card(tmp_path, bar2=True)
    (folder / "resource2").write_bytes(bytes(register_bytes(registers=False)))
    writer = os.open(tmp_path / "dev" / "uio0", os.O_RDWR)
    try:
        with opened(tmp_path) as transport:
            assert not transport.registers_mapped
            assert transport.read(regmap.offset("ID")) == regmap.ID_MAGIC << 16 | regmap.VERSION
    finally:
        os.close(writer)


def test_registers_reachable_neither_way_are_refused_with_both_reasons(tree, monkeypatch):
    root, folder, _ = tree
    refuse(monkeypatch, "resource0", errno.EACCES)
    with pytest.raises(TransportError) as error:
        opened(root)
    message = str(error.value)
    assert "neither through a memory BAR (BAR2: the card has none)" in message
    assert str(folder / "resource0") in message and "udev rule" in message


def test_fifo_words_are_32_bit_stores_into_resource1(tree):
    root, folder, _ = tree
    words = [w for w in encode("LINE", 5, -7) + encode("MARK", TAG=9)]
    with opened(root) as transport:
        transport.fifo_write(words)
        assert transport.mem_read(0, 4) == words
    data = (folder / "resource1").read_bytes()
    assert [int.from_bytes(data[i:i + 4], "little") for i in range(0, 16, 4)] == words


def test_interrupts_come_through_uio_and_intx_is_unmasked(tree):
    root, folder, writer = tree
    with opened(root) as transport:
        assert transport.config_read(0) == DEVICE_ID << 16 | VENDOR_ID
        assert not transport.wait_interrupt(0.01)
        command = int.from_bytes((folder / "config").read_bytes()[4:6], "little")
        assert command == 0x0003  # Interrupt Disable cleared, the rest kept
        os.write(writer, (1).to_bytes(4, "little"))  # the kernel counts one interrupt
        assert transport.wait_interrupt(1.0)
        assert not transport.wait_interrupt(0.01)


def test_the_card_api_identifies_the_card_through_sysfs(tree):
    root, _, _ = tree
    with open_transport("pci", sysfs=root / "sys", dev=root / "dev") as transport:
        identity = Card(transport).identity
    assert identity.fifo_words == regmap.register("FIFO_SIZE").reset
    assert (identity.vendor_id, identity.device_id) == (VENDOR_ID, DEVICE_ID)


def test_another_bitstream_is_refused_by_the_card_api(tmp_path):
    fake_card(tmp_path, registers=False)
    with opened(tmp_path) as transport:
        with pytest.raises(IdentityError, match="not a DDA card"):
            Card(transport)


def test_no_card(tmp_path):
    fake_card(tmp_path, ids=(0x8086, 0x1234))
    with pytest.raises(TransportError, match="no DDA card"):
        opened(tmp_path)


def test_several_cards_are_named_and_one_is_chosen(tmp_path):
    fake_card(tmp_path)
    fake_card(tmp_path, "0000:04:00.0", uio="uio1")
    assert find_cards(tmp_path / "sys") == [ADDRESS, "0000:04:00.0"]
    with pytest.raises(TransportError, match=f"2 DDA cards: {ADDRESS}, 0000:04:00.0; choose one with --card pci:"):
        opened(tmp_path)
    writer = os.open(tmp_path / "dev" / "uio1", os.O_RDWR)
    try:
        with opened(tmp_path, "04:00.0") as transport:
            assert transport.address == "0000:04:00.0"
    finally:
        os.close(writer)


@pytest.mark.parametrize("address, text", [
    ("0000:09:00.0", "no PCI device at 0000:09:00.0"),
    ("0000:05:00.0", "is 8086:1234, not the DDA card"),
    ("5:0.0", "give the address as pci:DDDD:BB:DD.F"),
])
def test_a_named_address_must_be_the_card(tmp_path, address, text):
    fake_card(tmp_path)
    fake_card(tmp_path, "0000:05:00.0", ids=(0x8086, 0x1234), uio=None)
    with pytest.raises((TransportError, ValueError), match=text):
        opened(tmp_path, address)


def refuse(monkeypatch, name, code):
    real = sysfs.open_file

    def refusing(path, flags, *args):
        if path.endswith(name):
            raise PermissionError(code, os.strerror(code), path)
        return real(path, flags, *args)

    monkeypatch.setattr(sysfs, "open_file", refusing)


def test_no_permission_names_the_file_and_the_fix(tree, monkeypatch):
    root, folder, _ = tree
    refuse(monkeypatch, "resource1", errno.EACCES)
    with pytest.raises(TransportError) as error:
        opened(root)
    message = str(error.value)
    assert str(folder / "resource1") in message and "udev rule" in message and "group" in message


def test_kernel_lockdown_is_named(tree, monkeypatch):
    root, _, _ = tree
    (root / "sys" / "kernel" / "security").mkdir(parents=True)
    (root / "sys" / "kernel" / "security" / "lockdown").write_text("none [integrity] confidentiality\n")
    refuse(monkeypatch, "resource0", errno.EPERM)
    with pytest.raises(TransportError, match=r"kernel lockdown \(integrity\)"):
        opened(root)


def test_uio_not_bound_says_how_to_bind_it(tmp_path):
    folder = fake_card(tmp_path, uio=None)
    driver = tmp_path / "sys" / "bus" / "pci" / "drivers" / "some_driver"
    driver.mkdir(parents=True)
    (folder / "driver").symlink_to(driver)
    with pytest.raises(TransportError, match=r"uio_pci_generic is not bound \(bound to some_driver\).*new_id"):
        opened(tmp_path)


@pytest.mark.hardware
def test_a_real_card_identifies_and_passes_its_selftest():
    if not find_cards():
        pytest.skip("no DDA card in this machine")
    from host.selftest import selftest

    with open_transport("pci") as transport:
        card = Card(transport)
        assert card.identity.version[0] == regmap.VERSION >> 8
        assert all(problem is None for _, problem in selftest(card))
