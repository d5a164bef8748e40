"""cocotb test of the generated card (``gen/card.v``, split PCI ports) with
the host's cocotb front end (``sim.pci.cocotb_bus``): the same transaction layer
and protocol checker as the MyHDL benches.  Run by
``sim/card/test_cocotb_card.py`` through cocotb's runner in Icarus (not a pytest
file itself: cocotb imports it inside the simulator).

The test enumerates the card (IDs, class, BAR sizes against the
configuration the converter was given), writes and reads registers over
I/O, bursts a LINE and a MARK into the FIFO over memory, waits for the DDA
to finish and checks the position registers and the STEP pulses on the pins
against the line's end point; the checker watches every clock, in float
mode, with the X/Z detector.
"""
import cocotb
from cocotb.clock import Clock
from cocotb.triggers import ClockCycles, FallingEdge

from models import instructions as isa
from models import registers as regmap
from models.parameters import PARAMETERS
from rtl.convert import GEN_DIR
from models.parameters import AXES
from rtl.interfaces import machine_inputs
from sim.pci.cocotb_bus import CocotbPciBus, split_pins
from sim.pci.master import PciMaster

CLOCK_NS = 30
DX, DY = 37, -21
MARK = 0x5A


async def count_steps(dut, counts):
    """Count rising edges of the STEP pins and remember the last DIR levels."""
    before = (0, 0)
    while True:
        await FallingEdge(dut.clock)
        now = (int(dut.pins_step_x.value), int(dut.pins_step_y.value))
        for axis in (0, 1):
            counts[axis] += now[axis] and not before[axis]
        counts[2:] = [int(dut.pins_dir_x.value), int(dut.pins_dir_y.value)]
        before = now


@cocotb.test()
async def card_enumerate_registers_fifo_move(dut):
    Clock(dut.clock, CLOCK_NS, unit="ns").start()
    dut.reset.value = 0
    for name in machine_inputs(AXES.default):   # gen/card.v's switches at rest: nothing stops the card
        getattr(dut, f"pins_{name}").value = 0
    bus = CocotbPciBus(dut, split_pins([GEN_DIR / "card.v"], "card"), dut.clock, dut.reset,
                       idsel="pci_idsel_in", host=PciMaster(max_retries=1 << 20))
    bus.start()
    counts = [0, 0, 0, 0]
    cocotb.start_soon(count_steps(dut, counts))
    await ClockCycles(dut.clock, 3)
    dut.reset.value = 1
    await ClockCycles(dut.clock, 2)
    host = bus.host

    (device,) = await bus.run(host.enumerate_bus(devices=[0]))
    assert (device.vendor_id, device.device_id) == (PARAMETERS["vendor_id"].default, PARAMETERS["device_id"].default)
    assert device.class_code == PARAMETERS["class_code"].default
    io, mem = device.bar(0)["base"], device.bar(1)["base"]
    status = await bus.run(host.config_read(0, 0x04))
    assert status.value >> 16 & 0x8000 == 0  # no parity error detected: no X latched in Status

    async def write(name, value):
        result = await bus.run(host.io_write(io + regmap.offset(name), value))
        assert result.complete, f"I/O write of {name}: {result.termination}"

    async def read(name):
        result = await bus.run(host.io_read(io + regmap.offset(name)))
        assert result.complete, f"I/O read of {name}: {result.termination}"
        return result.value

    await write("FEED_RATE", regmap.RATE_MAX)
    assert await read("FEED_RATE") == regmap.RATE_MAX
    await write("CONTROL", 1)
    words = isa.encode("LINE", DX, DY) + isa.encode("MARK", TAG=MARK)
    burst = await bus.run(host.mem_write(mem, words))
    assert burst.complete
    for _ in range(2000):
        if not regmap.field_value("STATUS", "BUSY", await read("STATUS")):
            break
    else:
        raise AssertionError("the card stayed busy")
    x = regmap.field_value("POS_X", "STEPS", await read("POS_X"))
    y = regmap.field_value("POS_Y", "STEPS", await read("POS_Y"))
    assert (x, y) == (DX, DY)
    assert counts[:2] == [abs(DX), abs(DY)]
    assert regmap.field_value("MARK_TAG", "TAG", await read("MARK_TAG")) == MARK
    assert bus.checker.unknown_clocks == 0 and len(bus.checker.transactions) > 40
    dut._log.info("checked %d clocks, %d transactions", bus.checker.edges, len(bus.checker.transactions))
