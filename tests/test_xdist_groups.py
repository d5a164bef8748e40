"""The xdist groups hold.  Tests that share a costly run (a card model, a
scenario's MyHDL reference) or LinuxCNC carry one ``xdist_group`` so that one
worker runs them all (``--dist loadgroup``, setup.cfg); pytest-xdist's
scheduler finds a test's group in the ``@group`` it appends to the node id on
the worker.  A pytest whose node ids drop that suffix (9.2: pytest-xdist issue
1386) spreads every group over both workers without a word: each builds the
same models, and a worker waits for the other's LinuxCNC.  This test fails then."""
import pytest

GROUP = "xdist_group_check"

pytestmark = pytest.mark.xdist_group(GROUP)


def test_a_grouped_test_reaches_the_scheduler_with_its_group(request):
    if not getattr(request.config.option, "loadgroup", False):  # set on the workers of --dist loadgroup
        pytest.skip("not on a worker of --dist loadgroup (-n 0, or another --dist): nothing is grouped")
    assert request.node.nodeid.endswith(f"@{GROUP}"), (
        f"{request.node.nodeid} carries no @{GROUP}: this pytest drops xdist's group suffix (setup.cfg pins "
        "pytest below 9.2 for that)")
