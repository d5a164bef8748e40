"""Verilog of the iCE40 primitives the ``ice40`` build instantiates; nothing else uses them.

- ``sb_io``: the I/O cell, for the PCI pads (``rtl/pci/pci_pads.py``), whose
  registers hold the PCI target's boundary flip-flops;
- ``sb_lut4``: a logic cell's LUT, for the PCI target's one-LUT paths from
  FRAME#, IRDY# and PAR (``rtl/pci/pin_lut.py``), so that synthesis merges no
  logic into them.

Both are written as user-defined Verilog by the blocks that use them; the
``generic`` build writes plain Verilog in their place.  yosys's
``cells_sim.v`` (``sim/card/top_harness.py``) simulates them.
"""

# SB_IO PIN_TYPE: output mode in bits 5:2, input mode in bits 1:0.
PIN_REGISTERED_IO = "100100"      # registered output, direct enable, registered input
PIN_REGISTERED_OUTPUT = "100101"  # registered output, direct enable (input unused)
PIN_REGISTERED_INPUT = "000000"   # input register only
PIN_PLAIN_IO = "101001"           # plain output, direct enable, plain input: no register


def sb_io(label, index, width, pin_type, has_input, has_output):
    """One ``SB_IO`` (bit ``index`` of a ``width``-bit pin), named ``<label>_<index>``,
    in MyHDL's user-defined-code notation (``$pin``, ``$clock``, ``$enable``,
    ``$to_pin``, ``$from_pin``)."""
    bit = f"[{index}]" if width > 1 else ""
    # Every input of the cell is tied: the DDR and latch inputs are unused.
    ports = [f".PACKAGE_PIN($pin{bit})", ".LATCH_INPUT_VALUE(1'b0)", ".CLOCK_ENABLE(1'b1)",
             ".INPUT_CLK($clock)", ".OUTPUT_CLK($clock)", ".D_OUT_1(1'b0)"]
    if has_output:
        ports += [".OUTPUT_ENABLE($enable)", f".D_OUT_0($to_pin{bit})"]
    else:
        ports += [".OUTPUT_ENABLE(1'b0)", ".D_OUT_0(1'b0)"]
    if has_input:
        ports.append(f".D_IN_0($from_pin{bit})")
    return f"SB_IO #(.PIN_TYPE(6'b{pin_type})) {label}_{index} (\n    " + ",\n    ".join(ports) + "\n);\n"


def sb_lut4(out, name, inputs, init):
    """One ``SB_LUT4`` named ``name`` driving ``out`` from ``inputs`` (up to
    four net names, I0 first; the rest tied to 0) with truth table ``init``."""
    tied = [*inputs, *["1'b0"] * (4 - len(inputs))]
    ports = ", ".join(f".I{k}({net})" for k, net in enumerate(tied))
    return f"SB_LUT4 #(.LUT_INIT(16'h{init:04X})) {name} (.O({out}), {ports});"
