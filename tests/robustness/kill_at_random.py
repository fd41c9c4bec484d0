#!/usr/bin/python3
"""Robustness: SIGKILL at random moments of a run that replaces a good output directory with a
big one never leaves a mix. After each kill the directory is the previous outputs whole or the
new ones whole: results.json parses, its title is the previous model's or the new one's, and
steps.csv has a row per converged step of that same results.json. The next run removes every
temporary the killed runs left (io/output_directory.hpp). Half the kills are aimed at the end of
the run, where the files are written and the directory committed.

    /usr/bin/python3 tests/robustness/kill_at_random.py TSMFRAME [KILLS] [SEED]
"""
import json
import os
import random
import signal
import subprocess
import sys
import tempfile
import time


def model(title, steps, output):
    """A cantilever of 200 elements rolled up by a tip moment."""
    return {
        "format": "tsmframe-model/1", "title": title,
        "materials": {"steel": {"E": 2.05e11, "G": 7.9e10}},
        "sections": {"s": {"A": 0.01, "I": 8.333333333333335e-06, "shear_area": 0.008333333333333335}},
        "nodes": [{"id": 1, "x": 0.0, "y": 0.0}, {"id": 2, "x": 10.0, "y": 0.0}],
        "members": [{"from": 1, "to": 2, "divisions": 200, "element": "timoshenko", "material": "steel", "section": "s"}],
        "supports": [{"node": 1, "type": "fixed"}],
        "loads": [{"node": 2, "mz": 1073377.489976513}],
        "analysis": {"control": {"type": "load", "steps": steps}, "output": output},
    }


def check_whole(out, titles):
    """The directory is one run's outputs whole; returns its title."""
    with open(os.path.join(out, "results.json")) as f:
        results = json.load(f)  # a half-written file does not parse
    assert results["title"] in titles, results["title"]
    converged = sum(1 for s in results["steps"] if s["converged"])
    with open(os.path.join(out, "steps.csv")) as f:
        rows = f.read().splitlines()[1:]
    assert len(rows) == converged, f"{results['title']}: results.json has {converged} converged steps, steps.csv {len(rows)} rows"
    leftovers = [name for name in os.listdir(out) if name not in ("results.json", "steps.csv")]
    assert not leftovers, f"in the output directory: {leftovers}"
    return results["title"]


def temporaries(directory):
    return [name for name in os.listdir(directory) if ".tsmframe-" in name or ".tmp-" in name]


def main():
    binary = sys.argv[1]
    kills = int(sys.argv[2]) if len(sys.argv) > 2 else 30
    rng = random.Random(int(sys.argv[3]) if len(sys.argv) > 3 else 33)
    with tempfile.TemporaryDirectory() as d:
        paths = {}
        for name, m in {"previous": model("previous", 2, "last"), "new": model("new", 600, "all")}.items():
            paths[name] = os.path.join(d, name + ".json")
            with open(paths[name], "w") as f:
                json.dump(m, f)
        out = os.path.join(d, "out")
        run = lambda name: [binary, "run", paths[name], "--out", out, "-q", "--threads", "1"]
        assert subprocess.run(run("previous"), capture_output=True).returncode == 0
        start = time.monotonic()
        assert subprocess.run(run("new"), capture_output=True).returncode == 0  # ~16 MB of results.json
        duration = time.monotonic() - start
        seen = {"previous": 0, "new": 0}
        left = 0
        for k in range(kills):
            left += len(temporaries(d))
            assert subprocess.run(run("previous"), capture_output=True).returncode == 0  # removes them
            assert not temporaries(d), f"temporaries after the next run: {temporaries(d)}"
            at = rng.uniform(0.0, duration) if k % 2 == 0 else rng.uniform(0.7 * duration, 1.1 * duration)
            p = subprocess.Popen(run("new"), stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
            time.sleep(at)
            p.send_signal(signal.SIGKILL)
            p.wait()
            seen[check_whole(out, ("previous", "new"))] += 1
        left += len(temporaries(d))
        assert subprocess.run(run("previous"), capture_output=True).returncode == 0
        check_whole(out, ("previous",))
        assert not temporaries(d), f"temporaries after the next run: {temporaries(d)}"
        print(f"{kills} kills in {duration:.2f} s runs: {seen['previous']} left the previous outputs, "
              f"{seen['new']} the new ones; {left} temporaries of killed runs, each removed by the next run")


if __name__ == "__main__":
    main()
