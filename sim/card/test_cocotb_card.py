"""The cocotb front end of the host and monitor on the generated card in
Icarus (``sim/card/cocotb_card.py``), through cocotb's runner."""
from cocotb_tools.runner import get_results, get_runner

from rtl.convert import GEN_DIR, ROOT, build_dir


def test_cocotb_enumerates_programs_and_moves_the_card():
    runner = get_runner("icarus")
    build = build_dir("cocotb", "card")
    runner.build(sources=[GEN_DIR / "card.v"], hdl_toplevel="card", build_dir=build, timescale=("1ns", "1ps"),
                 always=True)
    results = runner.test(test_module="sim.card.cocotb_card", hdl_toplevel="card", build_dir=build,
                          test_dir=build, extra_env={"PYTHONPATH": str(ROOT)})
    tests, failures = get_results(results)
    assert (tests, failures) == (1, 0), f"cocotb: {failures} of {tests} failed, see {results}"
