"""How the host reaches a card: one interface (``base.Transport``), several implementations.

* ``simulated.SimTransport``: the simulated card on MyHDL, Icarus or
  Verilator (the only part of ``host`` that needs ``sim/``);
* ``sysfs.SysfsTransport``: a real card on Linux, through sysfs and
  ``uio_pci_generic``.

``open_transport(spec)`` picks one from a ``--card`` value and imports only
the one it picks.
"""
from host.transports.base import SIM_KINDS, Transport, TransportError

__all__ = ["SIM_KINDS", "Transport", "TransportError", "open_transport"]


def open_transport(spec, **options):
    """The transport a ``--card`` value names: ``myhdl``, ``icarus``,
    ``verilator`` (the simulated card), ``pci`` (the one real card) or
    ``pci:DDDD:BB:DD.F`` (that real card).  ``options`` go to the
    implementation's constructor."""
    if spec in SIM_KINDS:
        from host.transports.simulated import SimTransport

        return SimTransport(spec, **options)
    if spec == "pci" or spec.startswith("pci:"):
        from host.transports.sysfs import SysfsTransport

        return SysfsTransport(spec[4:] or None, **options)
    raise ValueError(f"unknown card {spec!r}: use one of {', '.join(SIM_KINDS)}, pci or pci:DDDD:BB:DD.F")
