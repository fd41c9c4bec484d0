"""tsmframe from Python: geometrically nonlinear plane frames by the Tangent Stiffness Method.

Build a model in code or load a docs/format.md file, run it, get numpy arrays::

    import tsmframe as tf
    m = tf.Model("cantilever rolled into a circle")
    m.material("steel", E=2.05e11, G=7.9e10)
    m.section("s", A=1e-2, I=8.33e-6, shear_area=8.33e-3)
    m.node(1, 0, 0); m.node(2, 10, 0)
    m.member(1, 2, divisions=52, element="timoshenko", material="steel", section="s")
    m.support(1, "fixed")
    m.load(2, mz=6.283185307 * 2.05e11 * 8.33e-6 / 10)
    r = tf.run(m)                 # or tf.run("model.json")
    r.status, r.displacement(2)   # ("converged", array([ux, uy, rz]) at the last step)

Bad input raises ValueError with the same "JSON.path: reason" as the command line;
non-convergence is r.status, never an exception. The numbers come from the same C++ solver as
`tsmframe run` (results equal bit for bit: r.results_json is the CLI's results.json).
"""
import json as _json
import os as _os

import numpy as _np

from ._core import __version__, element_curves as _element_curves, read_model as _read_model, run_json as _run_json
from ._core import model_drawing as _model_drawing, study_json as _study_json

__all__ = ["Model", "Result", "run", "load", "__version__"]


def _plain(value, path):
    """`value` as plain JSON values: numpy scalars and arrays as Python numbers and lists (a node
    id from np.arange is an id like any other). A number that is not finite (NaN, ±inf; JSON has
    none) is bad input, named by its JSON path as the reader names every other."""
    if isinstance(value, dict):
        return {k: _plain(v, f"{path}.{k}" if path else str(k)) for k, v in value.items()}
    if isinstance(value, (list, tuple, _np.ndarray)):
        return [_plain(v, f"{path}[{i}]") for i, v in enumerate(value)]
    if isinstance(value, _np.generic):
        value = value.item()
    if isinstance(value, float) and not _np.isfinite(value):
        raise ValueError(f"{path or 'the document'}: {value} is not a finite number")
    return value


def _dumps(document, indent=None):
    """The JSON text of a model or study document (_plain's rules)."""
    return _json.dumps(_plain(document, ""), indent=indent, allow_nan=False)


