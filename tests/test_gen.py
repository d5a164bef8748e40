"""``gen/`` holds exactly what the converter writes now (run ``python -m rtl.top --convert``)."""
from rtl.top import GEN_DIR, convert_all


def _files(folder):
    return {path.name: path.read_bytes() for path in folder.iterdir()
            if path.is_file() and not path.name.startswith(".")}


def test_gen_is_what_the_converter_writes(tmp_path):
    convert_all(tmp_path)
    fresh, committed = _files(tmp_path), _files(GEN_DIR)
    missing = sorted(set(fresh) - set(committed))
    extra = sorted(set(committed) - set(fresh))
    stale = sorted(name for name in set(fresh) & set(committed) if fresh[name] != committed[name])
    assert not (missing or extra or stale), (
        f"gen/ is out of date (run `python -m rtl.top --convert`): "
        f"missing {missing}, not written by the converter {extra}, different {stale}")
