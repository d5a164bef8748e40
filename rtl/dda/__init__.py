"""The interpolator's units, below ``rtl/dda_arc.py``: set-up, iteration, checks and their
arithmetic."""
