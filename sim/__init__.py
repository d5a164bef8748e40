"""Verification above the RTL: the PCI verification IP (``pci/``), the card's benches
(``card/``) and the simulation back ends (``backends/``).  Never imported by ``rtl/`` or
``models/``; ``host`` uses it only in its simulated transport."""