class Model:
    """A model built in code; mirrors docs/format.md key for key (see to_dict())."""

    def __init__(self, title="", units=None):
        self._doc = {"format": "tsmframe-model/1", "title": title, "materials": {}, "sections": {},
                     "nodes": [], "members": [], "supports": [], "loads": [], "prescribed": [],
                     "contacts": [], "analysis": {}}
        if units:
            self._doc["units"] = dict(units)

    @classmethod
    def from_dict(cls, document):
        m = cls()
        m._doc = _json.loads(_dumps(document))
        return m

    def material(self, name, E, G=None, nu=None, density=None):
        entry = {"E": E}
        if G is not None:
            entry["G"] = G
        if nu is not None:
            entry["nu"] = nu
        if density is not None:
            entry["density"] = density
        self._doc["materials"][name] = entry
        return self

    def gravity(self, gx, gy):
        """The acceleration of gravity: every member whose material has a density weighs
        density × A × g per unit length (a member load, scaled by the load factor)."""
        self._doc["gravity"] = [gx, gy]
        return self

    def section(self, name, A, I, shear_area=None):
        entry = {"A": A, "I": I}
        if shear_area is not None:
            entry["shear_area"] = shear_area
        self._doc["sections"][name] = entry
        return self

    def node(self, id, x, y):
        self._doc["nodes"].append({"id": id, "x": x, "y": y})
        return self

    def member(self, start, end, material, section, divisions=1, element="euler-bernoulli", arc=None, release=None,
               load=None, pressure=None, end_springs=None, foundation=None):
        """A straight member (or an arc: arc=(centre_x, centre_y, sweep_radians), or the model file's
        {"center": [x, y], "sweep": s}) of `divisions` elements;
        release: "start", "end" or "both" puts a hinge (no moment) at that end; load=(fx, fy): a
        distributed load, force per unit length in global directions; pressure=p: a follower load
        per unit current length, normal to the deformed member, pushing from its left side (seen
        from start to end) to its right (load may also be the file's {"fx": …, "fy": …}); end_springs={"start": k, "end": k}: rotational springs
        (semi-rigid connections, moment per radian) between the member's ends and their nodes;
        foundation=k: an elastic (Winkler) foundation, force per length per unit deflection, normal to
        the member as drawn."""
        entry = {"from": _ref(start), "to": _ref(end), "divisions": divisions, "element": element,
                 "material": material, "section": section}
        if arc is not None:  # (cx, cy, sweep) or the file's {"center": [cx, cy], "sweep": s}
            entry["arc"] = dict(arc) if isinstance(arc, dict) else {"center": [arc[0], arc[1]], "sweep": arc[2]}
        if release is not None:
            entry["release"] = release
        if end_springs is not None:
            entry["end_springs"] = dict(end_springs)
        if load is not None or pressure is not None:
            entry["load"] = {}
        if load is not None:  # (fx, fy) or the file's {"fx": …, "fy": …}
            entry["load"].update(dict(load) if isinstance(load, dict) else {"fx": load[0], "fy": load[1]})
        if pressure is not None:
            entry["load"]["pressure"] = pressure
        if foundation is not None:
            entry["foundation"] = foundation
        self._doc["members"].append(entry)
        return self

    def spring(self, node, kx=None, ky=None, kr=None, k=None, direction=None):
        """Linear springs from a node to the ground: kx, ky (force per length along x, y), kr (moment
        per radian), or k along direction=(dx, dy)."""
        entry = {"node": _ref(node)}
        for key, value in (("kx", kx), ("ky", ky), ("kr", kr), ("k", k)):
            if value is not None:
                entry[key] = value
        if direction is not None:
            entry["direction"] = list(direction)
        self._doc.setdefault("springs", []).append(entry)
        return self

    def support(self, node, type=None, fix=None, roller=None):
        """type: "fixed", "pinned", "roller-x", "roller-y"; or fix: a list out of "ux", "uy", "rz";
        or roller: (dx, dy), a roller on a plane of that direction (a skew roller; fix=["rz"] may
        join it)."""
        entry = {"node": _ref(node)}
        if type is not None:
            entry["type"] = type
        if fix is not None:
            entry["fix"] = list(fix)
        if roller is not None:
            entry["roller"] = [float(roller[0]), float(roller[1])]
        self._doc["supports"].append(entry)
        return self

    def _applied(self, key):
        """Where load() and prescribe() add: the newest stage, or the model (no stages)."""
        if "stages" in self._doc:
            return self._doc["stages"][-1].setdefault(key, [])
        return self._doc[key]

    def load(self, node, fx=0.0, fy=0.0, mz=0.0, follower=False):
        """A nodal load scaled by λ (of the newest stage, if any); follower=True: the force (fx, fy,
        as drawn) turns with its node."""
        entry = {"node": _ref(node), "fx": fx, "fy": fy, "mz": mz}
        if follower:
            entry["follower"] = True
        self._applied("loads").append(entry)
        return self

    def load_along(self, member, at, fx=0.0, fy=0.0, mz=0.0, follower=False):
        """A point load along a member (index, in the order added), at a fraction 0 < at < 1 of its
        length from its start: the mesh puts a node there."""
        entry = {"member": int(member), "at": at, "fx": fx, "fy": fy, "mz": mz}
        if follower:
            entry["follower"] = True
        self._applied("loads").append(entry)
        return self

    def prescribe(self, node, increment=False, **dofs):
        """Prescribed displacements reached at λ = 1, e.g. prescribe(100, uy=2.0); in a stage, the
        values are where the dofs end (increment=True: by how much they move in the stage)."""
        entry = {"node": _ref(node), **dofs}
        if increment:
            entry["increment"] = True
        self._applied("prescribed").append(entry)
        return self

    def stage(self, name="", control=None, steps=None, output=None, contacts=None):
        """Starts a stage (docs/format.md, "Stages"): the load() and prescribe() calls after it are
        its own, scaled by its λ from 0; what earlier stages applied stays at its final level. The
        members' loads and self-weight are the first stage's. control as in analysis(), or steps=N;
        contacts: the indices of the contact() entries that exist in the stage (default: all)."""
        if control is not None and steps is not None:
            raise ValueError("stage: give control or steps, not both")
        if "stages" not in self._doc and (self._doc["loads"] or self._doc["prescribed"]):
            raise ValueError("stage: loads or prescribed displacements were given before the first stage; give them after it")
        entry = {}
        if name:
            entry["name"] = name
        if steps is not None:
            control = {"type": "load", "steps": steps}
        if control is not None:
            entry["control"] = control
        if output is not None:
            entry["output"] = output
        if contacts is not None:
            entry["contacts"] = [int(c) for c in contacts]
        self._doc.setdefault("stages", []).append(entry)
        return self

    def contact(self, node=None, members="all", nodes=None, between=None, **options):
        """A contact node, or several with the same options: nodes=[refs] or nodes={"members": [i, …]}
        (every node of those members), or between=([members A], [members B]): every node of each
        side a contact node on the other (beam on beam from both sides); options: element, frame,
        normal ("deflected", the default, or "chord"), gap, edge, max_stiffness_ratio,
        sliding_tangent (docs/format.md, README)."""
        if between is not None:
            if node is not None or nodes is not None:
                raise ValueError("contact: give between, or node(s) and members (not both)")
            self._doc["contacts"].append({"between": [list(side) for side in between], **options})
            return self
        if (node is None) == (nodes is None):
            raise ValueError("contact: give node or nodes (not both)")
        if node is not None:
            self._doc["contacts"].append({"node": _ref(node), "members": members, **options})
        else:
            listed = nodes if isinstance(nodes, dict) else [_ref(n) for n in nodes]
            self._doc["contacts"].append({"nodes": listed, "members": members, **options})
        return self

    def analysis(self, control=None, steps=None, **settings):
        """control: {"type": "load", "steps": N} | {"type": "displacement", …} | {"type": "arc-length", …},
        or steps=N alone for load control in N equal steps;
        settings: tolerance, max_iterations, cutback, max_cutbacks, output, monitor, buckling ({"modes": k, "at": "unloaded", "end" or a step})."""
        if control is not None and steps is not None:
            raise ValueError("analysis: give control or steps, not both")
        if steps is not None:
            control = {"type": "load", "steps": steps}
        if control is not None:
            self._doc["analysis"]["control"] = control
        self._doc["analysis"].update(settings)
        return self

    def to_dict(self):
        """The docs/format.md document (empty optional lists left out)."""
        return {k: v for k, v in self._doc.items() if not (isinstance(v, (list, dict)) and not v and k not in ("materials", "sections", "nodes", "members"))}

    def to_json(self, indent=1):
        return _dumps(self.to_dict(), indent=indent)

    def save(self, path):
        with open(path, "w") as f:
            f.write(self.to_json())

    def drawing(self):
        """The model's drawing document (tsmframe-drawing/1, docs/format.md "Model drawing"): the
        meshed nodes and elements, supports, springs, loads per stage, contacts, and `mechanism`
        (the free motion named) where the supports leave the structure free. ValueError for bad input."""
        return _json.loads(_model_drawing(self.to_json()))

    def _repr_png_(self):
        """Jupyter shows a Model as its drawing (None, and so its text, where it cannot be read)."""
        try:
            drawing = self.drawing()
        except ValueError:
            return None
        from .model_plot import plot_model
        return _png(lambda ax: plot_model(drawing, ax))

    def plot(self, ax=None, node_labels=None):
        """Draw the model before solving (matplotlib): members, supports by their usual symbols,
        hinges, springs, loads as arrows, contact nodes and the members they may touch — what
        `tsmframe plot` draws. A mechanism is drawn too, its free motion written under it. Returns ax."""
        from .model_plot import plot_model
        return plot_model(self.drawing(), ax, node_labels)


