"""Cd, Cm and the joint losses from logs of the water run alone (``fit.hydro_from_water_logs``,
``uwml fit hydro --water-only``; docs/model.md section 13, "13.3 Identifying a vehicle"): the
paper's leg from its URDF (tests/data/paper_leg.urdf), its motor torques made with known Cd, Cm
and losses as ``mj_inverse`` (written out here, fluid and constraints off) minus
``Robot.environment``; the fit recovers them."""

from __future__ import annotations

import copy
import json
from pathlib import Path

import mujoco
import numpy as np
import pytest
import uwml
from uwml import fit
from uwml.cli import main
from uwml.io.logs import Log, write_log
from uwml.robot.files import model_and_robot
from uwml.sim.prescribed import SineTrajectory

DATA = Path(__file__).resolve().parent / "data"
URDF, HYDRO = DATA / "paper_leg.urdf", DATA / "paper_leg.hydro.toml"
CD, CM, DEPTH = 2.2, 0.5, 200.0
#: Losses of the truth: a smaller drive than the default, and a seal with pressure slopes.
SEAL = uwml.Seal(c0=3.0, c1_per_mpa=0.5, s0=5.0, s1_per_mpa=1.0, d0=0.8, d1_per_mpa=0.05, stribeck_speed=0.1)
LOSSES = uwml.JointLosses(drive=uwml.Drive(ratio=100.0), oil=uwml.OilDrag(k_oil=2e-3), seal=SEAL)
TRAJECTORY = SineTrajectory([0.8, 0.6, 0.7], period=4.0, offsets=[0.0, 0.3, -0.5])


def rigid_body_torques(model: mujoco.MjModel, q: np.ndarray, qd: np.ndarray, qdd: np.ndarray) -> np.ndarray:
    """``mj_inverse`` with MuJoCo's fluid model and constraints off, gravity on (the land run)."""
    m = copy.deepcopy(model)
    m.opt.density, m.opt.viscosity = 0.0, 0.0
    m.opt.disableflags |= int(mujoco.mjtDisableBit.mjDSBL_CONSTRAINT)
    d = mujoco.MjData(m)
    out = np.zeros_like(q)
    for i in range(len(q)):
        d.qpos[:], d.qvel[:], d.qacc[:] = q[i], qd[i], qdd[i]
        mujoco.mj_inverse(m, d)
        out[i] = d.qfrc_inverse
    return out


def water_log(losses: uwml.JointLosses = LOSSES, depth: float = DEPTH, noise: float = 0.0, seconds: float = 12.0) -> Log:
    """The water run: ``τ_motor = ID_RB − τ_env`` at Cd = 2.2, Cm = 0.5 and ``losses`` at ``depth``,
    200 Hz, with ``noise`` [N·m] of Gaussian noise on each torque (seed 0)."""
    model, robot = model_and_robot(URDF, HYDRO)
    t = np.arange(int(seconds * 200)) / 200.0
    q, qd, qdd = TRAJECTORY.joint_states(t)
    env = robot.environment(q, qd, qdd, cd=CD, cm=CM, losses=losses, depth=depth).total
    tau = rigid_body_torques(model, q, qd, qdd) - env + noise * np.random.default_rng(0).standard_normal(q.shape)
    return Log(time=t, q=q, qd=qd, qdd=qdd, tau=tau, source="water")


def truth(name: str, seal: uwml.Seal = SEAL, k_oil: float = 2e-3) -> float:
    term = name.split(".")[-1]
    if name.startswith(("cd", "cm")):
        return CD if name.startswith("cd") else CM
    return k_oil if term == "k_oil" else float(getattr(seal, term))


@pytest.fixture(scope="module")
def exact() -> Log:
    return water_log()


@pytest.mark.parametrize("per", ["leg", "link"])
def test_noise_free_torques_give_cd_cm_and_the_losses_back(exact: Log, per: str) -> None:
    result = fit.hydro_from_water_logs(exact, URDF, HYDRO, per=per, losses=True, joint_losses=LOSSES, depth=DEPTH)
    names = {"leg": ["cd", "cm"], "link": ["cd_thigh", "cd_calf", "cm_thigh", "cm_calf"]}[per]
    assert list(result.var_names) == names + [f"{j}.{t}" for j in ("hip_yaw", "hip_roll", "knee") for t in ("k_oil", "c0", "s0")]
    assert result.dropped == (("cd_hip", "cm_hip") if per == "link" else ())  # the hip has no segment
    for name in result.var_names:
        assert result.params[name] == pytest.approx(truth(name), rel=1e-8), name
    assert result.losses == tuple(result.var_names[len(names) :]) and not result.negative
    report = result.fit_report()
    assert "mj_inverse" in report and "200 m, 20 °C" in report
    assert result.summary()["model"] == "water_only"


