"""``gen/`` holds exactly what ``python -m rtl.top --convert`` writes now.

The converter runs in-process into a temporary folder (its ``--out``), so the
comparison covers every file it writes, the C header included.
"""
from rtl.convert import GEN_DIR, main


def _files(folder):
    return {path.name: path.read_bytes() for path in folder.iterdir()
            if path.is_file() and not path.name.startswith(".")}


def test_gen_is_what_the_converter_writes(tmp_path, capsys):
    assert main(["--convert", "--out", str(tmp_path)]) == 0
    capsys.readouterr()
    fresh, committed = _files(tmp_path), _files(GEN_DIR)
    missing = sorted(set(fresh) - set(committed))
    extra = sorted(set(committed) - set(fresh))
    stale = sorted(name for name in set(fresh) & set(committed) if fresh[name] != committed[name])
    assert not (missing or extra or stale), (
        f"gen/ is out of date (run `python -m rtl.top --convert`): "
        f"missing {missing}, not written by the converter {extra}, different {stale}")
