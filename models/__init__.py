"""The card described in plain Python, beneath everything else: its tables (build parameters,
registers, instructions, PCI facts, the simulated card's socket protocol) and a golden model of
every block.  Imports neither MyHDL nor a simulator; ``rtl``, ``sim``, ``host`` and the tools
stand on it."""
