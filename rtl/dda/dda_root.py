"""Square root of the DDA's setup stage: the nearest integer root of xs**2 + ys**2."""
from myhdl import Signal, always, always_comb, always_seq, block, concat, intbv, modbv


@block
def dda_root(clock, reset, root):
    """Restoring square root, one bit a clock, and its rounding bit.

    Ports:
        clock, reset  clock and reset (``card_reset()``)
        root          ``DdaRoot``: ``load`` and ``radicand`` in; ``root`` (t) and
                      ``grows`` out
    Parameters: none; W is ``root.coord_width``.

    Each clock takes the next two radicand bits: trial = {remainder, bits},
    and the next root bit is 1 when trial >= {root, 01} (one subtractor; the
    remainder becomes the difference, or stays the trial).  After W bits a
    last trial with bits 00 gives r: the radicand is nearer (root + 1)**2
    exactly when it exceeds root**2 + root.  ``root.root`` is then
    t = 2 root + r, so Rq = (t + 1) >> 1 and 2 Rq = t + r::

        clock   _/~\\_/~\\_/~\\_ ... _/~\\_/~\\_
        load    _/~~~\\_____ ... __________
        root    -----<b(W-1)>< ... ><b0 >< r >   one bit a clock, W + 1 clocks
    """
    width = root.coord_width
    radicand = Signal(modbv(0)[2 * width:])
    remainder = Signal(intbv(0)[width + 2:])
    steps = Signal(intbv(0, min=0, max=width + 2))
    started, all_ones = Signal(bool(0)), Signal(bool(0))
    fits = Signal(bool(0))
    keep = Signal(intbv(0)[width + 2:])

    @always_comb
    def trial():
        # the new remainder, when the trial fits, is below 2 root: the difference of the low
        # W + 2 bits is the whole difference, and the trial's two top bits only say "fits"
        value = intbv(0)[width + 4:]
        difference = modbv(0)[width + 3:]
        value[:] = concat(remainder, radicand[2 * width:2 * width - 2])
        difference[:] = concat(False, value[width + 2:]) - concat(False, root.root[width:], intbv(1)[2:])
        fits.next = value[width + 4:width + 2] != 0 or not difference[width + 2]
        keep.next = value[width + 2:]
        if value[width + 4:width + 2] != 0 or not difference[width + 2]:
            keep.next = difference[width + 2:]

    @always_comb
    def length():
        # a root bit from the first 1 on, or the rounding of an all-ones root
        root.grows.next = False
        if steps > 1:
            root.grows.next = started or fits
        elif steps == 1:
            root.grows.next = fits and started and all_ones

    @always_seq(clock.posedge, reset=reset)
    def count():
        if root.load:
            steps.next = width + 1
        elif steps != 0:
            steps.next = steps - 1

    @always(clock.posedge)
    def digits():
        # loaded before they are read: no reset
        if root.load:
            radicand.next = root.radicand
            remainder.next = 0
            root.root.next = 0
            started.next = False
            all_ones.next = True
        elif steps != 0:
            remainder.next = keep
            root.root.next = concat(root.root[width:], fits)
            radicand.next = radicand << 2
            if fits:
                started.next = True
            elif started:
                all_ones.next = False

    return trial, length, count, digits
