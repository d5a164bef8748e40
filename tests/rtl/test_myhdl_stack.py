"""MyHDL's elaboration without source lines (``rtl/myhdl_stack.py``) builds
what the stock ``inspect.stack()`` builds."""
import inspect

import myhdl._block
import myhdl._instance
import pytest

from rtl import myhdl_stack
from rtl.regs.sync_fifo import sync_fifo, sync_fifo_ports


def test_importing_rtl_installs_the_quick_stack():
    for module in myhdl_stack.PATCHED_MODULES:
        assert isinstance(module.inspect, myhdl_stack.QuickInspect), module.__name__
        assert module.inspect.getsourcefile is inspect.getsourcefile


def _records_and_stock(depth):
    """(quick records, stock records) taken ``depth`` calls deep, from the same frame."""
    if depth:
        return _records_and_stock(depth - 1)
    return myhdl_stack.frame_records(), inspect.stack(0)


@pytest.mark.parametrize("depth", [0, 5])
def test_records_are_the_stock_records_without_source_lines(depth):
    quick, stock = _records_and_stock(depth)
    assert len(quick) == len(stock)
    for mine, theirs in zip(quick, stock):
        assert mine.frame is theirs.frame and mine.function == theirs.function
        assert (mine.filename, mine.lineno) == (theirs.frame.f_code.co_filename, theirs.lineno)
        assert mine.code_context is None and mine[0] is mine.frame and mine[3] == mine.function


def _hierarchy(block):
    """Names and kinds of ``block``'s instances, all the way down."""
    rows = []
    for sub in block.subs:
        rows.append((sub.name, type(sub).__name__))
        if hasattr(sub, "subs"):
            rows += _hierarchy(sub)
    return rows


def _converted(tmp_path, folder):
    ports = sync_fifo_ports(depth=8)
    block = sync_fifo(**ports, depth=8)
    (tmp_path / folder).mkdir()
    block.convert(hdl="Verilog", path=str(tmp_path / folder), name="sync_fifo", testbench=False)
    text = (tmp_path / folder / "sync_fifo.v").read_text()
    # the header names the file and the time it was written: the rest must be the same
    return _hierarchy(block), [line for line in text.splitlines() if not line.startswith(("// File:", "// Date:"))]


def test_a_unit_elaborates_and_converts_as_with_the_stock_stack(tmp_path, monkeypatch):
    quick = _converted(tmp_path, "quick")
    for module in myhdl_stack.PATCHED_MODULES:
        monkeypatch.setattr(module, "inspect", inspect)
    stock = _converted(tmp_path, "stock")
    assert quick[0] and quick == stock
