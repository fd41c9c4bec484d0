"""The Python module (issue 7), run by pytest from the README's test command:
results equal the CLI's results.json bit for bit, bad input raises ValueError with the JSON path,
arrays have the documented shapes, the model builder works, plots are written as PNG."""
import html
import json
import math
import os
import re
import subprocess
import sys

import numpy as np
import pytest

import tsmframe as tf

SOURCE = os.environ.get("TSMFRAME_SOURCE_DIR", os.path.join(os.path.dirname(__file__), "..", ".."))
CLI = os.environ.get("TSMFRAME_CLI", os.path.join(SOURCE, "build", "tsmframe"))


@pytest.mark.parametrize("example", ["contact-push.json", "lee-frame-arc-length.json", "portal-frame.json"])
def test_results_equal_the_command_line_bit_for_bit(example, tmp_path):
    path = os.path.join(SOURCE, "examples", example)
    cli = subprocess.run([CLI, "run", path, "--out", str(tmp_path), "-q"], capture_output=True, text=True)
    assert cli.returncode == 0, cli.stderr
    r = tf.run(path)
    assert r.results_json == (tmp_path / "results.json").read_text()
    assert r.steps_csv == (tmp_path / "steps.csv").read_text()


def test_arrays_have_the_documented_shapes():
    r = tf.run(os.path.join(SOURCE, "examples", "contact-push.json"))  # output every 20th step
    n, m, c = len(r.node_ids), len(r.element_ids), len(r.contact_nodes)
    S, C = len(r.step), int(r.converged.sum())
    K = len(r.state_steps)
    assert (n, m, c, S, C, K) == (20, 18, 1, 200, 200, 10)
    assert r.node_xy.shape == (n, 2) and r.element_nodes.shape == (m, 2)
    assert r.displacements.shape == (K, n, 3) and r.element_forces.shape == (K, m, 3) and r.reactions.shape == (K, n, 3)
    assert r.contact_element.shape == (C, c) and r.contact_alpha.shape == (C, c) and r.contact_force.shape == (C, c)
    assert r.contact_also.shape == (C, c) and not r.contact_also.any()  # never resting on a node
    assert len(r.residual_norms) == S and len(r.criterion) == S
    assert list(r.state_steps) == list(range(20, 201, 20))
    # the pusher is at its prescribed 2 m, the contact point in element 10, compression positive
    assert r.displacement(100)[1] == pytest.approx(2.0, abs=1e-12)
    assert r.contact_element[-1, 0] == 10 and r.contact_force[-1, 0] > 0
    assert json.loads(r.results_json)["steps"][-1]["contacts"][0]["xi"] == r.contact_alpha[-1, 0]


def test_a_vertex_names_both_elements():
    # A pinned beam of 20 elements pushed 0.1 m on its mid-span node: both elements at the node
    # carry the contact (a vertex); the arrays say which, as results.json does.
    m = tf.Model("vertex").material("steel", E=2e11, G=7.7e10).section("s", A=4e-3, I=2e-5, shear_area=2e-3)
    m.node(1, 0, 0).node(2, 10, 0).node(9, 5, 0.001)
    m.member(1, 2, "steel", "s", divisions=20, element="timoshenko")
    m.support(1, "pinned").support(2, "pinned").support(9, fix=["ux"]).prescribe(9, uy=-0.1).contact(9)
    m.analysis(steps=4)  # load control in 4 steps
    r = tf.run(m)
    assert len(r.step) == 4
    assert r.ok, r.message
    last = json.loads(r.results_json)["steps"][-1]["contacts"][0]
    assert (r.contact_element[-1, 0], r.contact_also[-1, 0], r.contact_alpha[-1, 0]) == (last["element"], last["also"], 1.0)
    assert r.contact_also[-1, 0] == r.contact_element[-1, 0] + 1


def test_one_contact_entry_for_many_nodes():
    # A ring of 20 elements squeezed 1 cm between two plates: nodes={"members": [0, 1]} makes
    # every ring node a contact node on both plates, one column each in the contact arrays; the
    # bottom and top nodes (resting on the plates from the start) carry the same force. A node
    # list gives the same run; node and nodes together are refused.
    import math
    def ring(nodes):
        m = tf.Model("ring").material("steel", E=2e11, nu=0.3).section("ring", A=1e-3, I=1e-7).section("plate", A=0.1, I=1e-4)
        m.node(1, 0, -1).node(2, 0, 1).node(101, -1.5, -1.01).node(102, 1.5, -1.01).node(103, -1.5, 1.01).node(104, 1.5, 1.01)
        m.member(1, 2, "steel", "ring", divisions=10, arc=(0, 0, math.pi)).member(2, 1, "steel", "ring", divisions=10, arc=(0, 0, math.pi))
        m.member(101, 102, "steel", "plate", divisions=30).member(103, 104, "steel", "plate", divisions=30)
        for n in (101, 102, 103, 104):
            m.support(n, "fixed")
        m.support(1, fix=["ux"]).support(2, fix=["ux"]).prescribe(103, uy=-0.01).prescribe(104, uy=-0.01)
        m.contact(nodes=nodes, members=[2, 3], gap=0.01, edge=0.1).analysis(steps=2)
        return tf.run(m)
    r = ring({"members": [0, 1]})
    assert r.ok, r.message
    assert r.contact_force.shape[1] == 20
    touching = [k for k in range(20) if r.contact_element[-1, k] > 0]  # element id, 0 where none
    assert len(touching) == 2
    assert r.contact_force[-1, touching[0]] == pytest.approx(r.contact_force[-1, touching[1]], rel=1e-6)
    listed = ring([1, 2] + list(range(105, 123)))
    def without_state(result):  # the restart state lists the contacts in the order they were made
        document = json.loads(result.results_json)
        for step in document["steps"]:
            step.pop("state", None)
        return document
    assert without_state(listed) == without_state(r)
    with pytest.raises(ValueError, match="give node or nodes"):
        tf.Model().contact(1, nodes=[2])


def test_a_contact_between_two_beams_is_the_files_entry():
    # Two overlapping cantilevers (20 elements each), the upper tip pushed down onto the lower
    # beam: contact(between=(...)) writes the file's "between" entry, every node of each beam a
    # contact node on the other (42), and either order gives the same tip force.
    def crossing(between):
        m = tf.Model("crossing").material("steel", E=2.05e11, nu=0.3).section("bar", A=1e-3, I=1e-6)
        m.node(1, 0, 0).node(2, 2, 0).node(3, 3, 0.05).node(4, 1, 0.05)
        m.member(1, 2, "steel", "bar", divisions=20).member(3, 4, "steel", "bar", divisions=20)
        m.support(1, "fixed").support(3, "fixed").load(4, fy=-2e4).contact(between=between).analysis(steps=10)
        return tf.run(m)
    ab, ba = crossing(([0], [1])), crossing(([1], [0]))
    assert ab.ok and ba.ok, (ab.message, ba.message)
    assert ab.contact_force.shape[1] == 42
    assert ab.contact_force[-1].max() == pytest.approx(ba.contact_force[-1].max(), rel=1e-12)
    assert ab.contact_force[-1].max() > 1e4
    with pytest.raises(ValueError, match="give between"):
        tf.Model().contact(1, between=([0], [1]))


