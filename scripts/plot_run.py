#!/usr/bin/python3
"""Plots for one `tsmframe run` (called by `tsmframe run … --plot`; Debian python3-matplotlib).

    /usr/bin/python3 scripts/plot_run.py DIR [SHOWN]

Reads DIR/results.json and DIR/steps.csv; writes DIR/plots/model.png|svg (the model as drawn
before solving: supports, loads, contacts — `tsmframe plot`'s picture), DIR/plots/deformed.png|svg (the steps that
carry full state, up to 12 of them, elements drawn as the deflected curves results.json carries
— straight chords, and the legend says so, where it has none) and
DIR/plots/load-displacement.png|svg (λ against ux, uy, rz of every monitored node, but those that
only carry rounding noise) and, where prescribed displacements drive the model,
DIR/plots/force-displacement.png|svg (the reactions there against those displacements). SHOWN:
the directory as the closing line names it (`tsmframe run` plots into its temporary directory).
"""
import csv
import json
import os
import sys
import textwrap

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from shapes import draw_shape, has_curves, magnification, model_plot, size_of, undeformed  # noqa: E402  (shared with report.py)


def short_title(title, width=90, lines=3):
    """A model's title as at most `lines` lines of `width` characters (titles may be paragraphs)."""
    wrapped = textwrap.wrap(title or "", width)
    if len(wrapped) > lines:
        wrapped = wrapped[:lines]
        wrapped[-1] = wrapped[-1][: width - 1] + "…"
    return "\n".join(wrapped)


def visible_columns(results, rows, noise=1e-7):
    """The monitored dofs (steps.csv columns) worth a curve: a dof that stays within `noise` of the
    largest movement is rounding noise (a rotation compared as a rotation times the model's size),
    e.g. the 1e-9 rad a symmetric ring's crown turns: plotted, it filled the rotation axis."""
    columns = [c for c in (rows[0].keys() if rows else []) if c[:3] in ("ux_", "uy_", "rz_")]
    size = size_of(results) or 1.0
    reach = {c: max(abs(float(r[c])) for r in rows) * (size if c[:2] == "rz" else 1.0) for c in columns}
    floor = max(noise * max(reach.values(), default=0.0), 1e-12 * size)  # nothing moving at all: no curve
    return [c for c in columns if reach[c] > floor]


def moved_curves(results, rows):
    """Force against displacement where prescribed displacements move dofs (steps.csv's Rx_, Ry_,
    Mz_ columns: the reactions there): per such dof, its displacement — λ times its value at λ = 1,
    read off the newest state — and its reaction; and, where several dofs of one kind move alike
    (a plate pushed at both ends), their sum. [(label, displacements, forces)], [] if none."""
    columns = [c for c in (rows[0].keys() if rows else []) if c[:3] in ("Rx_", "Ry_", "Mz_")]
    states = [s for s in results["steps"] if "displacements" in s and float(s["load_factor"]) != 0.0]
    if not columns or not states or "stage" in rows[0]:  # a staged run's λ starts again each stage
        return []
    last = states[-1]
    kind = {"Rx": 0, "Ry": 1, "Mz": 2}
    curves, groups = [], {}
    for c in columns:
        node = c[3:]
        target = last["displacements"][node][kind[c[:2]]] / float(last["load_factor"])
        u = [0.0] + [float(r["load_factor"]) * target for r in rows]
        f = [0.0] + [float(r[c]) for r in rows]
        curves.append((f"{c[:2]} at node {node} ({'uy' if c[:2] == 'Ry' else 'ux' if c[:2] == 'Rx' else 'rz'} prescribed)", u, f))
        groups.setdefault((c[:2], round(target, 12)), []).append((u, f))
    for (name, _), members in groups.items():
        if len(members) > 1:
            total = [sum(v) for v in zip(*(f for _, f in members))]
            curves.append((f"{name}, sum over {len(members)} nodes moved alike", members[0][0], total))
    return curves


def force_displacement(results, rows, plots):
    """plots/force-displacement.png|svg where prescribed displacements drive the model; False if none."""
    curves = moved_curves(results, rows)
    if not curves:
        return False
    fig, ax = plt.subplots(figsize=(8, 5))
    for i, (label, u, f) in enumerate(curves):
        ax.plot(u, f, ".-" if "sum" not in label else "-", ms=3, lw=1.5 if "sum" in label else 1, color=f"C{i % 10}", label=label)
    ax.set_xlabel("prescribed displacement (rotation for Mz)")
    ax.set_ylabel("reaction (the force driving it)")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8)
    ax.set_title("force–displacement at the prescribed dofs")
    for ext in ("png", "svg"):
        fig.savefig(os.path.join(plots, f"force-displacement.{ext}"), dpi=130, bbox_inches="tight")
    plt.close(fig)
    return True