def _png(draw, size=(7.0, 4.5)):
    """PNG bytes of a figure `draw(ax)` fills, drawn off pyplot (no figure left open to show twice)."""
    import io
    from matplotlib.figure import Figure
    fig = Figure(figsize=size)
    draw(fig.subplots())
    buffer = io.BytesIO()
    fig.savefig(buffer, format="png", dpi=90, bbox_inches="tight")
    return buffer.getvalue()


def _read_text(path):
    """A file's text; ValueError "PATH: cannot read: reason" where it cannot be read."""
    try:
        with open(path) as f:
            return f.read()
    except OSError as e:
        raise ValueError(f"{path}: cannot read: {e.strerror}") from None


def _ref(node):
    return list(node) if isinstance(node, (tuple, list)) else node


def study(definition, jobs=0, client=None, scheduler=None, progress=None):
    """Run a parameter study (a tsmframe-study/1 document: a dict, or a path to one; README
    "Parameter studies") with its cases in parallel on `jobs` threads (0: all cores) — or on a
    Dask cluster: `client` (a distributed.Client: a LocalCluster's, or one connected anywhere) or
    `scheduler` (its address, "tcp://HOST:8786"), the cases in shards over the workers' threads
    (tsmframe.distributed; the workers import tsmframe), `progress(done, total, worker)` called as
    each shard ends (the cases done, the address of the worker it ran on); the same rows, the
    seconds aside. Returns one dict per case in case order, with study.csv's columns: the parameters' values, status,
    converged, steps, iterations, last_iterations, load_factor, negative_eigenvalues (None where
    unknown), seconds, the first contact's story where the model has contacts, each `record`
    (None where the case has no value), notes, message.
    A bad study file raises ValueError (JSON path: reason); a failing case is a row."""
    if isinstance(definition, (str, _os.PathLike)):
        path = _os.fspath(definition)
        text, directory = _read_text(path), _os.path.dirname(_os.path.abspath(path))
    else:
        text, directory = _dumps(definition), _os.getcwd()
    if client is not None or scheduler is not None:
        from .distributed import study_on_cluster
        return study_on_cluster(text, directory, client=client, scheduler=scheduler, progress=progress)
    return _json.loads(_study_json(text, directory, jobs))["cases"]  # study.json's rows, as the CLI writes them


