"""Tests of the synthesis flow (``fpgaflow/``), the pin files and the FuseSoC core."""
