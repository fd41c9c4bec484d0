"""The model drawn before solving, from its drawing document (tsmframe-drawing/1, written by
`tsmframe plot` and the extension's model_drawing; docs/format.md, "Model drawing"): members,
supports by their usual symbols, hinges and end springs, springs to the ground, loads as arrows
(moments as arcs, follower loads dashed, pressures along their members, prescribed displacements
hollow), contact nodes and the members they may touch. Plain matplotlib on a dict: the command
line's script (scripts/plot_model.py) loads this file by its path, Model.plot() imports it.
"""
import math
import textwrap

import matplotlib.pyplot as plt
from matplotlib.lines import Line2D
from matplotlib.patches import Arc, Circle, FancyArrowPatch, Polygon, Rectangle

MEMBER = "black"
SUPPORT = "0.25"
CONTACT = "tab:orange"
CASE_COLOURS = ("tab:red", "tab:blue", "tab:green", "tab:purple", "tab:brown", "tab:pink")


def _unit(x, y):
    n = math.hypot(x, y)
    return (x / n, y / n) if n > 0 else (0.0, -1.0)


class _Frame:
    """Where things are: node positions, the elements at each node, the symbols' size."""

    def __init__(self, drawing):
        self.xy = {n["id"]: (n["x"], n["y"]) for n in drawing["nodes"]}
        xs = [p[0] for p in self.xy.values()] or [0.0]
        ys = [p[1] for p in self.xy.values()] or [0.0]
        self.size = math.hypot(max(xs) - min(xs), max(ys) - min(ys)) or 1.0
        self.symbol = 0.035 * self.size
        self.texts = {}  # per node: how many texts are written beside it
        self.at = {}
        for e in drawing["elements"]:
            a, b = e["nodes"]
            self.at.setdefault(a, []).append(b)
            self.at.setdefault(b, []).append(a)

    def away(self, node):
        """The unit direction pointing away from the elements at a node (down where none leads away)."""
        x, y = self.xy[node]
        sx = sum(_unit(self.xy[o][0] - x, self.xy[o][1] - y)[0] for o in self.at.get(node, []))
        sy = sum(_unit(self.xy[o][0] - x, self.xy[o][1] - y)[1] for o in self.at.get(node, []))
        return _unit(-sx, -sy) if math.hypot(sx, sy) > 1e-9 else (0.0, -1.0)


def _ground(ax, frame, base, normal, width):
    """A hatched ground line across `normal` at `base` (hatching on the far side)."""
    t = (-normal[1], normal[0])
    a = (base[0] - t[0] * width / 2, base[1] - t[1] * width / 2)
    b = (base[0] + t[0] * width / 2, base[1] + t[1] * width / 2)
    ax.plot([a[0], b[0]], [a[1], b[1]], color=SUPPORT, lw=1.5, zorder=3)
    h = 0.35 * frame.symbol
    for k in range(6):
        s = (k + 0.5) / 6
        p = (a[0] + s * (b[0] - a[0]), a[1] + s * (b[1] - a[1]))
        ax.plot([p[0], p[0] + h * (normal[0] - t[0])], [p[1], p[1] + h * (normal[1] - t[1])], color=SUPPORT, lw=0.8, zorder=3)


