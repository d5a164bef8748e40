"""``python -m fpgaflow`` refuses a bad command line before any tool runs (exit 2, one message)."""
import pytest

from fpgaflow.__main__ import main


@pytest.mark.parametrize("argv, message", [
    (["--sweep", "0"], "--sweep must be >= 1"),
    (["--paths", "-1"], "--paths must be >= 0"),
    (["--rows", "0"], "--rows must be >= 1"),
    (["--freq", "0"], "--freq must be > 0"),
    (["--skip", "("], "is not a regular expression"),
    (["--family", "xc7"], "invalid choice: 'xc7'"),
    (["--table", "--every-seed"], "do not go together"),
])
def test_bad_options_are_refused(argv, message, capsys, tmp_path):
    with pytest.raises(SystemExit) as stop:
        main([*argv, "--build", str(tmp_path / "never")])
    assert stop.value.code == 2
    assert message in capsys.readouterr().err
    assert not (tmp_path / "never").exists()


def test_a_folder_without_verilog_is_refused(capsys, tmp_path):
    with pytest.raises(SystemExit) as stop:
        main(["--gen", str(tmp_path)])
    assert stop.value.code == 2
    assert "no Verilog in" in capsys.readouterr().err
