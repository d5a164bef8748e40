"""The card's generated Verilog compiled with Verilator and driven from Python.

``build`` makes and caches the shared library (model + ``harness.cpp``),
``model`` loads it (ports by name, the clock loop, runs until an event, the
STEP/DIR edges as numpy arrays, one bus clock per call), ``card`` binds the
card's ports, ``bench`` puts it on the PCI bus with the host engine and the
protocol checker.  ``docs/simulation.md`` has the whole picture.
"""
