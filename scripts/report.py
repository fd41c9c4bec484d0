#!/usr/bin/python3
"""The paper's two studies as plots and a one-page report, from the files `scripts/run.sh`
leaves in out/ (Debian's /usr/bin/python3 with python3-matplotlib; nothing else).

    /usr/bin/python3 scripts/report.py [OUT]      (default OUT = out)

Reads   OUT/studies/fig3/study.csv, OUT/studies/fig7/study.csv and cases/*/steps.csv,
        OUT/cantilever-circle/results.json, OUT/contact-push/results.json, and every
        OUT/<example>/results.json of examples/*.json (a section of their shapes and notes)
Writes  OUT/plots/*.png and *.svg, OUT/report.html (self-contained: images embedded)
"""
import base64
import csv
import html
import json
import math
import os
import sys
from collections import defaultdict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from shapes import draw_shape, has_curves, magnification, model_plot, undeformed  # noqa: E402  (shared with plot_run.py)

COLOURS = {"euler-bernoulli": "tab:red", "timoshenko": "tab:blue"}
NAMES = {"euler-bernoulli": "Euler–Bernoulli", "timoshenko": "Timoshenko"}


def read_csv(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def save(fig, out, name):
    """OUT/plots/name.png and .svg; the PNG's path."""
    plots = os.path.join(out, "plots")
    os.makedirs(plots, exist_ok=True)
    for ext in ("png", "svg"):
        fig.savefig(os.path.join(plots, f"{name}.{ext}"), dpi=130, bbox_inches="tight")
    plt.close(fig)
    return os.path.join(plots, f"{name}.png")


def chords_only(results):
    """A plot title's remark where results.json carries no curves (shapes.has_curves)."""
    return "" if has_curves(results) else " (straight chords: results.json has no curves)"


# ---- Fig. 3: iterations per mesh, one load step to a full circle ----

def fig3(out):
    path = os.path.join(out, "studies", "fig3", "study.csv")
    if not os.path.exists(path):
        return None, []
    rows = read_csv(path)
    groups = defaultdict(list)
    for r in rows:
        groups[(r["setup"], r["element"])].append(r)
    setups = sorted({r["setup"] for r in rows}, key=lambda s: (("pin" in s), ("20" in s)))
    fig, axes = plt.subplots(2, 2, figsize=(12, 8), sharex=True)
    summary = []
    for ax, setup in zip(axes.flat, setups):
        for element in ("euler-bernoulli", "timoshenko"):
            data = sorted(groups[(setup, element)], key=lambda r: int(r["divisions"]))
            ok = [(int(r["divisions"]), int(r["iterations"])) for r in data if r["converged"] == "true"]
            bad = [int(r["divisions"]) for r in data if r["converged"] != "true"]
            ax.plot([m for m, _ in ok], [i for _, i in ok], ".", ms=3, color=COLOURS[element],
                    label=f"{NAMES[element]}: converged")
            if bad:
                top = max([i for _, i in ok] + [10]) * 1.15
                ax.plot(bad, [top] * len(bad), "x", ms=3, color=COLOURS[element], label=f"{NAMES[element]}: failed")
            stable = 0
            for r in data:
                if r["converged"] != "true":
                    break
                stable = int(r["divisions"])
            its = [i for _, i in ok]
            summary.append({"setup": setup, "element": NAMES[element], "stable_to": stable,
                            "converged": len(ok), "failed": len(bad),
                            "iterations": f"{min(its)}–{max(its)}" if its else "–"})
        ax.set_title(setup)
        ax.set_xscale("log")
        ax.set_xlabel("elements in the beam (mesh)")
        ax.set_ylabel("Newton iterations in the single load step")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=8)
    fig.suptitle("Fig. 3 reproduced: a straight beam bent into a full circle (M = 2πEI/L) in ONE load step")
    fig.tight_layout(rect=(0, 0, 1, 0.95))
    return save(fig, out, "fig3-iterations-vs-mesh"), summary


