#!/usr/bin/python3
"""Contact at scale (issue 28): the presses, run by one build or by two alternately, as a table.

A flexible beam (Timoshenko, EI 2e4, pinned ends, every node a contact node, drawn 1 cm above
the lower beam's 5 cm gap) pressed onto a beam 200 times as stiff (3 elements per upper one)
under 2 kN/m in 10 load steps, output "last" (tests/support/models.hpp, pressed_beams):

  press N        10 m long, the lower beam simply supported (the sizes bench/README.md quotes);
  continuous L   the issue's target shape, L metres of 10 cm upper elements on a lower beam
                 supported every 10 m (the target is L = 1000: 10^4 contact nodes); the upper
                 beam 5 mm shorter at each end, so that its nodes pass from 5 mm beside the
                 lower beam's nodes (α 0.15) to over them (the middle) and back;
  midway L       the same with every upper node over the middle of a lower element (α ½; the
                 upper beam one element shorter): no point starts near a lower beam's node;
  pipeline N     the issue's 10⁵-contact shape at N elements a beam: a pipe resting on a bed,
                 lifted at its middle (pipeline() below).

Each row also runs the same beams without contacts (the upper one supported where the lower one
is, every 10 m; the pipe on a foundation of its own) for the cost of an iteration without
contacts. Wall time and peak memory of the whole command (/usr/bin/time), one run per build per
row, builds alternating.

  /usr/bin/python3 bench/contact_scale.py BUILD [OLD_BUILD] [--rows press:501,press:701,continuous:50,pipeline:1000]
      [--repeat N] [--threads T]   (N alternating runs of each row per build and their medians)
"""
import argparse, json, os, statistics, subprocess, tempfile, time


def model(kind, size, contacts=True):
    if kind == "press":
        upper, length, spacing = size - 1, 10.0, 10.0
    else:
        length = float(size)
        upper, spacing = int(round(length / 0.1)), 10.0
    lower = 3 * upper
    inset = 0.005 if contacts or kind == "press" else 0.0  # without contacts: upper nodes over the supports
    start, end = inset, length - inset
    if kind == "midway" and contacts:
        upper -= 1
        start = 0.5 * length / lower
        end = start + 0.1 * upper
    nodes = [{"id": 1, "x": 0.0, "y": 0.0}, {"id": 2, "x": length, "y": 0.0},
             {"id": 3, "x": start, "y": 0.06}, {"id": 4, "x": end, "y": 0.06}]
    supports = [{"node": 1, "type": "pinned"}, {"node": 2, "type": "roller-x"},
                {"node": 3, "type": "pinned"}, {"node": 4, "type": "pinned"}]
    if kind in ("continuous", "midway"):  # a support every 10 m under the lower beam (and the upper one without contacts)
        for k in range(1, int(round(length / spacing))):
            supports.append({"node": [k * spacing, 0.0], "fix": ["uy"]})
            if not contacts:
                supports.append({"node": [k * spacing, 0.06], "fix": ["uy"]})
    m = {"materials": {"steel": {"E": 2e11, "nu": 0.3}},
         "sections": {"beam": {"A": 4e-3, "I": 2e-5, "shear_area": 3.3e-3},
                      "top": {"A": 1e-3, "I": 1e-7, "shear_area": 8e-4}},
         "nodes": nodes,
         "members": [{"from": 1, "to": 2, "divisions": lower, "material": "steel", "section": "beam", "element": "timoshenko"},
                     {"from": 3, "to": 4, "divisions": upper, "material": "steel", "section": "top",
                      "element": "timoshenko", "load": {"fy": -2000.0}}],
         "supports": supports,
         "analysis": {"control": {"type": "load", "steps": 10}, "output": "last"}}
    if contacts:
        m["contacts"] = [{"nodes": {"members": [1]}, "members": [0], "gap": 0.05}]
    return m


