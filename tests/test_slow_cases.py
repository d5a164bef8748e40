"""Every case ``conftest.SLOW_CASES`` leaves to the slow set names a test that exists
(a renamed test or parameter would otherwise slip back into the default suite)."""
import subprocess
import sys

import conftest
from rtl.convert import ROOT


def test_every_slow_case_names_a_collected_test():
    collected = subprocess.run([sys.executable, "-m", "pytest", "--collect-only", "-q", "-m", "slow or not slow",
                                "-n", "0"], cwd=ROOT, capture_output=True, text=True, timeout=300).stdout.splitlines()
    ids = [line for line in collected if "::" in line]
    assert len(ids) > 1000, collected[-5:]
    unmatched = [case for case in conftest.SLOW_CASES if not any(test.startswith(case) for test in ids)]
    assert unmatched == []
