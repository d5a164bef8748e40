"""The step request of an axis past Y: the interpolator's step, or else the axis's direct pulse."""
from myhdl import always_comb, block


@block
def axis_request(step, direction, out, request, request_dir):
    """Axis Z, A, ...: the interpolator's step (``step``, ``direction``) or else
    the axis's direct pulse (``out``), as ``regs_fifo``'s ``merge_requests`` does for X and Y.

    Ports: ``step``, ``direction`` in (the interpolator's), ``out`` a ``StepRequest`` in (the
    direct pulse's ``step`` and ``dir``), ``request``, ``request_dir`` out.  Combinational::

        step     ____/~~\\_______
        out.step ________/~~\\___
        request  ____/~~~~~~\\___   (request_dir: direction while step, else out.dir)
    """

    @always_comb
    def merge():
        request.next = step or out.step
        request_dir.next = direction if step else out.dir

    return merge
