"""The host's encoder helpers (host/encoders.py): the velocity estimator from ENC_TIME, and a card
without encoders refused."""
from types import SimpleNamespace

import pytest

from host import encoders
from host.encoders import EncoderReading

CLOCK_HZ = 33_000_000


def reading(count, time, stamp):
    return EncoderReading(count, time, stamp, 0, False, False, 0, 0, 0, 0)


@pytest.mark.parametrize("before, after, last, expected", [
    # 10 counts over the 3,300 clocks between the last count edges: 100,000 counts/s, not 10 per read interval
    ((0, 1_000, 5_000), (10, 4_300, 9_000), 0.0, 100_000.0),
    ((10, 4_300, 9_000), (4, 5_950, 9_900), 0.0, -6 * CLOCK_HZ / 1_650),
    # a count across the 32-bit wrap of both the count and the time stamp
    ((0x7FFFFFFF, 0xFFFFFF00, 0xFFFFFF10), (-0x7FFFFFFF, 0x00000100, 0x00000200), 0.0, 2 * CLOCK_HZ / 0x200),
    # no count since: at most one count in (TIMESTAMP - ENC_TIME) clocks, falling while the motor stands
    ((5, 100, 200), (5, 100, 33_100), 5_000.0, 1_000.0),
    ((5, 100, 200), (5, 100, 33_100), -300.0, -300.0),
])
def test_velocity_divides_counts_by_the_clocks_between_count_edges(before, after, last, expected):
    assert encoders.velocity(reading(*before), reading(*after), CLOCK_HZ, last) == pytest.approx(expected)


def test_a_card_without_encoders_is_refused_before_any_access():
    card = SimpleNamespace(identity=SimpleNamespace(encoders=False))
    with pytest.raises(ValueError, match="without encoders"):
        encoders.read_encoder(card, 0)
