"""Paths of the DDA variants over the ideal arc: ``python -m bench.plot_arcs [--out DIR]``.

Writes PNGs like the paper's figures (into ``build/plots/`` by default):

* ``fig4_example_8.png``: the (8, 0) -> (0, 8) example, traditional (figure 4);
* ``fig6_traditional.png``, ``fig7_weighted.png``, ``fig10_improved.png``:
  the paper's configuration of each variant on (100, 0) -> (0, 100);
* ``fig11_comparison.png``: traditional, improved and the precise default
  over a stretch of the arc, up close (figure 11);
* ``precise_100.png``: the default precise mode on the same quarter arc.

Needs matplotlib (``pip install -e '.[plot]'``).
"""
import argparse
import math
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")  # before pyplot: no display needed
import matplotlib.pyplot as plt  # noqa: E402

from models.dda_model import (IMPROVED, PRECISE, TRADITIONAL, VARIANT_NAMES, WEIGHTED, ArcCommand,  # noqa: E402
                              iterate, metrics, paper_configuration)
from rtl.convert import build_dir  # noqa: E402


def ideal_arc(axes, radius, start=0.0, stop=math.pi / 2):
    angles = [start + (stop - start) * i / 400 for i in range(401)]
    axes.plot([radius * math.cos(a) for a in angles], [radius * math.sin(a) for a in angles],
              color="0.6", linewidth=1, label="ideal arc")


def draw_path(axes, command, options, label, **style):
    path = iterate(command, **options)
    xs, ys = zip(*path.points())
    axes.plot(xs, ys, drawstyle="default", linewidth=1, label=label, **style)
    return metrics(path)


def figure(title, radius):
    fig, axes = plt.subplots(figsize=(6, 6))
    axes.set_aspect("equal")
    axes.set_title(title)
    axes.set_xlabel("x (steps)")
    axes.set_ylabel("y (steps)")
    axes.grid(True, linewidth=0.3)
    ideal_arc(axes, radius)
    return fig, axes


def save(fig, axes, out, name):
    axes.legend(loc="lower left", fontsize=8)
    path = out / name
    fig.savefig(path, dpi=120)
    plt.close(fig)
    print(f"wrote {path}")


def paper_figure(out, variant, name):
    command, options = paper_configuration(variant)
    fig, axes = figure(f"{VARIANT_NAMES[variant]} DDA, paper configuration", 100)
    result = draw_path(axes, command, options, "", color="C0")
    axes.lines[-1].set_label(f"{VARIANT_NAMES[variant]}: V_arc {result.v_arc:.4f}")
    save(fig, axes, out, name)


def comparison_figure(out):
    fig, axes = plt.subplots(figsize=(7, 6))
    axes.set_aspect("equal")
    axes.set_title("traditional, improved and precise up close")
    axes.grid(True, linewidth=0.3)
    ideal_arc(axes, 100, math.radians(30), math.radians(60))
    styles = ((TRADITIONAL, "C3"), (IMPROVED, "C0"))
    for variant, color in styles:
        command, options = paper_configuration(variant)
        result = draw_path(axes, command, options, "", color=color, marker=".")
        axes.lines[-1].set_label(f"{VARIANT_NAMES[variant]} (paper): V_arc {result.v_arc:.3f}")
    result = draw_path(axes, ArcCommand(100, 0, 0, 100), {}, "", color="C2", marker=".")
    axes.lines[-1].set_label(f"precise: V_arc {result.v_arc:.3f}")
    axes.set_xlim(45, 90)
    axes.set_ylim(45, 90)
    save(fig, axes, out, "fig11_comparison.png")


def main(argv=None):
    parser = argparse.ArgumentParser(prog="python -m bench.plot_arcs", description=__doc__.split("\n")[0])
    parser.add_argument("--out", type=Path, default=None, help="output folder (default build/plots)")
    args = parser.parse_args(argv)
    out = args.out or build_dir("plots")
    out.mkdir(parents=True, exist_ok=True)

    fig, axes = figure("traditional DDA, (8, 0) -> (0, 8)", 8)
    draw_path(axes, ArcCommand(8, 0, 0, 8, variant=TRADITIONAL), {}, "traditional", marker="o")
    save(fig, axes, out, "fig4_example_8.png")
    for variant, name in ((TRADITIONAL, "fig6_traditional.png"), (WEIGHTED, "fig7_weighted.png"),
                          (IMPROVED, "fig10_improved.png")):
        paper_figure(out, variant, name)
    comparison_figure(out)
    fig, axes = figure("precise DDA (default), R = 100", 100)
    result = draw_path(axes, ArcCommand(100, 0, 0, 100, variant=PRECISE), {}, "", color="C2")
    axes.lines[-1].set_label(f"precise: V_arc {result.v_arc:.4f}")
    save(fig, axes, out, "precise_100.png")
    return 0


if __name__ == "__main__":
    sys.exit(main())
