"""Cd and Cm of any robot from a land/water experiment (``fit.hydro_coefficients(log, robot)``,
``uwml fit hydro --robot``): the same identification as the paper's leg, with the regressors of
the whole-robot core (one column per segment and normal direction, summed per robot, link or
link and direction)."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest
import uwml
from uwml import fit
from uwml.cli import main
from uwml.io.logs import write_log
from uwml.paper import synthetic
from uwml.robot.examples import arm_on_rov
from uwml.sim.prescribed import SineTrajectory

ARM_TRAJECTORY = SineTrajectory([0.6, 0.5, 0.7, 0.8, 0.6, 0.9, 0.02], period=2.5)


def test_sine_trajectory_derivatives_are_exact() -> None:
    """q̇ and q̈ against central differences of q (step 1e-4 s: truncation ~1e-8 relative)."""
    trajectory = SineTrajectory([0.5, 0.3], period=1.5, offsets=[0.1, -0.2], harmonics=[1, 3], phases=[0.0, 1.0])
    t, h = np.linspace(0.0, 3.0, 31), 1e-4
    q, qd, qdd = trajectory.joint_states(t)
    qp, qm = trajectory.joint_states(t + h)[0], trajectory.joint_states(t - h)[0]
    np.testing.assert_allclose(qd, (qp - qm) / (2 * h), atol=1e-6)
    np.testing.assert_allclose(qdd, (qp - 2 * q + qm) / h**2, atol=1e-4)
    np.testing.assert_allclose(q[0], [0.1, -0.2 + 0.3 * np.sin(1.0)], rtol=1e-15)
    with pytest.raises(ValueError, match="period must be finite and > 0"):
        SineTrajectory([0.1], period=0.0)


@pytest.mark.parametrize("per", ["leg", "link", "direction"])
def test_the_paper_leg_as_a_robot_fits_as_the_leg(per: str) -> None:
    """The robot path (regressors of the tree core) and the chain path (the leg's one-pass
    design) give the same fit of the same log."""
    log = synthetic.land_water_experiment(seed=3, cycles=2)
    joints = (0, 1, 2)
    as_leg = fit.hydro_coefficients(log, uwml.paper_leg(), joints=joints, per=per)
    as_robot = fit.hydro_coefficients(log, uwml.paper_leg(), joints=joints, per=per)
    assert as_robot.var_names == as_leg.var_names and as_robot.dropped == as_leg.dropped
    for name in as_leg.var_names:
        assert as_robot.params[name] == pytest.approx(as_leg.params[name], rel=1e-9), name
        assert as_robot.stderr[name] == pytest.approx(as_leg.stderr[name], rel=1e-6), name
    assert as_robot.chisqr == pytest.approx(as_leg.chisqr, rel=1e-8)


def arm_truth() -> tuple[uwml.Robot, np.ndarray, np.ndarray, dict[str, float]]:
    """The arm of uwml.robot.examples with one true (Cd, Cm) per link (the hull's segments too)."""
    arm = arm_on_rov()
    cd_link = [1.1, 1.3, 0.9, 1.6, 1.2, 2.0, 2.4]
    cm_link = [0.9, 1.2, 1.05, 0.8, 1.0, 0.7, 0.6]
    owners = [-1] * len(arm.base.segments) + [i for i, link in enumerate(arm.links) for _ in link.segments]  # type: ignore[union-attr]
    cd = np.array([1.0 if o < 0 else cd_link[o] for o in owners])
    cm = np.array([1.0 if o < 0 else cm_link[o] for o in owners])
    names = [link.name or f"link{i}" for i, link in enumerate(arm.links)]
    truth = {f"cd_{n}": c for n, c in zip(names, cd_link)} | {f"cm_{n}": c for n, c in zip(names, cm_link)}
    return arm, cd, cm, truth


def test_an_arm_recovers_its_per_link_coefficients_exactly_without_noise() -> None:
    arm, cd, cm, truth = arm_truth()
    log = synthetic.land_water_experiment(arm, ARM_TRAJECTORY, cycles=2, rate_hz=100.0, cd=cd, cm=cm, torque_noise=0.0, seed=0)
    result = fit.hydro_coefficients(log, arm, joints=range(arm.n_joints), per="link")
    # The hull does not move on a fixed base: its columns are zero and left out.
    assert result.dropped == ("cd_base", "cm_base")
    assert set(result.params) == set(truth)
    for name, value in truth.items():
        assert result.params[name] == pytest.approx(value, rel=1e-8), name


def test_an_arm_with_noise_is_within_its_error_bars() -> None:
    arm, cd, cm, truth = arm_truth()
    log = synthetic.land_water_experiment(arm, ARM_TRAJECTORY, cycles=4, rate_hz=200.0, cd=cd, cm=cm, torque_noise=0.2, seed=11)
    result = fit.hydro_coefficients(log, arm, joints=range(arm.n_joints), per="link", sigma=0.2 * np.sqrt(2.0))
    for name, value in truth.items():
        error = result.stderr[name]
        assert error is not None and error > 0.0, name
        assert abs(result.params[name] - value) < 5.0 * error, (name, result.params[name], value, error)
        # Link 0 turns about its own axis next to the hull and sweeps little water: its
        # coefficients are poorly determined (σ ≈ 0.65 and 0.2 here); every other link's to 1 %.
        if not name.endswith("_link0"):
            assert error < 0.01 * value, (name, error)
    # Known sigma: the reduced chi-square is a test of the model (about 1 for a right one).
    assert 0.9 < result.redchi < 1.1


def test_one_coefficient_per_robot_and_per_direction() -> None:
    arm = arm_on_rov()
    # Link 3 keeps only its cylinder.
    links = [
        uwml.Link(link.mass, link.com, link.volume, cob=link.cob, segments=[s for s in link.segments if i != 3 or s.section == "circular"])
        for i, link in enumerate(arm.links)
    ]
    arm = uwml.Robot(arm.joints, links, base=arm.base)
    log = synthetic.land_water_experiment(arm, ARM_TRAJECTORY, cycles=2, rate_hz=100.0, cd=1.4, cm=0.8, torque_noise=0.0, seed=0)
    one = fit.hydro_coefficients(log, arm, joints=range(arm.n_joints), per="leg")
    assert one.params == pytest.approx({"cd": 1.4, "cm": 0.8}, rel=1e-9)
    direction = fit.hydro_coefficients(log, arm, joints=range(arm.n_joints), per="direction")
    # A circular segment's drag is along the whole normal velocity: its column is n0's; a link
    # of cylinders only has no n1 column.
    assert {"cd_link3_n1", "cm_link3_n1", "cd_base_n0", "cd_base_n1"} <= set(direction.dropped)
    assert "cd_link3_n0" in direction.params and "cd_link2_n1" in direction.params
    for name, value in direction.params.items():
        assert value == pytest.approx(1.4 if name.startswith("cd") else 0.8, rel=1e-8), name


def test_uwml_fit_hydro_with_robot(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    arm, cd, cm, truth = arm_truth()
    model = tmp_path / "arm.toml"
    arm.save(model)
    log = synthetic.land_water_experiment(arm, ARM_TRAJECTORY, cycles=2, rate_hz=100.0, cd=cd, cm=cm, torque_noise=0.0, seed=0)
    path = tmp_path / "land_water.csv"
    write_log(log, path)
    joints = ",".join(str(j + 1) for j in range(arm.n_joints))
    assert main(["fit", "hydro", str(path), "--robot", str(model), "--joints", joints, "--per", "link", "--json"]) == 0
    summary = json.loads(capsys.readouterr().out)
    for name, value in truth.items():
        assert summary["params"][name] == pytest.approx(value, rel=1e-7), name
    assert main(["fit", "hydro", str(path), "--robot", str(model), "--joints", "1,2"]) == 0
    out = capsys.readouterr().out
    assert f"--robot {model}" in out or str(model) in out
    # A joint the robot does not have, and a log of another robot.
    assert main(["fit", "hydro", str(path), "--robot", str(model), "--joints", "8"]) == 2
    assert "the robot (" in capsys.readouterr().err
    assert main(["fit", "hydro", str(path)]) == 2
    assert "column 'q4': the log has more joints than the 3 expected" in capsys.readouterr().err
