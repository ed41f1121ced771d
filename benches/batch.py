"""Throughput of the batch evaluations from Python, per state: the paper's leg (``hydro`` on one and
two threads, ``environment`` with the default losses on all three joints, ``hydro_regressors``,
on a moving base in a current) and the 7-joint arm of 15 segments on an ROV of
:func:`uwml.examples.arm_on_rov` (moving, in a current, one and two threads); against the
numpy reference; and what the checks against a description's joint limits cost
(``uwml.plausibility``): the arm of ``examples/my_arm`` from its URDF with and without its limits
(needs MuJoCo; skipped without it).

Run: ``python benches/batch.py [n_states] [--against REF] [--rounds K]`` (default 1e6 states).
Each figure is the best of 3 calls. With ``--against REF`` (a git revision: the commit before a
change, or the last with the chain path, ``e7430d7^``) the same measurements of the package
built at ``REF`` (``benches/_against.py``) are taken in the same run, alternately with this
build's, ``K`` rounds each (default 3), and printed side by side.
"""

from __future__ import annotations

import os

# numpy's BLAS threads, left spinning after a call, would take the second core from ``threads=2``
# and from the other build's subprocess.
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import sys
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np
from _against import arm_on_rov, paper_leg, run


def best_of(runs: int, call: Callable[[], Any]) -> float:
    best = np.inf
    for _ in range(runs):
        start = time.perf_counter()
        call()
        best = min(best, time.perf_counter() - start)
    return best


def evaluations(n: int) -> dict[str, Callable[[], Any]]:
    """The batch calls measured, on ``n`` states each (every revision's API)."""
    import uwml

    rng = np.random.default_rng(0)
    q = rng.uniform(-np.pi, np.pi, (n, 3))
    qd = rng.uniform(-3, 3, (n, 3))
    qdd = rng.uniform(-10, 10, (n, 3))
    leg, arm = paper_leg(uwml), arm_on_rov()
    robot = uwml.Robot(leg.joints, leg.links)
    losses = uwml.JointLosses()
    q7, qd7, qdd7 = (rng.uniform(-1, 1, (n, 7)) * scale for scale in (1.0, 0.5, 2.0))
    quaternion = rng.normal(size=(n, 4))
    motion = uwml.BaseMotion(
        orientation=quaternion / np.linalg.norm(quaternion, axis=1, keepdims=True),
        velocity=rng.normal(0, 0.3, (n, 3)),
        angular_velocity=rng.normal(0, 0.1, (n, 3)),
    )
    current = (0.3, 0.1, 0.0)
    return {
        "paper leg, hydro, 1 thread": lambda: leg.hydro(q, qd, qdd),
        "paper leg, hydro, 2 threads": lambda: leg.hydro(q, qd, qdd, threads=2),
        "paper leg, environment (losses), 1 thread": lambda: leg.environment(q, qd, qdd, depth=1000.0, temperature_c=4.0, losses=losses),
        "paper leg, environment (losses), 2 threads": lambda: leg.environment(
            q, qd, qdd, depth=1000.0, temperature_c=4.0, losses=losses, threads=2
        ),
        "paper leg, hydro_regressors, 1 thread": lambda: leg.hydro_regressors(q, qd, qdd),
        "paper leg, moving base, current": lambda: robot.hydro(q, qd, qdd, base_motion=motion, current=current),
        "7-joint arm on a moving ROV, current, 1 thread": lambda: arm.hydro(q7, qd7, qdd7, base_motion=motion, current=current),
        "7-joint arm on a moving ROV, current, 2 threads": lambda: arm.hydro(q7, qd7, qdd7, base_motion=motion, current=current, threads=2),
    }


def measure(n: int) -> dict[str, float]:
    """Seconds per state of each evaluation, best of 3 calls."""
    calls = evaluations(n)
    for call in calls.values():
        call()  # warm: the lanes' robot, the conditions
    return {label: best_of(3, call) / n for label, call in calls.items()}


def main() -> None:
    n = int(float(sys.argv[1])) if len(sys.argv) > 1 and not sys.argv[1].startswith("-") else 1_000_000
    timings = run(__file__, lambda size: measure(int(float(size))), str(n), "ns per state", 1e9)
    if timings is None:
        return
    print(f"states: {n:,}")
    for label, t in timings.items():
        print(f"uwml {label:52s} {t * n:7.3f} s  {1e-6 / t:7.2f} M states/s  {t * 1e9:7.1f} ns/state")
    limits_cost(n, np.random.default_rng(1))
    reference_cost(n, timings["paper leg, hydro, 1 thread"])


def reference_cost(n: int, one_thread: float) -> None:
    """The numpy reference on the paper's leg, for scale."""
    m = min(n, 200_000)
    per_state = reference_per_state(m)
    print(
        f"uwml.reference.hydro (numpy){'':25s} {per_state * 1e9:7.1f} ns/state (on {m:,} states): the core {per_state / one_thread:.0f}x faster"
    )


def reference_per_state(m: int, runs: int = 1) -> float:
    """Seconds per state of the numpy reference (``uwml.reference.hydro``) on ``m`` states of the
    paper's leg, best of ``runs`` calls."""
    import uwml
    from uwml import reference

    leg = uwml.paper_leg()
    rng = np.random.default_rng(0)
    q, qd, qdd = (rng.uniform(-3, 3, (m, 3)) for _ in range(3))
    return best_of(runs, lambda: reference.hydro(leg.joints, leg.links, q, qd, qdd)) / m


def limits_cost(n: int, rng: np.random.Generator) -> None:
    """``Robot.hydro`` and ``Robot.environment`` on the README's arm with and without its joint
    limits, alternately, best of 3 each: the warnings' checks (no state here warns)."""
    times = limits_times(n, rng)
    if times is None:
        print("limits: skipped (no MuJoCo to read the URDF)")
        return
    for label, (without, with_) in times.items():
        print(
            f"uwml Robot.{label}, my_arm, without / with its limits: {without * 1e9:6.1f} / {with_ * 1e9:6.1f} ns/state ({with_ / without:.3f}x)"
        )


def limits_times(n: int, rng: np.random.Generator) -> dict[str, tuple[float, float]] | None:
    """Seconds per state of ``Robot.hydro`` and ``Robot.environment`` on the arm of
    ``examples/my_arm`` without and with its joint limits (the plausibility checks), alternately,
    best of 3 each; None without MuJoCo (which reads the URDF)."""
    try:
        import mujoco  # noqa: F401
    except ImportError:
        return None
    import dataclasses
    import functools

    import uwml

    folder = Path(__file__).resolve().parents[1] / "examples" / "my_arm"
    limited = uwml.Robot.from_urdf(folder / "my_arm.urdf", folder / "my_arm.hydro.toml")
    joints = [dataclasses.replace(j, range=None, velocity_limit=None, effort_limit=None) for j in limited.joints]
    free = uwml.Robot(joints, limited.links, base=limited.base, water=limited.water)
    q, qd, qdd = rng.uniform(-1, 1, (n, 2)), rng.uniform(-1, 1, (n, 2)), rng.uniform(-2, 2, (n, 2))
    result = {}
    for label, call in [
        ("hydro", lambda robot: robot.hydro(q, qd, qdd)),
        ("environment", lambda robot: robot.environment(q, qd, qdd, depth=100.0)),
    ]:
        times: dict[str, list[float]] = {"without": [], "with": []}
        for _ in range(3):
            for name, robot in (("without", free), ("with", limited)):
                times[name].append(best_of(1, functools.partial(call, robot)))
        result[label] = (min(times["without"]) / n, min(times["with"]) / n)
    return result


if __name__ == "__main__":
    main()
