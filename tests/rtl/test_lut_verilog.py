"""The simulation model of the PCI target's pin LUTs (``rtl.pci.pin_lut.lut_verilog``,
every device) in Icarus: with an input floating (Z) or X, the output is X only where the
function depends on that input; elsewhere it is the function's value.  The
expected values come from the Python function itself, evaluated for both
values of the floating input."""
import itertools
import random
import shutil
import subprocess

import pytest

from rtl.pci.pin_lut import lut_verilog

NAMES = ["i0", "i1", "i2", "i3"]


def simulate(tmp_path, inputs, function, cases, device):
    """Output of the LUT (as Icarus prints it: 0, 1, x) for each case (a
    tuple of '0', '1', 'x', 'z' per input)."""
    lines = lut_verilog("o", "probe", inputs, function, device=device)
    stimulus = []
    for case in cases:
        stimulus += [f"{net} = 1'b{value};" for net, value in zip(inputs, case)]
        stimulus += ["#1;", '$display("%b", o);']
    source = tmp_path / "lut.v"
    source.write_text("module t;\n" + "".join(f"reg {net};\n" for net in inputs) + "wire o;\n"
                      + "\n".join(lines) + "\ninitial begin\n" + "\n".join(stimulus)
                      + "\nend\nendmodule\n")
    image = tmp_path / "lut.vvp"
    subprocess.run(["iverilog", "-o", str(image), str(source)], check=True)
    run = subprocess.run(["vvp", "-n", str(image)], check=True, capture_output=True, text=True)
    return [line.strip() for line in run.stdout.splitlines() if line.strip()]


def expected(function, case):
    """'0'/'1' if every value of the unknown inputs gives the same output, else 'x'."""
    unknown = [i for i, value in enumerate(case) if value in "xz"]
    outputs = set()
    for values in itertools.product((0, 1), repeat=len(unknown)):
        bits = [int(v) if v in "01" else 0 for v in case]
        for index, value in zip(unknown, values):
            bits[index] = value
        outputs.add(function(*bits))
    return str(outputs.pop()) if len(outputs) == 1 else "x"


@pytest.mark.skipif(shutil.which("iverilog") is None, reason="needs Icarus Verilog")
@pytest.mark.parametrize("device", ["generic", "ice40", "ecp5"])
@pytest.mark.parametrize("count, seed", [(1, 1), (2, 2), (3, 3), (4, 4), (4, 5), (4, 6)])
def test_an_input_the_output_does_not_depend_on_cannot_make_it_x(tmp_path, count, seed, device):
    rng = random.Random(seed)
    table = rng.getrandbits(1 << count)

    def function(*bits):
        return table >> sum(bit << k for k, bit in enumerate(bits)) & 1

    cases = list(itertools.product("01xz", repeat=count))
    seen = simulate(tmp_path, NAMES[:count], function, cases, device)
    assert seen == [expected(function, case) for case in cases]