def fig2(out):
    path = os.path.join(out, "cantilever-circle", "results.json")
    if not os.path.exists(path):
        return None
    with open(path) as f:
        r = json.load(f)
    step = [s for s in r["steps"] if "displacements" in s][-1]
    fig, ax = plt.subplots(figsize=(6, 6))
    nodes = {n["id"]: (n["x"], n["y"]) for n in r["nodes"]}
    xs = [n[0] for n in nodes.values()]
    ax.plot([min(xs), max(xs)], [0, 0], color="0.7", lw=1, label="undeformed")
    draw_shape(ax, r, step, color="tab:blue", lw=1.5, label="converged, one load step")
    L = max(xs) - min(xs)
    R = L / (2 * math.pi)
    t = [2 * math.pi * k / 200 for k in range(201)]
    ax.plot([R * math.sin(a) for a in t], [R - R * math.cos(a) for a in t], "k:", lw=1, label="exact circle")
    ax.set_aspect("equal")
    ax.set_xlabel("x")
    ax.set_ylabel("y")
    ax.legend(fontsize=8)
    ax.set_title(f"Fig. 2: cantilever, tip moment 2πEI/L, {len(r['elements'])} elements, "
                 f"{step['iterations']} iterations" + chords_only(r))
    return save(fig, out, "fig2-circle")


# ---- Fig. 6 and 7: the contact point at an element end ----

def fig7(out):
    base = os.path.join(out, "studies", "fig7")
    path = os.path.join(base, "study.csv")
    if not os.path.exists(path):
        return None, []
    rows = read_csv(path)
    xs = sorted({r["x"] for r in rows}, key=float)
    fig, axes = plt.subplots(2, 3, figsize=(13, 7), sharey=True)
    table = []
    for ax, x in zip(axes.flat, xs):
        for r in rows:
            if r["x"] != x:
                continue
            steps = read_csv(os.path.join(base, "cases", r["case"], "steps.csv"))
            push, where = [], []
            for s in steps:
                if s["contact_element_100"]:
                    push.append(float(s["uy_100"]))
                    where.append(int(s["contact_element_100"]) - 1 + float(s["contact_xi_100"]))
            table.append(r)
            if r["treatment"] != "tsmframe":
                continue  # the curves of our treatment; the paper's are in the table
            frame = r.get("frame", "chord")
            ax.plot(push, where, "-" if frame == "chord" else "--", color=COLOURS[r["element"]], lw=1.2,
                    label=f"{NAMES[r['element']]}, {frame} frame")
        ax.axhline(9.0, color="0.5", lw=0.8, ls=":")
        ax.set_title(f"contact node at x = {x} m")
        ax.set_xlabel("push of the contact node (m)")
        ax.set_ylabel("contact position (element − 1 + α)")
        ax.grid(True, alpha=0.3)
    axes.flat[0].legend(fontsize=7)
    fig.suptitle("Fig. 7 reproduced: the contact point along the push; the dotted line is the end of element 9")
    fig.tight_layout(rect=(0, 0, 1, 0.95))
    return save(fig, out, "fig7-alpha-vs-push"), table


def fig6(out):
    path = os.path.join(out, "contact-push", "results.json")
    if not os.path.exists(path):
        return None
    with open(path) as f:
        r = json.load(f)
    fig, ax = plt.subplots(figsize=(9, 5))
    pusher = [n for n in r["nodes"] if n["id"] == 100][0]
    states = [s for s in r["steps"] if "displacements" in s]
    cmap = plt.get_cmap("viridis")
    for k, s in enumerate(states):
        colour = cmap(k / max(1, len(states) - 1))
        draw_shape(ax, r, s, color=colour, lw=1.2, label=f"push {s['displacements']['100'][1]:.2f} m")
        p = s["displacements"]["100"]
        ax.plot([pusher["x"] + p[0]], [pusher["y"] + p[1]], "o", color=colour, ms=4)
    ax.set_aspect("equal")
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    ax.legend(fontsize=7, ncol=2)
    ax.set_title("Fig. 6: deformed shapes as the contact node pushes the cantilever" + chords_only(r))
    return save(fig, out, "fig6-deformed-shapes")


