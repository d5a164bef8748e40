"""MyHDL's elaboration without reading source files.

MyHDL finds the caller of every block and every process it makes with
``inspect.stack()``, which reads the source lines of every frame on the stack
and looks each frame's module up among all loaded modules.  Elaborating the
whole card that way took most of a short MyHDL bench (7 s of a 7 s run) and
most of a conversion, and grew with the number of modules a process had
loaded (a test worker that had run hundreds of tests took several times as
long).  MyHDL reads only each record's frame and function name (records
``[0]`` and ``[3]`` in ``myhdl._block._getCallInfo`` and
``myhdl._instance._getCallInfo``).

``install()`` (the ``rtl`` package calls it on import) gives those two MyHDL
modules an ``inspect`` whose ``stack()`` returns the same records without
source lines (what ``inspect.stack(context=0)`` returns, made straight from
the frames); every other name is the standard ``inspect``.  What MyHDL
builds is unchanged: ``tests/rtl/test_gen.py`` finds ``gen/`` byte for byte
what the converter writes, and ``tests/rtl/test_myhdl_stack.py`` compares the
records with ``inspect.stack(0)``'s.
"""
import inspect
import sys

import myhdl._block
import myhdl._instance

PATCHED_MODULES = (myhdl._block, myhdl._instance)


def frame_records(context=1):
    """``inspect.stack(context)``'s records from the caller outwards, without source lines."""
    del context  # no source lines are read, whatever the caller asks
    frame = sys._getframe(1)
    records = []
    while frame is not None:
        code = frame.f_code
        records.append(inspect.FrameInfo(frame, code.co_filename, frame.f_lineno, code.co_name, None, None))
        frame = frame.f_back
    return records


class QuickInspect:
    """The ``inspect`` module with ``stack`` = ``frame_records``."""

    stack = staticmethod(frame_records)

    def __getattr__(self, name):
        return getattr(inspect, name)


def install():
    """Give MyHDL's block and process decorators ``QuickInspect``; idempotent."""
    for module in PATCHED_MODULES:
        if not isinstance(module.inspect, QuickInspect):
            module.inspect = QuickInspect()
