"""One axis's encoder input: A, B and index conditioned, decoded, the index latched (docs/encoders.md)."""
from myhdl import Signal, always_comb, block

from models.encoder_model import POLARITY_A, POLARITY_B, POLARITY_INDEX
from rtl.encoder.conditioner import conditioner
from rtl.encoder.decoder import decoder
from rtl.encoder.index_latch import index_latch
from rtl.interfaces import EncoderPins, EncoderPort, card_reset, named


@block
def encoder(clock, reset, pins, port):
    """One axis's encoder, clock for clock ``models.encoder_model.EncoderModel``
    (but its following error: ``following_error.py``).

    Ports (``rtl/interfaces/encoder.py``): ``pins`` (``EncoderPins``, as
    wired), ``port`` (``EncoderPort``: controls, count, errors, time, index
    latch; ``port.coming``, the card's ``Timestamp.coming``, is stored in
    ``time`` at a count edge).

    Seams: each pin through a ``conditioner`` (``conditioner_a``, ``_b``,
    ``_index``: two flip-flops, its ENC_POLARITY bit, the filter of
    ``port.filter``), then the ``decoder`` (count, direction, time,
    quadrature errors) and the ``index_latch``.
    A pin change before edge e is counted at edge e + 3 + ENC_FILTER.

    ENC_FILTER 0, A rising with the index armed (count 1 before):
        edge        e     e+1   e+2   e+3   e+4
        pin A, idx _/~~~~~~~~~~~~~~~~~~~~~~~~~~~~
        synced     ______/~~~~~~~~~~~~~~~~~~~~~~~
        level      ____________/~~~~~~~~~~~~~~~~~
        count        1     1     1    =2==========
        latch        0     0     0    =1==========  (the count before the sample)
        armed      ~~~~~~~~~~~~~~~~~~\\___________
        time         0     0     0    =value at e+3
    """
    levels = [Signal(bool(0)) for _ in range(3)]
    inverts = [Signal(bool(0)) for _ in range(3)]

    @always_comb
    def polarities():
        inverts[0].next = (port.polarity & POLARITY_A) != 0
        inverts[1].next = (port.polarity & POLARITY_B) != 0
        inverts[2].next = (port.polarity & POLARITY_INDEX) != 0

    inputs = [named(f"conditioner_{name}", conditioner(clock, reset, pin, invert, port.filter, level))
              for name, pin, invert, level in zip(("a", "b", "index"), (pins.a, pins.b, pins.index), inverts, levels)]
    return (polarities, inputs, named("decoder", decoder(clock, reset, levels[0], levels[1], port)),
            named("index_latch", index_latch(clock, reset, levels[2], port)))


def encoder_ports():
    """Fresh ports of ``encoder`` for conversion and benches."""
    return dict(clock=Signal(bool(0)), reset=card_reset(), pins=EncoderPins(), port=EncoderPort())