# ---- The examples: each one's deformed shapes and how its run ended ----

def engineer_figures(out, name, model, results_path):
    """The M diagram at the last state and the first buckling mode (with analysis.buckling) of one
    example, drawn by the tsmframe package from its results read back: [png], [] where the
    package is not built (PYTHONPATH=build/python, as scripts/run.sh runs this)."""
    try:
        import tsmframe as tf
    except ImportError:
        return []
    r = tf.Result.load(results_path, model=model)
    pngs = []
    if len(r.state_steps):
        fig, ax = plt.subplots(figsize=(4.2, 3.0))
        r.plot_diagram("M", ax=ax)
        ax.set_title(f"{name}: M at step {r.state_steps[-1]}", fontsize=8)
        pngs.append(save(fig, out, f"moment-{name}"))
    if len(r.buckling_load_factors):
        fig, ax = plt.subplots(figsize=(4.2, 3.0))
        r.plot_buckling(0, ax=ax)
        ax.set_title(f"{name}: buckling mode 1, λ = {r.buckling_load_factors[0]:.4g}", fontsize=8)
        pngs.append(save(fig, out, f"buckling-{name}"))
    return pngs


def examples(out):
    """[(name, title, summary, notes, [png])] for every examples/*.json run into OUT/<name>/: the
    model as drawn before solving, its deformed shapes, its M diagram, its first buckling mode."""
    drawing = model_plot()
    source = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "examples")
    rows = []
    for file in sorted(os.listdir(source)):
        name, ext = os.path.splitext(file)
        path = os.path.join(out, name, "results.json")
        if ext != ".json" or not os.path.exists(path):
            continue
        with open(path) as f:
            results = json.load(f)
        steps = results["steps"]
        converged = [s for s in steps if s["converged"]]
        summary = (f"{results['status']}: {len(converged)} steps, {sum(s['iterations'] for s in steps)} iterations"
                   + (f", λ = {converged[-1]['load_factor']:.4g} at the end" if converged else ""))
        if results.get("stages"):  # a staged run: where each stage ended
            summary += "; " + ", ".join(f"stage {s['stage']}{' (' + s['name'] + ')' if s['name'] else ''} to step {s['last_step']}"
                                        for s in results["stages"])
        fig, ax = plt.subplots(figsize=(4.2, 3.0))
        drawing.plot_model(results, ax, node_labels=False)
        ax.set_title(name + ": the model", fontsize=8)
        ax.get_legend().remove()  # the symbols speak for themselves at this size
        model_png = save(fig, out, f"model-{name}")
        states = [s for s in steps if "displacements" in s]
        if len(states) > 6:
            states = [states[round(k * (len(states) - 1) / 5)] for k in range(6)]
        fig, ax = plt.subplots(figsize=(4.2, 3.0))
        draw_shape(ax, results, undeformed(results), color="0.75", lw=0.8)
        scale = magnification(results, states)
        cmap = plt.get_cmap("viridis")
        for k, state in enumerate(states):
            draw_shape(ax, results, state, scale=scale, color=cmap(k / max(1, len(states) - 1)), lw=1.0)
        ax.set_aspect("equal")
        ax.set_xticks([])
        ax.set_yticks([])
        ax.set_title(name + (f" (displacements × {scale:g})" if scale != 1.0 else "") + chords_only(results), fontsize=8)
        pngs = [model_png, save(fig, out, f"example-{name}")] + engineer_figures(out, name, os.path.join(source, file), path)
        rows.append((name, results.get("title", ""), summary, results.get("notes", []), pngs))
    return rows


