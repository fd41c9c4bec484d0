"""tf.study on a Dask cluster (tsmframe.distributed): a scheduler and two single-thread workers
started on 127.0.0.1 as processes (Debian's python3-distributed), stopped at the end. The paper's
Fig. 7 study through them gives the local run's rows; a worker killed mid-study loses no case
and doubles none; a bad study is refused before any task."""

import json
import os
import signal
import subprocess
import sys
import tempfile
import time

import pytest

import tsmframe as tf

SOURCE = os.environ.get("TSMFRAME_SOURCE_DIR", os.path.join(os.path.dirname(__file__), "..", ".."))
FIG7 = os.path.join(SOURCE, "studies", "fig7-contact-edge.json")
BIN = os.path.dirname(sys.executable) if os.path.exists(os.path.join(os.path.dirname(sys.executable), "dask-scheduler")) else "/usr/bin"


def without_seconds(rows):
    return [{k: v for k, v in row.items() if k != "seconds"} for row in rows]


@pytest.fixture
def cluster():
    """A scheduler and two workers (one thread each, no nanny: a killed worker stays dead); the
    scheduler's address, the workers' processes and their addresses."""
    directory = tempfile.mkdtemp(prefix="tsmframe-dask-")
    scheduler_file = os.path.join(directory, "scheduler.json")
    env = dict(os.environ, PYTHONPATH=os.path.dirname(os.path.dirname(os.path.abspath(tf.__file__))))
    common = dict(env=env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, cwd=directory)
    processes = [subprocess.Popen([os.path.join(BIN, "dask-scheduler"), "--host", "127.0.0.1", "--port", "0",
                                   "--no-dashboard", "--scheduler-file", scheduler_file], **common)]
    try:
        deadline = time.monotonic() + 60
        while not os.path.exists(scheduler_file) and time.monotonic() < deadline:
            time.sleep(0.1)
        with open(scheduler_file) as f:
            address = json.load(f)["address"]
        workers = [subprocess.Popen([os.path.join(BIN, "dask-worker"), address, "--nthreads", "1", "--no-nanny",
                                     "--no-dashboard", "--host", "127.0.0.1"], **common) for _ in range(2)]
        processes += workers
        from distributed import Client
        with Client(address, timeout=30) as client:
            client.wait_for_workers(2, timeout=60)
            worker_addresses = set(client.scheduler_info()["workers"])
        yield address, workers, worker_addresses
    finally:
        for p in reversed(processes):
            p.kill()
            p.wait(timeout=30)


def test_the_fig7_study_through_two_workers_gives_the_local_rows(cluster):
    address, _, worker_addresses = cluster
    local = tf.study(FIG7)
    seen = []
    remote = tf.study(FIG7, scheduler=address, progress=lambda done, total, worker: seen.append((done, total, worker)))
    assert without_seconds(remote) == without_seconds(local)
    assert len(seen) == 8  # 4 shards per worker thread
    assert seen[-1][:2] == (len(local), len(local)) and [done for done, _, _ in seen] == sorted(done for done, _, _ in seen)
    assert {worker for _, _, worker in seen} <= worker_addresses  # where each shard ran


def test_a_worker_killed_mid_study_loses_no_case_and_doubles_none(cluster):
    address, workers, _ = cluster
    local = tf.study(FIG7)
    killed = []

    def kill_one(done, total, worker):  # as the first shard ends: the other worker is in the middle of one
        if not killed:
            workers[0].send_signal(signal.SIGKILL)
            killed.append(done)

    remote = tf.study(FIG7, scheduler=address, progress=kill_one)
    assert killed
    assert [row["case"] for row in remote] == list(range(1, len(local) + 1))
    assert without_seconds(remote) == without_seconds(local)


def test_a_bad_study_is_refused_before_any_task(cluster):
    address, _, _ = cluster
    with open(FIG7) as f:
        study = json.load(f)
    study["sweep"][0]["path"] = 7
    with pytest.raises(ValueError, match=r"^sweep\[0\]: give either"):
        tf.study(study, scheduler=address)


