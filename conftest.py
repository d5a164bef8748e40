"""Names each test's waveforms after the test (``sim/backends/waves.py``)."""
import pytest

from sim.backends import waves


@pytest.fixture(autouse=True)
def _waves_named_after_the_test(request):
    with waves.named_after(request.node.nodeid):
        yield
