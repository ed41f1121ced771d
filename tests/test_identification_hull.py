"""A hull identified from a captive test (docs/model.md sections 4 and 12.1): the BlueROV2 of
examples/bluerov2 on a rig that moves it in six degrees of freedom, in air and in water, the
rig's wrench on the base logged in both runs. The data are made by the independent numpy
reference (uwml.reference) with the published parameters; the fit (the Rust core's regressors,
uwml.fit.hydro_coefficients, ``uwml fit hydro --base``) recovers them."""

import json
import re
from pathlib import Path

import numpy as np
import pytest
import uwml
from uwml import fit
from uwml import reference as ref
from uwml.cli import main
from uwml.io.logs import Log, read_log, write_log

ROOT = Path(__file__).resolve().parents[1]
URDF, HYDRO = ROOT / "examples/bluerov2/bluerov2_arm.urdf", ROOT / "examples/bluerov2/bluerov2_arm.hydro.toml"
#: The published hull (magnitudes), (x, y, z, roll, pitch, yaw).
ADDED = [6.36, 7.12, 18.68, 0.189, 0.135, 0.222]
LINEAR = [13.7, 0.0, 33.0, 0.0, 0.8, 0.0]
QUADRATIC = [141.0, 217.0, 190.0, 1.19, 0.47, 1.5]


def captive_test(robot: uwml.Robot, n: int = 1200, rate: float = 100.0, tilt: bool = False, arm: bool = False) -> Log:
    """The rig's motion: a sum of sines on each axis (incommensurate frequencies, so that every
    column is excited), the arm held still (or moving); the rig's wrench on land is an arbitrary
    smooth signal (the rigid body's inertia and weight, which the difference cancels), in water
    that minus the water's wrench (reference): ``ΔW = −(W_hydro + W_buoy)``."""
    t = np.arange(n) / rate
    amplitude = np.array([0.6, 0.5, 0.4, 0.8, 0.7, 0.9])
    frequency = np.array([0.31, 0.43, 0.57, 0.37, 0.49, 0.61])
    phase = np.arange(6) * 0.7
    nu = amplitude * np.sin(2 * np.pi * frequency * t[:, None] + phase)
    nu_dot = amplitude * 2 * np.pi * frequency * np.cos(2 * np.pi * frequency * t[:, None] + phase)
    orientation = np.array([np.cos(0.1), np.sin(0.1), 0.0, 0.0]) if tilt else np.array([1.0, 0.0, 0.0, 0.0])
    q = np.zeros((n, robot.n_joints))
    qd, qdd = np.zeros_like(q), np.zeros_like(q)
    if arm:
        q = 0.5 * np.sin(0.7 * t[:, None] + np.arange(robot.n_joints))
        qd = 0.35 * np.cos(0.7 * t[:, None] + np.arange(robot.n_joints))
        qdd = -0.245 * np.sin(0.7 * t[:, None] + np.arange(robot.n_joints))
    water = ref.robot_hydro(
        robot.joints, robot.links, robot.base, q, qd, qdd, density=robot.water.density, gravity=robot.water.gravity,
        orientation=orientation, velocity=nu[:, :3], angular_velocity=nu[:, 3:], acceleration=nu_dot[:, :3],
        angular_acceleration=nu_dot[:, 3:],
    )  # fmt: skip
    hydro_base = water["base_drag"] + water["base_added_mass"] + water["base_buoyancy"]
    hydro_joints = water["drag"] + water["added_mass"] + water["buoyancy"]
    wrench_land = 40.0 * np.sin(0.9 * t[:, None] + np.arange(6))
    tau_land = 3.0 * np.cos(1.1 * t[:, None] + np.arange(robot.n_joints))
    return Log(
        time=t, q=q, qd=qd, qdd=qdd, tau_land=tau_land, tau_water=tau_land - hydro_joints,
        base_orientation=np.tile(orientation, (n, 1)) if tilt else None, base_twist=nu, base_twist_dot=nu_dot,
        wrench_land=wrench_land, wrench_water=wrench_land - hydro_base, source="captive",
    )  # fmt: skip


@pytest.mark.parametrize("tilt", [False, True])
def test_a_captive_test_gives_back_the_published_hull(tilt: bool) -> None:
    robot = uwml.Robot.from_urdf(URDF, HYDRO)
    result = fit.hydro_coefficients(captive_test(robot, tilt=tilt), robot, joints=(), base=range(6))
    assert result.base == (0, 1, 2, 3, 4, 5) and result.joints == ()
    expected = {f"base.added_mass[{i}][{i}]": value for i, value in enumerate(ADDED)}
    expected |= {f"base.linear_damping[{i}][{i}]": value for i, value in enumerate(LINEAR)}
    expected |= {f"base.quadratic_damping[{i}]": value for i, value in enumerate(QUADRATIC)}
    # The arm's strips move with the base: their Cd and Cm are in the fit too.
    expected |= {"cd": 1.2, "cm": 1.0}
    assert set(result.var_names) == set(expected)
    for name, value in expected.items():
        assert result.params[name] == pytest.approx(value, rel=1e-8, abs=1e-8), name
    assert np.all(np.isin(result.joint, [-1, -2, -3, -4, -5, -6]))


