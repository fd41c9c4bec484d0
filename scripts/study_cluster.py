"""`tsmframe study STUDY.json --scheduler ADDRESS`: the study's cases on a Dask cluster
(tsmframe.distributed), each shard's rows appended to the study journal the command made, as the
shard ends; the command then writes study.csv and study.json from the journal.

    study_cluster.py PYTHON_DIR STUDY.json ADDRESS JOURNAL quiet|progress

Exit 0 when every shard ended; 1 on Ctrl-C (the rows of the shards that ended are in the
journal); 2 where Dask is missing or the scheduler cannot be reached (one line on stderr)."""

import os
import sys


def main(python_dir, study, address, journal, mode):
    sys.path.insert(0, python_dir)
    from tsmframe import distributed

    with open(study) as f:
        text = f.read()

    def progress(done, total, worker):
        if mode != "quiet":
            print(f"{study}: {done}/{total} cases done (the last shard on worker {worker})", file=sys.stderr, flush=True)

    try:
        distributed.journal_on_cluster(text, os.path.dirname(os.path.abspath(study)), journal, address, progress)
    except ImportError as e:
        if e.name == "tsmframe":  # raised where a worker reads a task: it cannot import tsmframe
            print(f"{study}: --scheduler {address}: the workers cannot import tsmframe (install it where they run, "
                  f"or start them with PYTHONPATH={python_dir})", file=sys.stderr)
        else:
            print(f"{study}: --scheduler: {e}", file=sys.stderr)
        return 2
    except (OSError, TimeoutError) as e:
        print(f"{study}: --scheduler {address}: cannot reach the Dask scheduler ({e})", file=sys.stderr)
        return 2
    except KeyboardInterrupt:
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main(*sys.argv[1:6]))
