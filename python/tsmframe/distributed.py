"""A study's cases on a Dask cluster (Debian's python3-distributed): the study split into shards
(case k from 0 where k mod N = I, as `tsmframe study --shard`), each shard one task that runs its
cases on one thread of a worker, the rows gathered back in case order. Dask schedules the tasks
and runs a task again elsewhere where its worker dies; each shard's rows come back once, so no
case is lost or counted twice. The workers import tsmframe themselves: it must be installed (or
on PYTHONPATH) where they run."""

import json as _json
import os as _os
import tempfile as _tempfile

from ._core import study_cases as _study_cases, study_json as _study_json, study_rows_jsonl as _study_rows_jsonl

# Shards per worker thread: enough that a slow shard does not hold the study up at its end, few
# enough that Dask's cost per task (~1 ms) stays small beside the cases'.
SHARDS_PER_THREAD = 4


def _self_contained(text, directory):
    """The study's text with its model_file read in (the workers need not see the file)."""
    document = _json.loads(text)
    if isinstance(document, dict) and isinstance(document.get("model_file"), str):
        path = _os.path.join(directory, document.pop("model_file"))
        with open(path) as f:
            document["model"] = _json.load(f)
    return _json.dumps(document)


def shard_rows(text, index, count):
    """Run on a worker: the rows of shard `index` of `count` (study.json's rows)."""
    return _json.loads(_study_json(text, ".", 1, index, count))["cases"]


def shard_journal_lines(text, index, count):
    """Run on a worker: the rows of shard `index` of `count` as the study journal's lines, and
    where the study keeps cases ("keep": true) their files: {"cases/<case>/results.json": bytes, …}
    (the workers need share no storage with the command)."""
    with _tempfile.TemporaryDirectory(prefix="tsmframe-shard-") as kept:
        lines = _study_rows_jsonl(text, ".", 1, index, count, kept)
        files = {}
        for root, _, names in _os.walk(kept):
            for name in names:
                path = _os.path.join(root, name)
                with open(path, "rb") as f:
                    files[_os.path.relpath(path, kept)] = f.read()
    return lines, files


def _located(task, text, index, count):
    """Run on a worker: the task's result and the address of the worker that ran it."""
    from distributed import get_worker
    return task(text, index, count), get_worker().address


def _on_cluster(text, directory, client, scheduler, task, collect, progress):
    """Runs `task(text, index, count)` for each shard of the study on the cluster; `collect` takes
    each shard's result as it ends and returns its number of cases; `progress(done, total,
    worker)` with the address of the worker the shard ran on."""
    try:
        import distributed
    except ImportError:
        raise ImportError("a study on Dask needs Dask's distributed (Debian: apt-get install python3-distributed)") from None
    total = _study_cases(text, directory)  # a bad study: ValueError here, before any task
    text = _self_contained(text, directory)
    own = client is None
    if own:
        client = distributed.Client(scheduler, timeout=10)  # an address where no scheduler listens: said within 10 s
    futures = []
    try:
        threads = max(1, sum(client.nthreads().values()))
        count = max(1, min(total, SHARDS_PER_THREAD * threads))
        futures = client.map(_located, [task] * count, [text] * count, range(count), [count] * count, pure=False)
        done = 0
        for future in distributed.as_completed(futures):
            result, worker = future.result()
            done += collect(result)
            if progress is not None:
                progress(done, total, worker)
    finally:
        for future in futures:
            future.cancel()
        if own:
            client.close()


def study_on_cluster(text, directory, client=None, scheduler=None, progress=None):
    """The rows of the study in `text` (model_file relative to `directory`) run on the cluster of
    `client` (a distributed.Client) or at `scheduler` (its address, "tcp://HOST:8786"), in case
    order. `progress(done, total, worker)` (if given) is called as each shard ends: the cases done,
    and the address of the worker the shard ran on."""
    rows = []

    def collect(shard):
        rows.extend(shard)
        return len(shard)

    _on_cluster(text, directory, client, scheduler, shard_rows, collect, progress)
    return sorted(rows, key=lambda row: row["case"])


def journal_on_cluster(text, directory, journal, scheduler, progress=None):
    """As study_on_cluster, each shard's rows appended to the study journal at `journal` (its
    header written) as the shard ends, and the cases the study keeps written beside it (cases/):
    `tsmframe study --scheduler`'s cases."""
    directory_out = _os.path.dirname(_os.path.abspath(journal))
    with open(journal, "a") as f:
        def collect(shard):
            lines, files = shard
            for relative, content in files.items():  # the kept cases before their rows: a row in the journal has its files
                path = _os.path.join(directory_out, relative)
                _os.makedirs(_os.path.dirname(path), exist_ok=True)
                with open(path, "wb") as out:
                    out.write(content)
            f.write(lines)
            f.flush()
            return lines.count("\n")

        _on_cluster(text, directory, None, scheduler, shard_journal_lines, collect, progress)
