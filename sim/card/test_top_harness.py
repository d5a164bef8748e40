"""``sim/card/top_harness.py``: how the harness reads the top level's PCI pins.

Expected classes come from the pad ring's description (``rtl/pci/pci_pads.py``
with I/O registers): AD, PAR, TRDY#, DEVSEL#, STOP#, PERR# leave through
SB_IO cells, SERR# and INTA# through plain open-drain buffers the card never
reads, C/BE# (SB_IO input registers), FRAME#, IRDY# are inputs.  The harness's end-to-end behaviour
is checked in ``sim/card/test_card_e2e.py`` (clock for clock against the
split-port card).
"""
import pytest

from sim.backends.icarus import CosimError
from sim.card.top_harness import TopHarness, generated_top
from sim.pci.bus import LINE_WIDTHS

IDSEL_BIT = 16


def test_lines_of_the_generated_top():
    harness = TopHarness(generated_top(), IDSEL_BIT)
    assert harness.private == ["serr", "inta"]
    assert harness.shared == ["ad", "cbe", "par", "frame", "irdy", "trdy", "devsel", "stop", "perr"]
    assert harness.driven == ["ad", "par", "trdy", "devsel", "stop", "perr", "serr", "inta"]
    assert harness.card.lines == tuple(harness.driven)
    text = harness.verilog()
    assert "tri1 bus_frame;" in text and "tri [31:0] bus_ad;" in text  # pull-ups; AD floats
    assert "tri0 [31:0] bus_ad;" in TopHarness(generated_top(), IDSEL_BIT, floating=False).verilog()
    assert f"wire bus_idsel = bus_ad[{IDSEL_BIT}];" in text
    assert all(f"dut.pad_ad_{bit}.OUTPUT_ENABLE" in text for bit in range(32))


def _fake_top(tmp_path, serr_code):
    """A top with every PCI pin, SERR# as given, the rest through nothing."""
    ports = ["clock", "reset"] + [f"pci_pins_{line}" for line in [*LINE_WIDTHS, "idsel"]]
    declarations = ["input clock;", "input reset;"]
    for line, width in [*LINE_WIDTHS.items(), ("idsel", 1)]:
        bits = f"[{width - 1}:0] " if width > 1 else ""
        direction = "input" if line in ("cbe", "frame", "irdy") else "inout"
        declarations.append(f"{direction} {bits}pci_pins_{line};")
    path = tmp_path / "top.v"
    path.write_text(f"module top ({', '.join(ports)});\n" + "\n".join(declarations)
                    + f"\nreg q;\n{serr_code}\nendmodule\n")
    return path


def test_a_plain_pin_is_split_only_while_the_card_does_not_read_it(tmp_path):
    driver = "assign pci_pins_serr = q ? 1'b0 : 1'bz;\n"
    assert "serr" in TopHarness(_fake_top(tmp_path, driver), IDSEL_BIT).private
    read_back = _fake_top(tmp_path, driver + "always @(posedge clock) q <= pci_pins_serr;")
    with pytest.raises(CosimError, match="cannot tell the card's own drive of pci_pins_serr"):
        TopHarness(read_back, IDSEL_BIT)


def test_refuses_a_top_with_other_ports(tmp_path):
    path = _fake_top(tmp_path, "")
    path.write_text(path.read_text().replace("input clock;", "input clock;\ninput spare;"))
    with pytest.raises(CosimError, match="spare"):
        TopHarness(path, IDSEL_BIT)
