"""Identification of Cd and Cm from land/water logs (``uwml.fit.hydro_coefficients``) of the paper's
leg and of any robot (``uwml fit hydro --robot``): recovery, error bars, the robust fit, the report
and figure, the streamed fit of large logs. The logs a fit reads are ``test_identification_logs.py``'s.

Nothing expected here is produced by the code under test: the truth is the coefficients given to
the synthetic experiment (``uwml.paper.synthetic.land_water_experiment``, Gaussian torque noise);
recovery is judged by the fit's own standard errors.
"""

import json
import math
from dataclasses import replace
from pathlib import Path

import matplotlib
import numpy as np
import pytest
import uwml
from matplotlib.figure import Figure
from test_identification_logs import _take
from uwml import fit
from uwml.cli import main
from uwml.examples import arm_on_rov
from uwml.fit.log_set import log_set
from uwml.io.logs import write_log
from uwml.paper import synthetic
from uwml.sim.prescribed import SineTrajectory
from uwml.viz import plot

matplotlib.use("Agg")

CD, CM = 2.2, 0.5
SEEDS = (0, 1, 2, 3, 4)
ARM_TRAJECTORY = SineTrajectory([0.6, 0.5, 0.7, 0.8, 0.6, 0.9, 0.02], period=2.5)


def _within_three_stderr(result, truth: dict) -> None:
    assert result.success and result.errorbars, result.message
    for name, value in truth.items():
        error = result.stderr[name]
        assert error is not None and error > 0.0
        assert abs(result.params[name] - value) <= 3.0 * error, (name, result.params[name], value, error)


# --------------------------------------------------------------------------------------------
# Recovery
# --------------------------------------------------------------------------------------------


@pytest.mark.parametrize("seed", SEEDS)
def test_recovery_joint_1(seed: int) -> None:
    """The paper's setting: joint 1 (index 0) only, one Cd and one Cm."""
    result = fit.hydro_coefficients(synthetic.land_water_experiment(seed=seed))
    assert result.var_names == ("cd", "cm") and result.joints == (0,)
    assert result.ndata == 3 * 400  # 3 cycles of 2 s at 200 Hz, one joint
    _within_three_stderr(result, {"cd": CD, "cm": CM})
    # Noise 0.5 N·m on each torque against a hydrodynamic torque of tens of N·m: tight.
    assert result.stderr["cd"] < 0.01 and result.stderr["cm"] < 0.01
    assert result.rsquared > 0.99


@pytest.mark.parametrize("seed", SEEDS[:3])
def test_recovery_per_link_all_joints(seed: int) -> None:
    """One Cd and one Cm per link, every joint; different true values on the two links with a
    segment (link 0, the hip-yaw link of the paper's leg, has none: its columns are dropped)."""
    leg = uwml.paper_leg()
    cd, cm = np.array([1.8, 2.6]), np.array([0.4, 0.7])  # per segment: links 1 and 2
    log = synthetic.land_water_experiment(leg=leg, cd=cd, cm=cm, seed=seed)
    result = fit.hydro_coefficients(log, leg=leg, joints=(0, 1, 2), per="link")
    without_segment = [f"{p}_link{i}" for p in ("cd", "cm") for i, link in enumerate(leg.links) if not link.segments]
    assert without_segment == ["cd_link0", "cm_link0"]
    assert result.dropped == tuple(without_segment) and "cd_link0" in result.message
    _within_three_stderr(result, {"cd_link1": 1.8, "cd_link2": 2.6, "cm_link1": 0.4, "cm_link2": 0.7})


def test_recovery_per_direction() -> None:
    result = fit.hydro_coefficients(synthetic.land_water_experiment(seed=11), joints=(0, 1, 2), per="direction")
    truth = {name: CD if name.startswith("cd") else CM for name in result.var_names}
    assert len(truth) == 8
    _within_three_stderr(result, truth)


