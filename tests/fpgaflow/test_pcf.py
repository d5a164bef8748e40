"""The pin files pin every port of ``gen/top.v`` and nothing else: ``constraints/ice40_hx8k_ct256.pcf``
(iCE40) and ``constraints/ecp5_25k_cabga256.lpf`` (ECP5, the generic build has the same ports)."""
import re
from collections import Counter

import pytest

from fpgaflow import CLOCK_PORT, ECP5, ICE40
from rtl.convert import GEN_DIR, ROOT

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
    top = GEN_DIR / "top.v"
    if not top.exists():
        pytest.skip("gen/top.v not written yet")
    ports, pinned = verilog_port_bits(top), set(ICE40.pins())
    assert ports == pinned, f"ports without a pin: {sorted(ports - pinned)}; pins without a port: {sorted(pinned - ports)}"


def sdc_port_patterns(text):
    """The names in every ``[get_ports ...]`` of an SDC file (``*`` is a wildcard)."""
    groups = re.findall(r"\[get_ports (?:\{([^}]*)\}|(\w+))\]", text)
    return [name for braced, bare in groups for name in (braced.split() if braced else [bare])]


def test_sdc_names_only_ports_of_the_top():
    top = GEN_DIR / "top.v"
    if not top.exists():
        pytest.skip("gen/top.v not written yet")
    ports = verilog_port_bits(top)
    patterns = sdc_port_patterns((ROOT / "constraints" / "pci_card.sdc").read_text())
    assert {"clock", "reset", "pci_pins_ad[*]"} <= set(patterns)
    unmatched = [p for p in patterns
                 if not any(re.fullmatch(re.escape(p).replace(r"\*", ".*"), port) for port in ports)]
    assert not unmatched, f"SDC names ports gen/top.v does not have: {unmatched}"


# ECP5 LFE5U-25F CABGA256: primary clock input balls, and the balls of banks 2 and 3
# (the right edge of the die), from the device's pinout.
ECP5_PRIMARY_CLOCK_BALLS = {"J16", "J15", "K16", "K15", "L16", "L15", "M16", "M15"}
ECP5_BANK_2_AND_3 = set(
    "B15 B16 C14 C15 C16 D14 D16 E14 E15 E16 F12 F13 F14 F15 F16 G12 G13 G14 G15 G16 H12 H13 H14 H15 J12 J13 "
    "J14 J15 J16 K14 K15 K16 K12 K13 L12 L13 L14 L15 L16 M11 M12 M13 M14 M15 M16 N11 N12 N13 N14 N16 P11 P12 "
    "P13 P14 P15 P16 R12 R13 R14 R15 R16 T13 T14 T15".split())


def test_lpf_puts_pci_on_one_bank_group_at_3v3_and_clock_on_a_primary_clock_ball():
    pins = ECP5.pins()
    shared = [ball for ball, count in Counter(pins.values()).items() if count > 1]
    assert not shared, f"balls used twice: {shared}"
    assert pins[CLOCK_PORT] in ECP5_PRIMARY_CLOCK_BALLS
    pci = {port: ball for port, ball in pins.items() if port.startswith("pci_pins_") or port == "reset"}
    assert len(pci) == sum(PCI_PINS.values()) + 1
    assert set(pci.values()) <= ECP5_BANK_2_AND_3
    io_types = dict(re.findall(r'IOBUF PORT "([^"]+)" IO_TYPE=(\w+);', ECP5.constraints.read_text()))
    assert set(io_types) == set(pins) and set(io_types.values()) == {"LVCMOS33"}


def test_lpf_matches_the_top_ports():
    top = GEN_DIR / "top.v"
    if not top.exists():
        pytest.skip("gen/top.v not written yet")
    ports, pinned = verilog_port_bits(top), set(ECP5.pins())
    assert ports == pinned, f"ports without a pin: {sorted(ports - pinned)}; pins without a port: {sorted(pinned - ports)}"


# The encoder pins a top built with encoders has beyond gen/top.v's (rtl/interfaces/card.py: MotorPins)
ENCODER_PORTS = {f"motor_enc_{pin}_{axis}" for pin in ("a", "b", "index") for axis in "xy"} | {"motor_probe"}


@pytest.mark.parametrize("family", [ICE40, ECP5], ids=["ice40", "ecp5"])
def test_a_top_with_encoders_gets_their_pins_added_on_balls_of_their_own(family, tmp_path):
    base = family.pins()
    assert family.top_constraints(set(base), tmp_path) == family.constraints
    path = family.top_constraints(set(base) | ENCODER_PORTS, tmp_path)
    pins = family.pins(path)
    assert set(pins) == set(base) | ENCODER_PORTS
    shared = [ball for ball, count in Counter(pins.values()).items() if count > 1]
    assert not shared, f"balls used twice: {shared}"


# The STEP/DIR, limit and home pins of the axes beyond X and Y (rtl/interfaces/card.py: MotorPins, axes)
AXIS_PORTS = {axis: {f"motor_{pin}_{axis}" for pin in ("step", "dir", "limit_pos", "limit_neg", "home")}
              for axis in "zabc"}


@pytest.mark.parametrize("axes", [3, 4, 6])
def test_a_top_of_more_axes_gets_their_pins_added_on_balls_of_their_own(axes, tmp_path):
    base = ECP5.pins()
    extra = set().union(*(AXIS_PORTS[axis] for axis in "zabc"[:axes - 2]))
    pins = ECP5.pins(ECP5.top_constraints(set(base) | extra, tmp_path))
    assert set(pins) == set(base) | extra
    shared = [ball for ball, count in Counter(pins.values()).items() if count > 1]
    assert not shared, f"balls used twice: {shared}"


def test_every_ecp5_pin_file_uses_balls_no_other_uses(tmp_path):
    every = set(ECP5.pins()) | ENCODER_PORTS | set().union(*AXIS_PORTS.values())
    pins = ECP5.pins(ECP5.top_constraints(every, tmp_path))
    assert set(pins) == every
    shared = [ball for ball, count in Counter(pins.values()).items() if count > 1]
    assert not shared, f"balls used twice: {shared}"
