"""The card's generated Verilog compiled with Verilator and driven from Python.

``build`` makes and caches the shared library (model + ``harness.cpp``),
``model`` loads it (ports by name, the clock loop, runs until an event, the
STEP/DIR edges as numpy arrays), ``card`` binds the card's ports and puts it
on a bench's PCI segment.  ``docs/simulation.md`` has the whole picture.
"""
