"""Command line of ``python -m rtl.top``: ranges in ``--help``, one line and exit 2
for every bad value, nothing written on a failure, ``--out`` replaced whole.

Bad values are refused before anything is converted (and before the
converter re-runs itself with a fixed hash seed), so ``main`` runs in this
process for them; the process-level behaviour (exit code, stderr, files) is
checked with real runs too.  The ranges expected here are written out from
the issue and the hardware (PCI 2.3, iCE40 HX8K data sheet, register
widths), not read from the parameter table.
"""
import os
import subprocess
import sys

import pytest

from models.parameters import PARAMETERS
from rtl import convert
from rtl.convert import C_HEADER, ROOT, UNITS, convert_all, main, unit_builds

PROG = "python -m rtl.top"

# option -> (words --help must show, values just inside the range)
RANGES = {
    "--axes": ("2..6", ["2", "6"]),  # X Y Z A B C (issue 26); tests/rtl/test_lint.py converts 3 and 6
    "--coord-width": ("14..29", ["14", "29"]),
    "--fifo-depth": ("a power of two, 4..32,768", ["4", "4096"]),
    "--clock-hz": ("1..33,333,333", ["1", "33333333"]),
    "--vendor-id": ("0x0000..0xFFFE", ["0", "0xFFFE"]),
    "--device-id": ("0x0000..0xFFFF", ["0", "0xFFFF"]),
    "--revision-id": ("0x00..0xFF", ["0", "0xFF"]),
    "--class-code": ("0x000000..0xFFFFFF", ["0", "0xFFFFFF"]),
    "--subsystem-vendor-id": ("0x0000..0xFFFF", ["0", "0xFFFF"]),
    "--subsystem-id": ("0x0000..0xFFFF", ["0", "0xFFFF"]),
    "--io-bar-bits": ("2..8", ["2", "8"]),
    "--mem-bar-bits": ("4..24", ["4", "24"]),
    "--reg-bar-bits": ("4..16", ["4", "16"]),
    "--device": ("generic, ice40 or ecp5", ["generic", "ice40", "ecp5"]),
    "--variants": ("improved,precise or all", ["improved,precise", "all"]),
    "--encoders": ("0..1", ["0", "1"]),   # a bare option on the command line (issue 27)
}

# option -> values outside the range (edges on both sides, wrong types)
BAD_VALUES = {
    "--axes": ["1", "7", "0", "-2", "2.0", "x", ""],
    "--coord-width": ["13", "30", "4", "48", "24.0", "abc", ""],
    "--fifo-depth": ["2", "1", "0", "-4", "3", "48", "65536", "32768.0", "x200"],
    "--clock-hz": ["0", "33333334", "-1", "33.3e6"],
    "--vendor-id": ["0xFFFF", "-1", "0x10000", "0xG"],
    "--device-id": ["-1", "0x10000"],
    "--revision-id": ["-1", "256"],
    "--class-code": ["-1", "0x1000000"],
    "--subsystem-vendor-id": ["-1", "0x10000"],
    "--subsystem-id": ["-1", "0x10000"],
    "--io-bar-bits": ["1", "9"],
    "--mem-bar-bits": ["3", "25"],
    "--reg-bar-bits": ["3", "17"],
    "--device": ["xilinx", "ICE40", "", "ecp5u"],
    "--variants": ["precise", "improved", "precise,improved", "ALL", "all,precise"],
    "--encoders": ["1", "0", "2", "yes"],   # bare: a value after it is refused
}
ICE40_BLOCK_RAM_WORDS = 32 * 4096 // 32   # iCE40 HX8K: 32 blocks of 4 Kbit


def test_every_parameter_is_covered():
    assert set(RANGES) == set(BAD_VALUES) == {p.option for p in PARAMETERS.values()}


def run_cli(*args, env=None):
    return subprocess.run([sys.executable, "-m", "rtl.top", *args], cwd=ROOT, env=env,
                          capture_output=True, text=True, timeout=900)


def one_line_error(text):
    lines = [line for line in text.splitlines() if line.strip()]
    assert len(lines) == 1, f"expected a one-line error, got:\n{text}"
    assert lines[0].startswith(f"{PROG}: error: "), lines[0]
    return lines[0]


def refused_in_process(capsys, *args):
    """``main(args)`` refuses: exit 2 and one line on stderr, which is returned."""
    with pytest.raises(SystemExit) as stop:
        main(list(args))
    assert stop.value.code == 2
    captured = capsys.readouterr()
    assert captured.out == ""
    return one_line_error(captured.err)


def leftovers(folder):
    """Staging or old copies the converter left beside its output."""
    return sorted(path.name for path in folder.iterdir() if path.name.startswith("."))


def test_help_states_every_range_and_the_ice40_limit():
    result = run_cli("--help")
    assert result.returncode == 0, result.stderr
    text = " ".join(result.stdout.split())
    for option, (bounds, _) in RANGES.items():
        assert option in text, f"{option} missing from --help"
        assert bounds in text, f"{option}: range {bounds!r} missing from --help"
    assert f"ice40: at most {ICE40_BLOCK_RAM_WORDS:,}" in text and "iCE40 HX8K" in text
    for option in ("--convert", "--out"):
        assert option in text


