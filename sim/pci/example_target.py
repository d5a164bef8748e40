"""The example PCI target of docs/verification.md on the bench.

``docs/example/scratch_target.v`` was written apart from the card, in the
style third-party sources have (tri-state ports in ANSI style, parameters
in port ranges, a Latin-1 byte in a comment, an include folder, a define):
its wiring for ``PciBench`` and the scenario that enumerates it and moves a
burst each way, used by its test and by ``bench/vip_figures.py``."""
from rtl.convert import ROOT
from sim.pci.verilog_target import VerilogTarget

EXAMPLE = ROOT / "docs" / "example"
PINS = {"ad": "ad", "cbe": "cbe_n", "par": "par", "frame": "frame_n", "irdy": "irdy_n",
        "trdy": "trdy_n", "devsel": "devsel_n", "stop": "stop_n"}
VENDOR, DEVICE, CLASS = 0x1234, 0x5C7A, 0x058000
WORDS = 16   # the example's memory BAR, in dwords


def scratch_target(defines=()):
    """The example as a ``PciBench`` target; ``defines`` e.g. ``["X_ON_RETRY"]``."""
    return VerilogTarget(files=[EXAMPLE / "scratch_target.v"], top="scratch_target", pins=PINS,
                         clock="clk", reset="rst_n", idsel="idsel", include_dirs=[EXAMPLE],
                         defines=defines)


def scenario(out):
    """Enumerate, write ``WORDS`` dwords, read them back, write one byte and
    read its dword; the results go into the dict ``out``."""
    def run(bench):
        host = bench.host
        (device,) = yield from host.enumerate_bus(devices=[0])
        out["device"] = device
        base = device.bars[0]["base"]
        values = [0x1000_0001 * (i + 1) & 0xFFFFFFFF for i in range(WORDS)]
        out["write"] = yield from host.mem_write(base, values)
        out["read"] = yield from host.mem_read(base, WORDS)
        out["byte"] = yield from host.mem_write(base + 5, 0xAB, size=1)
        out["word1"] = yield from host.mem_read(base + 4)
        out["values"] = values
    return run