def test_the_command_line_runs_a_study_on_the_cluster_and_writes_the_local_rows(cluster, tmp_path):
    # tsmframe study --scheduler: study.csv and study.json as a local run writes them (seconds
    # aside); an address where no scheduler listens is one line and exit 2, nothing written.
    address, _, worker_addresses = cluster
    cli = os.environ["TSMFRAME_CLI"]
    local, remote = tmp_path / "local", tmp_path / "remote"
    # Exit 1 for both: rows written, some of Fig. 7's cases do not converge (the same ones).
    expected = subprocess.run([cli, "study", FIG7, "-q", "--out", str(local)], timeout=300).returncode
    assert expected in (0, 1)
    done = subprocess.run([cli, "study", FIG7, "--scheduler", address, "--out", str(remote)], timeout=300,
                          capture_output=True, text=True)
    assert done.returncode == expected, done.stderr
    last = [line for line in done.stderr.splitlines() if "48/48 cases done" in line]
    assert len(last) == 1 and any(last[0].endswith(f"on worker {worker})") for worker in worker_addresses), done.stderr
    with open(local / "study.json") as a, open(remote / "study.json") as b:
        assert without_seconds(json.load(b)["cases"]) == without_seconds(json.load(a)["cases"])
    # The study keeps its cases: each one's files come back from the workers, the same as local ones.
    kept = sorted(p.relative_to(local) for p in (local / "cases").rglob("*") if p.is_file())
    assert len(kept) == 2 * 48 and kept == sorted(p.relative_to(remote) for p in (remote / "cases").rglob("*") if p.is_file())
    for name in kept:
        if name.name == "steps.csv":
            assert (remote / name).read_bytes() == (local / name).read_bytes(), name
    nowhere = subprocess.run([cli, "study", FIG7, "-q", "--scheduler", "tcp://127.0.0.1:9", "--out", str(tmp_path / "none")],
                             timeout=300, capture_output=True, text=True)
    assert nowhere.returncode == 2, nowhere.stderr
    assert "cannot reach the Dask scheduler" in nowhere.stderr and nowhere.stderr.count("\n") == 1, nowhere.stderr
    assert not (tmp_path / "none").exists()


def test_workers_that_cannot_import_tsmframe_are_named_in_one_line(tmp_path):
    # A worker started without tsmframe on its path: the command says so (exit 2), writes nothing.
    scheduler_file = tmp_path / "scheduler.json"
    env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
    common = dict(env=env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, cwd=tmp_path)
    processes = [subprocess.Popen([os.path.join(BIN, "dask-scheduler"), "--host", "127.0.0.1", "--port", "0",
                                   "--no-dashboard", "--scheduler-file", str(scheduler_file)], **common)]
    try:
        deadline = time.monotonic() + 60
        while not scheduler_file.exists() and time.monotonic() < deadline:
            time.sleep(0.1)
        address = json.loads(scheduler_file.read_text())["address"]
        processes.append(subprocess.Popen([os.path.join(BIN, "dask-worker"), address, "--nthreads", "1", "--no-nanny",
                                           "--no-dashboard", "--host", "127.0.0.1"], **common))
        from distributed import Client
        with Client(address, timeout=30) as client:
            client.wait_for_workers(1, timeout=60)
        done = subprocess.run([os.environ["TSMFRAME_CLI"], "study", FIG7, "-q", "--scheduler", address,
                               "--out", str(tmp_path / "out")], timeout=300, capture_output=True, text=True)
        assert done.returncode == 2, done.stderr
        assert "the workers cannot import tsmframe" in done.stderr and done.stderr.count("\n") == 1, done.stderr
        assert not (tmp_path / "out").exists()
    finally:
        for p in reversed(processes):
            p.kill()
            p.wait(timeout=30)
