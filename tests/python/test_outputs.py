#!/usr/bin/python3
"""ParaView and plot output of `tsmframe run` (issue 4): the .pvd/.vtu files parse as XML (and with
Debian's python3-vtk9 when it is installed), carry the documented arrays, the curved element points
of the one-step circle lie on the exact circle, contact forces appear at the contact point; --plot
writes non-empty PNG files; the study report is written. The elements' curves (--curves) are the
VTK files' and the plots', a pin-jointed truss's bars are drawn straight and a bent element bent.

    /usr/bin/python3 tests/python/test_outputs.py TSMFRAME_BINARY SOURCE_DIR
"""
import csv
import html
import json
import math
import os
import subprocess
import sys
import tempfile
import unittest
import xml.etree.ElementTree as ET

BINARY, SOURCE = sys.argv[1], sys.argv[2]
# --report draws with the Python module, which a build may leave out (scripts/sanitize.sh).
with_module = unittest.skipIf(os.environ.get("TSMFRAME_PYTHON_MODULE") == "0", "built without the Python module")


def run(*args):
    return subprocess.run([BINARY, *args], capture_output=True, text=True)


def arrays(piece, section):
    out = {}
    for a in piece.find(section).findall("DataArray"):
        comps = int(a.get("NumberOfComponents", "1"))
        values = [float(v) for v in a.text.split()]
        out[a.get("Name")] = [values[k:k + comps] for k in range(0, len(values), comps)]
    return out


def read_vtu(path):
    piece = ET.parse(path).getroot().find("UnstructuredGrid/Piece")
    points = [float(v) for v in piece.find("Points/DataArray").text.split()]
    points = [points[k:k + 3] for k in range(0, len(points), 3)]
    return piece, points, arrays(piece, "PointData"), arrays(piece, "CellData")


