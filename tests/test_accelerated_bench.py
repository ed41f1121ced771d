"""The accelerator benchmark (benches/accelerated.py, issue 34 point 5) runs as the accelerator
check runs it, here as a dry run on the CPU with tiny batches: it prints both robots'
evaluations in float32 and float64 and the vehicle's steps, bare MJX and uwml's full step, with
positive rates. A change that broke it would otherwise be found only on the GPU machine, whose
time is scarce. The figures themselves are not checked: a CPU's say nothing of a GPU's."""

from __future__ import annotations

import re
import subprocess
import sys
from pathlib import Path

import pytest

pytest.importorskip("jax")
pytest.importorskip("mujoco.mjx")

ROOT = Path(__file__).resolve().parents[1]


def test_the_benchmark_prints_every_row_with_a_positive_rate() -> None:
    arguments = ["--x64", "--states", "64", "--repeats", "1", "--mjx", "--sizes", "2"]
    command = [sys.executable, str(ROOT / "benches" / "accelerated.py"), *arguments]
    done = subprocess.run(command, capture_output=True, text=True, timeout=600, check=False)
    assert done.returncode == 0, done.stderr[-2000:]
    rows = re.findall(r"^  (\S.*?)\s{2,}(float32|float64|\d+)\s+(-?[\d.]+)\s+([\d.e+-]+)$", done.stdout, re.MULTILINE)
    found = {(what, size) for what, size, _, _ in rows}
    expected = {(robot, dtype) for robot in ("paper leg", "7-joint arm on a moving ROV") for dtype in ("float32", "float64")}
    expected |= {("bare MJX", "2"), ("full uwml step", "2")}
    assert found == expected, done.stdout
    assert all(float(rate) > 0 for _, _, _, rate in rows), done.stdout
    assert re.search(r"^device: cpu ", done.stdout, re.MULTILINE), done.stdout
