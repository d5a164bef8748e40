"""The encoder inputs' units (docs/encoders.md): the per-axis encoder
(conditioner, decoder, index latch), the card's time stamp, the following
error and the probe latch; stand-alone until the card wires them."""