def test_standard_errors_shrink_with_the_log() -> None:
    """Four times the samples: standard errors about halve (1/√n)."""
    short = fit.hydro_coefficients(synthetic.land_water_experiment(cycles=2, seed=5))
    long = fit.hydro_coefficients(synthetic.land_water_experiment(cycles=8, seed=6))
    for name in ("cd", "cm"):
        ratio = short.stderr[name] / long.stderr[name]
        assert 1.6 < ratio < 2.5, (name, ratio)


def test_model_error_shows_in_the_fit() -> None:
    """An unmodelled damping is absorbed into the coefficients and the fit's quality drops."""
    clean = fit.hydro_coefficients(synthetic.land_water_experiment(seed=3))
    wrong = fit.hydro_coefficients(synthetic.land_water_experiment(seed=3, model_error=20.0))
    assert abs(wrong.params["cd"] - CD) > 10.0 * wrong.stderr["cd"]
    assert wrong.rsquared < clean.rsquared


def test_known_sigma_gives_a_meaningful_reduced_chi_square() -> None:
    log = synthetic.land_water_experiment(seed=8, torque_noise=0.5)
    result = fit.hydro_coefficients(log, sigma=0.5 * math.sqrt(2.0), scale_covar=False)
    # χ²/ν of 1200 points has a standard deviation of √(2/1198) ≈ 0.04.
    assert abs(result.redchi - 1.0) < 0.15
    _within_three_stderr(result, {"cd": CD, "cm": CM})
    # Half the true σ: χ²/ν near 4.
    assert abs(fit.hydro_coefficients(log, sigma=0.25 * math.sqrt(2.0), scale_covar=False).redchi - 4.0) < 0.6


# --------------------------------------------------------------------------------------------
# Any robot: an arm on an ROV
# --------------------------------------------------------------------------------------------


def arm_truth() -> tuple[uwml.Robot, np.ndarray, np.ndarray, dict[str, float]]:
    """The arm of uwml.examples with one true (Cd, Cm) per link (the hull's segments too)."""
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


# --------------------------------------------------------------------------------------------
# Robust fit
# --------------------------------------------------------------------------------------------


@pytest.mark.parametrize("seed", (0, 1, 2))
def test_robust_fit_resists_outliers(seed: int) -> None:
    """Eight gross spikes (+60 N·m, 85 σ of the torque difference) on joint 1's water torque."""
    log = synthetic.land_water_experiment(seed=seed)
    rows = np.random.default_rng(100 + seed).choice(log.n_samples, 8, replace=False)
    tau_water = log.tau_water.copy()
    tau_water[rows, 0] += 60.0
    spiked = replace(log, tau_water=tau_water)
    plain, robust = fit.hydro_coefficients(spiked), fit.hydro_coefficients(spiked, robust=True)
    assert "huber" in robust.method and robust.init_values["cd"] == pytest.approx(plain.params["cd"], rel=0.05)
    _within_three_stderr(robust, {"cd": CD, "cm": CM})
    assert max(abs(plain.params["cd"] - CD) / robust.stderr["cd"], abs(plain.params["cm"] - CM) / robust.stderr["cm"]) > 5.0
    # Without outliers the robust fit agrees with the plain one.
    clean = synthetic.land_water_experiment(seed=seed)
    assert fit.hydro_coefficients(clean, robust=True).params["cd"] == pytest.approx(
        fit.hydro_coefficients(clean).params["cd"], abs=fit.hydro_coefficients(clean).stderr["cd"]
    )


# --------------------------------------------------------------------------------------------
# Report, summary, plot
# --------------------------------------------------------------------------------------------