def load(path):
    """A Model from a docs/format.md file (validated when run)."""
    with open(path) as f:
        try:
            return Model.from_dict(_json.load(f))
        except _json.JSONDecodeError as e:
            raise ValueError(f"{path}: invalid JSON at line {e.lineno}, column {e.colno}: {e.msg}") from None


class Result:
    """The results of one run, as numpy arrays (shapes: n nodes, m elements, c contacts;
    S = every step including a failed last attempt, C = converged steps, K = steps with state).

    status, message            how the run ended ("converged", "diverged", …)
    notes                      remarks on the path (list of sentences; e.g. a jump across a snap-back)
    critical_points            bifurcations found under load control: dicts of step, load_factor, bracket
    limit_points               λ's extrema along the path: dicts of step, kind ("maximum", "minimum"), load_factor
                               (the step's); under arc-length control without contacts "located": the extremum
                               between the steps (load_factor, and the node, dof and value there); "contact_kink"
                               where a contact changed elements around it (maybe the mesh's extremum)
    buckling_load_factors (b,), buckling_modes (b, n, 3)
                               with analysis.buckling: the linearised critical load factors, ascending, and their
                               mode shapes (ux, uy, rz per node, largest translation 1), at the unloaded state or
                               a converged one ("at": "end" or a step): buckling_step (0: unloaded)
    neutral_equilibria         steps whose supports let a part move as a rigid body, its loads doing no
                               work (a singular tangent; no eigenvalue count): dicts of step, node, part_nodes,
                               motion ("rotation" about (x, y), or "translation" along direction)
    rounded_inertia            steps whose stability round-off leaves unknown (negative_eigenvalues -1): dicts of
                               step, node, dof and ratio — the pivot whose sign is lost, against that node's own
                               stiffness (below 1e-12: a member very much longer than deep in many short elements)
    node_ids (n,), node_xy (n, 2), element_ids (m,), element_nodes (m, 2) node ids
    step (S,), load_factor (S,), iterations (S,), converged (S,), residual_norms: S arrays, criterion: S strings
    stage (S,)                 the stage (1, 2, …) each step belongs to (1 without stages); stages: where
                               each stage that ran ended, dicts of stage, name, status, last_step, load_factor
    negative_eigenvalues (S,)  of the tangent at each converged step: 0 stable, > 0 unstable
                               equilibrium; -1 unknown (a contact active, a failed attempt, or round-off:
                               rounded_inertia)
    state_steps (K,)           step numbers that carry full state (analysis.output)
    displacements (K, n, 3)    ux, uy, rz per node; rz is the true total rotation
    element_forces (K, m, 3)   N, M_i, M_j (chord frame)
    section_forces             per state, an array (q, 5) of the N, V, M diagrams' stations: rows of element
                               id, x from its start node along its chord, N (tension +), V = dM/dx, M (+ where
                               the element bends towards its left: sagging for one drawn left to right); each
                               element's ends, and both sides of a contact point on it (diagram(), plot_diagram())
    reactions (K, n, 3)        Rx, Ry, Mz (0 where the node is free)
    contact_nodes (c,), contact_element (C, c) element id or 0, contact_alpha (C, c), contact_force (C, c),
    contact_also (C, c)        at a vertex (a point resting on a beam node, both elements in contact):
                               the other element's id, else 0
    contact_tangential (C, c), contact_slip (C, c), contact_friction (C, c)
                               with "friction": the friction force along the beam (signed along the touched
                               element's direction), the slip since the contact touched, and "stick" or
                               "slip" ("" without friction)
    results_json, steps_csv    exactly what `tsmframe run` writes
    curves(k)                  (m, segments + 1, 2): every element's deflected curve at state k (hinges and
                               end springs included), computed by the solver's own shape functions
    """

    def __init__(self, data, model_text=None):
        data = dict(data)
        self._model = data.pop("model", None)  # the meshed model, for curves()
        self._model_text = model_text          # … and what it is read from again after pickling
        self.__dict__.update(data)

    def __getstate__(self):
        state = dict(self.__dict__)
        state["_model"] = None  # the extension's model does not pickle; curves() reads its text again
        return state

    @property
    def ok(self):
        return self.status == "converged"

    def _node(self, node_id):
        index = _np.flatnonzero(self.node_ids == node_id)
        if index.size != 1:
            raise KeyError(f"no node {node_id}")
        return int(index[0])

    def displacement(self, node_id, step=-1):
        """(ux, uy, rz) of a node at a step with state (index into state_steps; -1 = last)."""
        return self.displacements[step, self._node(node_id)]

    def history(self, node_id, dof):
        """(load factors, values) of one dof (0 ux, 1 uy, 2 rz, or the name) over the steps with state."""
        dof = {"ux": 0, "uy": 1, "rz": 2}.get(dof, dof)
        lam = _np.array([self.load_factor[_np.flatnonzero(self.step == s)[0]] for s in self.state_steps])
        return lam, self.displacements[:, self._node(node_id), dof]

    def write(self, directory):
        """results.json and steps.csv, as the command line writes them."""
        _os.makedirs(directory, exist_ok=True)
        with open(_os.path.join(directory, "results.json"), "w") as f:
            f.write(self.results_json)
        with open(_os.path.join(directory, "steps.csv"), "w") as f:
            f.write(self.steps_csv)

    def json(self):
        return _json.loads(self.results_json)

    @classmethod
    def load(cls, path, model=None):
        """A Result read back from a results.json that `tsmframe run` or Result.write wrote (and
        the steps.csv beside it): the same arrays as the run gave, but the contact columns, which
        follow the file's `contacts` (ascending node ids per entry). `model` (a Model, a dict, a
        JSON text or a file path: the model that ran) is needed by curves() only. ValueError for a
        file that is not a results.json."""
        from .results_file import read_results
        return cls(read_results(_os.fspath(path)), None if model is None else _model_text(model)[0])

    def curves(self, step=-1, segments=8):
        """Every element's deflected curve at a state (index into state_steps; -1 = last): an array
        (m, segments + 1, 2) of current (x, y) at s = k / segments along each element's chord —
        the element's own shape under its end rotations, a hinged end free of moment, an end
        spring in series (the same curves as the ParaView files and results.json's "curves")."""
        if self._model is None:
            if self._model_text is None:
                raise ValueError("curves() needs the model the results are of: Result.load(path, model=…)")
            self._model = _read_model(self._model_text)
        return _element_curves(self._model, self.displacements[step], self.element_forces[step], segments)

    def diagram(self, quantity, step=-1):
        """One quantity's diagram ("N", "V" or "M") at a state (index into state_steps; -1 = last):
        per element, in element order, an array (p, 2) of (x along the element from its start
        node, value) — its ends and, where a contact point acts on it, both sides of the point."""
        column = {"N": 2, "V": 3, "M": 4}.get(quantity)
        if column is None:
            raise ValueError(f'unknown quantity "{quantity}" (expected "N", "V" or "M")')
        rows = self.section_forces[step]
        cuts = _np.flatnonzero(_np.diff(rows[:, 0])) + 1
        return [part[:, [1, column]] for part in _np.split(rows, cuts)]

    def _repr_html_(self):
        """Jupyter shows a Result as how its run ended — status, steps, λ, limit and buckling load
        factors, notes — over its deformed shape at the last state."""
        import base64
        import html
        e = html.escape
        converged = self.load_factor[self.converged == 1]
        rows = [("status", self.status + (f": {self.message}" if self.message else "")),
                ("converged steps", f"{len(converged)} ({int(self.iterations.sum())} iterations)"),
                ("load factor at the end", f"{converged[-1]:.6g}" if len(converged) else "—")]
        if self.limit_points:
            rows.append(("limit points", ", ".join(
                f"{p['kind']} {p.get('located', p)['load_factor']:.6g} (step {p['step']})" for p in self.limit_points)))
        if len(self.buckling_load_factors):
            rows.append(("buckling load factors", ", ".join(f"{x:.6g}" for x in self.buckling_load_factors)))
        table = "".join(f"<tr><th style='text-align:left'>{e(k)}</th><td style='text-align:left'>{e(v)}</td></tr>" for k, v in rows)
        notes = "".join(f"<li>{e(n)}</li>" for n in self.notes)
        figure = ""
        if len(self.state_steps) and (self._model is not None or self._model_text is not None):
            png = _png(lambda ax: self.plot_shape(ax=ax))
            figure = f'<img src="data:image/png;base64,{base64.b64encode(png).decode()}">'
        return f"<table>{table}</table>" + (f"<ul>{notes}</ul>" if notes else "") + figure

    # plots (matplotlib, imported on use)
    def plot_model(self, ax=None, node_labels=None):
        """The model as drawn before solving (Model.plot's picture), from the supports, loads and
        contacts results.json carries."""
        from .model_plot import plot_model
        return plot_model(self.json(), ax, node_labels)

    def plot_shape(self, steps=(-1,), ax=None, **kw):
        from .plots import plot_shape
        return plot_shape(self, steps, ax, **kw)

    def plot_diagram(self, quantity="M", step=-1, ax=None, scale=None, **kw):
        from .plots import plot_diagram
        return plot_diagram(self, quantity, step, ax, scale, **kw)

    def plot_buckling(self, mode=0, ax=None, scale=None, **kw):
        from .plots import plot_buckling
        return plot_buckling(self, mode, ax, scale, **kw)

    def plot_load_displacement(self, node_id, dof="uy", ax=None, **kw):
        from .plots import plot_load_displacement
        return plot_load_displacement(self, node_id, dof, ax, **kw)

    def plot_contact(self, ax=None, **kw):
        from .plots import plot_contact
        return plot_contact(self, ax, **kw)

    def plot_iterations(self, ax=None, **kw):
        from .plots import plot_iterations
        return plot_iterations(self, ax, **kw)