def _support(ax, frame, support):
    node, held = support["node"], set(support["held"])
    x, y = frame.xy[node]
    s = frame.symbol
    translations = held & {"ux", "uy", "n"}
    away = frame.away(node)
    if "along" in support:  # a skew roller: held along the plane's normal
        tx, ty = support["along"]
        normal = (-ty, tx)
    elif translations == {"ux"}:
        normal = (-1.0, 0.0)
    elif translations == {"uy"}:
        normal = (0.0, -1.0)
    elif "rz" in held:  # fixed: the wall behind the member's end
        normal = away
    else:  # a pin: drawn under its node, over it where the structure hangs from it
        normal = (0.0, 1.0) if away[1] > 0.7 else (0.0, -1.0)
    if normal[0] * away[0] + normal[1] * away[1] < -1e-9:  # a roller on the side away from the structure
        normal = (-normal[0], -normal[1])
    t = (-normal[1], normal[0])
    if translations and "rz" in held and len(translations) == 2:  # fixed: a wall
        _ground(ax, frame, (x, y), normal, 2.2 * s)
        return
    if len(translations) == 2 or len(translations) == 1:  # a pin's or a roller's triangle
        base = (x + normal[0] * s, y + normal[1] * s)
        corners = [(x, y), (base[0] + t[0] * 0.6 * s, base[1] + t[1] * 0.6 * s), (base[0] - t[0] * 0.6 * s, base[1] - t[1] * 0.6 * s)]
        ax.add_patch(Polygon(corners, closed=True, fill=False, edgecolor=SUPPORT, lw=1.2, zorder=3))
        if len(translations) == 1:  # rollers under the triangle
            r = 0.17 * s
            for side in (-0.35, 0.35):
                c = (base[0] + t[0] * side * s + normal[0] * r, base[1] + t[1] * side * s + normal[1] * r)
                ax.add_patch(Circle(c, r, fill=False, edgecolor=SUPPORT, lw=0.9, zorder=3))
            base = (base[0] + normal[0] * 2 * r, base[1] + normal[1] * 2 * r)
        _ground(ax, frame, base, normal, 1.6 * s)
    if "rz" in held:  # a rotation held (alone, or beside one translation): a filled square
        q = 0.3 * s
        ax.add_patch(Rectangle((x - q / 2, y - q / 2), q, q, color=SUPPORT, zorder=4))


def _zigzag(ax, start, direction, length, colour):
    t = (-direction[1], direction[0])
    w = 0.12 * length
    pts = [start]
    for k in range(1, 8):
        s = k / 8
        side = 0 if k in (1, 7) else (w if k % 2 else -w)
        pts.append((start[0] + direction[0] * length * s + t[0] * side, start[1] + direction[1] * length * s + t[1] * side))
    pts.append((start[0] + direction[0] * length, start[1] + direction[1] * length))
    ax.plot([p[0] for p in pts], [p[1] for p in pts], color=colour, lw=0.9, zorder=3)
    return pts[-1]


def _spring(ax, frame, spring):
    x, y = frame.xy[spring["node"]]
    s = frame.symbol
    if spring["kind"] == "rotation":
        ax.add_patch(Arc((x, y), 1.2 * s, 1.2 * s, theta1=200, theta2=520, color=SUPPORT, lw=0.9, zorder=3))
        ax.plot([x - 0.6 * s, x - 0.6 * s], [y - 0.4 * s, y + 0.2 * s], color=SUPPORT, lw=1.5)
        return
    d = spring["direction"]
    away = frame.away(spring["node"])
    if d[0] * away[0] + d[1] * away[1] < 0:
        d = (-d[0], -d[1])
    end = _zigzag(ax, (x, y), d, 1.6 * s, SUPPORT)
    _ground(ax, frame, end, d, 0.8 * s)


def _ends(ax, frame, element):
    """Hinges (open circles) and end springs (open squares) just inside the element's ends."""
    a, b = element["nodes"]
    (xa, ya), (xb, yb) = frame.xy[a], frame.xy[b]
    length = math.hypot(xb - xa, yb - ya)
    if length == 0:
        return
    offset = min(0.35 * frame.symbol, 0.3 * length) / length
    release = element.get("release")
    springs = element.get("end_springs", {})
    for end, s in (("start", offset), ("end", 1 - offset)):
        p = (xa + s * (xb - xa), ya + s * (yb - ya))
        if release in (end, "both"):
            ax.add_patch(Circle(p, 0.22 * frame.symbol, facecolor="white", edgecolor=MEMBER, lw=1.0, zorder=5))
        elif end in springs:
            q = 0.4 * frame.symbol
            ax.add_patch(Rectangle((p[0] - q / 2, p[1] - q / 2), q, q, facecolor="white", edgecolor=MEMBER, lw=1.0, zorder=5))


def _arrow(ax, head, vector, colour, **style):
    tail = (head[0] - vector[0], head[1] - vector[1])
    ax.add_patch(FancyArrowPatch(tail, head, arrowstyle="-|>", mutation_scale=9, color=colour, lw=1.1, zorder=6, **style))


