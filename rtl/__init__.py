"""RTL of the PCI DDA motion-control card (MyHDL, convertible to Verilog)."""
