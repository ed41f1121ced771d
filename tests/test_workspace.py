"""A reusable result for one state (uwml.Workspace, ``workspace=``): the same bits as a fresh
result by every way in (the native one-state call, and the general path for what it declines),
the same result object every call, its values overwritten, the parts a call does not evaluate
zeroed, and clear errors for what a workspace does not take."""

import threading
from pathlib import Path

import numpy as np
import pytest
import uwml
from chains import random_chain
from robots import COMPONENTS
from test_single_state import ENVIRONMENT_FIELDS, assert_same_bits, bits
from uwml.examples import arm_on_rov

LOSS_FIELDS = ("visc", "seal", "current")
MOTION = uwml.BaseMotion(velocity=(0.5, 0.0, 0.1), angular_velocity=(0.0, 0.02, 0.01))


def assert_same(got: uwml.Torques, want: uwml.Torques, what: str) -> None:
    assert_same_bits(got, want, ENVIRONMENT_FIELDS, None, what)
    assert (got.base is None) == (want.base is None), what
    if want.base is not None:
        assert_same_bits(got.base, want.base, COMPONENTS, None, f"{what}: base")


def test_a_workspace_holds_the_bits_of_a_fresh_result_every_call() -> None:
    arm, leg = arm_on_rov(), uwml.paper_leg()
    rng = np.random.default_rng(5)
    cases = [
        (arm, uwml.Conditions(base_motion=MOTION, current=(0.2, 0.0, 0.0))),
        (arm, uwml.Conditions(base_motion=MOTION, cd=[[1.1, 1.1]] * len(arm.segments))),
        (leg, uwml.Conditions(depth=1000.0, temperature_c=4.0, losses=uwml.JointLosses())),
        (leg, uwml.Conditions(cd=2.0, cm=0.7)),
    ]
    for robot, conditions in cases:
        workspace = robot.workspace()
        results = set()
        for _ in range(3):
            q, qd, qdd = (rng.uniform(-0.5, 0.5, robot.n_joints).tolist() for _ in range(3))
            for evaluate in (robot.hydro, robot.environment):
                for base in (None, True, False):
                    got = evaluate(q, qd, qdd, conditions, base=base, workspace=workspace)
                    assert_same(got, evaluate(q, qd, qdd, conditions, base=base), f"{evaluate.__name__} base={base}")
                    results.add(id(got))
                    if got.base is None:  # the base's part of the array zeroed, not stale
                        assert not np.any(workspace._values[-24:])
                    if evaluate == robot.hydro:  # the losses' part zeroed after an environment call
                        assert all(not np.any(getattr(got, name)) for name in LOSS_FIELDS)
        assert len(results) == 2  # one object with the base wrench, one without, every call


@pytest.mark.filterwarnings("ignore::uwml.PlausibilityWarning")  # a state beyond plausible on purpose
def test_what_the_native_call_declines_is_evaluated_the_general_way_into_the_workspace() -> None:
    robot = random_chain(np.random.default_rng(7), 4)[0]
    workspace = robot.workspace()
    q, qd, qdd = [0.1, -0.2, 0.3, 0.4], [0.5, 0.1, -0.3, 0.2], [1.0, -1.0, 0.5, 0.0]
    conditions = uwml.Conditions(cd=1.3)
    given = {
        "float32 arrays": (np.float32(q), np.float32(qd), np.float32(qdd)),
        "keyword shortcuts": (q, qd, qdd),
        "two threads": (q, qd, qdd),
        "an angle beyond the plausible bound": ([40.0, -0.2, 0.3, 0.4], qd, qdd),
    }
    for what, states in given.items():
        options = {"threads": 2} if what == "two threads" else {}
        if what == "keyword shortcuts":
            got = robot.hydro(*states, cd=1.3, workspace=workspace)
        else:
            got = robot.hydro(*states, conditions, workspace=workspace, **options)
        want = robot.hydro(*(np.asarray(s, dtype=np.float64) for s in states), conditions)
        assert_same(got, want, what)
        assert got is robot.hydro(q, qd, qdd, conditions, workspace=workspace)  # the same object


def test_a_workspace_takes_one_state_of_its_own_robot() -> None:
    leg, other = uwml.paper_leg(), random_chain(np.random.default_rng(8), 3)[0]
    workspace = leg.workspace()
    state = [0.1, 0.2, 0.3]
    with pytest.raises(ValueError, match="another robot's"):
        other.hydro(state, state, state, workspace=workspace)
    with pytest.raises(ValueError, match="another robot's"):
        other.hydro(state, state, state, uwml.Conditions(), workspace=workspace)
    with pytest.raises(ValueError, match="one state's results"):
        leg.hydro([state, state], [state, state], [state, state], workspace=workspace)
    with pytest.raises(ValueError, match="one state's results"):
        leg.hydro(state, state, state, uwml.Conditions(current=np.zeros((2, 3))), workspace=workspace)
    assert repr(workspace) == "Workspace(n_joints=3)"


def test_threads_each_with_a_workspace_get_their_own_states_forces() -> None:
    arm = arm_on_rov()
    conditions = uwml.Conditions(base_motion=MOTION, current=(0.1, 0.0, 0.0))
    states = np.random.default_rng(9).uniform(-0.5, 0.5, (2, 50, 7))
    expected = [arm.hydro(s, s, s, conditions).total for s in states]
    errors: list[str] = []

    def run(k: int) -> None:
        workspace = arm.workspace()
        for i, state in enumerate(states[k]):
            got = arm.hydro(state.tolist(), state.tolist(), state.tolist(), conditions, workspace=workspace).total
            if bits(got) != bits(expected[k][i]):
                errors.append(f"thread {k}, state {i}")

    threads = [threading.Thread(target=run, args=(k,)) for k in range(2)]
    for thread in threads:
        thread.start()
    for thread in threads:
        thread.join()
    assert errors == []


def test_the_tours_loop_with_a_workspace_runs_and_gives_each_steps_forces() -> None:
    tour = (Path(__file__).resolve().parents[1] / "docs" / "tour.md").read_text(encoding="utf-8")
    code = tour.split("### One state a step", 1)[1].split("```python\n", 1)[1].split("```", 1)[0]
    namespace: dict = {}
    exec(compile(code, "docs/tour.md", "exec"), namespace)  # noqa: S102 - the tour's own example
    arm, conditions, q, qd, qdd = (namespace[k] for k in ("arm", "conditions", "q", "qd", "qdd"))
    assert namespace["result"] is arm.hydro(q, qd, qdd, conditions, workspace=namespace["workspace"])
    assert bits(namespace["feedforward"]) == bits(-arm.hydro(q, qd, qdd, conditions).total)
