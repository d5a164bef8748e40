"""The machine side's units, wired by ``rtl/regs_fifo.py``: input filter, machine guard (E-stop,
limits, watchdog, hold), homing."""