def stage_runs(rows):
    """steps.csv's rows by stage, in order: [(stage, rows)] (one run of all rows without stages)."""
    runs = []
    for r in rows:
        stage = r.get("stage", "1")
        if not runs or runs[-1][0] != stage:
            runs.append((stage, []))
        runs[-1][1].append(r)
    return runs or [("1", [])]


def main(directory, shown=None):
    with open(os.path.join(directory, "results.json")) as f:
        results = json.load(f)
    plots = os.path.join(directory, "plots")
    os.makedirs(plots, exist_ok=True)
    states = [s for s in results["steps"] if "displacements" in s]
    if len(states) > 12:
        states = [states[round(k * (len(states) - 1) / 11)] for k in range(12)]
    fig, ax = plt.subplots(figsize=(8, 6))
    cmap = plt.get_cmap("viridis")
    draw_shape(ax, results, undeformed(results), color="0.75", lw=1, label="undeformed")
    scale = magnification(results, states)
    for k, s in enumerate(states):
        draw_shape(ax, results, s, scale=scale, color=cmap(k / max(1, len(states) - 1)), lw=1.3,
                   label=f"step {s['step']}, λ = {s['load_factor']:.4g}")
    ax.set_aspect("equal")
    ax.set_xlabel("x")
    ax.set_ylabel("y")
    notes = ([f"displacements × {scale:g}"] if scale != 1.0 else []) + \
        ([] if has_curves(results) else ["straight chords: results.json has no curves"])
    ax.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.02, 1.0),  # beside a long, flat frame
              title="\n".join(notes) or None, title_fontsize=7)
    ax.set_title(short_title(results.get("title")) or "deformed shapes", fontsize=9)
    for ext in ("png", "svg"):
        fig.savefig(os.path.join(plots, f"deformed.{ext}"), dpi=130, bbox_inches="tight")
    plt.close(fig)

    with open(os.path.join(directory, "steps.csv"), newline="") as f:
        rows = list(csv.DictReader(f))
    columns = visible_columns(results, rows)
    translations = [c for c in columns if c[:2] != "rz"]
    rotations = [c for c in columns if c[:2] == "rz"]
    fig, ax = plt.subplots(figsize=(8, 5))
    # Rotations (radians) on an axis of their own, at the top, when there are translations too:
    # on one axis a frame's metres or millimetres squash them flat, or they squash the metres.
    rotation_ax = ax.twiny() if translations and rotations else ax
    lines = []
    stages = stage_runs(rows)
    for i, c in enumerate(columns):  # colours by column: the second axis would restart the cycle
        on = rotation_ax if c in rotations else ax
        start = 0.0
        for k, (stage, stage_rows) in enumerate(stages):  # each stage from where the one before ended, at its λ = 0
            style = ("x" if on is not ax else ".") + ("-", "--", ":", "-.")[k % 4]
            label = f"{c[:2]} of node {c[3:]}" + (f", stage {stage}" if len(stages) > 1 else "")
            lines += on.plot([start] + [float(r[c]) for r in stage_rows], [0.0] + [float(r["load_factor"]) for r in stage_rows],
                             style, ms=3, lw=1, color=f"C{i % 10}", label=label)
            start = float(stage_rows[-1][c])
    if rotation_ax is ax:
        ax.set_xlabel("rotation rz (rad)" if not translations else "displacement (ux, uy)")
    else:
        ax.set_xlabel("displacement (ux, uy), bottom axis")
        rotation_ax.set_xlabel("rotation rz (rad), top axis, dashed")
    ax.set_ylabel("load factor λ" + (" (each stage's own)" if len(stages) > 1 else ""))
    ax.grid(True, alpha=0.3)
    if columns:
        ax.legend(lines, [line.get_label() for line in lines], fontsize=8)
    ax.set_title("load–displacement")
    for ext in ("png", "svg"):
        fig.savefig(os.path.join(plots, f"load-displacement.{ext}"), dpi=130, bbox_inches="tight")
    plt.close(fig)
    written = ["model.png", "deformed.png", "load-displacement.png"]
    fig, ax = plt.subplots(figsize=(8, 6))  # the model as drawn: results.json carries its supports, loads, contacts
    model_plot().plot_model(results, ax)
    for ext in ("png", "svg"):
        fig.savefig(os.path.join(plots, f"model.{ext}"), dpi=130, bbox_inches="tight")
    plt.close(fig)
    if force_displacement(results, rows, plots):
        written.append("force-displacement.png")
    print(f"plots: {os.path.join(shown or directory, 'plots')}/{', '.join(written)} (and .svg)")


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "out", sys.argv[2] if len(sys.argv) > 2 else None)