def _moment(ax, frame, node, mz, colour):
    x, y = frame.xy[node]
    r = 0.9 * frame.symbol
    ax.add_patch(Arc((x, y), 2 * r, 2 * r, theta1=30, theta2=300, color=colour, lw=1.1, zorder=6))
    angle = math.radians(300 if mz > 0 else 30)
    tip = (x + r * math.cos(angle), y + r * math.sin(angle))
    turn = 1 if mz > 0 else -1  # the head along the arc's direction of turning
    d = (-math.sin(angle) * turn, math.cos(angle) * turn)
    _arrow(ax, tip, (0.3 * r * d[0], 0.3 * r * d[1]), colour)


def _arrows(ax, heads, vectors, colour, dashed=False):
    """Arrows ending at `heads`, each `vectors` long, as one artist (a distributed load's hundred
    lumped forces drawn one patch each took seconds)."""
    if not heads:
        return
    tails = [(x - dx, y - dy) for (x, y), (dx, dy) in zip(heads, vectors)]
    ax.quiver([t[0] for t in tails], [t[1] for t in tails], [v[0] for v in vectors], [v[1] for v in vectors],
              angles="xy", scale_units="xy", scale=1.0, color=colour, width=0.0025, headwidth=4, headlength=6,
              headaxislength=5.5, zorder=6, linestyle="--" if dashed else "-", facecolor="none" if dashed else colour,
              edgecolor=colour, linewidth=0.8 if dashed else 0.0)


def _load_case(ax, frame, drawing, case, colour, scale):
    labelled = len(case["loads"]) + len(case["follower"]) <= 12  # a distributed load's many arrows unlabelled
    heads, vectors = [], []
    for node, fx, fy, mz in case["loads"]:
        x, y = frame.xy[node]
        if fx or fy:
            heads.append((x, y))
            vectors.append((fx * scale, fy * scale))
            if labelled:
                ax.annotate(f"{math.hypot(fx, fy):.4g}", (x - fx * scale, y - fy * scale), fontsize=7, color=colour)
        if mz:
            _moment(ax, frame, node, mz, colour)
            if labelled:
                ax.annotate(f"{mz:.4g}", (x, y), xytext=(8, 8), textcoords="offset points", fontsize=7, color=colour)
    _arrows(ax, heads, vectors, colour)
    _arrows(ax, [frame.xy[node] for node, _, _ in case["follower"]], [(fx * scale, fy * scale) for _, fx, fy in case["follower"]],
            colour, dashed=True)
    pressures = dict((m, p) for m, p in case["pressures"])
    heads, vectors = [], []
    for e in drawing["elements"]:
        p = pressures.get(e["member"])
        if not p:
            continue
        (xa, ya), (xb, yb) = (frame.xy[n] for n in e["nodes"])
        t = _unit(xb - xa, yb - ya)
        push = (t[1] * math.copysign(1, p), -t[0] * math.copysign(1, p))  # from the member's left to its right
        heads.append(((xa + xb) / 2, (ya + yb) / 2))
        vectors.append((push[0] * 1.5 * frame.symbol, push[1] * 1.5 * frame.symbol))
    _arrows(ax, heads, vectors, colour, dashed=True)
    for p in case["prescribed"]:
        x, y = frame.xy[p["node"]]
        text = f'{p["dof"]} {"+" if p["increment"] else "="} {p["value"]:.4g}'
        if p["dof"] != "rz" and p["value"]:
            d = (1.0, 0.0) if p["dof"] == "ux" else (0.0, 1.0)
            d = (d[0] * math.copysign(1, p["value"]), d[1] * math.copysign(1, p["value"]))
            length = 2.5 * frame.symbol
            ax.add_patch(FancyArrowPatch((x, y), (x + d[0] * length, y + d[1] * length), arrowstyle="simple", mutation_scale=12,
                                         facecolor="white", edgecolor=colour, lw=1.0, zorder=6))
        line = frame.texts.get(p["node"], 0)  # the texts at one node one under the other
        frame.texts[p["node"]] = line + 1
        ax.annotate(text, (x, y), xytext=(6, -12 - 10 * line), textcoords="offset points", fontsize=7, color=colour)


def _force_scale(drawing, frame):
    """Length per unit force: the largest force drawn at 12 % of the model's size."""
    largest = 0.0
    for case in drawing.get("load_cases", []):
        for _, fx, fy, *_ in case["loads"] + case["follower"]:
            largest = max(largest, math.hypot(fx, fy))
    return 0.12 * frame.size / largest if largest > 0 else 0.0


