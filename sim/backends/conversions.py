"""Conversions of the RTL made once and kept: ``build/conv/<name>-<hash>/<name>.v``.

A bench that needs the Verilog of a build other than the one committed in
``gen/`` (another FIFO depth, a unit alone for Icarus) asks ``converted(name,
key, convert)``.  The hash covers MyHDL's version, every Python source the
converter reads (``rtl/`` and the ``models/`` tables beneath it) and ``key``
(the unit and its parameters), so a changed source or parameter is converted
afresh and an unchanged one is not converted again, by this process or by
another worker: the file appears whole (``os.replace``) or not at all, and a
worker that asks while another converts the same key waits for that one.
"""
import fcntl
import functools
import hashlib
import os
import shutil
import tempfile
from pathlib import Path

from myhdl import __version__ as myhdl_version
from myhdl._Signal import _Signal

from rtl.convert import ROOT, build_dir

SOURCE_PACKAGES = ("rtl", "models")


@functools.lru_cache(maxsize=None)
def sources_digest():
    """Hash of MyHDL's version and every ``.py`` file of ``SOURCE_PACKAGES``."""
    digest = hashlib.sha256(myhdl_version.encode())
    for package in SOURCE_PACKAGES:
        for source in sorted((ROOT / package).rglob("*.py")):
            digest.update(str(source.relative_to(ROOT)).encode() + b"\0" + source.read_bytes())
    return digest.hexdigest()


def converted(name, key, convert):
    """``<name>.v`` as ``convert(folder)`` writes it (returning its path), for ``key``."""
    digest = hashlib.sha256(f"{sources_digest()}\0{name}\0{key}".encode()).hexdigest()[:20]
    verilog = build_dir("conv", f"{name}-{digest}") / f"{name}.v"
    if verilog.exists():
        return verilog
    # one conversion of a key at a time: a second worker that wants it waits for the first's
    # (a card takes 5-15 s) instead of converting it again; as in build_model, the lock file
    # goes with the conversion, and a worker that comes between still finds the file
    lock_path = build_dir("conv") / f".{verilog.parent.name}.lock"
    with open(lock_path, "w") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)
        try:
            if not verilog.exists():
                staging = Path(tempfile.mkdtemp(prefix=f".{name}-", dir=build_dir("conv")))
                try:
                    os.replace(convert(staging), verilog)
                finally:
                    shutil.rmtree(staging, ignore_errors=True)
        finally:
            lock_path.unlink(missing_ok=True)
    return verilog


def port_key(ports):
    """What of ``{argument: Signal or interface}`` a conversion depends on, as text: each
    Signal's width, range, reset value and reset kind, each interface's other attributes."""
    parts = []
    for name, value in sorted(ports.items()):
        members = {name: value} if isinstance(value, _Signal) else {
            f"{name}_{attr}": member for attr, member in vars(value).items()}
        for member_name, member in sorted(members.items()):
            if isinstance(member, _Signal):
                parts.append(f"{member_name}:{len(member)}:{member.min}:{member.max}:{int(member.val)}:"
                             f"{getattr(member, 'active', '')}:{getattr(member, 'isasync', '')}")
            else:
                parts.append(f"{member_name}={member!r}")
    return ";".join(parts)
