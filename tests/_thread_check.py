"""Run as a script by ``tests/test_threads.py`` (a watchdog kills it if it hangs): every public
evaluation, called on one object from several threads at once, must give the bits of a
sequential run. Prints ``ok`` and exits 0, or names the evaluation that differed."""

from __future__ import annotations

import sys
import threading
from collections.abc import Callable
from typing import Any

import numpy as np
import uwml
from uwml.examples import arm_on_rov

THREADS = 8
CALLS = 30


def _arrays(result: Any) -> list[np.ndarray]:
    """Every array of a result (dataclasses, tuples, nested), in a fixed order."""
    if isinstance(result, np.ndarray):
        return [result]
    if isinstance(result, (float, int, np.floating)):
        return [np.asarray(result)]
    if hasattr(result, "__dataclass_fields__"):
        return [a for name in result.__dataclass_fields__ for a in _arrays(getattr(result, name))]
    if isinstance(result, (tuple, list)):
        return [a for x in result for a in _arrays(x)]
    return []


def _evaluations() -> dict[str, Callable[[], Any]]:
    rng = np.random.default_rng(7)
    leg, arm = uwml.paper_leg(), arm_on_rov()
    losses = [None, uwml.JointLosses(), uwml.JointLosses()]
    q, qd, qdd = (rng.uniform(-1, 1, (200, 3)) for _ in range(3))
    aq, aqd, aqdd = (rng.uniform(-1, 1, (200, 7)) for _ in range(3))
    motion = uwml.BaseMotion(velocity=(0.3, 0.1, 0.0), angular_velocity=(0.0, 0.1, 0.2))
    current = (0.2, -0.1, 0.05)
    joint = uwml.JointLosses()
    speeds = rng.uniform(-2, 2, 200)
    conditions = uwml.Conditions(cd=2.0, current=current)
    return {
        "paper leg hydro": lambda: leg.hydro(q, qd, qdd),
        "paper leg hydro one state": lambda: leg.hydro(q[0], qd[0], qdd[0]),
        "paper leg hydro, one conditions value": lambda: leg.hydro(q[0], qd[0], qdd[0], conditions),
        "paper leg environment": lambda: leg.environment(q, qd, qdd, depth=3000.0, losses=losses),
        "paper leg environment one state": lambda: leg.environment(q[0], qd[0], qdd[0], depth=3000.0, losses=losses),
        "paper leg jacobians": lambda: leg.jacobians(q, qd, qdd, depth=3000.0, losses=losses),
        "paper leg jacobians kirchhoff": lambda: leg.jacobians(q, qd, qdd, added_mass="kirchhoff"),
        "paper leg hydro_regressors": lambda: leg.hydro_regressors(q, qd, qdd),
        "paper leg point_jacobian": lambda: leg.point_jacobian(q),
        "Robot.hydro": lambda: arm.hydro(aq, aqd, aqdd, base_motion=motion, current=current),
        "Robot.hydro one state": lambda: arm.hydro(aq[0], aqd[0], aqdd[0], current=current),
        "Robot.hydro kirchhoff": lambda: arm.hydro(aq, aqd, aqdd, base_motion=motion, added_mass="kirchhoff"),
        "Robot.environment": lambda: arm.environment(aq, aqd, aqdd, depth=2000.0, losses=joint, current=current),
        "Robot.environment one state": lambda: arm.environment(aq[0], aqd[0], aqdd[0], depth=2000.0, losses=joint),
        "Robot.jacobians": lambda: arm.jacobians(aq, aqd, aqdd, base_motion=motion, current=current),
        "Robot.jacobians kirchhoff": lambda: arm.jacobians(aq, aqd, aqdd, losses=joint, depth=500.0, added_mass="kirchhoff"),
        "Robot.hydro_regressors": lambda: arm.hydro_regressors(aq, aqd, aqdd, base_motion=motion),
        "Robot.link_wrenches": lambda: arm.link_wrenches(aq, aqd, aqdd, current=current),
        "Robot.added_mass_matrix": lambda: arm.added_mass_matrix(aq),
        "JointLosses.torques": lambda: joint.torques(speeds, 10.0, 4.0),
    }


def _work(evaluate: Callable[[], Any], start: threading.Barrier, results: list[list[np.ndarray]], errors: list[Exception]) -> None:
    """One thread's calls, after all threads have started; an exception is kept for the report."""
    try:
        start.wait()
        for _ in range(CALLS):
            results.append(_arrays(evaluate()))
    except Exception as error:  # noqa: BLE001 (any failure of any evaluation is reported by main)
        errors.append(error)


def main() -> int:
    failures = []
    for name, evaluate in _evaluations().items():
        expected = _arrays(evaluate())
        results: list[list[list[np.ndarray]]] = [[] for _ in range(THREADS)]
        errors: list[Exception] = []
        start = threading.Barrier(THREADS)

        threads = [threading.Thread(target=_work, args=(evaluate, start, results[i], errors)) for i in range(THREADS)]
        for t in threads:
            t.start()
        for t in threads:
            t.join()
        if errors:
            failures.append(f"{name}: {errors[0]!r}")
            continue
        same = all(
            len(got) == len(expected) and all(np.array_equal(a, b, equal_nan=True) for a, b in zip(got, expected))
            for per_thread in results
            for got in per_thread
        )
        if not same:
            failures.append(f"{name}: a threaded result differs from the sequential one")
        print(name, "ok" if same else "DIFFERS", flush=True)
    if failures:
        print("\n".join(failures), file=sys.stderr)
        return 1
    print("ok")
    return 0


if __name__ == "__main__":
    sys.exit(main())
