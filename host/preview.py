"""A picture of the planned path over the drawing (matplotlib, the ``plot`` extra).

An XY drawing is one XY view.  A drawing of three or more axes gets four:
the XY, XZ and YZ projections and a 3-D view of X, Y, Z; the title gives the
largest deviation from the drawing (``host.check``: over every axis).
"""
import math

from models.axes import AXIS_NAMES

PROJECTIONS = ((0, 1), (0, 2), (1, 2))  # XY, XZ, YZ


def _samples(item, scale):
    samples = max(2, min(400, int(item.length * scale / 4) + 2))
    if hasattr(item, "sweep"):
        samples = max(samples, int(item.sweep / (math.pi / 90)) + 2)
    return [item.point(i / (samples - 1)) for i in range(samples)]


def _curves(plan, result):
    """(drawing curves, path curves): [(points in mm, rapid)] each."""
    machine = plan.machine
    scale = max(machine.steps_per_mm)
    drawing = [(_samples(item, scale), item.rapid) for item in plan.drawing if hasattr(item, "point")]
    path = [([machine.mm(p) for p in points], plan.drawing[primitive].rapid) for primitive, points in result.points]
    return drawing, path


def _plot(axes, curves, picked, drawing):
    for points, rapid in curves:
        coordinates = [[p[i] for p in points] for i in picked]
        if drawing:
            axes.plot(*coordinates, color="0.6", linewidth=3, linestyle="--" if rapid else "-",
                      solid_capstyle="round")
        else:
            axes.plot(*coordinates, color="tab:orange" if rapid else "tab:blue", linewidth=0.8,
                      linestyle="--" if rapid else "-")


def draw(plan, result, out_path, title="", measured=None):
    """Write ``out_path`` (PNG): the drawing in grey, the card's path (the model's
    step points) in colour, rapid moves dashed; ``measured`` (``[(primitive index,
    [points in steps])]``, the path the encoders measured): in green over it."""
    import matplotlib

    matplotlib.use("Agg")
    from matplotlib import pyplot

    drawing, path = _curves(plan, result)
    three_d = any(len(points[0]) > 2 for points, _ in drawing)
    title = title or (f"planned path (blue: fed, orange: rapid) over the drawing (grey); max deviation "
                      f"{result.max_deviation_steps:.2f} steps")
    if not three_d:
        figure, axes = pyplot.subplots(figsize=(8, 8))
        views = [(axes, (0, 1))]
    else:
        figure = pyplot.figure(figsize=(12, 11))
        views = [(figure.add_subplot(2, 2, n + 1), picked) for n, picked in enumerate(PROJECTIONS)]
        views.append((figure.add_subplot(2, 2, 4, projection="3d"), (0, 1, 2)))
    machine = plan.machine
    measured_mm = [[machine.mm(p) for p in points] for _, points in measured or () if points]
    for axes, picked in views:
        _plot(axes, drawing, picked, True)
        _plot(axes, path, picked, False)
        for points in measured_mm:
            axes.plot(*[[p[i] for p in points] for i in picked], color="tab:green", linewidth=0.6)
        axes.set_xlabel(f"{AXIS_NAMES[picked[0]]} (mm)")
        axes.set_ylabel(f"{AXIS_NAMES[picked[1]]} (mm)")
        if len(picked) == 3:
            axes.set_zlabel("Z (mm)")
            axes.set_title("3-D", fontsize=9)
        else:
            axes.set_aspect("equal")
            if three_d:
                axes.set_title(f"{AXIS_NAMES[picked[0]]}{AXIS_NAMES[picked[1]]} projection", fontsize=9)
    if three_d:
        figure.suptitle(title, fontsize=10)
    else:
        views[0][0].set_title(title, fontsize=9)
    figure.savefig(out_path, dpi=150 if not three_d else 110)
    pyplot.close(figure)
