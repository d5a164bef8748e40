"""Homing one axis with the card's HOME command (docs/machine.md, "Homing").

    card.home("X", direction="negative", seek_rate=5000, release_rate=1000, backoff=50, search=40000)

Rates are in steps per second, converted to clocks with the card's
CLOCK_HZ (the periods are 16-bit: at 33 MHz the slowest rate is 509
steps/s); every value is checked before any register is written.
"""
from host.transports.base import POLL_SECONDS
from models import registers as regmap
from models.axes import AXIS_NAMES

ANY_AXIS_VERSION = (2, 3)   # HOME.AXIS_INDEX: Z, A, B, C; before it HOME.AXIS named X or Y only
DIRECTIONS = ("positive", "negative")   # where the switch is


class HomingError(RuntimeError):
    """HOME ended without zeroing: ``reason`` is ``NOT_FOUND`` (the switch did
    not trip, or release, within ``search`` steps) or ``REFUSED`` (the card
    was busy: queued or moving), ``axis`` the axis asked for."""

    def __init__(self, reason, axis, detail):
        super().__init__(f"HOME {axis}: {reason}: {detail}")
        self.reason, self.axis = reason, axis


def _checked(name, value, what):
    reg = regmap.register(name)
    low = reg.minimum if reg.minimum is not None else 0
    high = reg.maximum if reg.maximum is not None else (1 << reg.width) - 1
    if not isinstance(value, int) or not low <= value <= high:
        raise ValueError(f"{name}: {what}, outside {low}..{high}")
    return value


def home_settings(clock_hz, seek_rate, release_rate, backoff, search):
    """{register: value} for the HOME_* registers; ValueError for a value the card cannot take."""
    settings = {}
    for name, rate in (("HOME_SEEK_PERIOD", seek_rate), ("HOME_RELEASE_PERIOD", release_rate)):
        if not rate > 0:
            raise ValueError(f"{name}: a rate of {rate} steps/s does not move")
        clocks = round(clock_hz / rate)
        settings[name] = _checked(name, clocks, f"{rate} steps/s is {clocks} clocks at {clock_hz} Hz")
    settings["HOME_BACKOFF"] = _checked("HOME_BACKOFF", backoff, f"a back-off of {backoff} steps")
    settings["HOME_SEARCH"] = _checked("HOME_SEARCH", search, f"a search of {search} steps")
    return settings


def home(card, axis, direction="negative", seek_rate=5000.0, release_rate=1000.0, backoff=0, search=65535,
         timeout=60.0):
    """Home ``axis`` (``"X"``, ``"Y"``, ``"Z"``, ... one the card has) with its switch at the ``direction``
    end: seek at ``seek_rate``, step off at ``release_rate``, zero the
    position where the switch releases, go on ``backoff`` steps.  Returns
    the position (that axis reads -backoff towards the switch's side).
    HomingError if the switch is not found or the card refuses (busy),
    MachineStopped if the guard stops it, TimeoutError after ``timeout`` s
    of card time."""
    name = str(axis).upper()
    axes = AXIS_NAMES[:card.identity.axes] if card.identity.version >= ANY_AXIS_VERSION else AXIS_NAMES[:2]
    if name not in axes:
        raise ValueError(f"HOME: axis {axis!r} is not one of {', '.join(axes)} (the card's axes; register map "
                         f"{ANY_AXIS_VERSION[0]}.{ANY_AXIS_VERSION[1]} homes those beyond X and Y)")
    if direction not in DIRECTIONS:
        raise ValueError(f"HOME: direction {direction!r} is not one of {', '.join(DIRECTIONS)}")
    settings = home_settings(card.identity.clock_hz, seek_rate, release_rate, backoff, search)
    card.check()
    for register, value in settings.items():
        card.write(register, value)
    index = AXIS_NAMES.index(name)
    # X and Y through AXIS, as every 2.x card takes them; the others through AXIS_INDEX
    which = dict(AXIS=index) if index < 2 else dict(AXIS_INDEX=index)
    card.write("HOME", regmap.field_of("HOME", **which, NEGATIVE=int(direction == "negative")))
    deadline = card.transport.now() + timeout
    while True:
        word = card.read("HOME_STATUS")
        if not regmap.field_value("HOME_STATUS", "BUSY", word):
            break
        card.check()
        if card.transport.now() > deadline:
            raise TimeoutError(f"HOME {name} still busy after {timeout} s (HOME_STATUS {word:#04x})")
        card.transport.sleep(POLL_SECONDS)
    card.check()
    if regmap.field_value("HOME_STATUS", "REFUSED", word):
        raise HomingError("REFUSED", name, "the card was busy (queued or moving) or stopped")
    if regmap.field_value("HOME_STATUS", "NOT_FOUND", word):
        raise HomingError("NOT_FOUND", name, f"the switch did not trip or release within {search} steps")
    return card.position()
