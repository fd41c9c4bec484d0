"""Deformed shapes drawn from a results.json (Debian's python3-matplotlib): what report.py and
plot_run.py share. The curves are the solver's own: results.json's "curves" (written by
`tsmframe run --curves`, or `--plot`), each element's deflected shape with its hinges and end
springs. A results.json without them (an older one, or a run without --curves) is drawn with
straight chords between the nodes, and `has_curves` says so for the legend: no shape formula is
derived here.

    import shapes
    shapes.draw_shape(ax, results, step, scale=shapes.magnification(results, states), color="C0")
"""
import importlib.util
import math
import os


def size_of(results):
    """The diagonal of the nodes' bounding box as drawn."""
    xs = [n["x"] for n in results["nodes"]]
    ys = [n["y"] for n in results["nodes"]]
    return math.hypot(max(xs) - min(xs), max(ys) - min(ys))


def magnification(results, states):
    """1, or a round factor (1, 2 or 5 × 10^k) that makes the largest translation of an element's
    node about a tenth of the model's size, where it is less than 2 % of it: small deflections
    drawn to scale are a flat line."""
    size = size_of(results)
    drawn = {str(n) for e in results["elements"] for n in e["nodes"]}  # a pusher's own travel is no deflection
    largest = max((math.hypot(u[0], u[1]) for s in states for k, u in s["displacements"].items() if k in drawn), default=0.0)
    if size <= 0.0 or largest <= 0.0 or largest >= 0.02 * size:
        return 1.0
    wanted = 0.1 * size / largest
    power = 10.0 ** math.floor(math.log10(wanted))
    return max(m * power for m in (1.0, 2.0, 5.0) if m * power <= wanted)


def has_curves(results):
    """Whether every step with state carries the solver's element curves (else chords are drawn)."""
    return all("curves" in s for s in results["steps"] if "displacements" in s)


def undeformed(results):
    """A state with no displacement (drawn as the straight elements)."""
    return {"displacements": {str(n["id"]): [0.0, 0.0, 0.0] for n in results["nodes"]}}


def element_lines(results, step, scale=1.0):
    """[(xs, ys)] per element at `step`: its curve from step["curves"] with the displacements of its
    points × `scale` (a point at s along the element moves from X_i + s (X_j − X_i)), or, where the
    step has no curves, the straight chord between its displaced nodes."""
    nodes = {n["id"]: (n["x"], n["y"]) for n in results["nodes"]}
    d = step["displacements"]
    curves = step.get("curves")
    lines = []
    for e in results["elements"]:
        a, b = e["nodes"]
        (Xi, Yi), (Xj, Yj) = nodes[a], nodes[b]
        if curves is None:
            ui, uj = d[str(a)], d[str(b)]
            lines.append(([Xi + scale * ui[0], Xj + scale * uj[0]], [Yi + scale * ui[1], Yj + scale * uj[1]]))
            continue
        flat = curves[str(e["id"])]
        last = len(flat) // 2 - 1
        xs, ys = [], []
        for k in range(last + 1):
            s = k / last
            X, Y = Xi + s * (Xj - Xi), Yi + s * (Yj - Yi)
            xs.append(X + scale * (flat[2 * k] - X))
            ys.append(Y + scale * (flat[2 * k + 1] - Y))
        lines.append((xs, ys))
    return lines


def draw_shape(ax, results, step, scale=1.0, **style):
    """Every element at `step` (element_lines) as one line broken between elements (one artist
    per state: a line per element made a 400-element model's plots take 25 s), one legend entry."""
    xs, ys = [], []
    for x, y in element_lines(results, step, scale):
        xs += list(x) + [math.nan]
        ys += list(y) + [math.nan]
    ax.plot(xs, ys, **style)


def model_plot():
    """The package's model drawing (python/tsmframe/model_plot.py, what Model.plot() draws), loaded
    by its path: the scripts run with Debian's python3, the extension need not be built."""
    path = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "python", "tsmframe", "model_plot.py")
    spec = importlib.util.spec_from_file_location("model_plot", path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module
