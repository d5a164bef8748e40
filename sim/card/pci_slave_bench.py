"""What the directed benches of the PCI target share (``sim/card/test_pci_slave*.py``):
the target's contract (IDs, BAR places and sizes, Command and Status bits
from PCI 2.3 section 6.2), a runner that returns the waveform it wrote, and
readers of that waveform.
"""
from sim.backends.waves import Waveform
from sim.pci.bench import CLOCK_PERIOD, PciBench
from sim.pci.host import (COMMAND_INTERRUPT_DISABLE, COMMAND_IO, COMMAND_MEMORY, COMMAND_PARITY_RESPONSE,
                          COMMAND_SERR_ENABLE)

TARGETS = ["myhdl", "verilog"]
DEVICE = 0
IO_BASE, MEM_BASE, ALIAS_BASE = 0x1000, 0x80000000, 0x90000000
IO_SIZE, MEM_SIZE = 64, 4096          # contract defaults: io_bar_bits=6, mem_bar_bits=12
ALIAS_SIZE = IO_SIZE                  # BAR2: BAR0's registers in memory space
VENDOR_ID, DEVICE_ID, CLASS_CODE = 0x1234, 0xDDA0, 0x088000
IMPLEMENTED_COMMAND = (COMMAND_IO | COMMAND_MEMORY | COMMAND_PARITY_RESPONSE
                       | COMMAND_SERR_ENABLE | COMMAND_INTERRUPT_DISABLE)
STATUS_INTERRUPT = 1 << 3
STATUS_DEVSEL_MEDIUM = 1 << 9
STATUS_SIGNALED_TARGET_ABORT = 1 << 11
STATUS_SIGNALED_SYSTEM_ERROR = 1 << 14
STATUS_DETECTED_PARITY_ERROR = 1 << 15
MEDIUM_DEVSEL_EDGE = 2   # DEVSEL# sampled two edges after the address edge


def run(target, scenario, name, trace=None, **options):
    """Run ``scenario(bench, out)``; return (out, bench, waveform or None if untraced:
    ``trace`` True when the test reads the waveform, as ``PciBench.run`` takes it)."""
    bench = PciBench(target=target, **options)
    out = {}

    def wrapped(b):
        yield from scenario(b, out)

    vcd = bench.run(wrapped, f"{name}_{target}", trace=trace)
    return out, bench, None if vcd is None else Waveform(vcd)


def setup(host, command=COMMAND_IO | COMMAND_MEMORY):
    """Place BAR0 at IO_BASE, BAR1 at MEM_BASE and BAR2 at ALIAS_BASE, enable ``command``."""
    yield from host.config_write(DEVICE, 0x10, IO_BASE)
    yield from host.config_write(DEVICE, 0x14, MEM_BASE)
    yield from host.config_write(DEVICE, 0x18, ALIAS_BASE)
    yield from host.config_write(DEVICE, 0x04, command, be=0x3)


def status(host):
    return ((yield from host.config_read(DEVICE, 0x04)).value >> 16) & 0xFFFF


def sampled(wave, name, edge):
    """Value the rising edge at time ``edge`` samples."""
    return wave.at(name, edge - 1)


def address_edges(wave):
    """Times of the rising edges that sample an address phase."""
    return [t + CLOCK_PERIOD for t in wave.edges("bus_frame", "0")]
