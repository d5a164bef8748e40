"""Fixtures of the LinuxCNC tests."""
import pytest

from tests.linuxcnc.session import one_linuxcnc


@pytest.fixture
def linuxcnc_alone():
    """The test runs alone among LinuxCNC and halrun sessions on this host."""
    with one_linuxcnc():
        yield
