"""Plots of a tsmframe Result with matplotlib (Debian's python3-matplotlib)."""
import matplotlib.pyplot as plt
import numpy as np


def _axes(ax):
    if ax is None:
        _, ax = plt.subplots()
    return ax


def plot_shape(result, steps=(-1,), ax=None, undeformed=True, scale=1.0, **kw):
    """The deformed shape at the given states (indices into result.state_steps): every element
    drawn as its deflected curve, as Result.curves gives it, its displacements from the drawn
    geometry magnified `scale` times (1: true size; small deflections made visible)."""
    ax = _axes(ax)
    index = {int(i): k for k, i in enumerate(result.node_ids)}
    ends = np.array([[index[int(a)], index[int(b)]] for a, b in result.element_nodes]).reshape(-1, 2)
    if undeformed:  # one line broken between elements: one artist, not one per element
        drawn = np.full((len(ends), 3, 2), np.nan)
        drawn[:, 0], drawn[:, 1] = result.node_xy[ends[:, 0]], result.node_xy[ends[:, 1]]
        ax.plot(drawn[:, :, 0].ravel(), drawn[:, :, 1].ravel(), color="0.75", lw=1)
    cmap = plt.get_cmap("viridis")
    given = kw.pop("color", None)  # one colour for every step drawn, else one per step from the colour map
    for n, k in enumerate(steps):
        colour = given or cmap(n / max(1, len(steps) - 1))
        points = result.curves(k, segments=12)  # (elements, 13, 2)
        if scale != 1.0:  # from each element's drawn chord, at the same place along it
            a, b = result.node_xy[ends[:, 0]], result.node_xy[ends[:, 1]]
            s = np.linspace(0.0, 1.0, points.shape[1])[None, :, None]
            drawn = a[:, None, :] + s * (b - a)[:, None, :]
            points = drawn + scale * (points - drawn)
        broken = np.concatenate([points, np.full((len(points), 1, 2), np.nan)], axis=1).reshape(-1, 2)
        ax.plot(broken[:, 0], broken[:, 1], color=colour, label=f"step {result.state_steps[k]}", **kw)
    ax.set_aspect("equal")
    ax.set_xlabel("x")
    ax.set_ylabel("y")
    if scale != 1.0:
        ax.set_title(f"displacements × {scale:g}")
    ax.legend(fontsize=8)
    return ax


def plot_diagram(result, quantity="M", step=-1, ax=None, scale=None, **kw):
    """The N, V or M diagram at a state (index into result.state_steps) drawn on the deformed
    frame, off each element's chord: M on its tension side (the engineer's convention), N and V
    on the chord's left for positive values. `scale`: drawing length per unit of the quantity
    (None: the largest value drawn at a tenth of the frame's size). The largest value is labelled."""
    ax = _axes(ax)
    parts = result.diagram(quantity, step)
    position = {int(i): result.node_xy[k] + result.displacements[step][k, :2] for k, i in enumerate(result.node_ids)}
    largest = max((float(np.abs(p[:, 1]).max()) for p in parts if len(p)), default=0.0)
    size = float(np.ptp(np.array(list(position.values())), axis=0).max()) or 1.0
    if scale is None:
        scale = 0.1 * size / largest if largest > 0 else 1.0
    sign = -1.0 if quantity == "M" else 1.0  # M drawn on the side it stretches (−n where positive)
    colour = kw.pop("color", {"N": "tab:green", "V": "tab:orange", "M": "tab:blue"}.get(quantity, "tab:blue"))
    peak = None
    for (a, b), part in zip(result.element_nodes, parts):
        start, end = position[int(a)], position[int(b)]
        chord = end - start
        length = np.hypot(*chord)
        e = chord / length if length > 0 else np.array([1.0, 0.0])
        n = np.array([-e[1], e[0]])
        on_chord = start + np.outer(part[:, 0], e)
        drawn = on_chord + sign * scale * np.outer(part[:, 1], n)
        outline = np.vstack([on_chord[:1], drawn, on_chord[-1:]])
        ax.fill(outline[:, 0], outline[:, 1], color=colour, alpha=0.25, lw=0)
        ax.plot(drawn[:, 0], drawn[:, 1], color=colour, lw=1, **kw)
        ax.plot([start[0], end[0]], [start[1], end[1]], color="0.3", lw=1)
        k = int(np.argmax(np.abs(part[:, 1])))
        if peak is None or abs(part[k, 1]) > abs(peak[0]):
            peak = (part[k, 1], drawn[k])
    if peak is not None and peak[0] != 0:
        ax.annotate(f"{quantity} = {peak[0]:.4g}", peak[1], fontsize=8, color=colour)
    ax.set_aspect("equal")
    ax.set_title(f"{quantity} at step {result.state_steps[step]}")
    return ax