def test_joints_and_base_together_every_lumped_entry_and_the_models_own_structure() -> None:
    robot = uwml.Robot.from_urdf(URDF, HYDRO)
    log = captive_test(robot, arm=True)
    both = fit.hydro_coefficients(log, robot, joints=(0, 1), base=range(6), per="link")
    assert both.params["base.added_mass[2][2]"] == pytest.approx(18.68, rel=1e-8)
    assert both.params["cd_upper_arm"] == pytest.approx(1.2, rel=1e-8) and both.params["cm_forearm"] == pytest.approx(1.0, rel=1e-8)
    assert set(np.unique(both.joint)) == {0, 1, -1, -2, -3, -4, -5, -6}
    # "given": the entries the model has (its zero dampings are not fitted).
    given = fit.hydro_coefficients(log, robot, joints=(), base=range(6), lumped="given")
    assert "base.linear_damping[1][1]" not in given.var_names and "base.linear_damping[0][0]" in given.var_names
    assert given.params["base.linear_damping[4][4]"] == pytest.approx(0.8, rel=1e-7)
    # "full": all 63 entries; the off-diagonal ones are zero here, and the diagonal ones found.
    full = fit.hydro_coefficients(log, robot, joints=(), base=range(6), lumped="full")
    lumped = [name for name in full.var_names if name.startswith("base.")]
    assert len(lumped) + len(full.dropped) >= 63
    assert full.params["base.quadratic_damping[1]"] == pytest.approx(217.0, rel=1e-6)
    assert abs(full.params["base.added_mass[0][4]"]) < 1e-6


