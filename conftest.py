"""Lets ``pytest`` find ``rtl`` and ``sim`` from a plain checkout, and names
each test's waveforms after the test (``sim/backends/waves.py``)."""
import sys
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parent))

from sim import waves  # noqa: E402  (needs the path above)


@pytest.fixture(autouse=True)
def _waves_named_after_the_test(request):
    with waves.named_after(request.node.nodeid):
        yield