def test_the_losses_held_at_the_description_leave_cd_and_cm(exact: Log) -> None:
    """Losses not fitted are the known part: the given models' torques are taken off exactly."""
    result = fit.hydro_from_water_logs(exact, URDF, HYDRO, joints=[0], joint_losses=LOSSES, depth=DEPTH)
    assert result.var_names == ("cd", "cm") and result.joints == (0,)
    assert result.params["cd"] == pytest.approx(CD, rel=1e-8) and result.params["cm"] == pytest.approx(CM, rel=1e-8)


def test_noisy_torques_give_them_back_within_their_error_bars() -> None:
    """0.5 N·m of noise on every torque (σ given): each coefficient within 4 standard errors, the
    reduced χ² near 1."""
    result = fit.hydro_from_water_logs(
        water_log(noise=0.5), URDF, HYDRO, per="link", losses=True, joint_losses=LOSSES, depth=DEPTH, sigma=0.5
    )
    for name in result.var_names:
        error = result.stderr[name]
        assert error is not None and abs(result.params[name] - truth(name)) < 4.0 * error, (name, result.params[name], error)
    assert 0.9 < result.redchi < 1.1


def test_an_oil_drag_of_exponent_one_and_the_seals_slope_are_refused_together(exact: Log) -> None:
    """Both ∝ ω away from rest: the fit names them instead of returning huge error bars."""
    with pytest.raises(ValueError, match=r"water: the data do not determine .*knee\.d0.*knee\.k_oil|knee\.k_oil.*knee\.d0"):
        fit.hydro_from_water_logs(exact, URDF, HYDRO, losses=("k_oil", "c0", "s0", "d0"), joint_losses=LOSSES, depth=DEPTH)


def test_refusals(exact: Log, tmp_path: Path) -> None:
    without = Log(time=exact.time, q=exact.q, source="no-torques")
    with pytest.raises(ValueError, match=r"no-torques: row 1 \(header\), column 'tau1': missing column .*tau1 … tau3"):
        fit.hydro_from_water_logs(without, URDF, HYDRO)
    two = Log(time=exact.time, q=exact.q[:, :2], tau=exact.q[:, :2], source="two")
    with pytest.raises(ValueError, match=r"two: row 1 \(header\), column 'q2': the log has 2 joints, the description 3"):
        fit.hydro_from_water_logs(two, URDF, HYDRO)
    with pytest.raises(ValueError, match="not a uwml model file"):
        fit.hydro_from_water_logs(exact, tmp_path / "robot.toml")
    with pytest.raises(ValueError, match="losses must be distinct terms among k_oil, c0, s0, d0"):
        fit.hydro_from_water_logs(exact, URDF, HYDRO, losses=["k_oil", "viscosity"])
    with pytest.raises(ValueError, match=r"joints must be distinct indices in 0\.\.2"):
        fit.hydro_from_water_logs(exact, URDF, HYDRO, joints=[3])
    moving = Log(time=exact.time, q=exact.q, tau=exact.q, base_twist=np.zeros((exact.n_samples, 6)), source="vehicle")
    with pytest.raises(
        ValueError, match=r"vehicle: row 1 \(header\), column 'u': the log moves the vehicle, but the description's base is fixed"
    ):
        fit.hydro_from_water_logs(moving, URDF, HYDRO)


def test_the_command_line(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    """``uwml fit hydro --water-only`` at the surface with the default drive (the URDF has no
    losses: the fitted levels take the default models' shapes); without the flag or without the
    description it says what to give."""
    seal = uwml.Seal(c0=3.0, c1_per_mpa=0.0, s0=5.0, s1_per_mpa=0.0, d0=0.0, d1_per_mpa=0.0)
    path = tmp_path / "water.csv"
    write_log(water_log(losses=uwml.JointLosses(oil=uwml.OilDrag(k_oil=5e-4), seal=seal), depth=0.0, seconds=8.0), path)
    assert main(["fit", "hydro", str(path), "--water-only", "--robot", str(URDF), "--hydro", str(HYDRO), "--losses", "--json"]) == 0
    summary = json.loads(capsys.readouterr().out)
    assert summary["model"] == "water_only" and summary["joints"] == [0, 1, 2]
    for name, value in summary["params"].items():
        assert value == pytest.approx(truth(name, seal, k_oil=5e-4), rel=1e-6), name
    assert main(["fit", "hydro", str(path)]) == 2
    error = capsys.readouterr().err
    assert "column 'tau_land1': a log of the water run alone (tau1 …): give --water-only" in error
    assert main(["fit", "hydro", str(path), "--water-only"]) == 2
    assert "--water-only: give the robot's description, --robot URDF or MJCF" in capsys.readouterr().err
    assert main(["fit", "hydro", str(path), "--losses"]) == 2
    assert "--losses, --depth and --temperature go with --water-only" in capsys.readouterr().err
