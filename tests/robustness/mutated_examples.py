#!/usr/bin/python3
"""Robustness: the examples, mutated at random (a seeded, repeatable draw), never crash the
command line. Each mutant has one or two values replaced (0, -1, 1e-30, 1e30, strings, null,
empty arrays and objects, booleans, huge integers …) or keys deleted; every run must end with exit
0 (converged), 1 (did not reach the end; results written) or 2 (bad input: exactly one line on
stderr, no output directory), never an internal error, and within a time limit. Each runs on one
thread: a second thread on a machine busy with other work (ctest -j2) only makes the slowest
mutants slower (a 1,000-contact press: 7 s on one thread, up to 80 s on two under load).

    /usr/bin/python3 tests/robustness/mutated_examples.py TSMFRAME SOURCE [COUNT] [SEED]
"""
import copy
import glob
import json
import os
import random
import subprocess
import sys
import tempfile

# Seconds a mutant may run; TSMFRAME_TEST_TIME_SCALE (scripts/sanitize.sh: an instrumented build
# runs 5–10 times slower) stretches it.
LIMIT = 60 * int(os.environ.get("TSMFRAME_TEST_TIME_SCALE", "1"))
VALUES = [0, -1, 1e-30, 1e30, 2.5, -0.0, "", "x", None, [], {}, True, [0, 0], 10**9, 0.5, -1e-9]


def paths(x, prefix=()):
    yield prefix
    if isinstance(x, dict):
        for k, v in x.items():
            yield from paths(v, prefix + (k,))
    elif isinstance(x, list):
        for i, v in enumerate(x):
            yield from paths(v, prefix + (i,))


SCALES = [-1.0, 0.0, 1e-6, 1e-3, 0.1, 10.0, 1e3, 1e6]
COUNT_SCALES = [-1, 0, 2, 10]


def mutate(model, rng):
    """Half the time a number scaled (a load 1e6 × too large, a section 1e-6 × too small: runs that
    reach the solver), else a value replaced or a key deleted (mostly bad input)."""
    for _ in range(rng.randint(1, 2)):
        places = [p for p in paths(model) if p]
        numbers = [p for p in places if isinstance(_at(model, p), (int, float)) and not isinstance(_at(model, p), bool)]
        scale = numbers and rng.random() < 0.5
        where = rng.choice(numbers if scale else places)
        parent = _at(model, where[:-1])
        if scale:  # a count (steps, divisions, ids) at most 10 × larger: a million steps is a long run, not a fault
            value = parent[where[-1]]
            parent[where[-1]] = value * rng.choice(COUNT_SCALES if isinstance(value, int) else SCALES)
        elif rng.random() < 0.3:
            if isinstance(parent, list):
                parent.pop(where[-1])
            else:
                del parent[where[-1]]
        else:
            parent[where[-1]] = copy.deepcopy(rng.choice(VALUES))
    return model


def _at(model, where):
    for k in where:
        model = model[k]
    return model


def finite_states(results_path):
    """Every converged step's displacements, element forces and reactions are numbers (the writer
    writes a non-finite one as null)."""
    with open(results_path) as f:
        results = json.load(f)
    for step in results["steps"]:
        for key in ("displacements", "element_forces", "reactions"):
            for values in step.get(key, {}).values():
                if any(v is None for v in values):
                    return False
    return True


def main():
    binary, source = sys.argv[1], sys.argv[2]
    count = int(sys.argv[3]) if len(sys.argv) > 3 else 60
    rng = random.Random(int(sys.argv[4]) if len(sys.argv) > 4 else 2026)
    examples = sorted(glob.glob(os.path.join(source, "examples", "*.json")))
    failures, exits = [], {0: 0, 1: 0, 2: 0}
    with tempfile.TemporaryDirectory() as d:
        for n in range(count):
            name = rng.choice(examples)
            with open(name) as f:
                model = mutate(json.load(f), rng)
            path = os.path.join(d, f"mutant{n}.json")
            with open(path, "w") as f:
                json.dump(model, f)
            out = os.path.join(d, f"out{n}")
            try:
                r = subprocess.run([binary, "run", path, "--out", out, "-q", "--threads", "1"], capture_output=True, text=True, timeout=LIMIT)
            except subprocess.TimeoutExpired:
                failures.append(f"{n} ({os.path.basename(name)}): no end within {LIMIT} s")
                continue
            err = r.stderr.strip()
            exits[r.returncode] = exits.get(r.returncode, 0) + 1
            if r.returncode not in (0, 1, 2) or "internal error" in err:
                failures.append(f"{n} ({os.path.basename(name)}): exit {r.returncode}: {err[:300]}")
            elif r.returncode == 2 and (err.count("\n") != 0 or os.path.exists(out)):
                failures.append(f"{n} ({os.path.basename(name)}): bad input not one line, or output written: {err[:300]}")
            elif r.returncode in (0, 1) and not os.path.exists(os.path.join(out, "results.json")):
                failures.append(f"{n} ({os.path.basename(name)}): exit {r.returncode} without results.json")
            elif r.returncode in (0, 1) and not finite_states(os.path.join(out, "results.json")):
                failures.append(f"{n} ({os.path.basename(name)}): a converged step with a non-finite value (null)")
    for f in failures:
        print(f)
    print(f"{count} mutants (exit 0: {exits[0]}, 1: {exits[1]}, 2: {exits[2]}), {len(failures)} failures")
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
