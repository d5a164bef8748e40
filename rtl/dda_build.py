"""Build options of the DDA interpolator, defined once: coordinate width, variants, widths.

The RTL (``rtl/dda_*.py``), the converter's parameter table (``rtl/top.py``),
the sequencer's check of the ARC header and the golden model
(``sim/dda_model.py``) all take these from here.

* ``coord_width``: signed width of the coordinates, ``COORD_WIDTH`` by
  default, ``COORD_WIDTH_RANGE`` allowed.
* ``variants``: which step rules a card is built with.  Lines are always
  there.  ``DEFAULT_VARIANTS`` (improved + precise) is the card's; ``"all"``
  adds the paper's traditional and weighted variants (to reproduce its
  figures).  On the command line and in the parameter table a set is
  written as names joined by ``+`` (``improved+precise``) or ``all``.
"""
TRADITIONAL, WEIGHTED, IMPROVED, PRECISE = range(4)
VARIANT_NAMES = {TRADITIONAL: "traditional", WEIGHTED: "weighted", IMPROVED: "improved",
                 PRECISE: "precise"}
PAPER_VARIANTS = frozenset({TRADITIONAL, WEIGHTED, IMPROVED})
ALL_VARIANTS = frozenset(VARIANT_NAMES)
DEFAULT_VARIANTS = frozenset({IMPROVED, PRECISE})

COORD_WIDTH = 24
COORD_WIDTH_RANGE = range(8, 32)

# n + k of the paper's variants may reach coord_width + this (threshold 2**(n + k))
MAX_THRESHOLD_EXTRA = 4


def parse_variants(text):
    """A variant set from ``all``, ``default`` or names joined by ``+``; ValueError if bad."""
    if isinstance(text, (set, frozenset, tuple, list)):
        return check_variants(text)
    words = str(text).strip().lower()
    if words == "all":
        return ALL_VARIANTS
    if words == "default":
        return DEFAULT_VARIANTS
    codes = {name: code for code, name in VARIANT_NAMES.items()}
    chosen = set()
    for word in words.split("+"):
        if word not in codes:
            raise ValueError(f"variants: '{word}' is not a variant ({', '.join(codes)}; join them with '+', "
                             f"or 'all')")
        chosen.add(codes[word])
    return check_variants(chosen)


def check_variants(variants):
    """``variants`` as a frozenset of codes; ValueError when empty or unknown."""
    chosen = frozenset(variants)
    if not chosen or not chosen <= ALL_VARIANTS:
        raise ValueError(f"variants must be a non-empty subset of {sorted(ALL_VARIANTS)}, not {sorted(chosen)}")
    return chosen


def variants_text(variants):
    """The option's spelling of a variant set (``improved+precise``, ``all``)."""
    chosen = check_variants(variants)
    if chosen == ALL_VARIANTS:
        return "all"
    return "+".join(VARIANT_NAMES[code] for code in sorted(chosen))


def variants_mask(variants):
    """A bit per built variant (bit ``code``), as the register map reports it."""
    return sum(1 << code for code in check_variants(variants))


def check_coord_width(coord_width):
    if coord_width not in COORD_WIDTH_RANGE:
        raise ValueError(f"coord_width must be {COORD_WIDTH_RANGE.start}..{COORD_WIDTH_RANGE.stop - 1}, "
                         f"not {coord_width}")
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
