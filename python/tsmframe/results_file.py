"""A results.json read back (docs/format.md, "results.json") into the arrays a Result holds, as
`tsf.run` gives them: Result.load(path). The contact columns follow the file's `contacts` (the
contact nodes grouped by what they may touch, ascending ids in each group)."""
import json
import os

import numpy as np


def _steps(document):
    steps = document["steps"]
    staged = any("stage" in s for s in steps)
    return {
        "step": np.array([s["step"] for s in steps], dtype=np.int32),
        "stage": np.array([s.get("stage", 1) if staged else 1 for s in steps], dtype=np.int32),
        "load_factor": np.array([s["load_factor"] for s in steps], dtype=float),
        "iterations": np.array([s["iterations"] for s in steps], dtype=np.int32),
        "converged": np.array([1 if s["converged"] else 0 for s in steps], dtype=np.int32),
        "negative_eigenvalues": np.array([s.get("negative_eigenvalues", -1) for s in steps], dtype=np.int32),
        "residual_norms": [np.array(s["residual_norms"], dtype=float) for s in steps],
        "criterion": [s.get("criterion", "") for s in steps],
    }


def _states(document, index, element_index):
    """displacements, element_forces, reactions (K, ·, 3) and the N, V, M stations per state."""
    states = [s for s in document["steps"] if "displacements" in s]
    n, m = len(index), len(element_index)
    displacements = np.zeros((len(states), n, 3))
    forces = np.zeros((len(states), m, 3))
    reactions = np.zeros((len(states), n, 3))
    sections = []
    for k, s in enumerate(states):
        for node, u in s["displacements"].items():
            displacements[k, index[int(node)]] = u
        for element, f in s["element_forces"].items():
            forces[k, element_index[int(element)]] = f[:3]  # [N, M_i, M_j] (and Y where a contact acts)
        for node, r in s.get("reactions", {}).items():
            reactions[k, index[int(node)]] = r
        rows = [[int(element), *station] for element in sorted(s.get("section_forces", {}), key=lambda e: element_index[int(e)])
                for station in s["section_forces"][element]]
        sections.append(np.array(rows, dtype=float).reshape(-1, 5))
    return {"state_steps": np.array([s["step"] for s in states], dtype=np.int32), "displacements": displacements,
            "element_forces": forces, "reactions": reactions, "section_forces": sections}


def _contacts(document):
    """Per converged step and contact node: element id (0: none), the vertex's other element, α, force."""
    nodes = [node for group in document.get("contacts", []) for node in group["nodes"]]
    column = {node: k for k, node in enumerate(nodes)}
    converged = [s for s in document["steps"] if s["converged"]] if nodes else []
    C, c = len(converged), len(nodes)
    element, also = np.zeros((C, c), dtype=np.int32), np.zeros((C, c), dtype=np.int32)
    alpha, force = np.zeros((C, c)), np.zeros((C, c))
    tangential, slip, friction = np.zeros((C, c)), np.zeros((C, c)), np.full((C, c), "", dtype="U5")
    for k, s in enumerate(converged):
        for p in s.get("contacts", []):
            j = column[p["node"]]
            element[k, j], also[k, j] = p["element"], p.get("also", 0)
            alpha[k, j], force[k, j] = p["xi"], p["force"]
            if "friction" in p:
                tangential[k, j], slip[k, j], friction[k, j] = p["tangential"], p["slip"], p["friction"]
    return {"contact_nodes": np.array(nodes, dtype=np.int32), "contact_element": element, "contact_also": also,
            "contact_alpha": alpha, "contact_force": force, "contact_tangential": tangential, "contact_slip": slip,
            "contact_friction": friction}


def _buckling(document, index):
    modes = document.get("buckling", [])
    shapes = np.zeros((len(modes), len(index), 3))
    for k, mode in enumerate(modes):
        for node, u in mode["shape"].items():
            shapes[k, index[int(node)]] = u
    return {"buckling_load_factors": np.array([m["load_factor"] for m in modes], dtype=float), "buckling_modes": shapes,
            "buckling_step": document.get("buckling_from", {}).get("step", 0)}


def read_results(path):
    """The data of a Result from a results.json (and the steps.csv beside it, if there): a dict of
    the arrays and texts Result holds. ValueError ("PATH: reason") where it is not one."""
    try:
        with open(path) as f:
            text = f.read()
        document = json.loads(text)
    except OSError as e:
        raise ValueError(f"{path}: cannot read: {e.strerror}") from None
    except json.JSONDecodeError as e:
        raise ValueError(f"{path}: invalid JSON at line {e.lineno}, column {e.colno}: {e.msg}") from None
    if not isinstance(document, dict) or document.get("format") != "tsmframe-results/1":
        raise ValueError(f'{path}: not a results.json of tsmframe (its "format" is not "tsmframe-results/1")')
    nodes, elements = document["nodes"], document["elements"]
    index = {n["id"]: k for k, n in enumerate(nodes)}
    element_index = {e["id"]: k for k, e in enumerate(elements)}
    csv = os.path.join(os.path.dirname(os.path.abspath(path)), "steps.csv")
    data = {
        "status": document["status"], "message": document["message"], "notes": document.get("notes", []),
        "critical_points": [{**c, "bracket": tuple(c["bracket"])} for c in document.get("critical_points", [])],
        "limit_points": document.get("limit_points", []),
        "neutral_equilibria": [{**n, **({"about": tuple(n["about"])} if "about" in n else {"direction": tuple(n["direction"])})}
                               for n in document.get("neutral_equilibria", [])],
        "rounded_inertia": document.get("rounded_inertia", []),
        "stages": document.get("stages", []),
        "node_ids": np.array([n["id"] for n in nodes], dtype=np.int32),
        "node_xy": np.array([[n["x"], n["y"]] for n in nodes], dtype=float).reshape(-1, 2),
        "element_ids": np.array([e["id"] for e in elements], dtype=np.int32),
        "element_nodes": np.array([e["nodes"] for e in elements], dtype=np.int32).reshape(-1, 2),
        "element_members": np.array([e["member"] for e in elements], dtype=np.int32),
        "element_kinds": [e["element"] for e in elements],
        "results_json": text,
        "steps_csv": open(csv).read() if os.path.exists(csv) else "",
    }
    data.update(_steps(document))
    data.update(_states(document, index, element_index))
    data.update(_contacts(document))
    data.update(_buckling(document, index))
    return data
