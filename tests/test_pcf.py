"""``constraints/ice40_hx8k_ct256.pcf`` pins every port of ``gen/top.v`` and nothing else."""
import re
from collections import Counter

import pytest

from fpgaflow import CLOCK_PORT, ICE40
from sim.paths import GEN, ROOT

# Balls measured to reach a global buffer directly (nextpnr accepts SB_GB_IO there).
GLOBAL_BUFFER_BALLS = {"J3", "G1", "C8", "F7", "R9"}
PCI_PINS = {"ad": 32, "cbe": 4, "par": 1, "frame": 1, "irdy": 1, "trdy": 1, "devsel": 1,
            "stop": 1, "idsel": 1, "perr": 1, "serr": 1, "inta": 1}

_PORT = re.compile(r"^\s*(input|output|inout)\s+(?:wire\s+|reg\s+)?(?:signed\s+)?(?:\[(\d+):(\d+)\]\s*)?(\w+)\s*;",
                   re.MULTILINE)


def verilog_port_bits(path):
    bits = set()
    for _, high, low, name in _PORT.findall(path.read_text()):
        if high:
            bits |= {f"{name}[{i}]" for i in range(int(low), int(high) + 1)}
        else:
            bits.add(name)
    return bits


def test_balls_are_distinct_and_clock_is_on_a_global_buffer_ball():
    pins = ICE40.pins()
    shared = [ball for ball, count in Counter(pins.values()).items() if count > 1]
    assert not shared, f"balls used twice: {shared}"
    assert pins[CLOCK_PORT] in GLOBAL_BUFFER_BALLS


def test_every_pci_signal_has_a_pin():
    pins = ICE40.pins()
    for name, width in PCI_PINS.items():
        expected = {f"pci_pins_{name}[{i}]" for i in range(width)} if width > 1 else {f"pci_pins_{name}"}
        assert expected <= set(pins), f"PCI {name} not fully pinned"
    assert "reset" in pins


def test_pcf_matches_the_top_ports():
    top = GEN / "top.v"
    if not top.exists():
        pytest.skip("gen/top.v not written yet")
    ports, pinned = verilog_port_bits(top), set(ICE40.pins())
    assert ports == pinned, f"ports without a pin: {sorted(ports - pinned)}; pins without a port: {sorted(pinned - ports)}"


def sdc_port_patterns(text):
    """The names in every ``[get_ports ...]`` of an SDC file (``*`` is a wildcard)."""
    groups = re.findall(r"\[get_ports (?:\{([^}]*)\}|(\w+))\]", text)
    return [name for braced, bare in groups for name in (braced.split() if braced else [bare])]


def test_sdc_names_only_ports_of_the_top():
    top = GEN / "top.v"
    if not top.exists():
        pytest.skip("gen/top.v not written yet")
    ports = verilog_port_bits(top)
    patterns = sdc_port_patterns((ROOT / "constraints" / "pci_card.sdc").read_text())
    assert {"clock", "reset", "pci_pins_ad[*]"} <= set(patterns)
    unmatched = [p for p in patterns
                 if not any(re.fullmatch(re.escape(p).replace(r"\*", ".*"), port) for port in ports)]
    assert not unmatched, f"SDC names ports gen/top.v does not have: {unmatched}"