def test_report_and_json_summary() -> None:
    result = fit.hydro_coefficients(synthetic.land_water_experiment(seed=0), joints=(0, 1, 2), per="link")
    report = result.fit_report()
    for text in ("reduced chi-square", "R-squared (COD)", "cd_link1:", "+/-", "dropped (no data)  = cd_link0, cm_link0"):
        assert text in report
    summary = json.loads(json.dumps(result.summary(), allow_nan=False))
    assert summary["model"] == "hydro" and summary["per"] == "link" and summary["dropped"] == ["cd_link0", "cm_link0"]
    assert summary["params"]["cd_link2"] == result.params["cd_link2"]
    assert len(summary["points"]["data"]) == result.ndata == 3 * 1200
    assert set(summary["points"]["joint"]) == {0, 1, 2}
    for name in ("time", "data", "sigma", "best_fit", "residual"):
        values = result.time if name == "time" else getattr(result, name)
        assert summary["points"][name] == [float(x) for x in values], name
    # Non-finite numbers become null (JSON has no NaN); the rest stay as they are.
    assert replace(result, residual=np.array([1.5, np.nan, -np.inf, 2.0])).summary()["points"]["residual"] == [1.5, None, None, 2.0]
    low, high = result.conf_int()["cd_link2"]
    assert low < result.params["cd_link2"] < high


def test_no_error_bars_without_free_degrees() -> None:
    log = synthetic.land_water_experiment(cycles=0.5, seed=0)
    result = fit.hydro_coefficients(_take(log, slice(40, 42)))
    assert not result.errorbars and result.covar is None and result.stderr == {"cd": None, "cm": None}
    assert "Warning: uncertainties could not be estimated" in result.fit_report()
    summary = json.loads(json.dumps(result.summary(), allow_nan=False))
    assert summary["redchi"] is None and summary["errorbars"] is False


def test_hydro_fit_plot(tmp_path) -> None:
    result = fit.hydro_coefficients(synthetic.land_water_experiment(seed=0), joints=(0, 2))
    path = tmp_path / "fig7.png"
    figure = plot.hydro_fit_plot(result, path)
    assert isinstance(figure, Figure) and len(figure.axes) == 4
    assert path.read_bytes().startswith(b"\x89PNG\r\n\x1a\n")
    measured, fitted = figure.axes[0].lines[:2]
    np.testing.assert_array_equal(measured.get_ydata(), result.data[result.joint == 0])
    np.testing.assert_array_equal(fitted.get_ydata(), result.best_fit[result.joint == 0])


# --------------------------------------------------------------------------------------------
# The streamed fit (large logs)
# --------------------------------------------------------------------------------------------


@pytest.mark.parametrize("per", ["leg", "link", "direction"])
def test_one_pass_design_is_the_regressors(per: str) -> None:
    """The core's one-pass design equals the regressors of ``Robot.hydro_regressors`` (held
    against the numpy reference elsewhere), grouped per link as ``per`` says (each segment's
    columns its link's; the paper leg's link 0 has none), with the target last."""
    log = synthetic.land_water_experiment(cycles=0.5, seed=3)
    leg, joints = uwml.paper_leg(), [2, 0]
    delta = log.tau_water - log.tau_land
    design = leg._core.hydro_design(log.q, log.qd, log.qdd, delta, leg._native(uwml.Conditions()), joints, per)
    reg = leg.hydro_regressors(log.q, log.qd, log.qdd)  # (n, joint, segment, k)
    for block, joint in zip(design, joints, strict=True):
        drag, added = (np.zeros((len(log.q), 3, 2)) for _ in range(2))
        drag[:, 1:], added[:, 1:] = reg.drag[:, joint], reg.added_mass[:, joint]
        if per == "leg":
            columns = [drag.sum(axis=(1, 2)), added.sum(axis=(1, 2))]
        elif per == "link":
            columns = [*drag.sum(axis=2).T, *added.sum(axis=2).T]
        else:
            columns = [*drag.reshape(len(drag), -1).T, *added.reshape(len(added), -1).T]
        expected = np.column_stack([*columns, -delta[:, joint] - reg.buoyancy[:, joint]])
        np.testing.assert_allclose(block, expected, rtol=1e-13, atol=1e-12)


