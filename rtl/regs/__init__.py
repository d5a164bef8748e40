"""The register/FIFO back end's units, below ``rtl/regs_fifo.py``: register words, data FIFO,
sequencer, feed rate, pulse outputs, direct pulses, status words."""