def test_a_study_runs_its_cases_and_returns_their_rows():
    # The README's cantilever (EI = 2.05e7) under 1 kN over two meshes: each row has the
    # parameter, how the case ended and the recorded tip deflection, PL³/3EI for an
    # Euler–Bernoulli mesh whatever its divisions (to the geometric effect, 1e-5 here). A bad
    # study file raises ValueError with its JSON path; a case that fails is a row.
    m = tf.Model("cantilever").material("steel", E=2.05e11).section("s", A=1e-2, I=1e-4)
    m.node(1, 0, 0).node(2, 4, 0).member(1, 2, "steel", "s", divisions=8).support(1, "fixed").load(2, fy=-1e3)
    definition = {"format": "tsmframe-study/1", "model": m.to_dict(),
                  "sweep": [{"name": "divisions", "path": "/members/0/divisions", "values": [2, 16]},
                            {"name": "allowed_iterations", "path": "/analysis/max_iterations", "values": [50, 1]}],
                  "record": [{"name": "tip_uy", "quantity": "displacement", "node": [4.0, 0.0], "dof": "uy"}]}
    rows = tf.study(definition, jobs=2)
    assert [(r["case"], r["divisions"], r["allowed_iterations"]) for r in rows] == [
        (1, 2, 50), (2, 2, 1), (3, 16, 50), (4, 16, 1)]  # numbers, as the study gave them
    exact = -1e3 * 4.0 ** 3 / (3 * 2.05e11 * 1e-4)
    for r in (rows[0], rows[2]):
        assert r["converged"] and r["tip_uy"] == pytest.approx(exact, rel=1e-5)
    assert not rows[1]["converged"] and rows[1]["message"]  # one Newton iteration is not enough
    with pytest.raises(ValueError, match=r"record\[0\]\.quantity: unknown quantity"):
        tf.study({**definition, "record": [{"name": "x", "quantity": "stress"}]})
    # A base model invalid where no parameter reaches: refused before any case runs.
    broken = json.loads(json.dumps(definition))
    broken["model"]["members"][0]["material"] = "stel"
    with pytest.raises(ValueError, match=r'^model: members\[0\]\.material: unknown material "stel" \(in the first and the last case alike'):
        tf.study(broken)


def test_a_studys_rows_say_whether_each_end_state_is_stable_and_what_the_run_noted():
    # A pinned-pinned Euler column (L = 4 m, EI = 2·10⁵ N m², 20 elements) under 0.95 and 1.05 of
    # π²EI/L² in one step: a perfect column stays straight, stable below the buckling load, and
    # with one negative eigenvalue above it — which a plain "converged" row did not tell.
    P = math.pi ** 2 * 2e11 * 1e-6 / 4.0 ** 2
    m = tf.Model("column").material("steel", E=2e11).section("s", A=1e-2, I=1e-6)
    m.node(1, 0, 0).node(2, 4, 0).member(1, 2, "steel", "s", divisions=20)
    m.support(1, "pinned").support(2, "roller-x").load(2, fx=-P)
    rows = tf.study({"format": "tsmframe-study/1", "model": m.to_dict(),
                     "sweep": [{"name": "axial_force", "path": "/loads/0/fx", "values": [-0.95 * P, -1.05 * P]}]})
    assert [(r["converged"], r["negative_eigenvalues"]) for r in rows] == [(True, 0), (True, 1)]
    assert rows[0]["notes"] == ""
    assert "unstable equilibrium" in rows[1]["notes"] and "bifurcation" in rows[1]["notes"]


def test_a_ring_closed_on_its_pin_is_neutral_and_says_how_it_may_move():
    # A beam (L = 10 m) on a pin and a roller bent by end moments M = 2πEI/L into a full circle
    # (exact for any mesh): its ends meet on the pin, where every support reaction acts, so the
    # ring may turn about it; the moments do no work on that turn. Neutral: no eigenvalue count.
    EI = 2e11 * 8e-6
    M = 2 * math.pi * EI / 10.0
    m = tf.Model("ring").material("steel", E=2e11).section("s", A=1e-2, I=8e-6)
    m.node(1, 0, 0).node(2, 10, 0).member(1, 2, "steel", "s", divisions=12)
    m.support(1, "pinned").support(2, "roller-x").load(1, mz=-M).load(2, mz=M).analysis(steps=2)
    r = tf.run(m)
    assert r.ok, r.message
    assert list(r.negative_eigenvalues) == [0, -1]  # a half circle is stable
    [neutral] = r.neutral_equilibria
    assert (neutral["step"], neutral["node"], neutral["part_nodes"], neutral["motion"]) == (2, 1, 13, "rotation")
    assert neutral["about"] == pytest.approx((0.0, 0.0), abs=1e-6 * 10.0)
    assert any("neutral equilibrium" in note for note in r.notes), r.notes
    rows = tf.study({"format": "tsmframe-study/1", "model": m.to_dict(),
                     "sweep": [{"name": "divisions", "path": "/members/0/divisions", "values": [12]}]})
    assert rows[0]["negative_eigenvalues"] is None and "neutral equilibrium" in rows[0]["notes"]


def test_a_column_whose_pivots_round_off_its_bending_stiffness_is_told_unknown_not_guessed(tmp_path):
    # A steel cantilever column 4 m long in 10⁴ elements, at 0.95 of its Euler load: its bending
    # stiffness as a whole is ~1e-13 of one element's, below the factorisation's rounding; the
    # count there came out 1 (unstable) before. In 10³ elements it is 0, known.
    E, I, L = 2.05e11, 1e-4 / 12, 4.0
    P = math.pi ** 2 * E * I / (4 * L * L)

    def column(divisions):
        m = tf.Model("column").material("steel", E=E).section("s", A=0.01, I=I)
        m.node(1, 0, 0).node(2, L, 0).member(1, 2, "steel", "s", divisions=divisions)
        return m.support(1, "fixed").load(2, fx=-0.95 * P)

    fine = tf.run(column(10000))
    assert fine.ok, fine.message
    assert list(fine.negative_eigenvalues) == [-1]
    [rounded] = fine.rounded_inertia
    assert rounded["step"] == 1 and rounded["dof"] in ("ux", "uy", "rz") and 0 < rounded["ratio"] < 1e-12
    assert 1 < rounded["node"] <= 10001
    assert any("stability unknown" in note for note in fine.notes), fine.notes
    fine.write(str(tmp_path))
    assert tf.Result.load(tmp_path / "results.json").rounded_inertia == fine.rounded_inertia
    coarse = tf.run(column(1000))
    assert list(coarse.negative_eigenvalues) == [0] and coarse.rounded_inertia == []


def test_a_study_file_that_is_no_json_says_so_as_the_command_line_does(tmp_path):
    path = tmp_path / "broken.json"
    path.write_text('{\n  "sweep": [\n    {"name": "n",, "values": [1]}\n  ]\n}\n')
    cli = subprocess.run([CLI, "study", str(path), "--out", str(tmp_path / "out")], capture_output=True, text=True)
    assert cli.returncode == 2
    assert cli.stderr.startswith(f"{path}: invalid JSON at line 3, column 18: "), cli.stderr
    with pytest.raises(ValueError) as raised:
        tf.study(str(path))
    assert f"{path}: {raised.value}" == cli.stderr.strip()


def test_bad_model_raises_value_error_with_the_path():
    doc = tf.load(os.path.join(SOURCE, "examples", "portal-frame.json")).to_dict()
    doc["members"][1]["section"] = "nope"
    with pytest.raises(ValueError, match=r"members\[1\]\.section: unknown section \"nope\""):
        tf.run(doc)
    with pytest.raises(ValueError, match=r"missing\.json: cannot read"):
        tf.run("missing.json")


