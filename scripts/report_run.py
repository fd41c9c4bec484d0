#!/usr/bin/python3
"""One run's report (called by `tsmframe run MODEL.json --report`): DIR/report.html, one
self-contained page (images embedded) of what an engineer reads — the model as drawn, how the run
ended and its notes, the deformed shapes, λ against the monitored dofs, the N, V and M diagrams at
the last state, the buckling modes, the contacts' positions — drawn by the tsmframe package's
own plots from the results read back (Result.load).

    /usr/bin/python3 scripts/report_run.py PYTHON_DIR DIR MODEL.json [SHOWN]

PYTHON_DIR: where the built package is (build/python); SHOWN: the directory as the closing line
names it (`tsmframe run` writes into its temporary directory).
"""
import base64
import csv
import html
import io
import json
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from shapes import magnification  # noqa: E402  (shared with plot_run.py and report.py)


def image(fig):
    """The figure as an embedded PNG."""
    buffer = io.BytesIO()
    fig.savefig(buffer, format="png", dpi=110, bbox_inches="tight")
    plt.close(fig)
    return f'<img src="data:image/png;base64,{base64.b64encode(buffer.getvalue()).decode()}" style="max-width:100%">'


def summary(r):
    converged = int(r.converged.sum())
    text = f"{r.status}: {converged} converged steps, {int(r.iterations.sum())} iterations"
    if converged:
        text += f", λ = {r.load_factor[r.converged == 1][-1]:.6g} at the end"
    return text + (f" — {r.message}" if r.message else "")


def monitored(directory):
    """(node, dof) of steps.csv's ux_/uy_/rz_ columns, as the run monitored them."""
    path = os.path.join(directory, "steps.csv")
    if not os.path.exists(path):
        return []
    with open(path, newline="") as f:
        header = next(csv.reader(f), [])
    return [(int(c[3:]), c[:2]) for c in header if c[:3] in ("ux_", "uy_", "rz_")]


def sections(r, directory):
    """[(heading, html)] of the page's figures."""
    results = json.loads(r.results_json)
    parts = []
    fig, ax = plt.subplots(figsize=(8, 5.5))
    r.plot_model(ax=ax)
    parts.append(("The model", image(fig)))
    if len(r.state_steps):
        states = list(range(len(r.state_steps)))
        if len(states) > 6:
            states = [states[round(k * (len(states) - 1) / 5)] for k in range(6)]
        kept = [s for s in results["steps"] if "displacements" in s]
        scale = magnification(results, [kept[k] for k in states])
        fig, ax = plt.subplots(figsize=(8, 5.5))
        r.plot_shape(steps=states, ax=ax, scale=scale)
        parts.append(("Deformed shapes", image(fig)))
        dofs = monitored(directory)
        if dofs:
            fig, ax = plt.subplots(figsize=(8, 5))
            for node, dof in dofs:
                r.plot_load_displacement(node, dof, ax=ax)
            ax.set_xlabel("displacement (rotation for rz)")
            parts.append(("Load–displacement", image(fig)))
        fig, axes = plt.subplots(3, 1, figsize=(8, 14))
        for ax, q in zip(axes, ("N", "V", "M")):
            r.plot_diagram(q, ax=ax)
            lam = r.load_factor[list(r.step).index(r.state_steps[-1])]
            ax.set_title(f"{q} at step {r.state_steps[-1]} (λ = {lam:.6g})", fontsize=9)
        parts.append(("N, V and M at the last state", image(fig)))
    for k in range(min(4, len(r.buckling_load_factors))):
        fig, ax = plt.subplots(figsize=(8, 4.5))
        r.plot_buckling(k, ax=ax)
        where = f"from step {r.buckling_step}" if getattr(r, "buckling_step", 0) else "at the unloaded state"
        parts.append((f"Buckling mode {k + 1} (linearised, {where})", image(fig)))
    if len(r.contact_nodes) and (r.contact_element > 0).any():
        fig, ax = plt.subplots(figsize=(8, 4.5))
        r.plot_contact(ax=ax)
        parts.append(("Contact positions", image(fig)))
    return parts


def main(python_dir, directory, model, shown=None):
    sys.path.insert(0, python_dir)
    import tsmframe as tf
    r = tf.Result.load(os.path.join(directory, "results.json"), model=model)
    e = html.escape
    title = e(json.loads(r.results_json).get("title") or os.path.basename(model))
    page = [f"""<!doctype html><html><head><meta charset="utf-8"><title>tsmframe: {title}</title>
<style>body{{font-family:sans-serif;max-width:1000px;margin:2em auto;line-height:1.4}}</style></head><body>
<h1>{title}</h1><p><code>{e(model)}</code>, run by tsmframe {e(tf.__version__)}.</p>
<p><b>{e(summary(r))}</b></p>"""]
    if r.buckling_load_factors.size:
        page.append("<p>Linearised critical load factors: " + ", ".join(f"{x:.6g}" for x in r.buckling_load_factors) + "</p>")
    if r.notes:
        page.append("<h2>Notes</h2><ul>" + "".join(f"<li>{e(n)}</li>" for n in r.notes) + "</ul>")
    for heading, figure in sections(r, directory):
        page.append(f"<h2>{e(heading)}</h2>{figure}")
    page.append("</body></html>")
    temporary = os.path.join(directory, f"report.tmp-{os.getpid()}.html")
    with open(temporary, "w") as f:
        f.write("\n".join(page))
    os.replace(temporary, os.path.join(directory, "report.html"))
    print(f"report: {os.path.join(shown or directory, 'report.html')}")


if __name__ == "__main__":
    main(*sys.argv[1:5])
