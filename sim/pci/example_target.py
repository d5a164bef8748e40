"""The example PCI targets of docs/verification.md on the bench.

``docs/example/scratch_target.v`` was written apart from the card, in the
style third-party sources have (tri-state ports in ANSI style, parameters
in port ranges, a Latin-1 byte in a comment, an include folder, a define):
its wiring for ``PciBench`` and the scenario that enumerates it and moves a
burst each way, used by its test and by ``bench/vip_figures.py``.

``docs/example/split_core.v`` has split ports with one output enable per
bit; ``body_ports_top.v`` puts it behind ports declared in the module body
(with functions and a task that have inputs of their own);
``two_clock_top.v`` gives it a back end in a second clock domain, clocked
from the wrapper, with two outputs for the bench to watch.  Their wiring
and a scenario that enumerates one and writes and reads its four dwords."""
from rtl.convert import ROOT
from sim.pci.verilog_target import VerilogTarget

EXAMPLE = ROOT / "docs" / "example"
PINS = {"ad": "ad", "cbe": "cbe_n", "par": "par", "frame": "frame_n", "irdy": "irdy_n",
        "trdy": "trdy_n", "devsel": "devsel_n", "stop": "stop_n"}
VENDOR, DEVICE, CLASS = 0x1234, 0x5C7A, 0x058000
WORDS = 16   # the example's memory BAR, in dwords

SPLIT_VENDOR, SPLIT_DEVICE = 0x1234, 0x5107
SPLIT_WORDS = 4   # split_core's memory BAR, in dwords
CONTROL_PINS = {"frame": ("frame_n", None, None), "irdy": ("irdy_n", None, None)}
SPLIT_PINS = {"ad": ("ad_in", "ad_out", "ad_oe"), "cbe": ("cbe_in", "cbe_out", "cbe_oe"),
              "par": ("par_in", "par_out", "par_oe"), **CONTROL_PINS,
              **{line: (None, f"{line}_n", "ctl_oe") for line in ("trdy", "devsel", "stop")}}
BODY_PINS = {"ad": ("ad_in", "ad_out", "ad_en"), "cbe": ("cbe_in", None, None),
             "par": ("par_in", "par_out", "par_en"), **CONTROL_PINS,
             **{line: (None, f"{line}_n", "ctl_en") for line in ("trdy", "devsel", "stop")}}
TWO_CLOCK_PINS = dict(SPLIT_PINS, cbe=("cbe_in", None, None))


def scratch_target(defines=()):
    """The example as a ``PciBench`` target; ``defines`` e.g. ``["X_ON_RETRY"]``."""
    return VerilogTarget(files=[EXAMPLE / "scratch_target.v"], top="scratch_target", pins=PINS,
                         clock="clk", reset="rst_n", idsel="idsel", include_dirs=[EXAMPLE],
                         defines=defines)


def split_target(top="split_core", defines=(), outputs=()):
    """``split_core`` (per-bit enables) or one of its wrappers
    (``body_ports_top``, ``two_clock_top``) as a ``PciBench`` target."""
    pins = {"split_core": SPLIT_PINS, "body_ports_top": BODY_PINS, "two_clock_top": TWO_CLOCK_PINS}[top]
    files = [EXAMPLE / "split_core.v"] + ([] if top == "split_core" else [EXAMPLE / f"{top}.v"])
    return VerilogTarget(files=files, top=top, pins=pins, clock="clk", reset="rst_n", idsel="idsel",
                         defines=defines, outputs=list(outputs))


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


def split_scenario(out, values=(0x0BAD_F00D, 0x1234_5678, 0x8000_0001, 0xFFFF_FFFF)):
    """Enumerate ``split_core`` (or a wrapper), write ``values`` into its
    dwords in one burst (disconnected after every dword) and read them
    back; the results go into the dict ``out``."""
    def run(bench):
        host = bench.host
        (device,) = yield from host.enumerate_bus(devices=[0])
        out["device"] = device
        base = device.bars[0]["base"]
        out["write"] = yield from host.mem_write(base, list(values))
        out["read"] = yield from host.mem_read(base, len(values))
        out["values"] = list(values)
    return run
