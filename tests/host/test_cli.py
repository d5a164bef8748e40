"""``python -m host plan``: figures printed, files written, one-line errors."""
import subprocess
import sys

import pytest

from rtl.convert import ROOT

PROG = "python -m host"
EXAMPLES = ROOT / "examples"


def run_host(*args):
    return subprocess.run([sys.executable, "-m", "host", *map(str, args)], cwd=ROOT,
                          capture_output=True, text=True, timeout=600)


def assert_one_line_error(result, text=""):
    lines = [line for line in result.stderr.splitlines() if line.strip()]
    assert result.returncode != 0
    assert len(lines) == 1, result.stderr
    assert lines[0].startswith(f"{PROG}: error: ") and text in lines[0], lines[0]


def test_help_names_the_options():
    result = run_host("plan", "--help")
    assert result.returncode == 0
    for option in ("--steps-per-mm", "--clock-hz", "--coord-width", "--rapid", "--acceleration",
                   "--start-feed", "--feed", "--tolerance", "--mark-interval", "--preview", "--words"):
        assert option in result.stdout


def test_plan_prints_the_figures_and_writes_the_words(tmp_path):
    words = tmp_path / "words.txt"
    result = run_host("plan", EXAMPLES / "part.ngc", "--words", words)
    assert result.returncode == 0, result.stderr
    for label in ("segments:", "commands:", "steps:", "deviation:", "job time:"):
        assert label in result.stdout
    assert "ends at (0, 0)" in result.stdout  # the part returns to the origin
    lines = words.read_text().split()
    assert lines and all(len(word) == 8 and int(word, 16) >= 0 for word in lines)
    assert int(lines[-1], 16) >> 28 == 0x6  # the job ends with a MARK


@pytest.mark.parametrize("option, value", [
    ("--steps-per-mm", "0"), ("--steps-per-mm", "1,2,3"), ("--steps-per-mm", "abc"),
    ("--clock-hz", "-5"), ("--coord-width", "40"), ("--rapid", "nan"), ("--acceleration", "0"),
    ("--start-feed", "-1"), ("--feed", "x"), ("--tolerance", "0"), ("--mark-interval", "0"),
])
def test_bad_values_are_refused_before_anything_is_written(option, value, tmp_path):
    words = tmp_path / "words.txt"
    result = run_host("plan", EXAMPLES / "part.ngc", option, value, "--words", words)
    assert_one_line_error(result)
    assert not words.exists()


def test_missing_file_and_missing_output_folder(tmp_path):
    assert_one_line_error(run_host("plan", tmp_path / "none.ngc"), "no such file")
    assert_one_line_error(run_host("plan", EXAMPLES / "part.ngc", "--preview", tmp_path / "no" / "p.png"),
                          "folder does not exist")


def test_a_bad_program_line_is_one_error_naming_it(tmp_path):
    program = tmp_path / "bad.ngc"
    program.write_text("G0 X1\nG1 X2 F100\nG1 Z1\n")
    words = tmp_path / "words.txt"
    result = run_host("plan", program, "--words", words)  # the default card: two axes
    assert_one_line_error(result, "bad.ngc:3: axis Z: the card has 2 axes (X, Y)")
    assert not words.exists()


def test_preview_draws_a_png(tmp_path):
    pytest.importorskip("matplotlib")
    out = tmp_path / "part.png"
    result = run_host("plan", EXAMPLES / "drawing.svg", "--preview", out)
    assert result.returncode == 0, result.stderr
    assert out.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