def plot_buckling(result, mode=0, ax=None, scale=None, **kw):
    """A buckling mode (analysis.buckling; index into result.buckling_load_factors) over the state
    it was estimated from (the frame as drawn, or its converged step): each element's ends moved
    by the mode's translations, scaled so that the largest is `scale` (None: a tenth of the
    frame's size); titled with its critical load factor and the step."""
    ax = _axes(ax)
    if not 0 <= mode < len(result.buckling_load_factors) and not -len(result.buckling_load_factors) <= mode < 0:
        raise IndexError(f"no buckling mode {mode} ({len(result.buckling_load_factors)} found)")
    size = float(np.ptp(result.node_xy, axis=0).max()) or 1.0
    scale = 0.1 * size if scale is None else scale
    index = {int(i): k for k, i in enumerate(result.node_ids)}
    shape = result.buckling_modes[mode]
    colour = kw.pop("color", "tab:red")
    step = int(getattr(result, "buckling_step", 0))
    base = result.node_xy
    if step > 0 and step in list(result.state_steps):
        base = base + result.displacements[list(result.state_steps).index(step)][:, :2]
    for a, b in result.element_nodes:
        ends = [index[int(a)], index[int(b)]]
        drawn = base[ends]
        moved = drawn + scale * shape[ends, :2]
        ax.plot(drawn[:, 0], drawn[:, 1], color="0.75", lw=1)
        ax.plot(moved[:, 0], moved[:, 1], color=colour, lw=1.5, **kw)
    ax.set_aspect("equal")
    where = f" (from step {step})" if step > 0 else ""
    ax.set_title(f"buckling mode {mode % len(result.buckling_load_factors) + 1}: λ = {result.buckling_load_factors[mode]:.4g}{where}")
    return ax


def plot_load_displacement(result, node_id, dof="uy", ax=None, **kw):
    """λ against one dof over the steps with state; a staged run's stages each from where the one
    before ended (its λ starts again at 0), solid, dashed, …."""
    ax = _axes(ax)
    lam, values = result.history(node_id, dof)
    stages = np.array([result.stage[np.flatnonzero(result.step == s)[0]] for s in result.state_steps])
    start, styles = 0.0, ("-", "--", ":", "-.")
    for k, stage in enumerate(dict.fromkeys(stages.tolist())):
        here = stages == stage
        label = f"{dof} of node {node_id}" + (f", stage {stage}" if len(set(stages.tolist())) > 1 else "")
        ax.plot(np.concatenate([[start], values[here]]), np.concatenate([[0.0], lam[here]]), "." + styles[k % 4],
                label=label, **kw)
        start = values[here][-1]
    ax.set_xlabel(f"{dof} of node {node_id}")
    ax.set_ylabel("load factor λ" + (" (each stage's own)" if len(set(stages.tolist())) > 1 else ""))
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8)
    return ax


def plot_contact(result, ax=None, legend_limit=12, **kw):
    """Contact position (element − 1 + α) against the load factor, for every contact node that
    touched at some converged step (a model with many contact nodes: those that never touched
    are left out). The legend names them where there are at most `legend_limit`."""
    ax = _axes(ax)
    lam = result.load_factor[result.converged == 1]
    touched = [c for c in range(len(result.contact_nodes)) if (result.contact_element[:, c] > 0).any()]
    for c in touched:
        where = np.where(result.contact_element[:, c] > 0, result.contact_element[:, c] - 1 + result.contact_alpha[:, c], np.nan)
        ax.plot(lam, where, ".-", label=f"contact node {result.contact_nodes[c]}", **kw)
    ax.set_xlabel("load factor λ")
    ax.set_ylabel("contact position (element − 1 + α)")
    ax.grid(True, alpha=0.3)
    if 0 < len(touched) <= legend_limit:
        ax.legend(fontsize=8)
    elif touched:
        ax.set_title(f"{len(touched)} of {len(result.contact_nodes)} contact nodes touched", fontsize=9)
    return ax


def plot_iterations(result, ax=None, **kw):
    """Relative residual of every iterate, step after step (log scale)."""
    ax = _axes(ax)
    for s, norms in zip(result.step, result.residual_norms):
        ax.semilogy(range(len(norms)), np.maximum(norms, 1e-17), ".-", lw=0.8, **kw)
    ax.set_xlabel("iterate")
    ax.set_ylabel("relative residual")
    ax.grid(True, which="both", alpha=0.3)
    return ax
