"""The tests that dump no waveform, mirrored by subject: ``models/``, ``rtl/`` (converter, lint,
generated files), ``sim/`` (pieces without a bench), ``host/``, ``linuxcnc/``, ``formal/``,
``fpgaflow/``.  The waveform-checked benches are under ``sim/``."""
