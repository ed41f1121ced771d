#!/usr/bin/env bash
# The accelerator check of issue 34 (docs/batched.md, docs/performance.md): benches/accelerated.py
# on one GPU, within 8 minutes, its output into $OUT (or ./accelerated) as accelerated.txt.
#
# The GPU machine has Python 3.12 and JAX, and no network: what it lacks is carried as wheels in
# .whl/, which benches/accelerated_wheels.sh puts there. Then, from the repository's root:
#   bash benches/accelerated_check.sh
# Arguments after it go to benches/accelerated.py and override its (a dry run on a CPU:
# bash benches/accelerated_check.sh --states 1e4 --sizes 64 --repeats 1).
set -euo pipefail
cd "$(dirname "$0")/.."
out=${OUT:-accelerated}
mkdir -p "$out"
if compgen -G ".whl/*.whl" >/dev/null; then
  python3 -m pip install -q --no-index --no-deps --no-compile --no-cache-dir --upgrade --target /tmp/site .whl/*.whl
  export PYTHONPATH=/tmp/site${PYTHONPATH:+:$PYTHONPATH}
fi
export PYTHONUNBUFFERED=1 XLA_PYTHON_CLIENT_PREALLOCATE=false
python3 -c "import jax; print('devices:', jax.devices())" | tee "$out/accelerated.txt"
# float32 and float64 (x64), 1e6 states a batch; the MJX steps at 65,536 / 8,192 / 1,024 envs
# (the target's size first, so that it is measured if the time runs out).
timeout 420 python3 benches/accelerated.py --x64 --states 1e6 --repeats 5 --mjx --sizes 65536,8192,1024 "$@" 2>&1 | tee -a "$out/accelerated.txt"
