"""Build options of the DDA interpolator: coordinate width, variants, widths.

The build parameters themselves (default, range, choices) are defined once,
in ``models/parameters.py`` (``coord_width``, ``variants``); this module turns
them into what the RTL (``rtl/dda_*.py``), the sequencer's check of the ARC
header and the golden model (``models/dda_model.py``) use: variant codes and
the datapath widths that follow from them.

* ``coord_width``: signed width of the coordinates.  The card's range is
  the parameter's; the interpolator alone also runs narrower, down to
  ``DDA_MIN_WIDTH`` (its narrow-width bench runs at 10 bits; at 6 bits every
  legal move is co-simulated, ``sim/card/dda_exhaustive.py``, and the proofs run).
* ``variants``: the parameter's choices, ``improved,precise`` (the default:
  the paper's improved DDA and the precise mode) or ``all`` (the paper's
  traditional and weighted DDA as well, to reproduce its figures), here as
  sets of ARC.VARIANT codes.  Lines are always there.
"""
from models import parameters

TRADITIONAL, WEIGHTED, IMPROVED, PRECISE = (parameters.VARIANT_NAMES.index(name) for name in
                                            ("traditional", "weighted", "improved", "precise"))
VARIANT_NAMES = dict(enumerate(parameters.VARIANT_NAMES))
PAPER_VARIANTS = frozenset({TRADITIONAL, WEIGHTED, IMPROVED})
VARIANT_SETS = {name: frozenset(parameters.variant_codes(name)) for name in parameters.VARIANTS.choices}
ALL_VARIANTS = VARIANT_SETS["all"]
DEFAULT_VARIANTS = VARIANT_SETS[parameters.VARIANTS.default]

COORD_WIDTH = parameters.COORD_WIDTH.default
DDA_MIN_WIDTH = 6

# n + k of the paper's variants may reach coord_width + this (threshold 2**(n + k))
MAX_THRESHOLD_EXTRA = 4


def variant_set(variants):
    """The codes of ``variants``: a choice of the ``variants`` parameter
    (``improved,precise``, ``all``) or one of their code sets; ValueError else."""
    if isinstance(variants, str):
        return VARIANT_SETS[parameters.VARIANTS.check(variants)]
    chosen = frozenset(variants)
    if chosen not in VARIANT_SETS.values():
        raise ValueError(f"variants must be one of {', '.join(VARIANT_SETS)}, not the codes {sorted(chosen)}")
    return chosen


def variants_choice(variants):
    """The ``variants`` parameter's choice that builds ``variants`` (codes)."""
    chosen = variant_set(variants)
    return next(name for name, codes in VARIANT_SETS.items() if codes == chosen)


def check_coord_width(coord_width):
    """``coord_width`` if the interpolator can be built with it."""
    maximum = parameters.COORD_WIDTH.maximum
    if isinstance(coord_width, bool) or not isinstance(coord_width, int) \
            or not DDA_MIN_WIDTH <= coord_width <= maximum:
        raise ValueError(f"coord_width of the DDA must be {DDA_MIN_WIDTH}..{maximum} "
                         f"(the card's: {parameters.COORD_WIDTH.bounds()}), not {coord_width!r}")
    return coord_width


def accumulator_width(coord_width, variants=ALL_VARIANTS):
    """Signed width of the accumulator registers (which hold A - T, or A - T - 1).

    The paper's variants need T = 2**(n + k) up to 2**(coord_width + 4), a
    look-ahead step that takes the register to -T - i, and room above T for
    the saturation value: coord_width + 6 bits.  The precise mode's threshold
    is the radius + 1 and its registers stay within a few T of zero:
    coord_width + 3 bits (the model checks that they never leave it).
    """
    return coord_width + (6 if set(variants) & PAPER_VARIANTS else 3)


def threshold_width(coord_width, variants=ALL_VARIANTS):
    """Unsigned width of T - 1 (T of a line, the radius + 1 of the precise mode, 2**(n + k))."""
    return coord_width + (MAX_THRESHOLD_EXTRA if set(variants) & PAPER_VARIANTS else 0)


def left_width(coord_width):
    """Width of ``stop_left``: four quadrant pieces of the largest radius, plus one bit."""
    return coord_width + 3