class Vtk(unittest.TestCase):
    def setUp(self):
        self.dir = tempfile.TemporaryDirectory()

    def tearDown(self):
        self.dir.cleanup()

    def test_buckling_modes_are_paraview_files_of_their_own(self):
        # The column (analysis.buckling, 2 modes): vtk/buckling.pvd lists buckling-mode-1.vtu and -2
        # by their critical load factors, as results.json has them; each node's "displacement" is
        # its mode shape scaled so that the largest translation is a tenth of the model's size (to
        # 1e-6 of the size: the drawn curves' ends, as in the step files).
        out = os.path.join(self.dir.name, "column")
        r = run("run", os.path.join(SOURCE, "examples", "column-buckling.json"), "--out", out, "--vtk", "-q")
        self.assertEqual(r.returncode, 0, r.stderr)
        with open(os.path.join(out, "results.json")) as f:
            results = json.load(f)
        pvd = ET.parse(os.path.join(out, "vtk", "buckling.pvd")).getroot()
        sets = list(pvd.iter("DataSet"))
        self.assertEqual([d.get("file") for d in sets], ["buckling-mode-1.vtu", "buckling-mode-2.vtu"])
        self.assertEqual([float(d.get("name").split()[-1]) for d in sets], [m["load_factor"] for m in results["buckling"]])
        xs = [n["x"] for n in results["nodes"]]
        ys = [n["y"] for n in results["nodes"]]
        size = math.hypot(max(xs) - min(xs), max(ys) - min(ys))
        for k, mode in enumerate(results["buckling"]):
            _, points, point_data, _ = read_vtu(os.path.join(out, "vtk", f"buckling-mode-{k + 1}.vtu"))
            moved = point_data["displacement"]
            for e, element in enumerate(results["elements"]):  # each element's first and last curve point: its nodes
                for node, point in ((element["nodes"][0], 9 * e), (element["nodes"][1], 9 * e + 8)):
                    shape = mode["shape"][str(node)]
                    self.assertAlmostEqual(moved[point][0], 0.1 * size * shape[0], delta=1e-6 * size)
                    self.assertAlmostEqual(moved[point][1], 0.1 * size * shape[1], delta=1e-6 * size)
            self.assertAlmostEqual(max(math.hypot(u, v) for u, v, _ in moved), 0.1 * size, delta=1e-3 * size)

    def test_circle_points_lie_on_the_exact_circle(self):
        out = os.path.join(self.dir.name, "circle")
        r = run("run", os.path.join(SOURCE, "examples", "cantilever-circle.json"), "--out", out, "--vtk", "-q")
        self.assertEqual(r.returncode, 0, r.stderr)
        pvd = ET.parse(os.path.join(out, "vtk", "results.pvd")).getroot()
        files = [d.get("file") for d in pvd.iter("DataSet")]
        self.assertEqual(len(files), 1)  # one converged step
        piece, points, point_data, cell_data = read_vtu(os.path.join(out, "vtk", files[0]))
        n_elements = int(piece.get("NumberOfCells"))
        self.assertEqual(n_elements, 52)
        self.assertEqual(len(points), 52 * 9)  # 8 segments per element
        for name in ("displacement", "rotation", "contact_force"):
            self.assertEqual(len(point_data[name]), len(points), name)
        for name in ("N", "M_i", "M_j", "Y", "element_id"):
            self.assertEqual(len(cell_data[name]), n_elements, name)
        # The discrete model's exact solution: every chord keeps its length l0 = L/52 (N = 0 in pure
        # bending), so the nodes lie on the circle of radius R = l0 / (2 sin(π/52)), centre (0, R).
        l0 = 10.0 / 52
        R = l0 / (2 * math.sin(math.pi / 52))
        nodes = points[::9] + [points[-1]]
        self.assertLess(max(abs(math.hypot(x, y - R) - R) for x, y, _ in nodes), 1e-7 * R)
        worst = max(abs(math.hypot(x, y - R) - R) for x, y, _ in points)
        self.assertLess(worst, 2e-5 * R, f"curve points off the circle by {worst}")
        # the interior points matter: a chord-only drawing would be off by R(1 - cos(π/52)) ≈ 1.8e-3 R
        self.assertGreater(R * (1 - math.cos(math.pi / 52)), 50 * 2e-5 * R)
        # rotations: 2π at the tip, 0 at the root
        self.assertAlmostEqual(point_data["rotation"][-1][0], 2 * math.pi, places=6)
        self.assertAlmostEqual(point_data["rotation"][0][0], 0.0, places=12)
        # pure bending: M is the tip moment at every point of every curve (counter-clockwise, bending
        # the beam towards its left: positive), N and V vanish
        with open(os.path.join(SOURCE, "examples", "cantilever-circle.json")) as f:
            tip_moment = next(load["mz"] for load in json.load(f)["loads"] if "mz" in load)
        for name in ("section_N", "section_V", "section_M"):
            self.assertEqual(len(point_data[name]), len(points), name)
        self.assertLess(max(abs(m[0] - tip_moment) for m in point_data["section_M"]), 1e-6 * tip_moment)
        self.assertLess(max(abs(v[0]) for v in point_data["section_N"] + point_data["section_V"]), 1e-6 * tip_moment)
        try:
            import vtk  # Debian's python3-vtk9, when installed
        except ImportError:
            return
        reader = vtk.vtkXMLUnstructuredGridReader()
        reader.SetFileName(os.path.join(out, "vtk", files[0]))
        reader.Update()
        grid = reader.GetOutput()
        self.assertEqual(grid.GetNumberOfPoints(), len(points))
        self.assertEqual(grid.GetNumberOfCells(), n_elements)
        self.assertIsNotNone(grid.GetCellData().GetArray("M_j"))

    def test_contact_force_vector_at_the_contact_point(self):
        out = os.path.join(self.dir.name, "push")
        r = run("run", os.path.join(SOURCE, "examples", "contact-push.json"), "--out", out, "--vtk", "-q")
        self.assertEqual(r.returncode, 0, r.stderr)
        files = [d.get("file") for d in ET.parse(os.path.join(out, "vtk", "results.pvd")).getroot().iter("DataSet")]
        self.assertEqual(len(files), 200)
        piece, points, point_data, cell_data = read_vtu(os.path.join(out, "vtk", files[-1]))
        self.assertEqual(int(piece.get("NumberOfCells")), 18 + 1)  # 18 elements and the contact vertex
        force = point_data["contact_force"][-1]
        self.assertGreater(math.hypot(force[0], force[1]), 1e5)
        self.assertGreater(force[1], 0.0)  # the pusher pushes the beam up
        self.assertEqual(points[-1][1], 2.0)  # the contact node, pushed 2 m up
        self.assertEqual(sum(1 for y in cell_data["Y"] if y[0] != 0.0), 2)  # the contact element and vertex

    def test_friction_force_and_status_at_the_contact_point(self):
        # The dragged column (examples/column-tip-dragged-with-friction.json): its last step slips
        # back, the friction force on the plane μF = 0.05 along −x (the tip dragged towards −x),
        # status 2; a frictionless model's files carry no friction arrays.
        out = os.path.join(self.dir.name, "column")
        r = run("run", os.path.join(SOURCE, "examples", "column-tip-dragged-with-friction.json"), "--out", out, "--vtk", "-q")
        self.assertEqual(r.returncode, 0, r.stderr)
        files = [d.get("file") for d in ET.parse(os.path.join(out, "vtk", "results.pvd")).getroot().iter("DataSet")]
        _, _, point_data, _ = read_vtu(os.path.join(out, "vtk", files[-1]))
        friction, status = point_data["friction_force"][-1], point_data["friction_status"][-1]
        self.assertAlmostEqual(friction[0], -0.05, delta=1e-5)
        self.assertAlmostEqual(friction[1], 0.0, delta=1e-8)
        self.assertEqual(status[0], 2)
        self.assertTrue(all(v == [0.0] for v in point_data["friction_status"][:-1]))
        plain = os.path.join(self.dir.name, "push")
        self.assertEqual(run("run", os.path.join(SOURCE, "examples", "contact-push.json"), "--out", plain, "--vtk", "-q").returncode, 0)
        first = [d.get("file") for d in ET.parse(os.path.join(plain, "vtk", "results.pvd")).getroot().iter("DataSet")][0]
        self.assertNotIn("friction_force", read_vtu(os.path.join(plain, "vtk", first))[2])

    def test_a_vertex_shows_the_resultant_at_its_own_node(self):
        # A pinned beam pushed down 0.5 m on its mid-span node (a vertex: both elements at the node
        # in contact), with an idle contact node listed first: the contact point's arrays belong to
        # the active contact's node, and its force is the resultant of both elements' pushes —
        # along the chords' normals or the bent beam's. Pushed within an element instead (x = 5.2),
        # the force along the bent beam's normal leans: it is still the pusher's support reaction.
        import json
        for normal in ("chord", "deflected"):
            for x in (5.0, 5.2):
                with self.subTest(normal=normal, x=x):
                    self.check_contact_force_drawn(normal, x)

    def check_contact_force_drawn(self, normal, x):
        import json
        model = {
            "materials": {"steel": {"E": 2e11, "G": 7.7e10}},
            "sections": {"s": {"A": 0.004, "I": 2e-5, "shear_area": 0.002}},
            "nodes": [{"id": 1, "x": 0.0, "y": 0.0}, {"id": 2, "x": 10.0, "y": 0.0},
                      {"id": 9, "x": x, "y": 0.001}, {"id": 7, "x": 5.0, "y": 3.0}],
            "members": [{"from": 1, "to": 2, "divisions": 20, "element": "timoshenko", "material": "steel", "section": "s"}],
            "supports": [{"node": 1, "type": "pinned"}, {"node": 2, "type": "pinned"},
                         {"node": 9, "fix": ["ux"]}, {"node": 7, "type": "fixed"}],
            "prescribed": [{"node": 9, "uy": -0.5}],
            "contacts": [{"node": 7, "members": "all"}, {"node": 9, "members": "all", "normal": normal}],
            "analysis": {"control": {"type": "load", "steps": 5}},
        }
        path = os.path.join(self.dir.name, "vertex.json")
        with open(path, "w") as f:
            json.dump(model, f)
        out = os.path.join(self.dir.name, "vertex-%s-%g" % (normal, x))
        r = run("run", path, "--out", out, "--vtk", "-q")
        self.assertEqual(r.returncode, 0, r.stderr)
        with open(os.path.join(out, "results.json")) as f:
            last = json.load(f)["steps"][-1]
        [contact] = last["contacts"]
        self.assertEqual(contact["node"], 9)
        files = [d.get("file") for d in ET.parse(os.path.join(out, "vtk", "results.pvd")).getroot().iter("DataSet")]
        piece, points, point_data, cell_data = read_vtu(os.path.join(out, "vtk", files[-1]))
        self.assertEqual(int(piece.get("NumberOfCells")), 20 + 1)
        self.assertAlmostEqual(point_data["displacement"][-1][1], -0.5, places=12)  # node 9's, not node 7's
        force = point_data["contact_force"][-1]
        reaction = last["reactions"]["9"]
        # the push on the beam, which the pusher's support supplies
        self.assertAlmostEqual(force[1], reaction[1], delta=1e-9 * abs(reaction[1]))
        self.assertAlmostEqual(force[0], reaction[0], delta=1e-9 * abs(reaction[1]))
        self.assertAlmostEqual(math.hypot(*force[:2]), contact["force"], delta=1e-9 * contact["force"])
        if x == 5.0:
            self.assertEqual((contact["xi"], "also" in contact), (1, True))
            self.assertLess(abs(force[0]), 1e-9 * abs(force[1]))  # symmetric
            self.assertEqual(sum(1 for y in cell_data["Y"][:20] if y[0] != 0.0), 2)  # both elements carry Y
        elif normal == "deflected":
            self.assertGreater(abs(force[0]), 1e-3 * abs(force[1]))  # the bent beam's normal leans


