"""The engine's cost per case of a study on Dask (issue 32): an imperfect pinned column (20
elements) loaded to 0.9 of its Euler load in 5 steps, its imperfection — a lateral load at
mid-height — sampled CASES times; cases per second through tf.study(jobs=2) on this machine
against two single-thread Dask workers (a LocalCluster of two processes) on it, alternating.

    PYTHONPATH=build/python /usr/bin/python3 bench/study_dask.py [CASES] [ROUNDS]
"""

import math
import random
import sys
import time

import tsmframe as tf


def column_study(cases):
    L, EI, P = 4.0, 2e5, 1e3
    m = tf.Model("imperfect column").material("steel", E=2e11).section("s", A=1e-2, I=1e-6)
    m.node(1, 0, 0).node(2, 0, L / 2).node(3, 0, L)
    m.member(1, 2, "steel", "s", divisions=10).member(2, 3, "steel", "s", divisions=10)
    load = 0.9 * math.pi ** 2 * EI / L ** 2
    m.support(1, "pinned").support(3, "roller-y").load(3, fy=-load).load(2, fx=1e-3 * load)
    m.analysis(steps=5)
    rng = random.Random(1)
    amplitudes = [round(rng.gauss(0.0, 1e-3 * load), 9) for _ in range(cases)]
    return {"format": "tsmframe-study/1", "model": m.to_dict(),
            "sweep": [{"name": "imperfection", "path": "/loads/1/fx", "values": amplitudes}],
            "record": [{"name": "mid_ux", "quantity": "displacement", "node": 2, "dof": "ux"}]}


def main():
    cases = int(sys.argv[1]) if len(sys.argv) > 1 else 10000
    rounds = int(sys.argv[2]) if len(sys.argv) > 2 else 3
    from distributed import Client, LocalCluster
    study = column_study(cases)
    with LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None) as cluster, \
            Client(cluster) as client:
        client.run(lambda: __import__("tsmframe"))  # the workers' import, outside the timing
        local_rate, dask_rate = [], []
        for r in range(rounds):
            for name, rates, kw in (("local --jobs 2", local_rate, {"jobs": 2}), ("dask 2 workers", dask_rate, {"client": client})):
                start = time.perf_counter()
                rows = tf.study(study, **kw)
                seconds = time.perf_counter() - start
                assert len(rows) == cases and all(row["converged"] for row in rows)
                rates.append(cases / seconds)
                print(f"round {r + 1}  {name:15s} {seconds:7.2f} s  {cases / seconds:8.0f} cases/s", flush=True)
    local, dask = sorted(local_rate)[len(local_rate) // 2], sorted(dask_rate)[len(dask_rate) // 2]
    print(f"medians: local {local:.0f} cases/s, dask {dask:.0f} cases/s: the engine's overhead {100 * (local / dask - 1):.1f} %")


if __name__ == "__main__":
    main()
