"""RTL of the PCI DDA motion-control card (MyHDL, convertible to Verilog).

Importing it makes MyHDL's elaboration read no source files
(``rtl/myhdl_stack.py``): the same blocks, several times faster."""
from rtl.myhdl_stack import install

install()