def off_chord(points):
    """The largest distance of a polyline's points from the line through its first and last, and
    that chord's length."""
    (x0, y0), (x1, y1) = points[0][:2], points[-1][:2]
    length = math.hypot(x1 - x0, y1 - y0)
    return max(abs((x1 - x0) * (p[1] - y0) - (y1 - y0) * (p[0] - x0)) / length for p in points), length


def curve_points(flat):
    """results.json's [x0, y0, x1, y1, …] as [(x, y)]."""
    return [(flat[k], flat[k + 1]) for k in range(0, len(flat), 2)]


class Curves(unittest.TestCase):
    def setUp(self):
        self.dir = tempfile.TemporaryDirectory()

    def tearDown(self):
        self.dir.cleanup()

    def test_a_pin_jointed_truss_is_drawn_with_straight_bars(self):
        # examples/warren-truss.json: every bar hinged at both ends carries no moment, so it stays
        # straight — in results.json's curves, in the ParaView files, and in what the plots draw
        # (scripts/shapes.py, which report.py and plot_run.py share), each point on its bar's chord
        # within 1e-12 of the bar's length. The S-shaped bars the node rotations would give (the
        # hinge nodes' rotations are held at 0 while the chords turn) are far beyond that.
        out = os.path.join(self.dir.name, "truss")
        r = run("run", os.path.join(SOURCE, "examples", "warren-truss.json"), "--out", out, "--vtk", "--plot", "-q")
        self.assertEqual(r.returncode, 0, r.stderr)
        with open(os.path.join(out, "results.json")) as f:
            results = json.load(f)
        self.assertTrue(all(e.get("release") == "both" for e in results["elements"]))
        states = [s for s in results["steps"] if "displacements" in s]
        files = [d.get("file") for d in ET.parse(os.path.join(out, "vtk", "results.pvd")).getroot().iter("DataSet")]
        self.assertEqual(len(files), len(states))
        sys.path.insert(0, os.path.join(SOURCE, "scripts"))
        import shapes
        nodes = {n["id"]: (n["x"], n["y"]) for n in results["nodes"]}
        for state, file in zip(states, files):
            _, points, _, _ = read_vtu(os.path.join(out, "vtk", file))
            for k, e in enumerate(results["elements"]):
                curve = curve_points(state["curves"][str(e["id"])])
                self.assertEqual(len(curve), 9)
                self.assertEqual([list(p) for p in curve], [p[:2] for p in points[9 * k:9 * k + 9]])  # one implementation
                off, length = off_chord(curve)
                self.assertLess(off, 1e-12 * length, f"element {e['id']} at step {state['step']}")
            for xs, ys in shapes.element_lines(results, state, scale=1000.0):
                off, length = off_chord(list(zip(xs, ys)))
                self.assertLess(off, 1e-12 * length)
            # What the old drawing would have bowed by: θ_i = θ_j = −β, w = −β l ξ(1−ξ)(1−2ξ), 0.096 β l at most.
            turned = 0.0
            for e in results["elements"]:
                (Xi, Yi), (Xj, Yj) = (nodes[n] for n in e["nodes"])
                ui, uj = (state["displacements"][str(n)] for n in e["nodes"])
                beta = math.atan2(Yj + uj[1] - Yi - ui[1], Xj + uj[0] - Xi - ui[0]) - math.atan2(Yj - Yi, Xj - Xi)
                turned = max(turned, abs(beta))
            self.assertGreater(0.096 * turned, 1e3 * 1e-12)
        self.assertGreater(os.path.getsize(os.path.join(out, "plots", "deformed.png")), 1000)

    def test_a_bent_element_is_drawn_bent_by_its_closed_form(self):
        # The one-step circle (examples/cantilever-circle.json): every element is bent by the tip
        # moment alone, θ_i = −θ_j = M l0 / 2EI against its chord (Timoshenko feels no shear in pure
        # bending), so its curve's mid-point lies M l0²/(8EI) off the chord, to the right of it
        # (1e-6: the solver's tolerance). The exact circle's sagitta differs by 3e-4 of that.
        out = os.path.join(self.dir.name, "circle")
        r = run("run", os.path.join(SOURCE, "examples", "cantilever-circle.json"), "--out", out, "--curves", "-q")
        self.assertEqual(r.returncode, 0, r.stderr)
        with open(os.path.join(SOURCE, "examples", "cantilever-circle.json")) as f:
            model = json.load(f)
        EI = model["materials"]["steel"]["E"] * model["sections"]["square-100mm"]["I"]
        M, l0 = model["loads"][0]["mz"], 10.0 / 52
        expected = M * l0 * l0 / (8 * EI)
        with open(os.path.join(out, "results.json")) as f:
            curves = json.load(f)["steps"][-1]["curves"]
        self.assertEqual(len(curves), 52)
        for flat in curves.values():
            (x0, y0), (xm, ym), (x1, y1) = curve_points(flat)[0], curve_points(flat)[4], curve_points(flat)[8]
            length = math.hypot(x1 - x0, y1 - y0)
            signed = ((x1 - x0) * (ym - y0) - (y1 - y0) * (xm - x0)) / length  # along n, the chord turned +90°
            self.assertAlmostEqual(signed, -expected, delta=1e-6 * expected)
        R = 10.0 / (2 * math.pi)
        self.assertAlmostEqual(R * (1 - math.cos(math.pi / 52)), expected, delta=4e-4 * expected)

    def test_curves_are_opt_in_and_change_nothing_else(self):
        # Without --curves results.json is as before; with it, each step with state gains "curves"
        # (an array of 2 × 9 numbers per element id) and nothing else changes.
        path = os.path.join(SOURCE, "examples", "semi-rigid-portal.json")
        plain, curved = os.path.join(self.dir.name, "plain"), os.path.join(self.dir.name, "curved")
        self.assertEqual(run("run", path, "--out", plain, "-q").returncode, 0)
        self.assertEqual(run("run", path, "--out", curved, "--curves", "-q").returncode, 0)
        with open(os.path.join(plain, "results.json")) as f:
            without = json.load(f)
        with open(os.path.join(curved, "results.json")) as f:
            with_curves = json.load(f)
        self.assertFalse(any("curves" in s for s in without["steps"]))
        states = [s for s in with_curves["steps"] if "displacements" in s]
        self.assertTrue(states)
        for s in states:
            self.assertEqual(sorted(s["curves"], key=int), [str(e["id"]) for e in with_curves["elements"]])
            self.assertTrue(all(len(v) == 18 for v in s["curves"].values()))
            del s["curves"]
        self.assertEqual(without, with_curves)
        with open(os.path.join(plain, "steps.csv")) as f, open(os.path.join(curved, "steps.csv")) as g:
            self.assertEqual(f.read(), g.read())

    def test_without_curves_the_plots_draw_chords_and_say_so(self):
        sys.path.insert(0, os.path.join(SOURCE, "scripts"))
        import shapes
        results = {"nodes": [{"id": 1, "x": 0.0, "y": 0.0}, {"id": 2, "x": 2.0, "y": 0.0}],
                   "elements": [{"id": 1, "nodes": [1, 2]}],
                   "steps": [{"displacements": {"1": [0, 0, 0], "2": [0.0, -0.1, -0.2]}}]}
        self.assertFalse(shapes.has_curves(results))
        self.assertEqual(shapes.element_lines(results, results["steps"][0]), [([0.0, 2.0], [0.0, -0.1])])
        results["steps"][0]["curves"] = {"1": [0.0, 0.0, 1.0, -0.2, 2.0, -0.1]}
        self.assertTrue(shapes.has_curves(results))
        # × 10 moves each curve point ten times as far from where it was drawn
        self.assertEqual(shapes.element_lines(results, results["steps"][0], scale=10.0), [([0.0, 1.0, 2.0], [0.0, -2.0, -1.0])])


