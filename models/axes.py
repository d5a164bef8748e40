"""The card's axes, named once, and the planes an arc turns in (docs/axes.md).

Axis index 0..5 is X, Y, Z, A, B, C: a card built with N axes (build
parameter ``axes``, ``models/parameters.py``) has axes 0..N-1.  X, Y and Z
are linear, A, B and C rotary (RS274/NGC: A turns about a line parallel to
X, B about Y, C about Z).  An axis mask has bit i for axis i.

A plane is a pair (u, v) of axis indices: an arc in it turns counter-
clockwise from +u towards +v, i.e. counter-clockwise as seen from the
plane's normal u x v.  G17, G18 and G19 select (X, Y), (Z, X) and (Y, Z),
whose normals are +Z, +Y and +X, as RS274/NGC defines the directions.
"""
AXIS_NAMES = ("X", "Y", "Z", "A", "B", "C")
MAX_AXES = len(AXIS_NAMES)
ROTARY_NAMES = ("A", "B", "C")
XY = (0, 1)
XY_MASK = 0b11
PLANES = {17: (0, 1), 18: (2, 0), 19: (1, 2)}  # G17, G18, G19 -> (u, v)


def names(indices):
    """``indices`` as axis names: (0, 2) -> 'X, Z'."""
    return ", ".join(AXIS_NAMES[i] for i in indices)


def mask_of(indices):
    """The axis mask with bit i set for every i in ``indices``."""
    mask = 0
    for index in indices:
        if not 0 <= index < MAX_AXES:
            raise ValueError(f"axis index {index} is not 0..{MAX_AXES - 1}")
        mask |= 1 << index
    return mask


def axes_of(mask):
    """The axis indices of ``mask``, ascending."""
    return tuple(i for i in range(MAX_AXES) if mask >> i & 1)


def moving_mask(deltas):
    """The mask of the axes whose displacement in ``deltas`` (indexed by axis) is not 0."""
    return mask_of(i for i, delta in enumerate(deltas) if delta)
