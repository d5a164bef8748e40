"""One LUT after FRAME# and IRDY#: choosing a register's next value by the pins.

The PCI target (``rtl/pci_slave.py``) computes, from registers only, what
each of its fast registers should take for each case of the two pins, and
lets the pins choose in one LUT level (PCI leaves 7 ns of set-up, no room for
more).  Each bit of the next value has three candidates: F (IRDY#
deasserted, so FRAME# is asserted), I (IRDY# asserted, FRAME# deasserted:
the last data phase) and B (both asserted); FRAME# and IRDY# both
deasserted only happens idle or ending, where the three are equal.  A
4-input LUT takes the two pins and two encoded values x, y, so a coding maps
(F, I, B) to (x, y) and back; it fits a bit if that bit's triples are among
the four it can tell apart.  The LUTs are written for the build's device by
``rtl/pci/pin_lut.py``.
"""
from myhdl import always_comb, block

from rtl.pci.pin_lut import lut_verilog

# coding: (x from F, I, B; y from F, I, B; out from FRAME#, IRDY#, x, y;
# x and y in Verilog, {f}, {i}, {b} standing for the bits).
PIN_CODINGS = {
    "stop": ((lambda f, i, b: f), (lambda f, i, b: b if f else i),
             (lambda frame, irdy, x, y: x | y if frame else (x if irdy else x & y)),
             ("{f}", "{f} ? {b} : {i}")),
    "trdy": ((lambda f, i, b: f ^ i), (lambda f, i, b: b if f ^ i else f),
             (lambda frame, irdy, x, y: x | y if frame else ((1 - x) & y if irdy else y)),
             ("{f} ^ {i}", "({f} ^ {i}) ? {b} : {f}")),
    "hold": ((lambda f, i, b: f), (lambda f, i, b: b ^ i),
             (lambda frame, irdy, x, y: x & (1 - y) if frame else (x if irdy else x | y)),
             ("{f}", "{b} ^ {i}")),
}


def pin_coding(triples):
    """Name of the first coding in ``PIN_CODINGS`` that gives back every
    (F, I, B) of ``triples`` for its pin case; ValueError if none does."""
    for name, (to_x, to_y, pick, _) in PIN_CODINGS.items():
        if all(pick(0, 1, to_x(*t), to_y(*t)) == t[0] and pick(1, 0, to_x(*t), to_y(*t)) == t[1]
               and pick(0, 0, to_x(*t), to_y(*t)) == t[2] for t in triples):
            return name
    raise ValueError(f"pin_pick: no one-LUT coding for the pin cases {sorted(triples)}")



@block
def pin_pick(frame_pin, irdy_pin, if_frame, if_irdy, if_both, picked, codings, *, device):
    """``picked`` is ``if_frame``, ``if_irdy`` or ``if_both`` as the FRAME#
    and IRDY# pins (bus polarity) say (IRDY# deasserted: ``if_frame``), one
    LUT per bit after the pins: each bit's candidates are coded into two
    nets by ``codings`` (a ``PIN_CODINGS`` name per bit, LSB first), the
    LUT written for ``device`` (``rtl/pci/pin_lut.py``).  Works on bools and on
    an enum (the state machine's).

        pins     --< sampled at edge k >--
        picked   --< value the register takes at k >--
    """
    width = len(codings)
    if width > 1:
        states = if_frame.val._type
        items = {int(getattr(states, name)._val, 2): getattr(states, name) for name in states._names}

    def code_of(value):
        return int(bool(value)) if width == 1 else int(value.val._val, 2)

    @always_comb
    def choose():
        f, i, b = code_of(if_frame), code_of(if_irdy), code_of(if_both)
        out = 0
        for bit, name in enumerate(codings):
            to_x, to_y, pick, _ = PIN_CODINGS[name]
            fib = (f >> bit & 1, i >> bit & 1, b >> bit & 1)
            out |= pick(int(frame_pin), int(irdy_pin), to_x(*fib), to_y(*fib)) << bit
        picked.next = bool(out) if width == 1 else items[out]

    picked.driven = "wire"
    lines = []
    for bit, name in enumerate(codings):
        sel = f"[{bit}]" if width > 1 else ""
        pick, (x_text, y_text) = PIN_CODINGS[name][2:]
        names = dict(f=f"$if_frame{sel}", i=f"$if_irdy{sel}", b=f"$if_both{sel}")
        x, y = f"${{picked}}_x{bit}", f"${{picked}}_y{bit}"
        lines += [f"wire {x} = {x_text.format(**names)};",
                  f"wire {y} = {y_text.format(**names)};",
                  *lut_verilog(f"$picked{sel}", f"${{picked}}_lut{bit}",
                               [x, y, "$frame_pin", "$irdy_pin"],
                               lambda x_bit, y_bit, frame, irdy, pick=pick:
                               pick(frame, irdy, x_bit, y_bit), device=device)]
    pin_pick.verilog_code = "\n".join(lines) + "\n"
    return choose