def results_y(results, node_id):
    """A node's y as drawn."""
    return next(n["y"] for n in results["nodes"] if n["id"] == node_id)


class Plots(unittest.TestCase):
    def test_plot_writes_png_files(self):
        with tempfile.TemporaryDirectory() as d:
            out = os.path.join(d, "frame")
            r = run("run", os.path.join(SOURCE, "examples", "portal-frame.json"), "--out", out, "--plot", "-q")
            self.assertEqual(r.returncode, 0, r.stderr)
            for name in ("model.png", "deformed.png", "load-displacement.png", "deformed.svg", "model.svg"):
                path = os.path.join(out, "plots", name)
                self.assertTrue(os.path.exists(path), name)
                self.assertGreater(os.path.getsize(path), 1000, name)
            with open(os.path.join(out, "plots", "deformed.png"), "rb") as f:
                self.assertEqual(f.read(8), b"\x89PNG\r\n\x1a\n")

    @with_module
    def test_report_writes_one_page_of_what_an_engineer_reads(self):
        # --report: DIR/report.html, self-contained, drawn by the package from the results read
        # back — the model, the shapes, λ against the monitored dofs, N/V/M and, for the column
        # (analysis.buckling), its modes with their load factors; nothing else left in DIR.
        with tempfile.TemporaryDirectory() as d:
            out = os.path.join(d, "column")
            r = run("run", os.path.join(SOURCE, "examples", "column-buckling.json"), "--out", out, "--report")
            self.assertEqual(r.returncode, 0, r.stderr)
            self.assertIn(f"report: {out}/report.html", r.stdout)
            self.assertEqual(sorted(os.listdir(out)), ["report.html", "results.json", "steps.csv"])
            with open(os.path.join(out, "report.html")) as f:
                page = f.read()
            for heading in ("The model", "Deformed shapes", "Load–displacement", "N, V and M at the last state",
                            "Buckling mode 1 (linearised, at the unloaded state)", "Buckling mode 2 (linearised, at the unloaded state)"):
                self.assertTrue(f"<h2>{heading}</h2>" in page, heading)
            self.assertEqual(page.count('<img src="data:image/png;base64,'), 6)
            with open(os.path.join(out, "results.json")) as f:
                factors = [m["load_factor"] for m in json.load(f)["buckling"]]
            self.assertTrue("Linearised critical load factors: " + ", ".join(f"{x:.6g}" for x in factors) in page)
            self.assertTrue("converged: 20 converged steps" in page)
            # A run that stops short is reported too: its converged steps and why it stopped.
            m = os.path.join(d, "short.json")
            with open(os.path.join(SOURCE, "examples", "portal-frame.json")) as f:
                model = json.load(f)
            model["analysis"]["max_iterations"] = 1
            model["analysis"]["max_cutbacks"] = 0
            with open(m, "w") as f:
                json.dump(model, f)
            r = run("run", m, "--out", os.path.join(d, "short"), "--report", "-q")
            self.assertEqual(r.returncode, 1, r.stderr)
            with open(os.path.join(d, "short", "report.html")) as f:
                page = f.read()
            self.assertTrue("<h2>The model</h2>" in page)
            self.assertTrue("<b>cutback-limit: 0 converged steps, 1 iterations — step 1 (load factor 0 -&gt; 0.1) failed" in page)

    @with_module
    def test_the_report_shows_each_example_run_with_its_shapes_and_notes(self):
        # out/ as scripts/run.sh leaves it, for two examples and no studies: the report has a
        # section per example (its shapes drawn, how it ended, its notes) and says the studies'
        # plots were not produced rather than failing.
        with tempfile.TemporaryDirectory() as d:
            for name in ("portal-frame", "push-on-a-node"):
                r = run("run", os.path.join(SOURCE, "examples", name + ".json"), "--out", os.path.join(d, name), "-q")
                self.assertEqual(r.returncode, 0, r.stderr)
            package = os.path.join(os.path.dirname(os.path.abspath(BINARY)), "python")  # as scripts/run.sh runs it
            r = subprocess.run(["/usr/bin/python3", os.path.join(SOURCE, "scripts", "report.py"), d],
                               capture_output=True, text=True, env={**os.environ, "PYTHONPATH": package})
            self.assertEqual(r.returncode, 0, r.stderr)
            with open(os.path.join(d, "report.html")) as f:
                page = f.read()
            self.assertIn("<h2>The examples</h2>", page)
            self.assertIn("<b>portal-frame</b>", page)
            # The summary's counts are the run's own, from its results.json: the example's 10 load
            # steps, each taking at least one iteration.
            with open(os.path.join(d, "portal-frame", "results.json")) as f:
                steps = json.load(f)["steps"]
            iterations = sum(s["iterations"] for s in steps)
            self.assertTrue(all(s["converged"] for s in steps))
            self.assertEqual(len(steps), 10)
            self.assertGreaterEqual(iterations, len(steps))
            self.assertIn(f"<em>converged: {len(steps)} steps, {iterations} iterations, λ = 1 at the end</em>", page)
            with open(os.path.join(d, "push-on-a-node", "results.json")) as f:
                notes = json.load(f)["notes"]
            self.assertTrue(notes)
            self.assertIn(f"<li>{html.escape(notes[0])}</li>", page)  # its strain note
            for name in ("portal-frame", "push-on-a-node"):
                self.assertGreater(os.path.getsize(os.path.join(d, "plots", f"example-{name}.png")), 1000)
                self.assertGreater(os.path.getsize(os.path.join(d, "plots", f"model-{name}.png")), 1000)  # the model drawn
                self.assertGreater(os.path.getsize(os.path.join(d, "plots", f"moment-{name}.png")), 1000)  # its M
            self.assertEqual(page.count('<img src="data:image/png;base64,'), 6)  # each example's model, shapes and M
            self.assertIn("not produced: run scripts/run.sh first", page)

    def test_a_paragraph_long_title_is_wrapped_not_a_page_wide_plot(self):
        # The example's title is a paragraph; drawn on one line it made the figure 4,213 px wide
        # with the frame a sliver in it.
        with tempfile.TemporaryDirectory() as d:
            out = os.path.join(d, "node")
            r = run("run", os.path.join(SOURCE, "examples", "push-on-a-node.json"), "--out", out, "--plot", "-q")
            self.assertEqual(r.returncode, 0, r.stderr)
            with open(os.path.join(out, "plots", "deformed.png"), "rb") as f:
                header = f.read(24)
            width = int.from_bytes(header[16:20], "big")  # the IHDR chunk
            self.assertLess(width, 1600)

    def test_small_deflections_are_magnified_by_a_round_factor_a_pushers_travel_not_counted(self):
        sys.path.insert(0, os.path.join(SOURCE, "scripts"))
        from plot_run import magnification
        results = {"nodes": [{"id": 1, "x": 0.0, "y": 0.0}, {"id": 2, "x": 10.0, "y": 0.0}, {"id": 9, "x": 1.0, "y": 0.05}],
                   "elements": [{"nodes": [1, 2]}]}
        def states(beam_uy, pusher_ux):
            return [{"displacements": {"1": [0, 0, 0], "2": [0, beam_uy, 0], "9": [pusher_ux, 0, 0]}}]
        # 3 cm on a 10 m frame: × 20 brings it to 0.6 m, about a tenth of the size (× 50 would pass it)
        self.assertEqual(magnification(results, states(-0.03, 8.0)), 20.0)
        self.assertEqual(magnification(results, states(-0.5, 0.0)), 1.0)   # 5 % of the size: drawn to scale
        self.assertEqual(magnification(results, states(0.0, 8.0)), 1.0)    # nothing deflects
        self.assertEqual(magnification(results, states(-1e-4, 0.0)), 10000.0)

    def test_a_displacement_driven_run_plots_its_driving_force(self):
        # The ring squeezed between plates: no load, the upper plate's ends moved down; the
        # reactions there against their displacement, and their sum (both move alike).
        with tempfile.TemporaryDirectory() as d:
            out = os.path.join(d, "ring")
            r = run("run", os.path.join(SOURCE, "examples", "ring-between-plates.json"), "--out", out, "--plot", "-q")
            self.assertEqual(r.returncode, 0, r.stderr)
            self.assertGreater(os.path.getsize(os.path.join(out, "plots", "force-displacement.png")), 1000)
            sys.path.insert(0, os.path.join(SOURCE, "scripts"))
            from plot_run import moved_curves
            with open(os.path.join(out, "results.json")) as f:
                results = json.load(f)
            with open(os.path.join(out, "steps.csv"), newline="") as f:
                rows = list(csv.DictReader(f))
            curves = moved_curves(results, rows)
            self.assertEqual([c[0] for c in curves], ["Ry at node 103 (uy prescribed)", "Ry at node 104 (uy prescribed)",
                                                      "Ry, sum over 2 nodes moved alike"])
            label, u, force = curves[2]
            self.assertAlmostEqual(u[-1], -0.9, places=12)
            # the plates' total push is what the ring's two crown contacts pass on: each plate's
            # contacts carry it (the last row's contact forces on the upper plate)
            last = results["steps"][-1]
            upper = sum(c["force"] for c in last["contacts"] if results_y(results, c["node"]) > 0)
            self.assertAlmostEqual(-force[-1], upper, delta=1e-6 * upper)
        with tempfile.TemporaryDirectory() as d:  # a load-driven run has no such plot
            out = os.path.join(d, "frame")
            run("run", os.path.join(SOURCE, "examples", "portal-frame.json"), "--out", out, "--plot", "-q")
            self.assertFalse(os.path.exists(os.path.join(out, "plots", "force-displacement.png")))

    def test_dofs_that_only_carry_rounding_noise_get_no_curve(self):
        sys.path.insert(0, os.path.join(SOURCE, "scripts"))
        from plot_run import visible_columns
        results = {"nodes": [{"id": 1, "x": 0.0, "y": 0.0}, {"id": 2, "x": 2.0, "y": 0.0}]}
        rows = [{"ux_2": "-0.3", "uy_2": "0.5", "rz_2": "1e-9", "ux_1": "0", "uy_1": "0", "rz_1": "0.02"},
                {"ux_2": "-0.4", "uy_2": "0.6", "rz_2": "-2e-9", "ux_1": "0", "uy_1": "0", "rz_1": "0.03"}]
        # the symmetric crown's 2e-9 rad and the held node's zeros are noise; 0.03 rad is not
        self.assertEqual(visible_columns(results, rows), ["ux_2", "uy_2", "rz_1"])
        rows = [{"rz_2": "1e-12"}]  # nothing moves: nothing to draw
        self.assertEqual(visible_columns(results, rows), [])


if __name__ == "__main__":
    unittest.main(argv=[sys.argv[0]], verbosity=2)