def test_design_input_errors() -> None:
    log = synthetic.land_water_experiment(cycles=0.1, seed=3)
    leg, delta = uwml.paper_leg(), log.tau_water - log.tau_land
    chain, conditions = leg._core, leg._native(uwml.Conditions())
    bad = delta.copy()
    bad[3, 1] = np.nan
    with pytest.raises(ValueError, match=r"delta\[3, 1\] is NaN: every value must be finite"):
        chain.hydro_design(log.q, log.qd, log.qdd, bad, conditions, [0], "leg")
    with pytest.raises(ValueError, match="delta must have shape"):
        chain.hydro_design(log.q, log.qd, log.qdd, delta[:-1], conditions, [0], "leg")
    with pytest.raises(ValueError, match="joints must be indices in 0..2, got 3"):
        chain.hydro_design(log.q, log.qd, log.qdd, delta, conditions, [0, 3], "leg")
    with pytest.raises(ValueError, match="per must be"):
        chain.hydro_design(log.q, log.qd, log.qdd, delta, conditions, [0], "joint")


@pytest.mark.parametrize("robust", [False, True])
def test_streamed_fit_is_independent_of_chunks_and_cache(monkeypatch, robust: bool) -> None:
    """Chunks of 97 samples (none aligned with anything), with and without the cache, give the
    fit of one chunk holding everything."""
    log = synthetic.land_water_experiment(seed=4, model_error=0.3)
    kwargs = {"joints": (0, 1, 2), "per": "link", "robust": robust}
    whole = fit.hydro_coefficients(log, **kwargs)
    monkeypatch.setattr(fit.design, "CHUNK_SAMPLES", 97)
    for cache_bytes in (0, 1 << 30):
        chunked = fit.hydro_coefficients(log, cache_bytes=cache_bytes, **kwargs)
        assert chunked.var_names == whole.var_names
        for name in whole.var_names:
            assert chunked.params[name] == pytest.approx(whole.params[name], rel=1e-9, abs=1e-12)
            assert chunked.stderr[name] == pytest.approx(whole.stderr[name], rel=1e-7)
        np.testing.assert_allclose(chunked.residual, whole.residual, rtol=1e-7, atol=1e-9)
        assert chunked.chisqr == pytest.approx(whole.chisqr, rel=1e-9)


def test_huber_iteration_finds_the_minimum_scipy_finds() -> None:
    """The iteratively reweighted fit minimizes Huber's loss: scipy's minimizer of the same loss
    on the same whitened problem agrees, and the loss is not lower nearby."""
    import scipy.optimize

    log = synthetic.land_water_experiment(seed=1)
    rng = np.random.default_rng(7)
    outliers = rng.choice(log.n_samples, 40, replace=False)
    log.tau_water[outliers, 0] += rng.normal(0.0, 40.0, outliers.size)
    result = fit.hydro_coefficients(log, robust=True, sigma=0.7)
    leg = uwml.paper_leg()
    design = leg._core.hydro_design(log.q, log.qd, log.qdd, log.tau_water - log.tau_land, leg._native(uwml.Conditions()), [0], "leg")[0]
    x, y = design[:, :2] / 0.7, design[:, 2] / 0.7
    reference = scipy.optimize.least_squares(
        lambda b: x @ b - y, [1.0, 1.0], loss="huber", f_scale=fit.HUBER_SCALE, xtol=1e-14, ftol=1e-14, gtol=1e-14
    )
    np.testing.assert_allclose([result.params["cd"], result.params["cm"]], reference.x, rtol=1e-7)

    def huber(b: np.ndarray) -> float:
        r = np.abs(x @ b - y)
        c = fit.HUBER_SCALE
        return float(np.sum(np.where(r <= c, 0.5 * r**2, c * r - 0.5 * c**2)))

    best = np.array([result.params["cd"], result.params["cm"]])
    for step in ([1e-4, 0.0], [0.0, 1e-4], [-1e-4, 1e-4]):
        assert huber(best) <= huber(best + np.array(step)) and huber(best) <= huber(best - np.array(step))