def embed(png):
    if not png:
        return "<p><em>(not produced: run scripts/run.sh first)</em></p>"
    with open(png, "rb") as f:
        data = base64.b64encode(f.read()).decode()
    return f'<img src="data:image/png;base64,{data}" style="max-width:100%">'


def main(out):
    fig3_png, fig3_rows = fig3(out)
    fig2_png = fig2(out)
    fig7_png, fig7_rows = fig7(out)
    fig6_png = fig6(out)
    e = html.escape
    parts = ["""<!doctype html><html><head><meta charset="utf-8"><title>tsmframe: the paper's studies</title>
<style>body{font-family:sans-serif;max-width:1100px;margin:2em auto;line-height:1.4}
table{border-collapse:collapse;margin:1em 0}td,th{border:1px solid #bbb;padding:3px 8px;text-align:right}
th{background:#eee}td:first-child,td:nth-child(2){text-align:left}</style></head><body>
<h1>The paper's two studies, reproduced with tsmframe</h1>
<p>Nizam, Obiya, Ijima &amp; Azhar, <em>A Comparison for the Simulation of Frictionless Contact Problem
with Large Displacement</em>. Produced by <code>bash scripts/run.sh</code>; the study files are
<code>studies/fig3-circle.json</code> and <code>studies/fig7-contact-edge.json</code>, every case's row is in
<code>out/studies/*/study.csv</code>.</p>"""]
    parts.append("""<h2>Fig. 3 — a beam bent into a full circle in one load step</h2>
<p>Beam L = 10 m, steel E = 2.05e11 Pa, G = 7.9e10 Pa, square section h = 0.1 m (L/h = 100) or
0.5 m (L/h = 20), shear area 5/6 A; moment M = 2πEI/L (a full circle) applied in ONE load step
from the straight beam; at most 200 iterations, no cutback. Set-ups: cantilever with a tip
moment, and pin + roller with −M and +M (FORMULATION §5: the text's one-moment set-up has no
circular solution). Meshes 6 … 200 (every one) and 250 … 1000 (every 50).</p>
<p><b>The paper:</b> Euler–Bernoulli stable up to 52 elements, Timoshenko up to 200.</p>
<table><tr><th>set-up</th><th>element</th><th>converges for every mesh up to</th><th>converged</th>
<th>failed</th><th>iterations</th></tr>""")
    for r in fig3_rows:
        parts.append(f"<tr><td>{e(r['setup'])}</td><td>{e(r['element'])}</td><td>{r['stable_to']}</td>"
                     f"<td>{r['converged']}</td><td>{r['failed']}</td><td>{r['iterations']}</td></tr>")
    parts.append("</table>" + embed(fig3_png) + embed(fig2_png))
    parts.append("""<h2>Fig. 6–7 — the contact point at an element end</h2>
<p>A 9 m steel cantilever of 18 Timoshenko or Euler–Bernoulli elements (E = 2.05e11 Pa, G = 7.9e10 Pa,
A = 1e-2 m², I = 1e-4 m⁴, A_s = 8.3e-3 m²), a rigid contact node starting on its axis at
x = 4.05 … 4.4 m (inside element 9, 4.0–4.5 m), pushed 2 m up in 200 steps with cutback.
<b>tsmframe</b>: our treatment of the element end (hand-over inside the Newton loop, compliance
floor δ = 0.01); <b>paper</b>: the paper's force law all the way to the node (edge 1e-12).</p>
<p><b>The paper:</b> largest α reached in the first contact element 87.4–92.3 % (Euler–Bernoulli),
99.499–99.933 % (Timoshenko), the cantilever-coordinate element in between; only Timoshenko slides
on into the next element.</p>
<p>Four formulations: the chord-frame element (Eq. 6–9) and the "cantilever coordinate" element
(FORMULATION §2b, the paper's third curve), each with Euler–Bernoulli and Timoshenko beams.</p>
<table><tr><th>treatment</th><th>formulation</th><th>x (m)</th><th>largest α in element 9</th>
<th>elements passed</th><th>status</th><th>iterations</th></tr>""")
    fig7_rows.sort(key=lambda r: (r["treatment"] != "tsmframe", r.get("frame", "chord"), r["element"], float(r["x"])))
    for r in fig7_rows:
        parts.append(f"<tr><td>{e(r['treatment'])}</td><td>{e(r.get('frame', 'chord'))} frame, {e(NAMES[r['element']])}</td><td>{e(r['x'])}</td>"
                     f"<td>{100 * float(r['contact_max_alpha_first']):.3f} %</td><td>{r['contact_elements_passed']}</td>"
                     f"<td>{e(r['status'])}</td><td>{r['iterations']}</td></tr>")
    parts.append("</table>" + embed(fig7_png) + embed(fig6_png))
    failed = sorted({(r.get("frame", "chord"), r["x"]) for r in fig7_rows
                     if r["treatment"] == "paper" and r["element"] == "euler-bernoulli" and r["converged"] != "true"})
    timoshenko_ok = all(r["converged"] == "true" for r in fig7_rows if r["element"] == "timoshenko")
    ours_ok = all(r["converged"] == "true" for r in fig7_rows if r["treatment"] == "tsmframe")
    where = ", ".join(f"x = {x} m ({frame} frame)" for frame, x in failed) or "none"
    parts.append(f"""<h2>Where we differ, and why</h2>
<p>Measured here: with our treatment every formulation {'passes' if ours_ok else 'does not always pass'} the element end;
with the paper's force law kept to the node, Euler–Bernoulli fails near the element end at: {where};
Timoshenko {'passes everywhere' if timoshenko_ok else 'fails somewhere too'}.</p>""")
    parts.append("""
<p>Our Euler–Bernoulli beams stay stable to finer meshes than the paper's 52 (with L/h = 100) and our
contact point passes the element end with both theories, because the paper gives no E, I, L (ours
are stated above, and the limits move with L/h) and because tsmframe hands the contact to the next
element inside the Newton loop and floors the contact compliance within 1 % of an element end,
instead of asking Newton to converge at α → 1.
With the paper's force law kept to the node, Euler–Bernoulli does fail near the element end at some
positions (listed above) while Timoshenko passes everywhere — the paper's ordering — but the largest
α it reaches before that (≈ 99 %) is higher than the paper's 87–92 %, since our step halving gets
closer to the edge.</p>""")
    example_rows = examples(out)
    if example_rows:
        parts.append("""<h2>The examples</h2>
<p>Every model in <code>examples/</code>, run by <code>scripts/run.sh</code> into <code>out/&lt;name&gt;/</code>
(results.json, steps.csv; <code>tsmframe run … --plot</code> draws the full plots): the model as
<code>tsmframe plot</code> draws it before solving (supports, hinges, springs, loads at λ = 1 — a stage's in
its own colour —, contact nodes and the members they may touch), its deformed shapes from the undeformed
(grey) to the last step (yellow), its bending moment M at the last state (drawn on the tension side), its
first buckling mode where the model asks for buckling, how the run ended, and its notes.</p>""")
        for name, title, summary, notes, pngs in example_rows:
            note_list = "".join(f"<li>{e(n)}</li>" for n in notes)
            figures = "".join(f'<div style="flex:0 0 260px">{embed(png)}</div>' for png in pngs)
            parts.append(f'<div style="margin:1.5em 0"><div><b>{e(name)}</b>: {e(title)}<br>'
                         f'<em>{e(summary)}</em>{"<ul>" + note_list + "</ul>" if notes else ""}</div>'
                         f'<div style="display:flex;flex-wrap:wrap;gap:0.5em">{figures}</div></div>')
    parts.append("</body></html>")
    os.makedirs(out, exist_ok=True)
    with open(os.path.join(out, "report.html"), "w") as f:
        f.write("\n".join(parts))
    print(f"report: {os.path.join(out, 'report.html')}; plots: {os.path.join(out, 'plots')}/")


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "out")
