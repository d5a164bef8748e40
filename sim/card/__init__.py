"""The card's benches: every unit and the whole card against the golden models (``models/``),
on MyHDL, Icarus and Verilator; the simulated card session and the card server the host
software and the LinuxCNC driver use.  Their waveform-checked tests sit beside them."""
