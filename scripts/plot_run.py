#!/usr/bin/python3
"""Plots for one `tsmframe run` (called by `tsmframe run … --plot`; Debian python3-matplotlib).

    /usr/bin/python3 scripts/plot_run.py DIR

Reads DIR/results.json and DIR/steps.csv; writes DIR/plots/deformed.png|svg (the steps that
carry full state, up to 12 of them, elements drawn as their true deflected curves) and
DIR/plots/load-displacement.png|svg (λ against ux, uy, rz of every monitored node).
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
from report import draw_shape  # noqa: E402  (the element-curve drawing shared with the report)


def short_title(title, width=90, lines=3):
    """A model's title as at most `lines` lines of `width` characters (titles may be paragraphs)."""
    wrapped = textwrap.wrap(title or "", width)
    if len(wrapped) > lines:
        wrapped = wrapped[:lines]
        wrapped[-1] = wrapped[-1][: width - 1] + "…"
    return "\n".join(wrapped)


def main(directory):
    with open(os.path.join(directory, "results.json")) as f:
        results = json.load(f)
    plots = os.path.join(directory, "plots")
    os.makedirs(plots, exist_ok=True)
    states = [s for s in results["steps"] if "displacements" in s]
    if len(states) > 12:
        states = [states[round(k * (len(states) - 1) / 11)] for k in range(12)]
    fig, ax = plt.subplots(figsize=(8, 6))
    cmap = plt.get_cmap("viridis")
    draw_shape(ax, results, {"displacements": {str(n["id"]): [0, 0, 0] for n in results["nodes"]}},
               color="0.75", lw=1, label="undeformed")
    for k, s in enumerate(states):
        draw_shape(ax, results, s, color=cmap(k / max(1, len(states) - 1)), lw=1.3,
                   label=f"step {s['step']}, λ = {s['load_factor']:.4g}")
    ax.set_aspect("equal")
    ax.set_xlabel("x")
    ax.set_ylabel("y")
    ax.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.02, 1.0))  # beside a long, flat frame
    ax.set_title(short_title(results.get("title")) or "deformed shapes", fontsize=9)
    for ext in ("png", "svg"):
        fig.savefig(os.path.join(plots, f"deformed.{ext}"), dpi=130, bbox_inches="tight")
    plt.close(fig)

    with open(os.path.join(directory, "steps.csv"), newline="") as f:
        rows = list(csv.DictReader(f))
    columns = [c for c in (rows[0].keys() if rows else []) if c[:3] in ("ux_", "uy_", "rz_")]
    fig, ax = plt.subplots(figsize=(8, 5))
    lam = [0.0] + [float(r["load_factor"]) for r in rows]
    for c in columns:
        ax.plot([0.0] + [float(r[c]) for r in rows], lam, ".-", ms=3, lw=1, label=f"{c[:2]} of node {c[3:]}")
    ax.set_xlabel("displacement (ux, uy) or rotation (rz)")
    ax.set_ylabel("load factor λ")
    ax.grid(True, alpha=0.3)
    if columns:
        ax.legend(fontsize=8)
    ax.set_title("load–displacement")
    for ext in ("png", "svg"):
        fig.savefig(os.path.join(plots, f"load-displacement.{ext}"), dpi=130, bbox_inches="tight")
    plt.close(fig)
    print(f"plots: {plots}/deformed.png, load-displacement.png (and .svg)")


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "out")
