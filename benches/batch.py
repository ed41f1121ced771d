"""Throughput of the batch calls ``Leg.hydro`` and ``Leg.environment`` (with the default losses on
all three joints) on one and on two threads, against the numpy reference; and of ``Robot.hydro``:
the paper's leg as a robot (fixed, and on a moving base in a current) and the 7-joint arm of 14
segments on an ROV of :func:`uwml.robot.examples.arm_on_rov` (moving, in a current); and what the
checks against a description's joint limits cost (``uwml.plausibility``): the README's arm of
``examples/my_arm`` from its URDF (velocity and effort limits, ranges) against the same robot
without its limits, alternately (needs MuJoCo; skipped without it). And what a leg's result alone
costs, its arrays allocated and written with nothing computed: a robot's (four joint arrays and
the base wrench's four 6-wide arrays, 36 numbers a state) against the chain path's former one
(the four joint arrays, 12 numbers a state).

Run: ``python benches/batch.py [n_states]`` (default 1e6). Prints states per second for each and
the ratios, measured in this one run (best of 3 for the Rust paths, 1 run of the reference).
"""

import sys
import time

import numpy as np
import uwml
from uwml import reference
from uwml.robot.examples import arm_on_rov


def best_of(runs: int, call) -> float:
    best = np.inf
    for _ in range(runs):
        start = time.perf_counter()
        call()
        best = min(best, time.perf_counter() - start)
    return best


def main() -> None:
    n = int(float(sys.argv[1])) if len(sys.argv) > 1 else 1_000_000
    rng = np.random.default_rng(0)
    q = rng.uniform(-np.pi, np.pi, (n, 3))
    qd = rng.uniform(-3, 3, (n, 3))
    qdd = rng.uniform(-10, 10, (n, 3))
    leg = uwml.Leg.paper()
    losses = uwml.JointLosses()
    leg.hydro(q[:10], qd[:10], qdd[:10])
    robot, arm = uwml.Robot.from_leg(leg), arm_on_rov()
    q7, qd7, qdd7 = (rng.uniform(-1, 1, (n, 7)) * scale for scale in (1.0, 0.5, 2.0))
    quaternion = rng.normal(size=(n, 4))
    motion = uwml.BaseMotion(
        orientation=quaternion / np.linalg.norm(quaternion, axis=1, keepdims=True),
        velocity=rng.normal(0, 0.3, (n, 3)),
        angular_velocity=rng.normal(0, 0.1, (n, 3)),
    )
    current = (0.3, 0.1, 0.0)

    print(f"states: {n:,}")
    timings = {}
    for label, call in [
        ("Leg.hydro, 1 thread", lambda: leg.hydro(q, qd, qdd)),
        ("Leg.hydro, 2 threads", lambda: leg.hydro(q, qd, qdd, threads=2)),
        ("Leg.environment (losses), 1 thread", lambda: leg.environment(q, qd, qdd, depth=1000.0, temperature_c=4.0, losses=losses)),
        (
            "Leg.environment (losses), 2 threads",
            lambda: leg.environment(q, qd, qdd, depth=1000.0, temperature_c=4.0, losses=losses, threads=2),
        ),
        ("Leg.hydro_regressors, 1 thread", lambda: leg.hydro_regressors(q, qd, qdd)),
        ("Robot.hydro, paper leg, fixed", lambda: robot.hydro(q, qd, qdd)),
        ("Robot.hydro, paper leg, moving, current", lambda: robot.hydro(q, qd, qdd, base_motion=motion, current=current)),
        ("Robot.hydro, 7-joint arm on ROV", lambda: arm.hydro(q7, qd7, qdd7, base_motion=motion, current=current)),
        ("Robot.hydro, 7-joint arm on ROV, 2 thr.", lambda: arm.hydro(q7, qd7, qdd7, base_motion=motion, current=current, threads=2)),
    ]:
        t = timings[label] = best_of(3, call)
        print(f"uwml {label:42s} {t:7.3f} s  {n / t / 1e6:7.2f} M states/s  {t / n * 1e9:7.1f} ns/state")

    limits_cost(n, rng)
    result_cost(n)

    m = min(n, 200_000)
    start = time.perf_counter()
    reference.hydro(leg.joints, leg.links, q[:m], qd[:m], qdd[:m])
    numpy_time = (time.perf_counter() - start) * n / m
    print(f"uwml.reference.hydro (numpy){'':15s} {numpy_time:7.3f} s  {n / numpy_time / 1e6:7.2f} M states/s  (timed on {m:,} states)")
    one, two = timings["Leg.hydro, 1 thread"], timings["Leg.hydro, 2 threads"]
    print(f"speed-up of Leg.hydro over the numpy reference: {numpy_time / one:.1f}x; 2 threads over 1: {one / two:.2f}x")


def result_cost(n: int) -> None:
    """Allocating and writing a leg's result arrays, with nothing computed (a floor under any
    batch call that returns them): all of them held at once, as a result holds them."""

    def written(widths: list[int]) -> None:
        arrays = [np.zeros((n, width)) for width in widths]
        for array in arrays:
            array.fill(1.0)

    for label, widths in (("a robot's (joints and base wrench)", [3] * 4 + [6] * 4), ("joints only (the former chain path's)", [3] * 4)):
        t = best_of(3, lambda widths=widths: written(widths))
        print(f"a leg's result arrays alone, {label:38s} {t / n * 1e9:7.1f} ns/state")


def limits_cost(n: int, rng: np.random.Generator) -> None:
    """``Robot.hydro`` and ``Robot.environment`` on the README's arm with and without its joint
    limits, alternately, best of 3 each: the warnings' checks (no state here warns)."""
    try:
        import mujoco  # noqa: F401
    except ImportError:
        print("limits: skipped (no MuJoCo to read the URDF)")
        return
    import dataclasses
    import functools
    from pathlib import Path

    folder = Path(__file__).resolve().parents[1] / "examples" / "my_arm"
    limited = uwml.Robot.from_urdf(folder / "my_arm.urdf", folder / "my_arm.hydro.toml")
    joints = [dataclasses.replace(j, range=None, velocity_limit=None, effort_limit=None) for j in limited.joints]
    free = uwml.Robot(joints, limited.links, base=limited.base, water=limited.water)
    q, qd, qdd = rng.uniform(-1, 1, (n, 2)), rng.uniform(-1, 1, (n, 2)), rng.uniform(-2, 2, (n, 2))
    for label, call in [
        ("hydro", lambda robot: robot.hydro(q, qd, qdd)),
        ("environment", lambda robot: robot.environment(q, qd, qdd, depth=100.0)),
    ]:
        times = {"without": [], "with": []}
        for _ in range(3):
            for name, robot in (("without", free), ("with", limited)):
                times[name].append(best_of(1, functools.partial(call, robot)))
        without, with_ = (min(times[k]) / n * 1e9 for k in ("without", "with"))
        print(f"uwml Robot.{label}, my_arm, without / with its limits: {without:6.1f} / {with_:6.1f} ns/state ({with_ / without:.3f}x)")


if __name__ == "__main__":
    main()
