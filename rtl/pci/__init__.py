"""The PCI target's units, below ``rtl/pci_slave.py``: control, decode, configuration header,
parity, buffers, back-end requests, pin LUTs, and the pads ``rtl/top.py`` puts around the card."""
