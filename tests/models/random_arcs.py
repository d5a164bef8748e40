"""Seeded random arcs for the model tests of helices (``test_dda_axes``, ``test_helix_area``)."""
import math

from models.dda_model import PRECISE, plan_arc
from models.dda_plan import ArcCommand


def random_arc(rng, plane, ccw, variant=PRECISE, radius=None):
    """A seeded random arc about the origin in ``plane``, a quarter to a full turn, that the model accepts."""
    while True:
        r = radius or rng.uniform(20, 120)
        start = rng.uniform(0, math.tau)
        end = start + (1 if ccw else -1) * rng.uniform(math.pi / 2, math.tau)
        command = ArcCommand(round(r * math.cos(start)), round(r * math.sin(start)), round(r * math.cos(end)),
                             round(r * math.sin(end)), ccw, variant, rng.randrange(4) if variant in (1, 2) else 0,
                             plane=plane)
        try:
            plan_arc(command)
        except ValueError:
            continue
        return command