def pipeline(elements, lift=0.5, contacts=True):
    """A pipeline of `elements` 10-cm elements lying on a bed beam of as many (every pipeline node a
    contact node resting on the bed, 5 cm between the centre lines), pressed by 2 kN/m and lifted at
    its middle by `lift` metres, both in proportion in 10 load steps. The bed rests on a Winkler
    foundation (10⁷ N/m²) and is pinned at its ends; the pipeline is held along its length at its
    left end only. Without contacts the pipeline rests on a foundation of its own instead (the
    same stiffness): the same two beams, for the cost of an iteration without contacts."""
    length, h = 0.1 * elements, 0.1
    middle = elements // 2
    nodes = [{"id": 1, "x": 0.0, "y": 0.0}, {"id": 2, "x": length, "y": 0.0},
             {"id": 3, "x": 0.5 * h, "y": 0.05}, {"id": 4, "x": length - 0.5 * h, "y": 0.05},
             {"id": 5, "x": 0.5 * h + middle * (length - h) / (elements - 1), "y": 0.05}]
    section = {"material": "steel", "element": "timoshenko"}
    upper = lambda a, b, n: {"from": a, "to": b, "divisions": n, "section": "top", "load": {"fy": -2000.0}, **section}
    m = {"title": f"a pipeline of {elements} elements lifted at its middle off a bed of {elements}",
            "materials": {"steel": {"E": 2e11, "nu": 0.3}},
            "sections": {"beam": {"A": 4e-3, "I": 2e-5, "shear_area": 3.3e-3},
                         "top": {"A": 1e-3, "I": 1e-7, "shear_area": 8e-4}},
            "nodes": nodes,
            "members": [{"from": 1, "to": 2, "divisions": elements, "section": "beam", "foundation": 1e7, **section},
                        upper(3, 5, middle), upper(5, 4, elements - 1 - middle)],
            "supports": [{"node": 1, "type": "pinned"}, {"node": 2, "type": "pinned"}, {"node": 3, "fix": ["ux"]}],
            "prescribed": [{"node": 5, "uy": lift}],
            "contacts": [{"nodes": {"members": [1, 2]}, "members": [0], "gap": 0.05}],
            "analysis": {"control": {"type": "load", "steps": 10}, "output": "last"}}
    if not contacts:
        del m["contacts"]
        for member in m["members"][1:]:
            member["foundation"] = 1e7
    return m


def run(binary, path, threads=None):
    out = tempfile.mkdtemp(prefix="contact-scale-")
    start = time.time()
    command = [binary, "run", path, "--out", out, "-q"] + (["--threads", str(threads)] if threads else [])
    p = subprocess.run(["/usr/bin/time", "-f", "%M"] + command, capture_output=True, text=True)
    wall = time.time() - start
    peak_mb = int(p.stderr.strip().splitlines()[-1]) / 1024.0
    try:
        r = json.load(open(os.path.join(out, "results.json")))
        steps = r["steps"][-1]["step"] if r["steps"] else 0
        iterations = sum(s["iterations"] for s in r["steps"])
        status = r["status"]
    except (OSError, ValueError, KeyError, IndexError):
        status, steps, iterations = "no results", 0, 0
    return {"status": status, "steps": steps, "iterations": iterations, "wall": wall, "peak": peak_mb}


def main():
    a = argparse.ArgumentParser()
    a.add_argument("build")
    a.add_argument("old", nargs="?")
    a.add_argument("--rows", default="press:501,press:701,press:1001,continuous:50")
    a.add_argument("--repeat", type=int, default=1,
                   help="runs of each row per build, alternating; then each build's median seconds")
    a.add_argument("--threads", type=int, help="threads for both builds (default: all cores)")
    args = a.parse_args()
    builds = [("new", args.build)] + ([("old", args.old)] if args.old else [])
    print(f"{'model':<16} {'build':<5} {'status':<14} {'steps':>5} {'its':>5} {'s':>7} {'MB':>6} "
          f"{'ms/it':>7} {'free ms/it':>10} {'ratio':>6}")
    work = tempfile.mkdtemp(prefix="contact-scale-models-")
    for row in args.rows.split(","):
        kind, size = row.split(":")
        paths = {}
        for contacts in (True, False):
            paths[contacts] = os.path.join(work, f"{kind}-{size}-{'contact' if contacts else 'free'}.json")
            shape = pipeline(int(size), contacts=contacts) if kind == "pipeline" else model(kind, int(size), contacts)
            json.dump(shape, open(paths[contacts], "w"))
        walls = {name: [] for name, _ in builds}
        for _ in range(args.repeat):
            for name, build in (builds[::-1] if len(builds) == 2 else builds):  # old first, then new
                binary = os.path.join(build, "tsmframe")
                r = run(binary, paths[True], args.threads)
                free = run(binary, paths[False], args.threads)
                walls[name].append(r["wall"])
                per = 1e3 * r["wall"] / max(r["iterations"], 1)
                free_per = 1e3 * free["wall"] / max(free["iterations"], 1)
                print(f"{kind + ' ' + size:<16} {name:<5} {r['status']:<14} {r['steps']:>5} {r['iterations']:>5} "
                      f"{r['wall']:>7.2f} {r['peak']:>6.0f} {per:>7.2f} {free_per:>10.3f} {per / free_per:>6.1f}", flush=True)
        if args.repeat > 1:
            for name, w in walls.items():
                print(f"{kind + ' ' + size:<16} {name:<5} median {statistics.median(w):.2f} s of {len(w)} runs "
                      f"({min(w):.2f} … {max(w):.2f})", flush=True)


if __name__ == "__main__":
    main()
