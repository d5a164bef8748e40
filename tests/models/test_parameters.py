"""``models/parameters.py``: each range is the hardware's, stated once; the
``Build`` record made from the table is checked once, where it is made, and
passed down; ``*_ports`` factories take their widths as plain keywords."""
import dataclasses
import re
import shutil
import subprocess

import pytest
from myhdl import intbv

from models import parameters
from models.parameters import COORD_WIDTH, FIFO_DEPTH, PARAMETERS, Build, ParameterError
from rtl.card import card, card_ports
from rtl.convert import ROOT, convert_unit
from rtl.dda_arc import dda_arc, dda_arc_ports
from rtl.interfaces import DdaPort
from rtl.pci.pci_pads import pci_pads_ports
from rtl.pci_slave import pci_slave, pci_slave_ports
from rtl.regs.feed_rate import COUNT_BITS, feed_rate, feed_rate_ports
from rtl.regs.sequencer import sequencer_ports
from rtl.regs_fifo import regs_fifo_ports


def test_the_narrowest_coordinates_are_the_narrowest_the_feed_rate_takes():
    """STOP_LEFT (coord_width + 3 bits) must be wider than the ramp's 16-bit count."""
    assert COUNT_BITS == 16 and COORD_WIDTH.minimum == 14
    narrow = feed_rate_ports()
    narrow["feed"].stop_left = DdaPort(COORD_WIDTH.minimum - 1).stop_left
    with pytest.raises(ValueError, match="stop_left must be wider"):
        feed_rate(**narrow)
    feed_rate(**feed_rate_ports(COORD_WIDTH.minimum))


def _lint(path, top):
    verilator = shutil.which("verilator")
    assert verilator, "verilator not found: install it (Debian package verilator)"
    return subprocess.run([verilator, "--lint-only", "-Wall", str(path), "--top-module", top],
                          capture_output=True, text=True, timeout=600)


def test_one_bit_wider_coordinates_than_the_widest_give_verilog_verilator_refuses(tmp_path, monkeypatch):
    """The reason for COORD_WIDTH.maximum: STOP_LEFT's reset value above 32 bits."""
    wider = dataclasses.replace(COORD_WIDTH, maximum=COORD_WIDTH.maximum + 1)
    monkeypatch.setattr(parameters, "COORD_WIDTH", wider)  # the DDA reads its limit from the table
    widest = _lint(convert_unit("dda_arc", {"coord_width": COORD_WIDTH.maximum}, tmp_path / "widest"), "dda_arc")
    assert widest.returncode == 0, widest.stderr
    beyond = dda_arc(**dda_arc_ports(COORD_WIDTH.maximum + 1))
    beyond.convert(hdl="Verilog", path=str(tmp_path), name="dda_arc")
    result = _lint(tmp_path / "dda_arc.v", "dda_arc")
    # the all-ones reset value of STOP_LEFT's count (dda_left's larger), 2**33 - 1
    assert result.returncode != 0 and "Too many digits" in result.stderr and str((1 << 33) - 1) in result.stderr


def test_the_fifo_depth_fills_status_fifo_level_at_the_top_of_its_range():
    from models import registers as regmap

    level_bits = regmap.register("STATUS").field("FIFO_LEVEL").width
    assert FIFO_DEPTH.maximum + 1 <= 1 << level_bits < 2 * FIFO_DEPTH.maximum + 1


@pytest.mark.parametrize("name", sorted(p.name for p in PARAMETERS.values() if p.choices is None))
def test_integer_bounds_are_taken_and_their_neighbours_refused(name):
    parameter = PARAMETERS[name]
    assert parameter.check(parameter.minimum) == parameter.minimum
    assert parameter.check(parameter.maximum) == parameter.maximum
    for value in (parameter.minimum - 1, parameter.maximum + 1, True, "1", 1.0):
        with pytest.raises(ParameterError, match=name):
            parameter.check(value)


def test_device_limit_applies_to_its_device_only():
    assert FIFO_DEPTH.check(32768, "generic") == 32768
    assert FIFO_DEPTH.check(4096, "ice40") == 4096
    with pytest.raises(ParameterError, match="ice40"):
        FIFO_DEPTH.check(8192, "ice40")
    # ECP5 LFE5U-25F: 56 EBRs of 512 x 36 bits hold 28,672 words; the next power of two down is 16,384
    assert FIFO_DEPTH.check(16384, "ecp5") == 16384
    with pytest.raises(ParameterError, match="ecp5"):
        FIFO_DEPTH.check(32768, "ecp5")


def test_every_default_is_within_its_range():
    for parameter in PARAMETERS.values():
        parameter.check(parameter.default)
        for device in parameters.DEVICES:
            parameter.check(parameter.default, device)


def test_no_default_is_restated_in_rtl():
    """Every default of an integer parameter lives in models/parameters.py only."""
    sources = list((ROOT / "rtl").rglob("*.py"))
    for parameter in PARAMETERS.values():
        if parameter.choices is not None:
            continue
        pattern = re.compile(rf"\b{parameter.name}\s*=\s*({parameter.default}|0x0*{parameter.default:x}|"
                             rf"0x0*{parameter.default:X})\b")
        for path in sources:
            assert not pattern.search(path.read_text()), f"{path.name} restates {parameter.name}'s default"


