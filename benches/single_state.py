"""Cost of one state per call from Python (a controller or a simulator stepping one state at a
time): ``Leg.hydro`` and ``Leg.environment`` on the paper's leg with 1-D states, default
coefficients and water, against the batch path's cost per state; and ``Robot.hydro`` (the paper's
leg as a robot, fixed and on a moving base in a current; the 7-joint arm of
:func:`uwml.robot.examples.arm_on_rov` on a moving ROV in a current).

Run: ``python benches/single_state.py [repeats]`` (default 7). Each figure is the best of
``repeats`` ``timeit`` runs of 20,000 calls (and the median, for the spread); the batch figures
are the best of ``repeats`` calls on 100,000 states, divided by 100,000.
"""

import statistics
import sys
import timeit

import numpy as np
import uwml
from uwml.robot.examples import arm_on_rov

CALLS = 20_000
BATCH = 100_000


def per_call(statement, repeats: int) -> tuple[float, float]:
    """Best and median seconds per call over ``repeats`` runs of ``CALLS`` calls."""
    runs = timeit.repeat(statement, number=CALLS, repeat=repeats)
    return min(runs) / CALLS, statistics.median(runs) / CALLS


def main() -> None:
    repeats = int(sys.argv[1]) if len(sys.argv) > 1 else 7
    leg = uwml.Leg.paper()
    losses = uwml.JointLosses()
    q, qd, qdd = [0.3, -0.6, 1.1], [0.8, -1.5, 2.0], [2.0, 4.0, -3.0]
    qa, qda, qdda = np.array(q), np.array(qd), np.array(qdd)
    cd_per_link = [2.2, 2.2, 2.2]
    print(f"uwml.Leg.paper(), one state per call; best (median) of {repeats} timeit runs of {CALLS:,} calls")
    for label, statement in [
        ("hydro(q, qd, qdd), lists", lambda: leg.hydro(q, qd, qdd)),
        ("hydro(q, qd, qdd), 1-D arrays", lambda: leg.hydro(qa, qda, qdda)),
        ("environment(..., depth, temperature_c), lists", lambda: leg.environment(q, qd, qdd, depth=1000.0, temperature_c=4.0)),
        ("environment(..., depth, temperature_c), 1-D arrays", lambda: leg.environment(qa, qda, qdda, depth=1000.0, temperature_c=4.0)),
        (
            "environment(..., losses=JointLosses()), 1-D arrays",
            lambda: leg.environment(qa, qda, qdda, depth=1000.0, temperature_c=4.0, losses=losses),
        ),
        # Per-link coefficients (the one-state path takes arrays too).
        ("hydro(q, qd, qdd, cd=[per link])", lambda: leg.hydro(qa, qda, qdda, cd=cd_per_link)),
        (
            "environment(..., cd=[per link])",
            lambda: leg.environment(qa, qda, qdda, depth=1000.0, temperature_c=4.0, cd=cd_per_link),
        ),
    ]:
        best, median = per_call(statement, repeats)
        print(f"  {label:52s} {best * 1e6:6.2f} µs  ({median * 1e6:.2f})")

    robot, arm = uwml.Robot.from_leg(leg), arm_on_rov()
    motion = uwml.BaseMotion(velocity=(0.5, 0.0, 0.0), angular_velocity=(0.0, 0.02, 0.0))
    q7 = [0.2, 0.4, -0.8, 0.0, 0.3, 0.0, 0.05]
    for label, statement in [
        ("Robot.hydro, paper leg, fixed base, lists", lambda: robot.hydro(q, qd, qdd)),
        ("Robot.hydro, paper leg, moving base, current", lambda: robot.hydro(q, qd, qdd, base_motion=motion, current=(0.2, 0.0, 0.0))),
        ("Robot.hydro, 7-joint arm, moving ROV, current", lambda: arm.hydro(q7, q7, q7, base_motion=motion, current=(0.2, 0.0, 0.0))),
    ]:
        best, median = per_call(statement, repeats)
        print(f"  {label:52s} {best * 1e6:6.2f} µs  ({median * 1e6:.2f})")

    rng = np.random.default_rng(0)
    qb, qdb, qddb = rng.uniform(-3.0, 3.0, (3, BATCH, 3))
    print(f"the batch path, for context: best of {repeats} calls on {BATCH:,} states, per state")
    for label, statement in [
        ("hydro, 1 thread", lambda: leg.hydro(qb, qdb, qddb)),
        ("environment (depth, temperature_c), 1 thread", lambda: leg.environment(qb, qdb, qddb, depth=1000.0, temperature_c=4.0)),
    ]:
        best = min(timeit.repeat(statement, number=1, repeat=repeats)) / BATCH
        print(f"  {label:52s} {best * 1e9:6.0f} ns")


if __name__ == "__main__":
    main()
