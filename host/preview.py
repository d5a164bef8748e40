"""A picture of the planned path over the drawing (matplotlib, the ``plot`` extra)."""
import math


def draw(plan, result, out_path, title=""):
    """Write ``out_path`` (PNG): the drawing in grey, the card's path (the model's
    step points) in colour, rapid moves dashed."""
    import matplotlib

    matplotlib.use("Agg")
    from matplotlib import pyplot

    machine = plan.machine
    figure, axes = pyplot.subplots(figsize=(8, 8))
    for item in plan.drawing:
        if not hasattr(item, "point"):
            continue
        samples = max(2, min(400, int(item.length * max(machine.steps_per_mm) / 4) + 2))
        if hasattr(item, "sweep"):
            samples = max(samples, int(item.sweep / (math.pi / 90)) + 2)
        points = [item.point(i / (samples - 1)) for i in range(samples)]
        axes.plot(*zip(*points), color="0.6", linewidth=3, linestyle="--" if item.rapid else "-",
                  solid_capstyle="round")
    for primitive, points in result.points:
        rapid = plan.drawing[primitive].rapid
        axes.plot(*zip(*(machine.mm(p) for p in points)), color="tab:orange" if rapid else "tab:blue",
                  linewidth=0.8, linestyle="--" if rapid else "-")
    axes.set_aspect("equal")
    axes.set_xlabel("X (mm)")
    axes.set_ylabel("Y (mm)")
    axes.set_title(title or f"planned path (blue: fed, orange: rapid) over the drawing (grey); "
                            f"max deviation {result.max_deviation_steps:.2f} steps", fontsize=9)
    figure.savefig(out_path, dpi=150)
    pyplot.close(figure)