def test_the_command_line_fits_a_hull_from_a_csv_with_noise(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    robot = uwml.Robot.from_urdf(URDF, HYDRO)
    log = captive_test(robot, n=3000)
    rng = np.random.default_rng(5)
    assert log.wrench_water is not None
    noisy = Log(
        time=log.time, q=log.q, tau_land=log.tau_land, tau_water=log.tau_water, base_twist=log.base_twist,
        wrench_land=log.wrench_land, wrench_water=log.wrench_water + rng.normal(0.0, 0.5, log.wrench_water.shape), source="noisy",
    )  # fmt: skip
    path = tmp_path / "captive.csv"
    write_log(noisy, path)
    back = read_log(path)
    assert back.base_twist is not None and back.base_twist_dot is None and back.wrench_water is not None
    figure = tmp_path / "fit.png"
    arguments = ["fit", "hydro", str(path), "--robot", str(URDF), "--hydro", str(HYDRO), "--base", "all", "--joints", "none"]
    code = main([*arguments, "--json", "--plot", str(figure)])
    assert figure.stat().st_size > 10_000, "a figure of the six base rows"
    assert code == 0
    summary = json.loads(capsys.readouterr().out)
    assert summary["base"] == ["fx", "fy", "fz", "mx", "my", "mz"] and summary["joints"] == []
    params, stderr = summary["params"], summary["stderr"]
    # The twist's derivative is estimated (Savitzky-Golay): within a few standard errors and 2 %.
    for i, value in enumerate(QUADRATIC[:3]):
        name = f"base.quadratic_damping[{i}]"
        assert abs(params[name] - value) <= max(4.0 * stderr[name], 0.02 * value), (name, params[name], stderr[name])
    for i, value in enumerate(ADDED[:3]):
        name = f"base.added_mass[{i}][{i}]"
        assert abs(params[name] - value) <= max(4.0 * stderr[name], 0.02 * value), (name, params[name], stderr[name])
    # The report names the base's rows.
    assert main(arguments) == 0
    report = capsys.readouterr().out
    assert "joints none (1-based), base fx,fy,fz,mx,my,mz" in report and "base wrench rows   = fx, fy, fz, mx, my, mz" in report
    with pytest.raises(SystemExit):
        main([*arguments[:-4], "--base", "fq"])
    assert "must be distinct components among fx, fy, fz, mx, my, mz" in capsys.readouterr().err
    assert main(["fit", "hydro", str(path), "--joints", "none"]) == 2


def test_bad_base_rows_and_logs_without_the_base_columns_are_refused(tmp_path: Path) -> None:
    robot = uwml.Robot.from_urdf(URDF, HYDRO)
    log = captive_test(robot, n=200)
    with pytest.raises(ValueError, match=r"base must be distinct components in 0\.\.5"):
        fit.hydro_coefficients(log, robot, joints=(), base=[6])
    with pytest.raises(ValueError, match="lumped must be"):
        fit.hydro_coefficients(log, robot, joints=(), base=[0], lumped="diag")  # type: ignore[arg-type]
    with pytest.raises(ValueError, match="the log has 2 joints, the robot 3"):
        fit.hydro_coefficients(log, uwml.paper_leg(), base=[0])
    without = Log(time=log.time, q=log.q, tau_land=log.tau_land, tau_water=log.tau_water, base_twist=log.base_twist, source="plain")
    with pytest.raises(ValueError, match=r"plain: row 1 \(header\), column 'fx_land': need fx_land … and fx_water … columns"):
        fit.hydro_coefficients(without, robot, joints=(), base=[0])
    still = Log(time=log.time, q=log.q, wrench_land=log.wrench_land, wrench_water=log.wrench_water, source="still")
    with pytest.raises(ValueError, match=r"still: row 1 \(header\), column 'u': a fit of the vehicle's wrench needs its twist"):
        fit.hydro_coefficients(still, robot, joints=(), base=[0])
    with pytest.raises(ValueError, match="at least one, or base rows"):
        fit.hydro_coefficients(log, robot, joints=())
    # A header with a vehicle group cut short names the missing column.
    path = tmp_path / "short.csv"
    path.write_text("time,q1,q2,u,v\n0,0,0,0,0\n")
    with pytest.raises(ValueError, match=r"column 'w': missing column \(the vehicle's twist is u, v, w, p, q, r; the header has u, v\)"):
        read_log(path)
    path.write_text("time,q1,qw,qx,qy,qz,roll,pitch,yaw\n0,0,1,0,0,0,0,0,0\n")
    with pytest.raises(ValueError, match=r"column 'roll': the orientation is given twice"):
        read_log(path)


def test_a_hull_fit_on_ray_is_the_fit_in_one_process() -> None:
    """The robot's design (lumped models, base rows) built by each Ray actor from the robot's
    parts: two halves of a captive test, on a local Ray of 2 CPUs, fit as in one process."""
    ray = pytest.importorskip("ray")
    robot = uwml.Robot.from_urdf(URDF, HYDRO)
    log = captive_test(robot, n=800)
    fields = ("time", "q", "qd", "qdd", "tau_land", "tau_water", "base_twist", "base_twist_dot", "wrench_land", "wrench_water")
    halves = [
        Log(**{name: getattr(log, name)[rows] for name in fields}, source=f"half{k}")
        for k, rows in enumerate((slice(0, 400), slice(400, None)))
    ]
    here = fit.hydro_coefficients(halves, robot, joints=(0,), base=range(6))
    ray.init(num_cpus=2, include_dashboard=False, logging_level="ERROR", log_to_driver=False)
    try:
        spread = fit.hydro_coefficients(halves, robot, joints=(0,), base=range(6), on_ray=True)
    finally:
        ray.shutdown()
    assert spread.var_names == here.var_names
    for name in here.var_names:
        assert spread.params[name] == pytest.approx(here.params[name], rel=1e-10, abs=1e-12), name
    assert spread.params["base.added_mass[2][2]"] == pytest.approx(18.68, rel=1e-8)


def test_an_orientation_that_is_not_a_unit_quaternion_names_the_file_row_and_column(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """A captive log whose base orientation at row 39 is twice a unit quaternion: the reader,
    the streaming reader (the row counted across chunks), the fit of the file and ``uwml fit
    hydro`` name the file, the row and the column (they named only 'sample 37' of no file)."""
    from dataclasses import replace

    from uwml.io._log_stream import log_chunks

    robot = uwml.Robot.from_urdf(URDF, HYDRO)
    log = captive_test(robot, n=300, tilt=True)
    assert log.base_orientation is not None
    orientation = log.base_orientation.copy()
    orientation[37] *= 2.0
    for name in ("captive.csv", "captive.parquet"):
        path = tmp_path / name
        write_log(replace(log, base_orientation=orientation), path)
        where = f"{path}: row 39, column 'qw': "
        with pytest.raises(ValueError, match="^" + re.escape(where) + ".*norm 1 within 0.001, got 2"):
            read_log(path)
        with pytest.raises(ValueError, match="^" + re.escape(where)):
            list(log_chunks(path, rows=16)[2])
        with pytest.raises(ValueError, match="^" + re.escape(where)):
            fit.hydro_coefficients(path, robot, joints=(), base=range(6))
        code = main(["fit", "hydro", str(path), "--robot", str(URDF), "--hydro", str(HYDRO), "--base", "all", "--joints", "none"])
        err = capsys.readouterr().err
        assert code == 2 and err.count("\n") == 1 and err.startswith(f"uwml: error: {where}"), err