@pytest.mark.parametrize("option, value", [(o, v) for o, values in BAD_VALUES.items() for v in values])
def test_bad_value_is_one_line_and_exit_2(option, value, capsys, tmp_path):
    out = tmp_path / "out"
    line = refused_in_process(capsys, "--convert", "--out", str(out), f"{option}={value}")
    assert f"argument {option}:" in line
    assert not out.exists() and not leftovers(tmp_path)


@pytest.mark.parametrize("option", sorted(RANGES))
def test_values_at_the_range_edges_are_taken(option):
    name = option[2:].replace("-", "_")
    for text in RANGES[option][1]:
        value = PARAMETERS[name].parse(text)
        values = {name: value, "device": "generic"} if name == "fifo_depth" else {name: value}
        builds = unit_builds(values)
        assert all(getattr(builds[unit], name) == value for unit in UNITS if name in UNITS[unit].names)


def test_bare_encoders_option_builds_the_card_and_top_with_encoders():
    args = convert._parser().parse_args(["--convert", "--encoders"])
    assert args.encoders == 1 and convert._parser().parse_args(["--convert"]).encoders is None
    builds = unit_builds({"encoders": args.encoders})
    assert [unit for unit in UNITS if getattr(builds[unit], "encoders")] == ["regs_fifo", "card", "top"]


def test_fifo_deeper_than_the_ice40_block_ram_is_refused_for_ice40(capsys, tmp_path):
    deeper = str(2 * ICE40_BLOCK_RAM_WORDS)
    line = refused_in_process(capsys, "--convert", "--out", str(tmp_path / "o"), "--device", "ice40",
                              "--fifo-depth", deeper)
    assert f"{ICE40_BLOCK_RAM_WORDS:,}" in line and "ice40" in line
    # without --device the top is built for iCE40, so the limit holds, and says why
    line = refused_in_process(capsys, "--convert", "--out", str(tmp_path / "o"), "--fifo-depth", deeper)
    assert "the top is built for ice40" in line
    # the generic build has no such limit
    assert unit_builds({"device": "generic", "fifo_depth": 32768})["top"].fifo_depth == 32768


def test_out_naming_a_file_is_one_line(capsys, tmp_path):
    target = tmp_path / "a_file"
    target.write_text("keep me")
    line = refused_in_process(capsys, "--convert", "--out", str(target))
    assert "is a file" in line
    assert target.read_text() == "keep me"


def test_out_holding_other_files_is_refused(capsys, tmp_path):
    (tmp_path / "notes.md").write_text("mine")
    line = refused_in_process(capsys, "--convert", "--out", str(tmp_path))
    assert "notes.md" in line
    assert (tmp_path / "notes.md").read_text() == "mine"


def test_nothing_to_do_and_unknown_options_are_one_line(capsys, tmp_path):
    refused_in_process(capsys)
    refused_in_process(capsys, "--convert", "--out", str(tmp_path / "o"), "--no-such-option")


def test_the_process_exits_2_with_one_line_and_writes_nothing(tmp_path):
    out = tmp_path / "out"
    result = run_cli("--convert", "--out", str(out), "--fifo-depth", "32768", "--coord-width", "20")
    assert result.returncode == 2
    assert "--fifo-depth" in one_line_error(result.stderr)
    assert result.stdout == "" and not out.exists() and not leftovers(tmp_path)


@pytest.mark.xdist_group("default_build")
def test_out_is_replaced_whole_and_every_file_reported(default_build_by_the_cli):
    out, result = default_build_by_the_cli   # --out held a stale file of an earlier build
    written = {path.name for path in out.iterdir()}
    assert written == {f"{unit}.v" for unit in UNITS} | {C_HEADER}
    for name in written:
        assert f"wrote {out / name}" in result.stdout.splitlines(), f"{name} written but not reported"
    assert not leftovers(out.parent)
    assert oct(out.stat().st_mode & 0o777) == oct(0o777 & ~_umask())


def _umask():
    mask = os.umask(0)
    os.umask(mask)
    return mask


def test_a_failing_conversion_leaves_the_old_output_untouched(tmp_path, monkeypatch):
    # two small units are enough to fail after a file was written (and quicker than the card)
    monkeypatch.setattr(convert, "UNITS", {unit: UNITS[unit] for unit in ("pci_slave", "dda_arc")})
    out = tmp_path / "gen"
    out.mkdir()
    before = {"card.v": "// previous card\n", "dda_card.h": "/* previous header */\n"}
    for name, text in before.items():
        (out / name).write_text(text)
    converted = []
    real_convert = convert.convert_block

    def failing_on_the_second_unit(unit, instance, out_dir):
        if converted:
            raise OSError(f"injected failure while writing {unit}")
        converted.append(real_convert(unit, instance, out_dir))
        return converted[-1]

    monkeypatch.setattr(convert, "convert_block", failing_on_the_second_unit)
    with pytest.raises(OSError, match="injected failure"):
        convert_all(out, device="generic")
    assert converted, "the failure must come after a file was written"
    assert {path.name: path.read_text() for path in out.iterdir()} == before
    assert not converted[0].exists() and not leftovers(tmp_path), "staging folder left behind"
