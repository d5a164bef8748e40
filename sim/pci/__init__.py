"""The PCI verification IP: the behavioural host (a simulator-free engine and transaction layer
with MyHDL and cocotb front ends), the bus model, the protocol checker and monitor, behavioural
targets, Verilog targets in Icarus, and the standard bench.  Its own tests sit beside it."""
