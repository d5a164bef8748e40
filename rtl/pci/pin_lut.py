"""One LUT from a PCI pin to a register, for the PCI target's fast paths.

``lut_verilog`` writes a function of up to four nets as Verilog:

- ``generic``: one continuous assignment, a nested ``? :`` over the inputs;
- ``ice40``: an ``SB_LUT4`` cell (``rtl/ice40.py``) under ``ifdef SYNTHESIS``,
  so that synthesis merges no logic into it and a pin among the inputs stays
  one logic cell from its register; the same nested ``? :`` for simulators;
- ``ecp5``: the same with an ECP5 ``LUT4`` cell (``rtl/ecp5.py``, ``in0`` on
  A, its fastest input).

The nested ``? :`` tests the inputs from the last to the first (``in0``,
the pin, innermost) and leaves out every input the function does not
depend on under the inputs tested before it.  Verilog merges the two
branches of a ``? :`` whose condition is X or Z bit by bit, so an input
that floats (as AD, C/BE# and PAR do between transactions) makes the
output X only when the output really depends on it, and never Z.
"""
from myhdl import block, instance

from models.parameters import DEVICE
from rtl.ecp5 import lut4
from rtl.ice40 import sb_lut4

ZERO, ONE = "1'b0", "1'b1"
_CELLS = {"generic": None, "ice40": sb_lut4, "ecp5": lut4}  # the device's LUT cell writer (None: plain logic)


def lut_table(function, inputs):
    """Truth table of ``function`` (of ``inputs`` bits, 0/1) as an integer:
    bit n is the value for the inputs' bits n[0], n[1], ... (LUT order)."""
    return sum(function(*(n >> k & 1 for k in range(inputs))) << n for n in range(1 << inputs))


def lut_expression(inputs, function):
    """``function`` of the nets ``inputs`` (0/1 each, first input first) as
    a Verilog expression: nested ``? :``, the last input outermost."""

    def expand(level, bits):
        # ``bits``: values of inputs[level:], already decided by the outer tests
        if level == 0:
            return ONE if function(*bits) else ZERO
        net = inputs[level - 1]
        high, low = expand(level - 1, (1, *bits)), expand(level - 1, (0, *bits))
        if high == low:
            return high
        return f"({net} ? {high} : {low})"  # a bare input would pass a Z on: a LUT drives 0, 1 or X

    return expand(len(inputs), ())


def lut_verilog(out, name, inputs, function, *, device):
    """Verilog lines driving ``out`` by ``function`` of ``inputs`` (1..4 net
    names) for ``device``; ``name`` names the LUT cell."""
    if not 1 <= len(inputs) <= 4:
        raise ValueError(f"{name}: a LUT takes 1 to 4 inputs, not {len(inputs)}")
    logic = f"assign {out} = {lut_expression(inputs, function)};"
    cell = _CELLS[DEVICE.check(device)]
    if cell is None:
        return [logic]
    init = lut_table(lambda *bits: function(*bits[:len(inputs)]), 4)   # unused inputs tied to 0
    return ["`ifdef SYNTHESIS", cell(out, name, inputs, init), "`else", logic, "`endif"]


@block
def pin_lut(out, function, in0, in1, in2=None, in3=None, *, device):
    """``out`` = ``function`` of the inputs (0/1 each, ``in0`` first) in one
    LUT (``lut_verilog``): for registers whose next value depends on a PCI
    pin, which goes in ``in0``.  Parameter: ``device`` (``models/parameters.py``).

        in0..in3  --< A >< B >--
        out       --< f(A) >< f(B) >--
    """
    inputs = tuple(sig for sig in (in0, in1, in2, in3) if sig is not None)

    @instance
    def follow():   # combinational: at the start and on every input change
        while True:
            out.next = bool(function(*(int(sig) for sig in inputs)))
            yield inputs

    out.driven = "wire"
    names = [f"$in{k}" for k in range(len(inputs))]
    pin_lut.verilog_code = "\n".join(lut_verilog("$out", "${out}_lut", names, function, device=device)) + "\n"
    return follow
