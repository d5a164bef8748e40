"""Tests of the LinuxCNC driver (``linuxcnc/``), under LinuxCNC on the simulated card."""
