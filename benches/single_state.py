"""Cost of one state per call from Python (a controller or a simulator stepping one state at a
time): the paper's leg (``hydro`` with lists or 1-D arrays, ``environment`` at depth, with one
``JointLosses``, coefficients per segment) and the 7-joint arm of
:func:`uwml.examples.arm_on_rov` on a moving ROV in a current, in every coefficient form
(the segments' own, a number, one per segment, one per segment and direction). Each is called
with keyword shortcuts, and, where the revision has ``uwml.Conditions``, with the conditions made
once and passed to every call (what a controller does), and, where the revision has
``Robot.workspace``, into a workspace (no result objects made per call).

Run: ``python benches/single_state.py [repeats] [--against REF] [--rounds K]`` (default 7).
Each figure is the best of ``repeats`` ``timeit`` runs of 20,000 calls. With ``--against REF``
the same calls on the package built at the git revision ``REF`` (``benches/_against.py``) are
timed in the same run, alternately with this build's, ``K`` rounds each (default 3).
"""

from __future__ import annotations

import os

# numpy's BLAS threads, left spinning after a call, would take the second core from ``threads=2``
# and from the other build's subprocess.
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import sys
import timeit
from collections.abc import Callable
from typing import Any

import numpy as np
from _against import arm_on_rov, paper_leg, run

CALLS = 20_000


def calls() -> dict[str, Callable[[], Any]]:
    """The one-state calls measured (every revision's API; those with ``uwml.Conditions`` too)."""
    import uwml

    leg, arm = paper_leg(uwml), arm_on_rov()
    losses = uwml.JointLosses()
    q, qd, qdd = [0.3, -0.6, 1.1], [0.8, -1.5, 2.0], [2.0, 4.0, -3.0]
    qa, qda, qdda = np.array(q), np.array(qd), np.array(qdd)
    motion = uwml.BaseMotion(velocity=(0.5, 0.0, 0.0), angular_velocity=(0.0, 0.02, 0.0))
    q7 = [0.2, 0.4, -0.8, 0.0, 0.3, 0.0, 0.05]
    s = len(arm.segments)
    per_segment = [1.1] * s
    per_direction = [[1.1, 1.1]] * s
    result: dict[str, Callable[[], Any]] = {
        "paper leg, hydro, lists": lambda: leg.hydro(q, qd, qdd),
        "paper leg, hydro, 1-D arrays": lambda: leg.hydro(qa, qda, qdda),
        "paper leg, hydro, cd=2.0": lambda: leg.hydro(q, qd, qdd, cd=2.0),
        "paper leg, environment at depth": lambda: leg.environment(q, qd, qdd, depth=1000.0, temperature_c=4.0),
        "paper leg, environment, one JointLosses": lambda: leg.environment(q, qd, qdd, depth=1000.0, temperature_c=4.0, losses=losses),
        "paper leg, moving base, current": lambda: leg.hydro(q, qd, qdd, base_motion=motion, current=(0.2, 0.0, 0.0)),
        "arm on a moving ROV, current": lambda: arm.hydro(q7, q7, q7, base_motion=motion, current=(0.2, 0.0, 0.0)),
        "arm on a moving ROV, current, cd=1.1": lambda: arm.hydro(q7, q7, q7, base_motion=motion, current=(0.2, 0.0, 0.0), cd=1.1),
        "arm on a moving ROV, current, cd per segment": lambda: arm.hydro(
            q7, q7, q7, base_motion=motion, current=(0.2, 0.0, 0.0), cd=per_segment
        ),
        "arm on a moving ROV, current, cd per direction": lambda: arm.hydro(
            q7, q7, q7, base_motion=motion, current=(0.2, 0.0, 0.0), cd=per_direction
        ),
    }
    if hasattr(uwml, "Conditions"):
        at_depth = uwml.Conditions(depth=1000.0, temperature_c=4.0, losses=losses)
        moving = uwml.Conditions(base_motion=motion, current=(0.2, 0.0, 0.0))
        forms = {"": moving, ", cd=1.1": moving.replace(cd=1.1)}
        forms |= {", cd per segment": moving.replace(cd=per_segment), ", cd per direction": moving.replace(cd=per_direction)}
        result |= {
            "paper leg, environment, one JointLosses, Conditions once": lambda: leg.environment(q, qd, qdd, at_depth),
            "paper leg, moving base, current, Conditions once": lambda: leg.hydro(q, qd, qdd, moving),
        }
        for suffix, conditions in forms.items():
            result[f"arm on a moving ROV, current{suffix}, Conditions once"] = lambda c=conditions: arm.hydro(q7, q7, q7, c)
    if hasattr(uwml.Robot, "workspace"):
        leg_space, arm_space = leg.workspace(), arm.workspace()
        result["paper leg, environment, one JointLosses, Conditions once, workspace"] = lambda: leg.environment(
            q, qd, qdd, at_depth, workspace=leg_space
        )
        for suffix, conditions in forms.items():
            result[f"arm on a moving ROV, current{suffix}, Conditions once, workspace"] = lambda c=conditions: arm.hydro(
                q7, q7, q7, c, workspace=arm_space
            )
    return result


def measure(repeats: int) -> dict[str, float]:
    """Seconds per call of each, the best of ``repeats`` runs of ``CALLS`` calls."""
    return {label: min(timeit.repeat(call, number=CALLS, repeat=repeats)) / CALLS for label, call in calls().items()}


def main() -> None:
    repeats = sys.argv[1] if len(sys.argv) > 1 and not sys.argv[1].startswith("-") else "7"
    timings = run(__file__, lambda size: measure(int(size)), repeats, "µs per call", 1e6)
    if timings is None:
        return
    print(f"one state per call; best of {repeats} timeit runs of {CALLS:,} calls")
    for label, seconds in timings.items():
        print(f"  {label:60s} {seconds * 1e6:6.2f} µs")


if __name__ == "__main__":
    main()
