"""The every-seed table names, on each seed's line, the PCI pins over PCI 33's budgets."""
from fpgaflow.flow import FAMILIES
from fpgaflow.report import format_sweep


def _figures(par_in):
    pins = {"pci_pins_par": {"in": par_in, "in_cells": 6, "out": 4.1, "oe": 1.9},
            "pci_pins_ad[0]": {"in": 2.3, "in_cells": 1, "out": 4.12, "oe": 4.05},
            "motor_step_x": {"in": None, "in_cells": 0, "out": 9.5, "oe": None}}   # no PCI budget
    return {"fmax_mhz": 68.1, "lcs": 9543, "fabric_ffs": 3642, "pins": pins}


def test_each_seed_names_its_pins_over_budget():
    # PCI 2.3 at 33 MHz: input set-up 7 ns, clock to output 11 ns
    lines = format_sweep([(1, _figures(7.57)), (2, _figures(6.99))], FAMILIES["ecp5"]).splitlines()
    seed_1 = next(line for line in lines if line.split()[0] == "1")
    seed_2 = next(line for line in lines if line.split()[0] == "2")
    assert seed_1.endswith("over budget: pci_pins_par in 7.57 ns")
    assert "over budget" not in seed_2
    assert "pin to register 7.57" in lines[-1]
