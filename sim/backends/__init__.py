"""The simulation back ends the benches run on: Icarus co-simulation, Verilator (compiled
harness, models, its PCI bus), the bench clock, and the waveforms (VCD, GTKWave save files)."""
