"""``fpgaflow.tools.run`` stops a tool by its CPU time, and by a wall-time cap for one that only waits."""
import sys
import time

import pytest

from fpgaflow.tools import WALL_FACTOR, SynthError, run


def test_a_tool_that_burns_cpu_is_stopped_by_its_cpu_time(tmp_path):
    started = time.monotonic()
    with pytest.raises(SynthError, match="within 1 s of CPU"):
        run([sys.executable, "-c", "while True: pass"], tmp_path / "log", tmp_path, timeout=1)
    assert time.monotonic() - started < WALL_FACTOR + 5


def test_a_tool_that_only_waits_is_stopped_by_the_wall_cap(tmp_path):
    started = time.monotonic()
    with pytest.raises(SynthError, match="within 1 s of CPU"):
        run([sys.executable, "-c", "import time; time.sleep(60)"], tmp_path / "log", tmp_path, timeout=1)
    assert WALL_FACTOR <= time.monotonic() - started < WALL_FACTOR + 5


def test_a_failing_tool_shows_its_log(tmp_path):
    (tmp_path / "log").write_text("the tool's last words")
    with pytest.raises(SynthError, match="(?s)exit 3.*the tool's last words"):
        run([sys.executable, "-c", "raise SystemExit(3)"], tmp_path / "log", tmp_path, timeout=30)
