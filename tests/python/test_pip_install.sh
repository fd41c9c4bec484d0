#!/usr/bin/env bash
# `pip install .` (README, Python): offline, into a venv over Debian's packages, reusing the
# CMake build; the installed module then runs a model from another directory, PYTHONPATH unset.
#   bash tests/python/test_pip_install.sh SOURCE_DIR BUILD_DIR
set -euo pipefail
source_dir=$1
build_dir=$2
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
/usr/bin/python3 -m venv --system-site-packages "$scratch/venv"
TSMFRAME_BUILD_DIR="$build_dir" "$scratch/venv/bin/pip" install -q --no-build-isolation --no-index --no-deps "$source_dir"
cd "$scratch"
env -u PYTHONPATH "$scratch/venv/bin/python" - <<'PY'
import math
import tsmframe as tf
assert "/venv/" in tf.__file__, tf.__file__  # the installed copy, not the build tree
# A cantilever (EI = 1, L = 1) rolled into a full circle by M = 2πEI/L in one load step:
# its tip comes back to the clamp, turned by 2π.
m = tf.Model("circle").material("m", E=1.0).section("s", A=1e4, I=1.0)
m.node(1, 0, 0).node(2, 1, 0).member(1, 2, "m", "s", divisions=10).support(1, "fixed").load(2, mz=2 * math.pi)
r = tf.run(m)
assert r.ok, r.message
ux, uy, rz = r.displacement(2)
assert abs(ux + 1) < 1e-9 and abs(uy) < 1e-9 and abs(rz - 2 * math.pi) < 1e-9, (ux, uy, rz)
print("pip-installed tsmframe: full circle in", int(r.iterations[0]), "iterations")
PY