def plot_model(drawing, ax=None, node_labels=None):
    """Draw the model of a drawing document — or of a results.json, which carries the same keys —
    on `ax` (a new figure's if None); returns ax.
    node_labels: label every node with its id (default: where the model has at most 40 nodes)."""
    if ax is None:
        _, ax = plt.subplots(figsize=(8, 6))
    frame = _Frame(drawing)
    touched = {m for c in drawing.get("contacts", []) for m in c["members"]}
    # Each kind of line one artist, broken between elements (a line per element is slow to draw).
    members, shaded = ([], []), ([], [])
    for e in drawing["elements"]:
        (xa, ya), (xb, yb) = (frame.xy[n] for n in e["nodes"])
        for lines in (members, shaded) if e["member"] in touched else (members,):
            lines[0].extend((xa, xb, math.nan))
            lines[1].extend((ya, yb, math.nan))
        _ends(ax, frame, e)
    if shaded[0]:
        ax.plot(*shaded, color=CONTACT, lw=6, alpha=0.3, solid_capstyle="butt", zorder=1)
    ax.plot(*members, color=MEMBER, lw=1.6, zorder=2)
    for s in drawing.get("supports", []):
        _support(ax, frame, s)
    hinged = any("release" in e for e in drawing["elements"])
    sprung = any("end_springs" in e for e in drawing["elements"])
    springs = drawing.get("springs", [])
    every = max(1, math.ceil(len(springs) / 40))  # a foundation's springs, thinned to about 40
    for s in springs[::every]:
        _spring(ax, frame, s)
    scale = _force_scale(drawing, frame)
    handles = [Line2D([], [], color=MEMBER, lw=1.6, label="members")]
    if hinged:
        handles.append(Line2D([], [], ls="", marker="o", mfc="white", mec=MEMBER, label="hinges"))
    if sprung:
        handles.append(Line2D([], [], ls="", marker="s", mfc="white", mec=MEMBER, label="end springs"))
    if every > 1:
        handles.append(Line2D([], [], color=SUPPORT, lw=0.9, label=f"{len(springs)} springs, every {every}th drawn"))
    for k, case in enumerate(drawing.get("load_cases", [])):
        colour = CASE_COLOURS[k % len(CASE_COLOURS)]
        _load_case(ax, frame, drawing, case, colour, scale)
        if any(case[key] for key in ("loads", "follower", "pressures", "prescribed")):
            name = case["name"] or (f"stage {k + 1}" if len(drawing.get("load_cases", [])) > 1 else "loads")
            handles.append(Line2D([], [], color=colour, marker=">", label=name + " (λ = 1)"))
    contact_nodes = [n for c in drawing.get("contacts", []) for n in c["nodes"]]
    if contact_nodes:
        ax.plot([frame.xy[n][0] for n in contact_nodes], [frame.xy[n][1] for n in contact_nodes], "o", ms=4,
                color=CONTACT, zorder=7)
        handles.append(Line2D([], [], color=CONTACT, marker="o", ms=4, lw=6, alpha=0.6,
                              label=f"{len(contact_nodes)} contact node{'s' if len(contact_nodes) != 1 else ''}, members they may touch"))
    if node_labels or (node_labels is None and len(frame.xy) <= 40):
        for node, (x, y) in frame.xy.items():
            ax.annotate(str(node), (x, y), xytext=(3, 3), textcoords="offset points", fontsize=7, color="0.35")
    ax.set_aspect("equal")
    ax.margins(0.12)
    ax.set_xlabel("x")
    ax.set_ylabel("y")
    title = "\n".join(textwrap.wrap(drawing.get("title", ""), 90)[:2])
    ax.set_title(title, fontsize=9)
    if "mechanism" in drawing:  # under the axes (a picture saved with bbox_inches="tight" keeps it)
        ax.annotate("\n".join(textwrap.wrap("Not solvable: " + drawing["mechanism"], 110)), (0.5, 0.0), xycoords="axes fraction",
                    xytext=(0, -36), textcoords="offset points", ha="center", va="top", fontsize=8, color="tab:red",
                    annotation_clip=False)
    ax.legend(handles=handles, fontsize=7, loc="best")
    return ax
