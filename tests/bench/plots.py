"""The benchmark's plots (matplotlib, small PNGs): time against error with the Pareto front, and scaling."""

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

# "spindrift" is a one-frame process's first frame; "spindrift, warm frame" the same frame in a running renderer,
# measured as VTK's frames and Cycles' renders are (tests/bench/method_notes.md, "Time").
METHOD_STYLES = {"spindrift": ("tab:blue", "o"), "spindrift, warm frame": ("tab:cyan", "D"),
                 "vtk": ("tab:green", "s"), "cycles": ("tab:red", "^")}


def pareto_front(points):
    """The points no other point beats in both time and error (lower is better in both), sorted by time."""
    front = []
    for time_ms, error, *rest in sorted(points, key=lambda p: (p[0], p[1])):
        if not front or error < front[-1][1]:
            front.append((time_ms, error, *rest))
    return front


def time_vs_error(points, error_label, path, title):
    """`points`: (time_ms, error, method, label) tuples. Log time axis; the Pareto front over all methods."""
    figure, axes = plt.subplots(figsize=(7.5, 4.6), dpi=90)
    for method, (colour, marker) in METHOD_STYLES.items():
        own = [p for p in points if p[2] == method]
        if own:
            axes.scatter([p[0] for p in own], [p[1] for p in own], c=colour, marker=marker, s=28, label=method,
                         zorder=3)
    for time_ms, error, method, label in points:
        if method == "spindrift, warm frame":
            continue  # the legend tells them apart; their labels would cover the one-frame points'
        if method != "spindrift" or label.startswith(("plane_fit", "none", "max_refr")):
            axes.annotate(label, (time_ms, error), fontsize=6, xytext=(3, 2), textcoords="offset points")
    front = pareto_front([p for p in points if p[1] == p[1]])
    axes.step([p[0] for p in front], [p[1] for p in front], where="post", c="k", lw=0.8, ls="--",
              label="Pareto front", zorder=2)
    axes.set_xscale("log")
    axes.set_xlabel("time per frame (ms, log)")
    axes.set_ylabel(error_label)
    axes.set_title(title, fontsize=10)
    axes.grid(True, which="both", alpha=0.3)
    axes.legend(fontsize=8)
    figure.tight_layout()
    figure.savefig(path)
    plt.close(figure)


def scaling(series, x_label, path, title):
    """`series`: {name: (xs, time_ms, memory_mib)}; time on the left axis, peak host memory on the right."""
    figure, time_axes = plt.subplots(figsize=(7.5, 4.2), dpi=90)
    memory_axes = time_axes.twinx()
    for index, (name, (xs, times, memories)) in enumerate(series.items()):
        colour = f"C{index}"
        time_axes.plot(xs, times, marker="o", c=colour, label=f"{name}: frame time")
        memory_axes.plot(xs, memories, marker="x", ls=":", c=colour, label=f"{name}: peak host memory")
    for axes in (time_axes, memory_axes):
        axes.set_xscale("log")
        axes.set_yscale("log")
    time_axes.set_xlabel(x_label)
    time_axes.set_ylabel("frame time (ms)")
    memory_axes.set_ylabel("peak host memory (MiB)")
    time_axes.grid(True, which="both", alpha=0.3)
    handles = time_axes.get_legend_handles_labels()
    more = memory_axes.get_legend_handles_labels()
    time_axes.legend(handles[0] + more[0], handles[1] + more[1], fontsize=7, loc="upper left")
    time_axes.set_title(title, fontsize=10)
    figure.tight_layout()
    figure.savefig(path)
    plt.close(figure)
