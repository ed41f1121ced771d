"""Another build of uwml for a benchmark to measure beside this one, in one run: ``--against REF``
builds the package at the git revision ``REF`` (its sources from ``git archive``, its native
module by ``cargo build --release``, as ``pip install`` builds it) into
``target/bench-against/<commit>/`` once, and runs the benchmark's measurements there in a
subprocess (``PYTHONPATH`` pointing at that package), alternately with this build's.

The measurements of a benchmark must then run on both builds: a benchmark's own code looks up
what a name was called at that revision (``uwml.paper_leg`` or ``uwml.Leg.paper``, say)."""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
import sysconfig
import tarfile
from collections.abc import Callable
from io import BytesIO
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parents[1]


def build(ref: str) -> Path:
    """The folder holding the ``uwml`` package built at ``ref`` (built on first use)."""
    commit = subprocess.run(["git", "rev-parse", "--verify", f"{ref}^{{commit}}"], cwd=ROOT, capture_output=True, text=True, check=True)
    sha = commit.stdout.strip()
    folder = ROOT / "target" / "bench-against" / sha[:12]
    package = folder / "python"
    native = package / "uwml" / f"_core{sysconfig.get_config_var('EXT_SUFFIX')}"
    if native.exists():
        return package
    sources = folder / "src"
    shutil.rmtree(folder, ignore_errors=True)
    sources.mkdir(parents=True)
    archive = subprocess.run(["git", "archive", sha], cwd=ROOT, capture_output=True, check=True).stdout
    with tarfile.open(fileobj=BytesIO(archive)) as tar:
        tar.extractall(sources, filter="data")
    target = ROOT / "target" / "bench-against" / "target"
    print(f"building uwml at {ref} ({sha[:12]}) into {folder} (a few minutes, once)", file=sys.stderr, flush=True)
    subprocess.run(
        ["cargo", "build", "--release", "-p", "uwml-py", "--manifest-path", str(sources / "Cargo.toml"), "--target-dir", str(target)],
        check=True,
        env={**os.environ, "PYO3_PYTHON": sys.executable},
    )
    shutil.copytree(sources / "python", package)
    shutil.copy2(target / "release" / "lib_core.so", native)
    return package


def measure_there(package: Path, script: Path, arguments: list[str]) -> dict[str, float]:
    """The measurements of ``script`` (run with ``--measure`` and ``arguments``) on the package in
    ``package``: its last line of output, a JSON object of label to seconds per state or call."""
    env = {**os.environ, "PYTHONPATH": str(package)}
    done = subprocess.run([sys.executable, str(script), "--measure", *arguments], capture_output=True, text=True, env=env, check=False)
    if done.returncode != 0:
        raise RuntimeError(f"{script.name} on the other build failed:\n{done.stderr[-3000:]}")
    result: dict[str, float] = json.loads(done.stdout.strip().splitlines()[-1])
    return result


def compare(this: list[dict[str, float]], other: list[dict[str, float]], ref: str, unit: str, scale: float) -> None:
    """The best of the rounds of each build, side by side, in ``unit`` (seconds times ``scale``)."""
    print(f"{'':60s} {'this build':>12s} {ref[:12]:>12s}   ratio  ({unit}, best of {len(this)} alternate rounds)")
    for label in this[0]:
        mine = min(round_[label] for round_ in this) * scale
        theirs = [round_[label] for round_ in other if label in round_]
        if theirs:
            best = min(theirs) * scale
            print(f"  {label:58s} {mine:12.2f} {best:12.2f}   {mine / best:5.2f}")
        else:
            print(f"  {label:58s} {mine:12.2f} {'—':>12s}")


def paper_leg(uwml: Any) -> Any:
    """The paper's leg, by the revision's name for it."""
    return uwml.paper_leg() if hasattr(uwml, "paper_leg") else uwml.Leg.paper()


def arm_on_rov() -> Any:
    """The 7-joint arm on an ROV, from where the revision keeps it."""
    try:
        from uwml.robot.examples import arm_on_rov as make
    except ImportError:
        from uwml.examples import arm_on_rov as make  # this revision, and those before uwml.robot
    return make()


def run(script: str, measure: Callable[[str], dict[str, float]], size: str, unit: str, scale: float) -> dict[str, float] | None:
    """A benchmark's command line: ``[size] [--against REF] [--rounds K]``, or ``--measure SIZE``
    (the other build's subprocess: prints the JSON of ``measure(SIZE)``). With ``--against``, the
    builds' figures side by side (``unit``: seconds times ``scale``), and None; else this build's
    measurements, for the benchmark to print."""
    arguments = sys.argv[1:]
    if "--measure" in arguments:
        arguments.remove("--measure")
        print(json.dumps(measure(arguments[0])))
        return None
    options = {}
    for name in ("--against", "--rounds"):
        if name in arguments:
            i = arguments.index(name)
            options[name] = arguments[i + 1]
            del arguments[i : i + 2]
    size = arguments[0] if arguments else size
    if "--against" not in options:
        return measure(size)
    ref = options["--against"]
    package = build(ref)
    this, other = [], []
    for _ in range(int(options.get("--rounds", "3"))):
        this.append(measure(size))
        other.append(measure_there(package, Path(script), [size]))
    compare(this, other, ref, unit, scale)
    return None
