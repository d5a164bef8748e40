"""Tests of ``rtl/`` that dump no waveform: the converter's command line, ``gen/``, lint, the C header, LUTs."""
