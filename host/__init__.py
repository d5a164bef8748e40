"""Host software of the PCI DDA card: from a G-code program or an SVG drawing
to the card's command stream.

``gcode`` and ``svg`` read the input into ``geometry`` primitives (mm);
``planner`` turns them into LINE, ARC, SET, DWELL and MARK commands
(``lattice`` puts arcs onto the step lattice); ``check`` runs the commands
through the DDA's golden model and measures the path against the drawing;
``preview`` draws it; ``cli`` is ``python -m host``.  See docs/host.md.
"""
