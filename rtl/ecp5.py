"""Verilog of the ECP5 primitives the ``ecp5`` build instantiates; nothing else uses them.

- ``lut4``: a slice's ``LUT4``, for the PCI target's one-LUT paths from
  FRAME#, IRDY# and PAR (``rtl/pci/pin_lut.py``), marked ``keep`` so that
  synthesis merges no logic into it.

The ``ecp5`` build has no other vendor cell yet: its pads are the generic
tri-states (``rtl/pci/pci_pads.py``; the ECP5 I/O registers would be
``IOLOGIC`` cells, not written), its FIFO memory is inferred like the
generic build's.  Written as user-defined Verilog by the block that uses it;
the ``generic`` build writes plain Verilog in its place.  yosys's ECP5
``cells_sim.v`` simulates it.
"""


def lut4(out, name, inputs, init):
    """One ``LUT4`` named ``name`` driving ``out`` (Z) from ``inputs`` (up to
    four net names on A, B, C, D; the rest tied to 0) with truth table
    ``init`` (bit ``D*8 + C*4 + B*2 + A``)."""
    tied = [*inputs, *["1'b0"] * (4 - len(inputs))]
    ports = ", ".join(f".{port}({net})" for port, net in zip("ABCD", tied))
    return f"(* keep *) LUT4 #(.INIT(16'h{init:04X})) {name} ({ports}, .Z({out}));"
