"""The simulated transports against the register map and the PCI IDs (the
spec tables), on every back end: sizes, byte lanes, the FIFO window,
configuration space, interrupts and card time."""
import pytest

from host.transports import TransportError, open_transport
from host.transports.simulated import SimTransport
from models import registers as regmap
from models.instructions import encode
from models.parameters import PARAMETERS

KINDS = ["verilator", "myhdl", "icarus"]
MARKS = [word for tag in range(64) for word in encode("MARK", TAG=tag)]


@pytest.fixture(scope="module", params=KINDS)
def transport(request):
    with SimTransport(request.param) as opened:
        yield opened


def test_id_reads_as_dword_words_and_bytes(transport):
    word = regmap.ID_MAGIC << 16 | regmap.VERSION
    offset = regmap.offset("ID")
    assert transport.read(offset) == word
    assert transport.read(offset, 2) == regmap.VERSION
    assert transport.read(offset + 2, 2) == regmap.ID_MAGIC
    assert [transport.read(offset + i, 1) for i in range(4)] == [(word >> 8 * i) & 0xFF for i in range(4)]


def test_writes_land_in_their_byte_lanes(transport):
    offset = regmap.offset("LOW_WATER")
    transport.write(offset, 0x1234)
    transport.write(offset + 1, 0xAB, 1)
    assert transport.read(offset) == 0xAB34
    transport.write(offset, 0, 2)
    assert transport.read(offset) == 0


def test_configuration_space_holds_the_build_ids(transport):
    assert transport.config_read(0x00) == PARAMETERS["device_id"].default << 16 | PARAMETERS["vendor_id"].default
    assert transport.config_read(0x02, 2) == PARAMETERS["device_id"].default
    assert transport.config_read(0x3D, 1) == 1  # interrupt pin INTA#


def test_fifo_words_are_counted_and_dropped_by_soft_reset(transport):
    transport.write(regmap.offset("CONTROL"), 0)  # hold the queue
    transport.fifo_write(MARKS[:39])
    level = regmap.field_value("STATUS", "FIFO_LEVEL", transport.read(regmap.offset("STATUS")))
    assert level == 38  # the instruction register holds the first command (docs/instructions.md)
    assert transport.mem_read(0x10, 2) == [0, 0]  # the FIFO window reads 0
    transport.write(regmap.offset("COMMAND"), regmap.field_of("COMMAND", SOFT_RESET=1))
    assert regmap.field_value("STATUS", "FIFO_LEVEL", transport.read(regmap.offset("STATUS"))) == 0


def test_interrupt_and_card_time(transport):
    start_clocks, start = transport.clocks, transport.now()
    assert not transport.wait_interrupt(2e-6)  # nothing enabled
    waited = transport.clocks - start_clocks
    assert waited == pytest.approx(2e-6 * transport.clock_hz, abs=1)
    assert transport.now() - start == pytest.approx(waited / transport.clock_hz)
    transport.write(regmap.offset("INT_ENABLE"), regmap.field_of("INT_ENABLE", CLAMPED=1))
    transport.write(regmap.offset("FEED_RATE"), regmap.RATE_MAX + 1)  # out of range: clamped, CLAMPED set
    assert transport.wait_interrupt(1e-3)
    assert transport.read(regmap.offset("FEED_RATE")) == regmap.RATE_MAX
    transport.write(regmap.offset("INT_STATUS"), regmap.field_of("INT_STATUS", CLAMPED=1))
    transport.write(regmap.offset("INT_ENABLE"), 0)
    transport.sleep(1e-6)
    assert not transport.wait_interrupt(1e-6)


# misaligned, a size PCI has no byte enables for, the dword just past BAR2 (beyond the I/O BAR
# the per-axis blocks), below it
@pytest.mark.parametrize("offset, size", [(2, 4), (1, 2), (1 << regmap.REG_BAR_BITS, 4), (0, 3), (-4, 4)])
def test_bad_accesses_are_refused_before_the_bus(transport, offset, size):
    clocks = transport.clocks
    with pytest.raises(ValueError):
        transport.read(offset, size)
    with pytest.raises(ValueError):
        transport.write(offset, 0, size)
    assert transport.clocks == clocks


def test_values_that_do_not_fit_are_refused(transport):
    with pytest.raises(ValueError):
        transport.write(regmap.offset("LOW_WATER"), 0x100, 1)
    with pytest.raises(ValueError):
        transport.fifo_write([1 << 32])


def test_unknown_card_names_are_refused():
    with pytest.raises(ValueError, match="unknown card"):
        open_transport("modelsim")


def test_a_fifo_that_stays_full_is_an_error_that_counts_the_words(transport):
    if transport.kind != "verilator":
        pytest.skip("the retry budget takes minutes of MyHDL clocks")
    depth = transport.read(regmap.offset("FIFO_SIZE"))
    transport.write(regmap.offset("CONTROL"), 0)
    with pytest.raises(TransportError, match=f"of {depth + 5} words taken") as error:
        transport.fifo_write(MARKS[:1] * (depth + 5))
    taken = int(str(error.value).split(": ")[1].split(" of ")[0])
    assert taken == depth + 1  # one command in the instruction register, the FIFO full, nothing more
    status = transport.read(regmap.offset("STATUS"))  # the card still answers
    assert regmap.field_value("STATUS", "FIFO_FULL", status)
    assert regmap.field_value("STATUS", "FIFO_LEVEL", status) == depth
    transport.write(regmap.offset("COMMAND"), regmap.field_of("COMMAND", SOFT_RESET=1))
