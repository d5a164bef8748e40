"""The capability registers over PCI: a host reads what the card was built with.

Cards built with chosen parameters, as MyHDL (``rtl/card.py``), as their
generated ``card.v`` and as the iCE40 top (``top.v`` with its pads) in
Icarus, the ``ecp5`` build's ``card.v`` with its ``LUT4`` cells (``SYNTHESIS``
defined, yosys's cell model: the card as synthesised behaves as the generic
one), and the committed default build in ``gen/``: the host enumerates
the card, reads ID, CLOCK_HZ, FIFO_SIZE and BUILD over I/O, then runs a
LINE through the FIFO (the smallest build's FIFO of two words is shorter
than the command) and reads the position back.  The chosen card and the
smallest are built with more axes than two (BUILD.AXES; X and Y move as on
the two-axis card).  The expected words are
written out here from the build parameters and the documented encodings
(docs/registers.md), not taken from the register table's reset values.
"""
import pytest

from models import instructions as isa
from models import registers as regmap
from models.parameters import Build
from rtl.card import card, card_ports
from rtl.convert import GEN_DIR, convert_unit
from rtl.interfaces import MotorPins
from sim.backends.icarus import cosimulate
from sim.card.top_harness import TopHarness, convert_top, ecp5_lut_model, top_on_bus
from sim.pci.bench import TARGET_DEVICE, PciBench

DEVICE = 0
DEFAULT = dict(clock_hz=33_333_333, fifo_depth=512, coord_width=24, variants="improved,precise")
CHOSEN = dict(clock_hz=25_000_000, fifo_depth=16, coord_width=20, variants="all")
SMALLEST = dict(clock_hz=1, fifo_depth=4, coord_width=14, variants="improved,precise", axes=6)
CHOSEN_AXES = dict(CHOSEN, axes=3)
MOVE = (5, -3)
VARIANT_BITS = {"improved,precise": 0b1100, "all": 0b1111}   # bit n: ARC.VARIANT n
DEVICE_CODES = {"generic": 0, "ice40": 1, "ecp5": 2}


def expected_words(build, device):
    """ID, CLOCK_HZ, FIFO_SIZE and BUILD as docs/registers.md defines them."""
    return {"ID": 0xDDAC << 16 | 0x0300,   # ID.VERSION 3.0
            "CLOCK_HZ": build["clock_hz"],
            "FIFO_SIZE": build["fifo_depth"],
            "BUILD": (build["coord_width"] | build.get("axes", 2) << 8 | VARIANT_BITS[build["variants"]] << 16
                      | DEVICE_CODES[device] << 24)}


def card_under_test(kind, build, device, tmp_path):
    """A PciBench target function for ``kind``: "myhdl", "card.v", "top.v"
    (converted for ``build``), "gen/card.v" or "gen/top.v"."""
    params = dict(build, device=device)

    def target(bench):
        if kind.endswith("top.v"):
            verilog = GEN_DIR / "top.v" if kind.startswith("gen/") else convert_top(**params)
            harness = TopHarness(verilog, idsel_bit=16 + TARGET_DEVICE)
            return harness.card, [(top_on_bus, (bench.clock, bench.reset, bench.host.agent, harness,
                                                MotorPins()))]
        ports = card_ports(build.get("axes", 2))
        ports["clock"], ports["reset"] = bench.clock, bench.reset
        if kind == "myhdl":
            return ports["pci"], [(card, (), dict(ports, build=Build(**params)))]
        verilog = GEN_DIR / "card.v" if kind.startswith("gen/") else convert_unit("card", params, tmp_path)
        # the ecp5 build's LUT4 branch (not its plain-Verilog one) with yosys's model of the cell
        cells = dict(libraries=[ecp5_lut_model()], defines=["SYNTHESIS"]) if device == "ecp5" else {}
        return ports["pci"], [(cosimulate("card", ports, [verilog], **cells), None)]

    return target


def read_build(kind, build, device, tmp_path):
    out = {}

    def scenario(b):
        found = yield from b.host.enumerate_bus(devices=[DEVICE])
        bars = {"io": found[0].bar(0)["base"], "mem": found[0].bar(1)["base"]}
        for name in ("ID", "CLOCK_HZ", "FIFO_SIZE", "BUILD"):
            result = yield from b.host.io_read(bars["io"] + regmap.offset(name))
            assert result.complete, f"{name}: {result.termination}"
            out[name] = result.value
        for name, value in (("FEED_RATE", regmap.RATE_MAX), ("CONTROL", 1)):
            result = yield from b.host.io_write(bars["io"] + regmap.offset(name), value)
            assert result.complete, f"{name}: {result.termination}"
        burst = yield from b.host.mem_write(bars["mem"], isa.encode("LINE", *MOVE))
        assert burst.complete, burst.termination
        for _ in range(200):
            status = (yield from b.host.io_read(bars["io"] + regmap.offset("STATUS"))).value
            if not regmap.field_value("STATUS", "BUSY", status):
                break
        out["STATUS"] = status
        out["position"] = []
        for name in ("POS_X", "POS_Y"):
            word = (yield from b.host.io_read(bars["io"] + regmap.offset(name))).value
            out["position"].append(regmap.field_value(name, "STEPS", word))

    PciBench(target=card_under_test(kind, build, device, tmp_path)).run(
        scenario, f"card_build_{kind.replace('/', '_').replace('.', '_')}_{device}", trace=False)
    return out


@pytest.mark.parametrize("kind, build, device", [
    pytest.param("myhdl", CHOSEN_AXES, "ice40", id="myhdl-chosen", marks=pytest.mark.slow(
        reason="the chosen build runs as card.v by default; MyHDL reads the smallest one")),
    pytest.param("myhdl", SMALLEST, "generic", id="myhdl-smallest"),
    pytest.param("card.v", CHOSEN_AXES, "generic", id="card_v-chosen"),
    pytest.param("card.v", CHOSEN_AXES, "ecp5", id="card_v-chosen-ecp5_cells"),
    pytest.param("top.v", CHOSEN, "ice40", id="top_v-chosen", marks=pytest.mark.slow(
        reason="another conversion of the chosen build; gen/top.v covers the top's path by default")),
    pytest.param("gen/card.v", DEFAULT, "generic", id="gen-card_v"),
    pytest.param("gen/top.v", DEFAULT, "ice40", id="gen-top_v"),
])
def test_capability_registers_read_back_the_build(kind, build, device, tmp_path):
    words = read_build(kind, build, device, tmp_path)
    for name, word in expected_words(build, device).items():
        assert words[name] == word, f"{name}: {words[name]:#010x}, built {word:#010x}"
    assert regmap.field_value("STATUS", "BUSY", words["STATUS"]) == 0
    assert regmap.field_value("STATUS", "ERROR", words["STATUS"]) == 0
    assert words["position"] == list(MOVE)