def test_numpy_numbers_are_numbers_like_any_other():
    # Ids, coordinates, divisions and loads from numpy (np.arange, np.linspace, np.float32) build
    # the same model as Python numbers: the same results bit for bit, the tip's deflection PL³/3EI
    # (to the geometric effect, 1e-5 here).
    def cantilever(number):
        m = tf.Model("cantilever").material("steel", E=number(2.05e11)).section("s", A=1e-2, I=number(1e-4))
        m.node(number(1), number(0.0), 0).node(2, np.linspace(0.0, 4.0, 3)[2], 0)
        return m.member(1, 2, "steel", "s", divisions=np.int64(8)).support(number(1), "fixed").load(2, fy=np.float64(-1e3))
    plain, numpy = tf.run(cantilever(lambda v: v)), tf.run(cantilever(lambda v: np.array([v])[0]))
    assert numpy.results_json == plain.results_json
    assert numpy.displacement(2)[1] == pytest.approx(-1e3 * 4.0 ** 3 / (3 * 2.05e11 * 1e-4), rel=1e-5)
    nodes = np.arange(10, 13)  # a contact entry's nodes as an array of int64
    m = cantilever(lambda v: v)
    for k, node in enumerate(nodes):
        m.node(node, 1.0 + k, 0.5).support(node, "fixed")
    assert tf.run(m.contact(members="all", nodes=nodes)).status == "converged"


def test_a_number_json_cannot_hold_is_named_by_its_path():
    # NaN and infinities have no JSON: named where they are, as the reader names any bad value,
    # not "invalid JSON at line 47".
    def cantilever():
        m = tf.Model("t").material("m", E=2e11).section("s", A=1e-2, I=1e-4).node(1, 0, 0).node(2, 4, 0)
        return m.member(1, 2, "m", "s").support(1, "fixed")
    m = cantilever().load(2, fy=float("nan"))
    with pytest.raises(ValueError, match=r"^loads\[0\]\.fy: nan is not a finite number$"):
        tf.run(m)
    with pytest.raises(ValueError, match=r"^loads\[0\]\.fy: nan is not a finite number$"):
        m.to_json()
    m = cantilever().load(2, fy=-1.0)
    document = json.loads(m.to_json())
    document["loads"] = [{"node": 2, "fy": np.float64("-inf")}]
    with pytest.raises(ValueError, match=r"^loads\[0\]\.fy: -inf is not a finite number$"):
        tf.run(document)
    study = {"format": "tsmframe-study/1", "model": json.loads(m.to_json()),
             "sweep": [{"name": "E", "path": "/materials/m/E", "values": [2e11, float("inf")]}]}
    with pytest.raises(ValueError, match=r"^sweep\[0\]\.values\[1\]: inf is not a finite number$"):
        tf.study(study)


def test_non_convergence_is_a_status_not_an_exception():
    # PL²/EI = 1 in one step, without cutback, in one Newton iteration: not reached.
    m = tf.Model("too few iterations").material("m", E=1.0).section("s", A=1e4, I=1.0)
    m.node(1, 0, 0).node(2, 1, 0).member(1, 2, "m", "s", divisions=4).support(1, "fixed").load(2, fy=1.0)
    m.analysis({"type": "load", "steps": 1}, cutback=False, max_iterations=1)
    r = tf.run(m)
    assert r.status != "converged" and not r.ok and r.message
    assert r.converged.tolist() == [0]


