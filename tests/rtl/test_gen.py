"""``gen/`` holds exactly what ``python -m rtl.top --convert`` writes now.

The converter's command line runs into a temporary folder (its ``--out``), so
the comparison covers every file it writes, the C header included.
"""
import pytest

from rtl.convert import GEN_DIR

pytestmark = pytest.mark.xdist_group("default_build")


def _files(folder):
    return {path.name: path.read_bytes() for path in folder.iterdir()
            if path.is_file() and not path.name.startswith(".")}


def test_gen_is_what_the_converter_writes(default_build_by_the_cli):
    out, _ = default_build_by_the_cli
    fresh, committed = _files(out), _files(GEN_DIR)
    missing = sorted(set(fresh) - set(committed))
    extra = sorted(set(committed) - set(fresh))
    stale = sorted(name for name in set(fresh) & set(committed) if fresh[name] != committed[name])
    assert not (missing or extra or stale), (
        f"gen/ is out of date (run `python -m rtl.top --convert`): "
        f"missing {missing}, not written by the converter {extra}, different {stale}")
