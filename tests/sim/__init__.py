"""Tests of ``sim/`` pieces that dump no waveform: the card server, the Verilog port reader."""
