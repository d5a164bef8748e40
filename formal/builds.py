"""Builds other than gen/'s that proof groups read (docs/formal.md): each
converted whole by the converter, once a process, into its own folder under
build/formal/generated, beside the includes generated for it."""
import subprocess
import sys
from functools import cache

from models.parameters import PARAMETERS
from rtl.convert import BUILD_DIR, ROOT

GENERATED = BUILD_DIR / "formal" / "generated"


def build_folder(values):
    """The folder, under build/formal/generated, of a build's converted units and generated includes."""
    return "_".join(f"{name}{value}" for name, value in sorted(values.items()))


@cache
def _built(items):
    values = dict(items)
    folder = GENERATED / build_folder(values) / "units"
    folder.parent.mkdir(parents=True, exist_ok=True)
    options = []
    for name, value in items:
        option = PARAMETERS[name].option
        options += ([option] if value else []) if PARAMETERS[name].flag else [option, str(value)]
    result = subprocess.run([sys.executable, "-m", "rtl.top", "--convert", "--out", str(folder), *options],
                            capture_output=True, text=True, cwd=ROOT)
    if result.returncode != 0:
        raise RuntimeError(f"python -m rtl.top --convert {' '.join(options)} failed:\n{result.stderr}")
    return folder


def built_unit(unit, values):
    """``unit`` (regs_fifo, card) of the build ``values`` (build parameters): the converter's
    whole output for that build, written once a process into the work folder by
    ``python -m rtl.top --convert`` in a process of its own, so the instance names are
    those of gen/ (the converter numbers them by the conversions before in its process); its path."""
    return _built(tuple(sorted(values.items()))) / f"{unit}.v"