@pytest.mark.parametrize("per", ["leg", "link", "direction"])
def test_the_one_pass_design_is_the_robots_design_from_its_regressors(per: str) -> None:
    """A robot whose columns are its segments' Cd and Cm on its joints takes the core's one-pass
    design: the same chunks, names and fitted values as its design summed from the regressors;
    a design kept in memory gives the values of one computed again."""
    log = synthetic.land_water_experiment(cycles=0.5, seed=5)
    leg, rows = uwml.paper_leg(), [6, 8]
    logs = log_set(log, 3, "the robot", True, False)
    one_pass = fit.robot_design._RobotHydroDesign(leg, logs, uwml.Water(), per, rows, cache_bytes=0)
    summed = fit.robot_design._RobotHydroDesign(leg, logs, uwml.Water(), per, rows, cache_bytes=1 << 30)
    assert one_pass._one_pass
    summed._one_pass = False
    assert one_pass.names == summed.names
    for a, b in zip(one_pass.chunks(), summed.chunks(), strict=True):
        np.testing.assert_allclose(a, b, rtol=1e-12, atol=1e-10)
    x = np.random.default_rng(2).normal(0.0, 2.0, len(one_pass.names))
    for got, want in zip(one_pass.fitted(x), summed.fitted(x), strict=True):
        np.testing.assert_allclose(got, want, rtol=1e-10, atol=1e-9)


def test_unweighted_statistics_are_ordinary_least_squares_in_the_datas_units() -> None:
    """Beside the weighted statistics, the fit reports the unweighted ones as Origin prints a fit
    without error bars (the paper's reduced χ² 2.425 N·m² and COD 0.826): the residual sum of
    squares, ``RSS / (N − p)``, ``1 − RSS / TSS`` and the adjusted COD. Held against an
    ordinary least-squares solve with numpy of the same regression built here from the log and
    ``Robot.hydro_regressors`` (joint 1: −(τ_water − τ_land) − buoyancy = Cd·drag + Cm·added mass)."""
    log = synthetic.land_water_experiment(seed=5, torque_noise=2.0)
    result = fit.hydro_coefficients(log)
    leg = uwml.paper_leg()
    regressors = leg.hydro_regressors(log.q, log.qd, log.qdd)
    y = -(log.tau_water[:, 0] - log.tau_land[:, 0]) - regressors.buoyancy[:, 0]
    x = np.column_stack([regressors.drag[:, 0].sum(axis=(-2, -1)), regressors.added_mass[:, 0].sum(axis=(-2, -1))])
    coefficients, *_ = np.linalg.lstsq(x, y, rcond=None)
    rss = float(np.sum((y - x @ coefficients) ** 2))
    n, p = len(y), 2
    cod = 1.0 - rss / float(np.sum((y - y.mean()) ** 2))
    assert result.rss == pytest.approx(rss, rel=1e-9)
    assert result.redchi_unweighted == pytest.approx(rss / (n - p), rel=1e-9)
    assert result.cod == pytest.approx(cod, rel=1e-12)
    assert result.adjusted_cod == pytest.approx(1.0 - (1.0 - cod) * (n - 1) / (n - p), rel=1e-12)
    # The weighted reduced χ² is 1 by construction here (σ from the residuals) and says so; the
    # unweighted one is the noise variance of the difference of two torques, 2·(2 N·m)².
    assert result.redchi == pytest.approx(1.0, abs=1e-9) and not result.sigma_given
    assert result.redchi_unweighted == pytest.approx(8.0, rel=0.15)
    report = result.fit_report()
    assert "1 by construction" in report and "reduced chi-square, unweighted" in report and "N·m²" in report
    summary = result.summary()
    assert summary["cod"] == result.cod and summary["sigma_given"] is False
    # With σ given, no such note.
    assert "by construction" not in fit.hydro_coefficients(log, sigma=2.0).fit_report()


def test_the_report_numbers_joints_from_1_as_the_command_line() -> None:
    report = fit.hydro_coefficients(synthetic.land_water_experiment(cycles=1, seed=2), joints=(0, 2)).fit_report()
    assert "joints             = 1, 3 (numbered from 1" in report and "0-based" not in report