def test_a_jump_across_a_snap_back_is_a_note():
    # DaDeppo & Schmidt's 215° arch as 60 straight elements, its crown driven down 150 under
    # displacement control: past the maximum (P R²/EI 8.97) the path snaps back and a step
    # lands on another branch. The run converges; r.notes says so, as results.json does.
    R, half, N = 100.0, math.radians(107.5), 60
    nodes = [{"id": i + 1, "x": R * math.sin(-half + 2 * half * i / N), "y": R * math.cos(-half + 2 * half * i / N)}
             for i in range(N + 1)]
    members = [{"from": i + 1, "to": i + 2, "material": "m", "section": "s"} for i in range(N)]
    doc = {"materials": {"m": {"E": 1e6}}, "sections": {"s": {"A": 100.0, "I": 1.0}}, "nodes": nodes,
           "members": members, "supports": [{"node": 1, "type": "pinned"}, {"node": N + 1, "type": "fixed"}],
           "loads": [{"node": N // 2 + 1, "fy": -100.0}],
           "analysis": {"control": {"type": "displacement", "node": N // 2 + 1, "dof": "uy", "target": -150,
                                    "steps": 30}}}
    r = tf.run(doc)
    assert r.ok, r.message
    assert max(r.load_factor) == pytest.approx(8.97, rel=0.01)
    assert "snap back" in r.notes[0]
    assert all("unstable equilibri" in note for note in r.notes[1:])
    assert json.loads(r.results_json)["notes"] == r.notes
    doc["analysis"]["control"]["target"] = -100  # before the maximum: nothing to note
    assert tf.run(doc).notes == []


def test_a_three_hinged_arch_built_in_code_has_the_thrust_of_statics():
    # Two members hinged at the crown (release), pinned feet: H = P L / (4 h).
    m = tf.Model("three-hinged arch").material("s", E=2e11).section("x", A=0.01, I=1e-4)
    m.node(1, 0, 0).node(2, 5, 2).node(3, 10, 0)
    m.member(1, 2, "s", "x", divisions=10, release="end").member(2, 3, "s", "x", divisions=10, release="start")
    m.support(1, "pinned").support(3, "pinned").load(2, fy=-1000.0)
    r = tf.run(m)
    assert r.ok, r.message
    left = r.reactions[-1, list(r.node_ids).index(1)]
    assert left[0] == pytest.approx(1250.0, rel=1e-4) and left[1] == pytest.approx(500.0, rel=1e-6)
    # A distributed load on the members (force per unit length, lumped at the element ends) in
    # place of the point load: the feet carry its total, w times the members' length.
    m = tf.Model("arch under its weight").material("s", E=2e11).section("x", A=0.01, I=1e-4)
    m.node(1, 0, 0).node(2, 5, 2).node(3, 10, 0)
    m.member(1, 2, "s", "x", divisions=10, release="end", load=(0.0, -100.0))
    m.member(2, 3, "s", "x", divisions=10, release="start", load=(0.0, -100.0))
    m.support(1, "pinned").support(3, "pinned")
    r = tf.run(m)
    assert r.ok, r.message
    feet = r.reactions[-1, [list(r.node_ids).index(1), list(r.node_ids).index(3)], 1].sum()
    assert feet == pytest.approx(100.0 * 2 * math.hypot(5.0, 2.0), rel=1e-8)  # to the run's tolerance
    # The same arch under its own weight: a density and gravity make the member load ρ A g.
    m = tf.Model("arch under its own weight").material("s", E=2e11, density=7850.0).section("x", A=0.01, I=1e-4)
    m.gravity(0.0, -9.81).node(1, 0, 0).node(2, 5, 2).node(3, 10, 0)
    m.member(1, 2, "s", "x", divisions=10, release="end").member(2, 3, "s", "x", divisions=10, release="start")
    m.support(1, "pinned").support(3, "pinned")
    r = tf.run(m)
    assert r.ok, r.message
    feet = r.reactions[-1, [list(r.node_ids).index(1), list(r.node_ids).index(3)], 1].sum()
    assert feet == pytest.approx(7850.0 * 0.01 * 9.81 * 2 * math.hypot(5.0, 2.0), rel=1e-8)


def test_stages_built_in_code_hold_what_earlier_stages_applied():
    # A cantilever (EI 1, L 1) given a tip force in stage 1, then a tip moment in stage 2, ends
    # where one stage with both takes it; each step says its stage.
    def cantilever():
        m = tf.Model("staged").material("m", E=1.0, G=0.5).section("s", A=1e4, I=1.0)
        m.node(1, 0, 0).node(2, 1, 0).member(1, 2, "m", "s", divisions=10).support(1, "fixed")
        return m.analysis(tolerance=1e-12)
    staged = cantilever().stage("force", steps=3).load(2, fy=1.5).stage("moment", steps=3).load(2, mz=0.8)
    single = cantilever().load(2, fy=1.5, mz=0.8).analysis(steps=6)
    a, b = tf.run(staged), tf.run(single)
    assert a.ok and b.ok, (a.message, b.message)
    assert list(a.stage) == [1, 1, 1, 2, 2, 2] and list(a.step) == [1, 2, 3, 4, 5, 6]
    assert [s["last_step"] for s in a.stages] == [3, 6]
    import matplotlib
    matplotlib.use("Agg")
    lines = a.plot_load_displacement(2).lines  # each stage its own curve, from where the one before ended
    assert [line.get_label() for line in lines] == ["uy of node 2, stage 1", "uy of node 2, stage 2"]
    assert lines[1].get_xdata()[0] == lines[0].get_xdata()[-1] and lines[1].get_ydata()[0] == 0.0
    assert np.abs(a.displacements[-1] - b.displacements[-1]).max() < 1e-9 * np.abs(b.displacements[-1]).max()
    # Loads given before the first stage are refused where they are given.
    with pytest.raises(ValueError, match="before the first stage"):
        cantilever().load(2, fy=1.0).stage("late")


def test_springs_and_a_foundation_built_in_code():
    # A cantilever tip on a spring twice its own stiffness takes two thirds of the load; a beam
    # on a foundation (k) under its own load w per length sinks w/k away from its ends.
    m = tf.Model("tip on a spring").material("s", E=2e11).section("x", A=1e-2, I=1e-4)
    k = 2 * 3 * 2e11 * 1e-4 / 4.0 ** 3
    m.node(1, 0, 0).node(2, 4, 0).member(1, 2, "s", "x", divisions=8).support(1, "fixed").spring(2, ky=k).load(2, fy=-1e3)
    r = tf.run(m)
    assert r.ok, r.message
    assert r.displacement(2)[1] == pytest.approx(-1e3 / (1.5 * k), rel=1e-6)
    b = tf.Model("beam on a foundation").material("s", E=2e11).section("x", A=1e-2, I=1e-4)
    b.node(1, 0, 0).node(2, 40, 0).member(1, 2, "s", "x", divisions=80, load=(0.0, -1e3), foundation=1e8).support(1, fix=["ux"])
    r = tf.run(b)
    assert r.ok, r.message
    middle = r.displacements[-1][list(r.node_xy[:, 0]).index(20.0)]  # 20 decay lengths from either end
    assert middle[1] == pytest.approx(-1e3 / 1e8, rel=1e-6)
    # A point load along a member: the simply supported beam's P a²b²/3EIL under it.
    s = tf.Model("off-node load").material("s", E=2e11).section("x", A=1e-2, I=1e-4)
    s.node(1, 0, 0).node(2, 4, 0).member(1, 2, "s", "x", divisions=4).support(1, "pinned").support(2, "roller-x")
    r = tf.run(s.load_along(0, 0.3, fy=-1e3))
    assert r.ok, r.message
    under = r.displacements[-1][list(np.round(r.node_xy[:, 0], 12)).index(1.2)]
    assert under[1] == pytest.approx(-1e3 * 1.2 ** 2 * 2.8 ** 2 / (3 * 2e11 * 1e-4 * 4), rel=1e-6)


def test_a_skew_roller_built_in_code_pushes_across_its_plane():
    # Pinned at one end, on a roller inclined at 30° at the other, P down at mid-span: the roller
    # pushes across its plane with P / (2 cos 30°); the node stays on the plane.
    m = tf.Model("skew roller").material("s", E=2e11).section("x", A=1e-2, I=1e-4)
    c, s = math.cos(math.pi / 6), math.sin(math.pi / 6)
    m.node(1, 0, 0).node(2, 4, 0).member(1, 2, "s", "x", divisions=8).support(1, "pinned")
    r = tf.run(m.support(2, roller=(np.float64(c), s)).load([2.0, 0.0], fy=-1e3))
    assert r.ok, r.message
    rx, ry = r.reactions[-1][1][:2]
    assert (rx, ry) == (pytest.approx(-1e3 / (2 * c) * s, rel=1e-6), pytest.approx(500.0, rel=1e-6))
    u = r.displacement(2)
    assert abs(-s * u[0] + c * u[1]) < 1e-15
    with pytest.raises(ValueError, match=r"supports\[2\]\.roller"):
        tf.run(m.support(2, roller=(0, 0)))


def test_a_run_goes_on_from_a_kept_step_of_an_earlier_one(tmp_path):
    # tf.run(m, start=result, step=k) is the CLI's --from: the steps after k, bit for bit.
    m = tf.Model("elastica").material("m", E=1.0, G=0.5).section("s", A=1e4, I=1.0)
    m.node(1, 0, 0).node(2, 1, 0).member(1, 2, "m", "s", divisions=10).support(1, "fixed").load(2, fy=4.0).analysis(steps=6)
    whole = tf.run(m)
    rest = tf.run(m, start=whole, step=2)
    assert rest.ok, rest.message
    assert list(rest.step) == [3, 4, 5, 6]
    assert np.array_equal(rest.displacements[-1], whole.displacements[-1])
    whole.write(tmp_path / "whole")
    done = tf.run(m, start=tmp_path / "whole" / "results.json")  # from its last step: nothing is left to run
    assert done.ok and len(done.step) == 0
    with pytest.raises(ValueError, match="start: steps: no step 9"):
        tf.run(m, start=whole, step=9)


def test_a_shallow_arch_built_in_code_snaps_through_and_says_so():
    # A pinned circular arch (span 10 m, rise 1.18 m, 40 elements) under 5 MN at its crown in 10
    # load steps: past the bifurcation at λ ≈ 0.78 step 9 lands on the inverted shape (its crown
    # 2.5 m down, beyond twice the rise). Found as a user: the run said nothing of the jump. The arc
    # given as the model file writes it ({"center", "sweep"}, which raised KeyError) builds the
    # same model as the tuple.
    def arch(arc):
        m = tf.Model("arch").material("steel", E=2e11, nu=0.3).section("s", A=0.01, I=1e-4)
        m.node(1, -5, 0).node(2, 5, 0).member(1, 2, "steel", "s", divisions=40, arc=arc)
        m.support(1, "pinned").support(2, "pinned").load([0.0, 11.180339887498949 - 10.0], fy=-5e6)
        return tf.run(m.analysis(steps=10))
    sweep = -2.0 * math.atan(0.5)
    r = arch({"center": [0.0, -10.0], "sweep": sweep})
    assert r.ok, r.message
    assert r.results_json == arch((0.0, -10.0, sweep)).results_json
    crown = int(np.flatnonzero((np.abs(r.node_xy[:, 0]) < 1e-9) & (r.node_xy[:, 1] > 1.0))[0])
    assert r.displacements[-1, crown, 1] < -2.0 * (11.180339887498949 - 10.0)  # below the feet's mirror image
    # The note names the step in which the crown went from above its feet to below them, a step
    # past the bifurcation.
    assert list(r.state_steps) == list(r.step)  # every step's state
    crown_y = r.node_xy[crown, 1] + r.displacements[:, crown, 1]
    [jump] = [k for k in range(1, len(crown_y)) if crown_y[k - 1] > 0.0 > crown_y[k]]
    assert r.load_factor[jump] > 0.78
    snaps = [n for n in r.notes if "snapped through" in n]
    assert len(snaps) == 1 and snaps[0].startswith(f"step {r.state_steps[jump]} moved "), r.notes


def test_a_beam_on_end_springs_built_in_code_has_the_moments_of_slope_deflection():
    # Clamped through springs k at both ends, P at mid-span: M = (PL/8) κ/(1 + κ), κ = kL/2EI.
    L, EI, P, k = 4.0, 2.0, 1e-6, 1.0
    m = tf.Model("semi-rigid beam").material("s", E=1.0).section("x", A=1e4, I=EI)
    m.node(1, 0, 0).node(2, L, 0)
    m.member(1, 2, "s", "x", divisions=10, end_springs={"start": k, "end": k})
    m.support(1, "fixed").support(2, "fixed").load((L / 2, 0.0), fy=-P)
    m.analysis({"type": "load", "steps": 1}, tolerance=1e-13)
    r = tf.run(m)
    assert r.ok, r.message
    kappa = k * L / (2 * EI)
    assert r.reactions[-1, list(r.node_ids).index(1), 2] == pytest.approx(P * L / 8 * kappa / (1 + kappa), rel=1e-8)
    assert r.json()["elements"][0]["end_springs"] == {"start": k}


def test_a_ring_built_in_code_loses_stability_at_its_critical_pressure():
    # Two half-circle arc members, external pressure (clockwise members: their left side is the
    # outside): stable below 3EI/R³, two negative eigenvalues (its ovalisation modes) above.
    def ring(p):
        m = tf.Model("ring").material("s", E=1.0).section("x", A=1e6, I=1.0)
        m.node(1, 1.0, 0.0).node(2, -1.0, 0.0)
        m.member(1, 2, "s", "x", divisions=32, arc=(0.0, 0.0, -math.pi), pressure=p)
        m.member(2, 1, "s", "x", divisions=32, arc=(0.0, 0.0, -math.pi), pressure=p)
        m.support(1, "pinned").support(2, fix=["uy"])
        return tf.run(m)
    below, above = ring(0.95 * 3.0), ring(1.05 * 3.0)
    assert below.ok and above.ok
    assert list(below.negative_eigenvalues) == [0] and list(above.negative_eigenvalues) == [2]
    assert "bifurcation point" in above.notes[0]
    assert below.critical_points == [] and above.critical_points == []  # one step: nothing to bracket


def test_model_built_in_code_rolls_into_a_circle():
    L, EI = 10.0, 2.05e11 * 8.333e-6
    m = tf.Model("circle").material("steel", E=2.05e11, G=7.9e10).section("s", A=1e-2, I=8.333e-6, shear_area=8.33e-3)
    m.node(1, 0, 0).node(2, L, 0).member(1, 2, "steel", "s", divisions=40, element="timoshenko")
    m.support(1, "fixed").load(2, mz=2 * math.pi * EI / L)
    m.analysis({"type": "load", "steps": 1}, max_iterations=100)
    r = tf.run(m)
    assert r.ok, r.message
    ux, uy, rz = r.displacement(2)
    assert rz == pytest.approx(2 * math.pi, abs=1e-8)
    assert math.hypot(L + ux, uy) < 1e-6 * L  # the tip is back at the root


def test_a_follower_tip_force_built_in_code_stays_normal_to_the_tip():
    # The support carries the force turned with the tip: −P (−sin θ, cos θ), whatever θ (statics).
    P = 3.0
    m = tf.Model("follower").material("m", E=1.0, G=1.0).section("s", A=1e8, I=1.0, shear_area=1e14)
    m.node(1, 0, 0).node(2, 1, 0).member(1, 2, "m", "s", divisions=20)
    m.support(1, "fixed").load(2, fy=P, follower=True)
    m.analysis(steps=4)
    r = tf.run(m)
    assert r.ok, r.message
    theta = r.displacement(2)[2]
    assert theta > 1.0  # turned far enough for the direction to matter
    rx, ry = r.reactions[-1, r._node(1), :2]
    assert rx == pytest.approx(P * math.sin(theta), abs=1e-8)
    assert ry == pytest.approx(-P * math.cos(theta), abs=1e-8)


def off_chord(curve):
    """The largest distance of a curve's points (k, 2) from the line through its ends, and its chord's length."""
    chord = curve[-1] - curve[0]
    length = math.hypot(*chord)
    offset = curve - curve[0]
    return float(np.abs(chord[0] * offset[:, 1] - chord[1] * offset[:, 0]).max()) / length, length


def pieces(line):
    """A drawn line's pieces between its NaN breaks (plot_shape: one line per state, one piece per element)."""
    points = np.column_stack(line.get_data())
    parts = (part[~np.isnan(part[:, 0])] for part in np.split(points, np.flatnonzero(np.isnan(points[:, 0]))))
    return [part for part in parts if len(part)]


def test_a_pin_jointed_truss_is_drawn_with_straight_bars(tmp_path):
    # examples/warren-truss.json: every bar is hinged at both ends and carries no moment, so its
    # curve lies on its chord (within 1e-12 of its length) — the solver's own curve (Result.curves),
    # the command line's results.json "curves" to the bit, and what plot_shape draws.
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    path = os.path.join(SOURCE, "examples", "warren-truss.json")
    r = tf.run(path)
    cli = subprocess.run([CLI, "run", path, "--out", str(tmp_path), "--curves", "-q"], capture_output=True, text=True)
    assert cli.returncode == 0, cli.stderr
    states = [s for s in json.loads((tmp_path / "results.json").read_text())["steps"] if "displacements" in s]
    assert len(states) == len(r.state_steps)
    for k, state in enumerate(states):
        curves = r.curves(k)
        assert curves.shape == (len(r.element_ids), 9, 2)
        for element, curve in zip(r.element_ids, curves):
            assert list(curve.ravel()) == state["curves"][str(element)]
            off, length = off_chord(curve)
            assert off < 1e-12 * length, f"element {element} bowed by {off}"
    fig, ax = plt.subplots()
    r.plot_shape(ax=ax, undeformed=False)
    drawn = r.curves(-1, segments=12)
    assert len(ax.lines) == 1  # one artist per state
    assert len(pieces(ax.lines[0])) == len(drawn)
    for piece, curve in zip(pieces(ax.lines[0]), drawn):
        assert np.array_equal(piece, curve)
    plt.close(fig)


def test_a_colour_given_to_plot_shape_draws_every_step_in_it():
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.colors
    import matplotlib.pyplot as plt
    r = tf.run(os.path.join(SOURCE, "examples", "contact-push.json"))
    fig, ax = plt.subplots()
    r.plot_shape(steps=(0, 4, -1), ax=ax, undeformed=False, color="red")
    assert len(ax.lines) == 3 and all(len(pieces(line)) == len(r.element_ids) for line in ax.lines)
    assert {matplotlib.colors.to_hex(line.get_color()) for line in ax.lines} == {"#ff0000"}
    plt.close(fig)
    fig, ax = plt.subplots()  # without one, each step its own colour
    r.plot_shape(steps=(0, -1), ax=ax, undeformed=False)
    assert len({matplotlib.colors.to_hex(line.get_color()) for line in ax.lines}) == 2
    plt.close(fig)
    # Magnified: every point of the curve 10 times as far from its place on the drawn chord.
    fig, ax = plt.subplots()
    r.plot_shape(ax=ax, undeformed=False, scale=10.0)
    curves = r.curves(-1, segments=12)
    for line, curve, (a, b) in zip(pieces(ax.lines[0]), curves, r.element_nodes):
        start, end = (r.node_xy[int(np.flatnonzero(r.node_ids == n)[0])] for n in (a, b))
        drawn = start + np.outer(np.linspace(0, 1, 13), end - start)
        assert np.allclose(line, drawn + 10.0 * (curve - drawn), rtol=0, atol=1e-12)
    assert "× 10" in ax.get_title()
    plt.close(fig)


def test_the_diagrams_of_a_portal_frame_follow_its_statics_and_are_drawn_on_it(tmp_path):
    # A fixed-base portal (columns 3 m, beam 4 m) with a small sway load H at the beam's left end:
    # at every section the moment is what the loads and the left base's reactions give about it
    # (statics, nearly the drawn geometry: H is small), V is the slope of M, and results.json
    # holds the same stations the Result does. The diagram is drawn on the frame.
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    H = 1e3
    m = tf.Model("portal").material("steel", E=2.1e11).section("s", A=5e-3, I=8e-5)
    m.node(1, 0, 0).node(2, 0, 3).node(3, 4, 3).node(4, 4, 0)
    m.member(1, 2, "steel", "s", divisions=3).member(2, 3, "steel", "s", divisions=4).member(3, 4, "steel", "s", divisions=3)
    m.support(1, "fixed").support(4, "fixed").load(2, fx=H)
    r = tf.run(m)
    assert r.ok, r.message
    M = r.diagram("M")
    V = r.diagram("V")
    assert len(M) == len(r.element_ids) == 10
    for part, shear in zip(M, V):
        assert part.shape == (2, 2) and part[0, 0] == 0.0
        assert shear[0, 1] == pytest.approx((part[1, 1] - part[0, 1]) / part[1, 0], rel=1e-9, abs=1e-9 * H)
    # Up the left column (e = +y, n = −x; 1-m elements) from its base, whose reaction (Rx, Ry, Mz)
    # acts on the first element's start: M(0) = −M_i = −Mz, V = R·n = −Rx, N = −R·e = −Ry, and
    # at a height z, M = −Mz − Rx z (to the sway's share of the levers: 1e-4 here).
    Rx, Ry, Mz = r.reactions[-1][0]
    scale = max(abs(v) for part in M for v in part[:, 1])
    for k in range(3):
        for x, value in M[k]:
            assert value == pytest.approx(-Mz - Rx * (k + x), abs=1e-4 * scale), (k, x)
        assert V[k][0, 1] == pytest.approx(-Rx, rel=1e-4)
        assert r.diagram("N")[k][0, 1] == pytest.approx(-Ry, rel=1e-4)
    assert 0.3 * H < -Rx < 0.7 * H  # the two columns share the sway load
    json_rows = json.loads(r.results_json)["steps"][-1]["section_forces"]
    for element, part in zip(r.element_ids, M):
        assert [row[3] for row in json_rows[str(element)]] == list(part[:, 1])
    with pytest.raises(ValueError, match='unknown quantity "X"'):
        r.diagram("X")
    fig, ax = plt.subplots()
    r.plot_diagram("M", ax=ax)
    assert len(ax.patches) == 10 and any("M = " in t.get_text() for t in ax.texts)
    plt.close(fig)


def test_buckling_modes_of_a_column_come_back_as_arrays():
    # A pinned column (L = 4 m, EI = 2·10⁵ N m², 20 elements) under P = 1 kN: λ_cr = π²EI/(L²P)
    # with the mesh's excess (kh)²/12 (docs/format.md), the second mode four times higher; the
    # first mode's shape is sin(πx/L), largest translation 1.
    P, EI, L = 1e3, 2e11 * 1e-6, 4.0
    m = tf.Model("column").material("steel", E=2e11).section("s", A=1e-2, I=1e-6)
    m.node(1, 0, 0).node(2, L, 0).member(1, 2, "steel", "s", divisions=20)
    m.support(1, "pinned").support(2, "roller-x").load(2, fx=-P).analysis(steps=1, buckling={"modes": 2})
    r = tf.run(m)
    kh = math.pi / 20
    assert r.buckling_load_factors[0] == pytest.approx(math.pi ** 2 * EI / (L ** 2 * P) * (1 + kh ** 2 / 12), rel=1e-4)
    assert r.buckling_load_factors[1] == pytest.approx(4 * r.buckling_load_factors[0], rel=2e-2)
    shape = r.buckling_modes[0]
    x = r.node_xy[:, 0]
    assert shape.shape == (len(r.node_ids), 3)
    assert np.abs(shape[:, 1]).max() == pytest.approx(1.0)
    assert shape[:, 1] == pytest.approx(np.sin(math.pi * x / L), abs=1e-3)
    written = json.loads(r.results_json)["buckling"]
    assert [mode["load_factor"] for mode in written] == list(r.buckling_load_factors)
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots()
    r.plot_buckling(1, ax=ax)
    assert len(ax.lines) == 2 * 20 and "buckling mode 2" in ax.get_title()
    with pytest.raises(IndexError, match="no buckling mode 5"):
        r.plot_buckling(5, ax=ax)
    plt.close(fig)


def test_buckling_from_a_converged_step_comes_back_with_its_step_and_is_drawn_on_that_state(tmp_path):
    # The column's path before buckling is linear: from step 2 (λ₀ = 0.5 of the critical load),
    # the estimate is the unloaded one within the shortening (< 1e-4); its step comes back, is
    # read back from results.json, and the mode is drawn on that state.
    P, EI, L = 1e3, 2e11 * 1e-6, 4.0
    m = tf.Model("column").material("steel", E=2e11).section("s", A=1e-2, I=1e-6)
    m.node(1, 0, 0).node(2, L, 0).member(1, 2, "steel", "s", divisions=20)
    m.support(1, "pinned").support(2, "roller-x").load(2, fx=-P)
    critical = math.pi ** 2 * EI / (L ** 2 * P)
    m.analysis({"type": "load", "path": [0.25 * critical, 0.5 * critical, 0.6 * critical]}, buckling={"modes": 1, "at": 2})
    r = tf.run(m)
    assert r.buckling_step == 2
    kh = math.pi / 20
    assert r.buckling_load_factors[0] == pytest.approx(critical * (1 + kh ** 2 / 12), rel=1e-4)
    path = tmp_path / "results.json"
    path.write_text(r.results_json)
    again = tf.Result.load(str(path), model=m)
    assert again.buckling_step == 2 and list(again.buckling_load_factors) == list(r.buckling_load_factors)
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots()
    r.plot_buckling(0, ax=ax)
    assert "from step 2" in ax.get_title()
    shortened = ax.lines[0].get_xydata()  # the first element's state, grey
    assert shortened[0, 0] == pytest.approx(0.0) and shortened[1, 0] < L / 20
    plt.close(fig)
    with pytest.raises(ValueError, match=r"analysis.buckling.at: expected"):
        m.analysis(steps=1, buckling={"modes": 1, "at": "middle"})
        tf.run(m)


def test_a_pickled_result_still_draws_its_curves():
    import pickle
    r = tf.run(os.path.join(SOURCE, "examples", "semi-rigid-portal.json"))
    again = pickle.loads(pickle.dumps(r))
    assert np.array_equal(again.curves(), r.curves()) and np.array_equal(again.displacements, r.displacements)


def test_a_bent_elements_curve_bends_by_its_closed_form():
    # A cantilever of 4 Euler–Bernoulli elements under a tip moment M bends into a circle; each
    # element turns its ends by ±M l0/2EI against its chord, so its curve's mid-point lies
    # M l0²/(8EI) off the chord, on its right (1e-6: the solver's tolerance).
    L, EI, M = 4.0, 2.05e11 * 1e-4, 2.05e11 * 1e-4 * 0.5 / 4.0  # the tip turns half a radian
    m = tf.Model("bent").material("steel", E=2.05e11).section("s", A=1e-2, I=1e-4)
    m.node(1, 0, 0).node(2, L, 0).member(1, 2, "steel", "s", divisions=4).support(1, "fixed").load(2, mz=M)
    r = tf.run(m)
    assert r.ok, r.message
    l0 = L / 4
    for curve in r.curves():
        chord = curve[-1] - curve[0]
        middle = curve[4] - curve[0]
        signed = (chord[0] * middle[1] - chord[1] * middle[0]) / math.hypot(*chord)
        assert signed == pytest.approx(-M * l0 * l0 / (8 * EI), rel=1e-6)


def test_plots_are_written_as_png(tmp_path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    r = tf.run(os.path.join(SOURCE, "examples", "contact-push.json"))
    for name, draw in [("shape", lambda ax: r.plot_shape(steps=range(len(r.state_steps)), ax=ax)),
                       ("load", lambda ax: r.plot_load_displacement(2, "uy", ax=ax)),
                       ("contact", lambda ax: r.plot_contact(ax=ax)),
                       ("iterations", lambda ax: r.plot_iterations(ax=ax))]:
        fig, ax = plt.subplots()
        draw(ax)
        path = tmp_path / f"{name}.png"
        fig.savefig(path)
        plt.close(fig)
        assert path.stat().st_size > 5000
        assert path.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_a_contact_plot_of_many_contact_nodes_shows_those_that_touched():
    # The ring between plates: 80 contact nodes, of which 22 touch at some step; a legend of 80
    # entries covered the plot. The plot draws the 22 and, past 12, says so in its title instead.
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    r = tf.run(os.path.join(SOURCE, "examples", "ring-between-plates.json"))
    touched = int(((r.contact_element > 0).any(axis=0)).sum())
    assert 2 < touched < len(r.contact_nodes)
    fig, ax = plt.subplots()
    r.plot_contact(ax=ax)
    assert len(ax.lines) == touched
    assert ax.get_legend() is None and ax.get_title() == f"{touched} of 80 contact nodes touched"
    plt.close(fig)
    fig, ax = plt.subplots()
    r.plot_contact(ax=ax, legend_limit=100)
    assert len(ax.get_legend().get_texts()) == touched
    plt.close(fig)


def test_ctrl_c_ends_a_run_at_its_next_step_with_keyboard_interrupt():
    # A cantilever of 400 elements rolled up in 10⁶ load steps takes minutes; SIGINT after half a
    # second raises KeyboardInterrupt as soon as the step in progress ends, not at the run's end.
    import signal
    import threading
    import time
    m = tf.Model("rolled").material("steel", E=2.05e11, G=7.9e10).section("s", A=0.01, I=8.333333333333335e-06, shear_area=0.008333333333333335)
    m.node(1, 0, 0).node(2, 10, 0).member(1, 2, "steel", "s", divisions=400, element="timoshenko").support(1, "fixed")
    m.load(2, mz=1073377.489976513).analysis(steps=1_000_000, output="last")
    threading.Timer(0.5, os.kill, (os.getpid(), signal.SIGINT)).start()
    start = time.monotonic()
    with pytest.raises(KeyboardInterrupt):
        tf.run(m)
    assert time.monotonic() - start < 10.0
    assert tf.run(os.path.join(SOURCE, "examples", "portal-frame.json")).status == "converged"  # the next run as ever


def test_a_run_the_machine_has_no_memory_for_is_a_memory_error_before_it_is_spent():
    # 80,001 contact nodes over a beam of 80,000 elements: every contact may touch every element,
    # 6.4·10⁹ candidates — ~3 GB by the estimate (a side each should every node move beyond the
    # broad phase's reach at once, the sparse LU kept as a fallback), more than the 2 GB a child
    # process may address here (ulimit -v, as a batch system sets it). Refused with the estimate,
    # as the command line's exit 3, before the memory is spent.
    child = """
import resource
resource.setrlimit(resource.RLIMIT_AS, (2 << 30, resource.RLIM_INFINITY))
import tsmframe as tf
m = tf.Model("too many candidates").material("m", E=2e11).section("s", A=1e-2, I=1e-4)
m.node(1, 0, 0).node(2, 10, 0).member(1, 2, "m", "s", divisions=80_000).support(1, "fixed")
nodes = list(range(10, 80_011))
for k, node in enumerate(nodes):
    m.node(node, 10.0 * (k + 0.5) / len(nodes), 1.0).support(node, "pinned")
m.load(2, fy=-1.0).contact(members="all", nodes=nodes)
try:
    tf.run(m)
except MemoryError as error:
    print(error)
"""
    p = subprocess.run([sys.executable, "-c", child], capture_output=True, text=True)
    assert p.returncode == 0, p.stderr
    assert re.match(r"^contacts: the run needs ~\d+(\.\d)? GB of memory \(80,001 contacts with 6,400,080,000 candidate elements",
                    p.stdout), p.stdout


def test_a_model_is_drawn_before_it_is_solved():
    # A portal fixed at one foot, on a roller at the other, its beam hinged at one end, a sway load
    # and a moment: the drawing document has the meshed model, and the picture its symbols — the
    # roller's triangle and two wheels, the hinge's circle, the forces' arrows and the moment's arc.
    m = tf.Model("portal").material("steel", E=2e11).section("s", A=1e-2, I=1e-4)
    m.node(1, 0, 0).node(2, 0, 3).node(3, 4, 3).node(4, 4, 0)
    m.member(1, 2, "steel", "s").member(2, 3, "steel", "s", divisions=4, release="start").member(3, 4, "steel", "s")
    m.support(1, "fixed").support(4, "roller-x").load(2, fx=1e3).load(3, fy=-2e3, mz=500.0)
    d = m.drawing()
    assert len(d["nodes"]) == 7 and len(d["elements"]) == 6 and "mechanism" not in d
    assert [s["held"] for s in d["supports"]] == [["ux", "uy", "rz"], ["uy"]]
    assert d["load_cases"][0]["loads"] == [[2, 1e3, 0.0, 0.0], [3, 0.0, -2e3, 500.0]]
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.patches import Arc, Circle, FancyArrowPatch, Polygon
    from matplotlib.quiver import Quiver
    fig, ax = plt.subplots()
    assert m.plot(ax=ax) is ax
    kinds = [type(p) for p in ax.patches]
    assert kinds.count(Polygon) == 1                 # the roller's triangle
    assert kinds.count(Circle) == 2 + 1              # the roller's two circles, the hinge
    assert kinds.count(FancyArrowPatch) == 1         # the moment's head
    forces = [c for c in ax.collections if isinstance(c, Quiver)]
    assert len(forces) == 1 and forces[0].N == 2     # the two forces, one artist
    assert kinds.count(Arc) == 1
    assert not any("Not solvable" in t.get_text() for t in ax.texts)
    plt.close(fig)
    document = m.to_dict()
    document["supports"][0] = {"node": 1, "type": "pinned"}  # a pin, a hinge above it and a roller: it sways
    assert tf.Model.from_dict(document).drawing()["mechanism"].startswith(
        "the structure is a mechanism: unloaded, it can move with no element deforming")
    document["supports"][0] = {"node": 1, "type": "roller-x"}  # both feet on rollers: free along x
    loose = tf.Model.from_dict(document)
    assert "free to move along x" in loose.drawing()["mechanism"]
    with pytest.raises(ValueError, match="supports: structure is a mechanism"):
        tf.run(loose)
    fig, ax = plt.subplots()
    loose.plot(ax=ax)
    assert any("Not solvable: structure is a mechanism" in t.get_text() for t in ax.texts)
    plt.close(fig)
    with pytest.raises(ValueError, match='sectoin'):
        tf.Model.from_dict({**m.to_dict(), "members": [{**m.to_dict()["members"][0], "sectoin": "s"}]}).drawing()


EXAMPLES = sorted(f for f in os.listdir(os.path.join(SOURCE, "examples")) if f.endswith(".json"))


@pytest.mark.parametrize("example", EXAMPLES)
def test_a_result_read_back_from_its_files_equals_the_run(example, tmp_path):
    # Every example: Result.load of what the run wrote holds the same arrays and texts, exactly
    # (results.json keeps every double's shortest round-trip text); the contact columns, which
    # follow the file's contacts, are matched by node.
    path = os.path.join(SOURCE, "examples", example)
    r = tf.run(path)
    r.write(tmp_path)
    back = tf.Result.load(tmp_path / "results.json", model=path)
    assert back.results_json == r.results_json and back.steps_csv == r.steps_csv
    column = [int(np.flatnonzero(r.contact_nodes == node)[0]) for node in back.contact_nodes]
    assert sorted(column) == list(range(len(r.contact_nodes)))
    contact_columns = ("contact_element", "contact_also", "contact_alpha", "contact_force", "contact_tangential",
                       "contact_slip", "contact_friction")
    for name in contact_columns:
        assert np.array_equal(getattr(back, name), getattr(r, name)[:, column]), name
    skipped = {"contact_nodes", *contact_columns, "_model", "_model_text"}
    for name, value in vars(r).items():
        if name in skipped:
            continue
        mine = getattr(back, name)
        if isinstance(value, np.ndarray):
            assert mine.dtype.kind == value.dtype.kind and np.array_equal(mine, value), name
        elif name in ("residual_norms", "section_forces"):
            assert len(mine) == len(value) and all(np.array_equal(a, b) for a, b in zip(mine, value)), name
        else:
            assert mine == value, name
    if len(back.state_steps):
        assert np.array_equal(back.curves(-1), r.curves(-1))


def test_a_result_read_back_without_its_model_has_all_but_the_curves(tmp_path):
    r = tf.run(os.path.join(SOURCE, "examples", "portal-frame.json"))
    r.write(tmp_path)
    back = tf.Result.load(str(tmp_path / "results.json"))
    assert np.array_equal(back.displacements, r.displacements) and back.ok
    with pytest.raises(ValueError, match="curves\\(\\) needs the model"):
        back.curves()
    (tmp_path / "other.json").write_text('{"format": "tsmframe-model/1"}')
    with pytest.raises(ValueError, match='other.json: not a results.json of tsmframe'):
        tf.Result.load(tmp_path / "other.json")
    with pytest.raises(ValueError, match="nothere.json: cannot read: No such file"):
        tf.Result.load(tmp_path / "nothere.json")
    (tmp_path / "cut.json").write_text(r.results_json[:1000])
    with pytest.raises(ValueError, match="cut.json: invalid JSON at line"):
        tf.Result.load(tmp_path / "cut.json")


def test_a_progress_callback_hears_every_step_and_may_stop_the_run():
    # Lee's frame under arc-length control: every step in order, the last twice — the arc-length
    # step that passed the `until` target, then the same step redone to land on it (as the
    # command line's progress lines show it).
    seen = []
    r = tf.run(os.path.join(SOURCE, "examples", "lee-frame-arc-length.json"), progress=seen.append)
    assert [s["step"] for s in seen] == list(r.step) + [r.step[-1]]
    last = {s["step"]: s for s in seen}
    assert [last[k]["load_factor"] for k in r.step] == list(r.load_factor)
    assert [last[k]["iterations"] for k in r.step] == list(r.iterations)
    assert all(s["converged"] and s["stage"] == 1 and s["message"] == "" for s in seen)

    class Enough(Exception):
        pass

    def stop_at_ten(s):
        if s["step"] >= 10:
            raise Enough(s["step"])

    with pytest.raises(Enough):
        tf.run(os.path.join(SOURCE, "examples", "lee-frame-arc-length.json"), progress=stop_at_ten)


def test_a_progress_callback_hears_an_attempt_cut_back_and_why():
    # The strip on the coarse arch cuts attempts back: each is heard, marked, with why it failed
    # and the load factor it started from, then the step that converges says how many it took.
    seen = []
    r = tf.run(os.path.join(SOURCE, "examples", "strip-on-coarse-arch.json"), progress=seen.append)
    cut = [s for s in seen if s["cut_back"]]
    kept = [s for s in seen if not s["cut_back"]]
    assert cut and all(not s["converged"] and s["message"] for s in cut)
    assert len(cut) == sum(s["cutbacks"] for s in kept)
    assert [s["step"] for s in kept] == list(r.step)
    started = {s["step"]: s["load_factor"] for s in kept}
    for s in cut:
        assert s["load_factor"] == (started[s["step"] - 1] if s["step"] > 1 else 0.0)


def test_jupyter_shows_a_model_as_its_drawing_and_a_result_as_its_end():
    m = tf.load(os.path.join(SOURCE, "examples", "williams-toggle-arc-length.json"))
    png = m._repr_png_()
    assert png[:8] == b"\x89PNG\r\n\x1a\n" and len(png) > 1000
    assert tf.Model.from_dict({"nodes": "not a list"})._repr_png_() is None  # a bad model shows as text
    r = tf.run(m)
    page = r._repr_html_()
    assert "<th style='text-align:left'>status</th><td style='text-align:left'>converged</td>" in page
    assert f"maximum {r.limit_points[0]['located']['load_factor']:.6g} (step {r.limit_points[0]['step']})" in page
    assert page.count('<img src="data:image/png;base64,') == 1
    assert r.notes and all(f"<li>{html.escape(n)}</li>" in page for n in r.notes)


def test_friction_arrays_carry_stick_slip_and_the_coulomb_force():
    # The dragged column (docs/friction.md §7a): sticking in the first drag step, slipping at
    # μ times the compression (0.2) forward, then back.
    r = tf.run(os.path.join(SOURCE, "examples", "column-tip-dragged-with-friction.json"))
    assert r.contact_friction.shape == r.contact_force.shape
    assert r.contact_friction[2, 0] == "stick" and r.contact_friction[-1, 0] == "slip"
    slipping = r.contact_friction[:, 0] == "slip"
    ratio = r.contact_tangential[slipping, 0] / r.contact_force[slipping, 0]
    assert np.allclose(np.abs(ratio), 0.2, rtol=0, atol=1e-9)
    assert r.contact_tangential[-1, 0] < 0 and r.contact_slip[-1, 0] == pytest.approx(0.3444574, abs=4e-5)
    assert np.all(np.diff(r.contact_slip[:, 0]) >= 0)  # accumulated
