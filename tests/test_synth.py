"""The card routes on iCE40 HX8K (ct256) and meets PCI's 33 MHz (``bench/synth.py``).

Synthesises ``top`` once it is in ``gen/``, else every unit there.  PCI pins of
the top must also fit PCI 33's budgets: 7 ns from pin to register, 11 ns from
clock to pin, with the pad and clock-buffer delays nextpnr leaves out added
from the data sheet (``bench/synth.py`` ``at_the_pins``).
"""
import sys

import pytest

from sim.paths import ROOT

sys.path.insert(0, str(ROOT / "bench"))
import synth  # noqa: E402

# In the default run: the top places and routes in about 90 s on a 2-core
# machine (plus 1-2 minutes once, while yowasp compiles its WebAssembly).
pytestmark = pytest.mark.synth
TOOL_TIMEOUT_S = 900

UNITS = synth.available_units()


@pytest.fixture(scope="module", params=UNITS)
def figures(request):
    return synth.synthesize(request.param, timeout=TOOL_TIMEOUT_S)


def test_routes_and_meets_the_pci_clock(figures):
    if not figures["placed"]:
        pytest.skip(f"{figures['unit']} has more port bits than the package has pins: packed only")
    assert figures["lcs"] <= 7680
    assert figures["meets"], (f"{figures['unit']}: fmax {figures['fmax_mhz']} MHz "
                              f"< {synth.PCI_MHZ} MHz; {figures['critical']}")


def test_pci_pins_meet_pci33_budgets(figures):
    if figures["unit"] != "top":
        pytest.skip("pin budgets apply to the card's pins (gen/top.v)")
    budgets = {"in": synth.PCI33_SETUP_NS, "out": synth.PCI33_CLOCK_TO_OUT_NS,
               "oe": synth.PCI33_CLOCK_TO_OUT_NS}
    late = [f"{pin} {key} {synth.at_the_pins(key, entry[key])} ns"
            for pin, entry in figures["pins"].items() if pin.startswith("pci_")
            for key in budgets
            if entry[key] is not None and synth.at_the_pins(key, entry[key]) > budgets[key]]
    assert not late, "PCI 33 budget missed at the balls: " + "; ".join(late)
