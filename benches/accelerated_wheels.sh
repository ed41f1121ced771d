#!/usr/bin/env bash
# The wheels that benches/accelerated_check.sh installs on the GPU machine (Python 3.12, JAX 0.11,
# no network, no MuJoCo), put into .whl/ at the repository's root (ignored by git):
#   - uwml itself for CPython 3.12 (maturin, with a python3.12 on this machine);
#   - mujoco==4.0.0 and mujoco-core (cp312), mujoco-mjx==3.17.0, trimesh and gsw, fetched for
#     cp312 on manylinux x86-64 without their own needs (the GPU machine has numpy, scipy, jax,
#     absl-py, etils, matplotlib and pyarrow).
# About 21 MB together. Run from anywhere:
#   bash benches/accelerated_wheels.sh
# then send the tree with .whl carried and run: bash benches/accelerated_check.sh
set -euo pipefail
cd "$(dirname "$0")/.."
mkdir -p .whl
rm -f .whl/*.whl
maturin build --release -q -i python3.12 -o .whl
platforms=()
for p in manylinux_2_28_x86_64 manylinux_2_27_x86_64 manylinux_2_17_x86_64 manylinux2014_x86_64 manylinux1_x86_64; do
  platforms+=(--platform "$p")
done
for wheel in mujoco==4.0.0 mujoco-core==4.0.0 mujoco-mjx==3.17.0 trimesh gsw; do
  python3 -m pip download -q --no-deps --only-binary=:all: --python-version 3.12 --implementation cp \
    "${platforms[@]}" -d .whl "$wheel"
done
ls -l .whl
du -sh .whl