def run(model, threads=0, start=None, step=None, progress=None):
    """Run a Model, a docs/format.md dict, a JSON text or a file path. Raises ValueError for bad input.
    start: go on from a kept step of an earlier run of the same model — a Result, or the path of
    its results.json — at step `step` (None: its newest step with state); the steps are numbered
    on from it (the CLI's --from).
    progress: called with a dict for each step as it ends (step, stage, load_factor, iterations,
    converged, cutbacks, cut_back, message; a step redone to land on an arc-length `until` is
    heard again; an attempt cut back is heard with cut_back True, its load factor the attempt's
    start and message why it failed, then the step again smaller),
    in the calling thread, every 50 ms at most behind the solver;
    an exception it raises stops the run at its next step and is raised here (as Ctrl-C does)."""
    start_text = ""
    if start is not None:
        start_text = start.results_json if isinstance(start, Result) else _read_text(_os.fspath(start))
    step = 0 if step is None else int(step)
    text, path = _model_text(model)
    try:
        return Result(_run_json(text, threads, start_text, step, progress), text)
    except ValueError as e:
        if path is None:
            raise
        raise ValueError(f"{path}: {e}") from None


def _model_text(model):
    """(the model's docs/format.md JSON text, its file's path or None) of a Model, a dict, a JSON
    text or a file path."""
    if isinstance(model, Model):
        return model.to_json(), None
    if isinstance(model, dict):
        return _dumps(model), None
    if isinstance(model, str) and model.lstrip().startswith("{"):
        return model, None
    path = _os.fspath(model)
    return _read_text(path), path
