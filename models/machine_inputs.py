"""The card's machine inputs, bit n of INPUT_POLARITY, INPUT_RAW and
INPUT_ACTIVE (MACHINE_STATUS's RAW and ACTIVE: the first XY_INPUTS): the
E-stop and X's and Y's as the two-axis card had them, then every further
axis's three.  The table describes the largest build; a card of N axes has
the inputs of its axes (``input_names``).  STOP_REASON.LIMITS bit n is
LIMIT_NAMES[n]: bit 2 * axis the axis's positive end, 2 * axis + 1 its negative.
"""
from models.axes import AXIS_NAMES
from models.register_types import BAR0_AXES

INPUT_TEXT = (("ESTOP", "emergency stop"), ("LIMIT_POS_X", "X limit, positive end"),
               ("LIMIT_NEG_X", "X limit, negative end"), ("LIMIT_POS_Y", "Y limit, positive end"),
               ("LIMIT_NEG_Y", "Y limit, negative end"), ("HOME_X", "X home switch"), ("HOME_Y", "Y home switch")
               ) + tuple(item for name in AXIS_NAMES[BAR0_AXES:] for item in (
                   (f"LIMIT_POS_{name}", f"{name} limit, positive end"),
                   (f"LIMIT_NEG_{name}", f"{name} limit, negative end"), (f"HOME_{name}", f"{name} home switch")))
INPUT_NAMES = tuple(name for name, _ in INPUT_TEXT)
XY_INPUTS = 7   # the two-axis card's inputs, those MACHINE_STATUS's RAW and ACTIVE carry
INPUTS_PER_AXIS = 3   # LIMIT_POS, LIMIT_NEG, HOME of an axis from Z on
LIMIT_NAMES = tuple(f"LIMIT_{end}_{name}" for name in AXIS_NAMES for end in ("POS", "NEG"))


def input_names(axes):
    """The machine inputs a card of ``axes`` axes has, bit n input n: ESTOP, X's and Y's, then Z's, ..."""
    if not BAR0_AXES <= axes <= len(AXIS_NAMES):
        raise ValueError(f"axes {axes} is not {BAR0_AXES}..{len(AXIS_NAMES)}")
    return INPUT_NAMES[:XY_INPUTS + INPUTS_PER_AXIS * (axes - BAR0_AXES)]


def limit_input(axis, positive):
    """The input index (INPUT_NAMES) of axis ``axis``'s limit switch at its positive or negative end."""
    return INPUT_NAMES.index(f"LIMIT_{'POS' if positive else 'NEG'}_{AXIS_NAMES[axis]}")


def home_input(axis):
    """The input index (INPUT_NAMES) of axis ``axis``'s home switch."""
    return INPUT_NAMES.index(f"HOME_{AXIS_NAMES[axis]}")


def limit_bit(axis, positive):
    """The STOP_REASON.LIMITS bit of axis ``axis``'s limit at its positive or negative end."""
    return LIMIT_NAMES.index(f"LIMIT_{'POS' if positive else 'NEG'}_{AXIS_NAMES[axis]}")