@pytest.mark.parametrize("width", [COORD_WIDTH.minimum, 20])
def test_ports_factories_follow_the_coordinate_width(width):
    for ports in (dda_arc_ports(width), regs_fifo_ports(coord_width=width), sequencer_ports(width)):
        port = ports["dda"] if "dda" in ports else ports["cmd"]
        assert port.coord_width == width and len(port.xs) == width
    assert len(feed_rate_ports(width)["feed"].stop_left) == width + 3


def test_dda_takes_its_width_from_its_port(tmp_path):
    path = convert_unit("dda_arc", {"coord_width": 17}, tmp_path)
    text = path.read_text()
    assert "input signed [16:0] cmd_xs;" in text
    # accumulators: coord_width + 6 bits (improved); the instance prefix varies
    assert re.search(r"reg signed \[22:0\] dda_run\w*_acc_x;", text)


def test_pad_ports_factory_checks_its_build():
    with pytest.raises(ValueError, match="io_registers"):
        pci_pads_ports(io_registers=1)


def test_the_build_record_holds_the_documented_defaults():
    """docs/parameters: 512 words, 24 bits, 33.33 MHz, generic Verilog; the top for iCE40."""
    build = Build()
    assert (build.fifo_depth, build.coord_width, build.clock_hz, build.device) == (512, 24, 33_333_333, "generic")
    assert (build.variants, build.vendor_id, build.device_id) == ("improved,precise", 0x1234, 0xDDA0)
    assert Build.for_unit("top") == build.replace(device="ice40")
    assert [field.name for field in dataclasses.fields(Build)] == list(PARAMETERS)


@pytest.mark.parametrize("values, message", [
    (dict(fifo_depth=3), "fifo_depth must be a power of two, 4..32,768 (4: the FIFO promises the PCI target "
     "three free places (LocalBus.room) before it acknowledges a posted dword; STATUS.FIFO_LEVEL, 16 bits, "
     "counts 0..depth), not 3"),
    (dict(device="ice40", fifo_depth=8192), "fifo_depth must be at most 4,096 for ice40 (the iCE40 HX8K has "
     "32 block RAMs of 4 Kbit, 4,096 32-bit words in all), not 8,192"),
    (dict(clock_hz=0), "clock_hz must be 1..33,333,333 (PCI 2.3 clocks a device that does not claim 66 MHz "
     "at up to 33.33 MHz), not 0"),
    (dict(variants="weighted"), "variants must be improved,precise or all, not 'weighted'"),
    (dict(device="xc7"), "device must be generic, ice40 or ecp5, not 'xc7'"),
    (dict(vendor_id=0xFFFF), "vendor_id must be 0x0000..0xFFFE (0xFFFF reads as no device), not 0xFFFF"),
])
def test_a_bad_value_is_refused_where_the_build_is_made_with_the_tables_message(values, message):
    with pytest.raises(ParameterError) as made:
        Build(**values)
    with pytest.raises(ParameterError) as replaced:
        Build().replace(**values)
    assert str(made.value) == str(replaced.value) == message


def test_an_unknown_parameter_is_refused_by_name():
    with pytest.raises(ParameterError, match=r"unknown build parameters \['bar_bits'\]"):
        Build().replace(bar_bits=6)
    with pytest.raises(ParameterError, match=r"unknown build parameters \['depth'\]"):
        Build.for_unit("top", depth=64)


# made (and checked) here, before any test counts the checks
PASSED_DOWN = Build(fifo_depth=64, coord_width=18, variants="all", vendor_id=0x10EE, io_bar_bits=4, mem_bar_bits=8)


@pytest.fixture
def checks(monkeypatch):
    """Every ``parameters.check`` call from here on: the values it was given."""
    checked, check = [], parameters.check
    monkeypatch.setattr(parameters, "check",
                        lambda values, device=None: checked.append(values) or check(values, device))
    return checked


def test_the_target_checks_the_build_it_receives_no_more(checks):
    pci_slave(**pci_slave_ports(4, 8), build=PASSED_DOWN)
    assert checks == []


@pytest.mark.slow(reason="elaborates the whole card (20 s); the target's part runs in the default suite")
def test_a_build_passed_down_the_card_is_checked_once_where_it_is_made(checks):
    """The card's blocks check nothing again; the one record made on the way is
    the target's, with the card's BAR sizes in it (``slave_build``)."""
    card(**card_ports(), build=PASSED_DOWN)
    # docs/registers.md: BAR0 of 256 bytes; the 4 KiB FIFO window (not the stand-alone target's BARs)
    assert checks == [dict(PASSED_DOWN.as_dict(), io_bar_bits=8, mem_bar_bits=12)]


@pytest.mark.parametrize("factory, params, message", [
    (regs_fifo_ports, dict(coord_width=13), "coord_width"),
    (pci_slave_ports, dict(io_bar_bits=9), "io_bar_bits"),
    (pci_slave_ports, dict(mem_bar_bits=3), "mem_bar_bits"),
])
def test_ports_factories_check_the_widths_they_take(factory, params, message):
    with pytest.raises(ValueError, match=message):
        factory(**params)


def test_ports_factories_refuse_what_the_interface_refuses():
    with pytest.raises(ValueError, match="coord_width"):
        dda_arc_ports(COORD_WIDTH.maximum + 1)
    with pytest.raises(ValueError, match="coord_width"):
        DdaPort(intbv(24))
