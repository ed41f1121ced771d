"""Identification of Cd and Cm from land/water logs (``uwml.io.logs``, ``uwml.fit.hydro_coefficients``).

Nothing expected here is produced by the code under test: the truth is the coefficients given to
the synthetic experiment (``uwml.paper.synthetic.land_water_experiment``, Gaussian torque noise);
recovery is judged by the fit's own standard errors; derivatives against the gait's analytic
ones; window lengths typed from the documented rule; bad files written by hand.
"""

import io
import json
import math
from dataclasses import replace

import matplotlib
import numpy as np
import pytest
import uwml
from matplotlib.figure import Figure
from uwml import WalkingGait, fit
from uwml.fit.log_set import log_set
from uwml.io import logs
from uwml.paper import synthetic
from uwml.viz import plot

matplotlib.use("Agg")

CD, CM = 2.2, 0.5
SEEDS = (0, 1, 2, 3, 4)
GAIT = WalkingGait(nominal_foot=synthetic.YAW_STEP_FOOT)


def _take(log: logs.Log, index) -> logs.Log:
    """The rows ``index`` of a log."""
    arrays = {name: getattr(log, name) for name in ("time", "q", "qd", "qdd", "tau_land", "tau_water", "tau")}
    return replace(log, **{name: None if a is None else a[index] for name, a in arrays.items()})


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
# Derivatives
# --------------------------------------------------------------------------------------------


def test_window_rule() -> None:
    """The documented rule: the odd number of samples closest to 0.1 s, at least 5 (cubic)."""
    assert logs.savgol_window(200.0) == 21
    assert logs.savgol_window(1000.0) == 101
    assert logs.savgol_window(100.0) == 11
    assert logs.savgol_window(20.0) == 5


def test_derivative_estimation_error_is_bounded() -> None:
    """Savitzky-Golay on q alone against the gait's analytic q̇, q̈ (200 Hz, 6 s, encoder noise
    1e-4 rad).

    The bounds were measured (q̇: 0.0064 rad/s inside, 0.014 at the ends; q̈: 0.94 rad/s² inside,
    1.4 at the ends, against peaks of 1.3 rad/s and 6.4 rad/s²) and given 50 % of margin. The
    q̈ error comes from the gait's jerk, which jumps by up to ~120 rad/s³ at lift-off and
    touch-down: a cubic over ±0.05 s smooths that corner, an error of order 0.15 · 120 · 0.05.
    A quarter of the window (5 samples) would leave the noise at 3.4 rad/s² (measured), beyond
    the bound.
    """
    t = np.arange(1200) / 200.0
    q, qd, qdd = GAIT.joint_states(t)
    noisy = q + np.random.default_rng(0).normal(0.0, 1e-4, q.shape)
    qd_hat, qdd_hat = logs.estimate_derivatives(t, noisy)
    inside = slice(10, -10)  # half a window from each end
    assert np.abs(qd_hat - qd)[inside].max() < 0.01
    assert np.abs(qdd_hat - qdd)[inside].max() < 1.4
    assert np.abs(qd_hat - qd).max() < 0.025
    assert np.abs(qdd_hat - qdd).max() < 2.1
    # On a smooth trajectory the error is the filter's truncation error. A least-squares cubic
    # over ±H (continuous limit) estimates f' as f' − f⁽⁵⁾H⁴/504 and f'' as f'' + f⁗H²/14 (the
    # projections of x⁵ on {x, x³} and of x⁴ on {1, x²}, worked out by hand); H = 0.05 s, a
    # sinusoid at the gait's period; 25 % margin for the discrete window (21 samples, ±0.05 s).
    omega, half = 2.0 * math.pi / GAIT.period, 0.05
    qd_s, qdd_s = logs.estimate_derivatives(t, np.sin(omega * t)[:, None])
    assert np.abs(qd_s[inside, 0] - omega * np.cos(omega * t[inside])).max() < 1.25 * omega**5 * half**4 / 504
    qdd_error = np.abs(qdd_s[inside, 0] + omega**2 * np.sin(omega * t[inside])).max()
    assert 0.75 * omega**4 * half**2 / 14 < qdd_error < 1.25 * omega**4 * half**2 / 14


def test_fit_with_estimated_derivatives() -> None:
    """Without qd, qdd columns: the smoothing of q̈ biases Cm by about 1 % on this gait (measured
    0.8-1.1 % over five seeds), far beyond its standard error but a small error for a user."""
    log = synthetic.land_water_experiment(seed=2, derivatives=False)
    assert log.qd is None and log.qdd is None
    result = fit.hydro_coefficients(log)
    assert abs(result.params["cd"] / CD - 1.0) < 0.01
    assert abs(result.params["cm"] / CM - 1.0) < 0.02


# --------------------------------------------------------------------------------------------
# Logs: files, two-log alignment
# --------------------------------------------------------------------------------------------


def test_csv_round_trip(tmp_path) -> None:
    log = synthetic.land_water_experiment(cycles=0.5, seed=1)
    path = tmp_path / "run.csv"
    logs.write_log(log, path)
    back = logs.read_log(path, 3)
    for name in ("time", "q", "qd", "qdd", "tau_land", "tau_water"):
        np.testing.assert_array_equal(getattr(back, name), getattr(log, name))
    assert back.tau is None and back.source == str(path)
    assert fit.hydro_coefficients(path).params == fit.hydro_coefficients(log).params


def test_two_logs_same_times_give_the_one_log_fit(tmp_path) -> None:
    log = synthetic.land_water_experiment(seed=4)
    land, water = tmp_path / "land.csv", tmp_path / "water.csv"
    logs.write_log(log.land(), land)
    logs.write_log(log.water(), water)
    assert logs.read_log(water).tau_water is None  # one environment: tau columns only
    one, two = fit.hydro_coefficients(log), fit.hydro_coefficients((land, water))
    for name in ("cd", "cm"):
        assert two.params[name] == pytest.approx(one.params[name], rel=1e-12)
        assert two.stderr[name] == pytest.approx(one.stderr[name], rel=1e-12)


def test_two_logs_are_aligned_by_time_not_by_row() -> None:
    """The water run sampled half a step later and starting 0.5 s later: interpolated onto the
    land times it gives the noise-free truth (linear interpolation of a smooth torque at
    200 Hz: a small error); paired row by row, it would be 100 rows off."""
    dense = synthetic.land_water_experiment(rate_hz=400.0, torque_noise=0.0)
    land = _take(dense.land(), slice(None, None, 2))
    water = _take(dense.water(), slice(201, None, 2))  # odd rows from 0.5025 s
    aligned = logs.align_logs(land, water)
    assert aligned.time[0] == pytest.approx(0.505) and aligned.time[-1] <= water.time[-1]
    result = fit.hydro_coefficients((land, water))
    assert result.params["cd"] == pytest.approx(CD, rel=2e-3)
    assert result.params["cm"] == pytest.approx(CM, rel=2e-3)
    by_row = _take(land, slice(None, water.n_samples))
    paired = replace(by_row, tau_land=by_row.tau, tau_water=water.tau, tau=None)
    wrong = fit.hydro_coefficients(paired)
    assert abs(wrong.params["cd"] / CD - 1.0) > 0.1 or abs(wrong.params["cm"] / CM - 1.0) > 0.1


def test_parquet_round_trip(tmp_path) -> None:
    pytest.importorskip("pyarrow")
    log = synthetic.land_water_experiment(cycles=0.5, seed=1)
    path = tmp_path / "run.parquet"
    logs.write_log(log, path)
    np.testing.assert_array_equal(logs.read_log(path).tau_water, log.tau_water)


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
# Bad files
# --------------------------------------------------------------------------------------------

HEADER = "time,q1,q2,q3,tau_land1,tau_land2,tau_land3,tau_water1,tau_water2,tau_water3"


def _csv(tmp_path, text: str, name: str = "bad.csv"):
    path = tmp_path / name
    path.write_text(text)
    return path


def _rows(n: int, times=None) -> str:
    times = np.arange(n) * 0.005 if times is None else times
    return "\n".join(",".join([repr(float(t))] + [f"{0.1 * i + 0.01 * k:.3f}" for k in range(9)]) for i, t in enumerate(times))


@pytest.mark.parametrize(
    ("text", "row", "column"),
    [
        pytest.param(HEADER.replace(",q2", "") + "\n0,0,0,0,0,0,0,0,0\n", 1, "q2", id="missing q2"),
        pytest.param(HEADER.replace("time", "t") + "\n" + _rows(3), 1, "time", id="missing time"),
        pytest.param(HEADER.replace(",tau_water1,tau_water2,tau_water3", "") + "\n0,0,0,0,0,0,0\n", 1, "tau_water1", id="no water torque"),
        pytest.param(HEADER + "\n" + _rows(3) + "\n0.015,0,0,abc,0,0,0,0,0,0\n", 5, "q3", id="non-numeric cell"),
        pytest.param(HEADER + "\n" + _rows(3) + "\n0.015,0,0,nan,0,0,0,0,0,0\n", 5, "q3", id="nan cell"),
        pytest.param(HEADER + "\n" + _rows(3) + "\n0.015,0,0\n", 5, "q3", id="short row"),
        pytest.param(HEADER + "\n" + _rows(3, times=[0.0, 0.01, 0.01]), 4, "time", id="time not increasing"),
        pytest.param(HEADER + ",q4\n" + "\n".join(r + ",0" for r in _rows(3).split("\n")), 1, "q4", id="four joints"),
        pytest.param(
            HEADER + "\n" + _rows(40, times=np.r_[np.arange(30) * 0.005, 0.16 + np.arange(10) * 0.005]), 32, "time", id="gap in time"
        ),
    ],
)
def test_bad_files_name_file_row_and_column(tmp_path, text: str, row: int, column: str) -> None:
    path = _csv(tmp_path, text)
    with pytest.raises(ValueError) as info:
        fit.hydro_coefficients(path)
    message = str(info.value)
    assert message.startswith(f"{path}: row {row}") and f"column {column!r}" in message, message
    assert not message[len(f"{path}: row {row}")].isdigit()


def test_read_log_joint_count(tmp_path) -> None:
    path = _csv(tmp_path, HEADER + "\n" + _rows(3))
    assert logs.read_log(path).n_joints == 3
    with pytest.raises(ValueError, match=r"bad\.csv: row 1 \(header\), column 'q4': missing column"):
        logs.read_log(path, 4)
    with pytest.raises(ValueError, match=r"column 'q3'.*more joints than the 2"):
        logs.read_log(path, 2)


def test_non_uniform_time_only_matters_when_derivatives_are_estimated(tmp_path) -> None:
    log = synthetic.land_water_experiment(seed=0)
    jittered = replace(log, time=log.time + np.random.default_rng(1).uniform(0.0, 2e-4, log.n_samples))
    assert fit.hydro_coefficients(jittered).success  # qd, qdd given: any increasing time is fine
    path = tmp_path / "jitter.csv"
    logs.write_log(replace(jittered, qd=None, qdd=None), path)
    with pytest.raises(ValueError, match=r"jitter\.csv: row \d+, column 'time': non-uniform sampling"):
        fit.hydro_coefficients(path)


def test_stream_errors_name_the_stream() -> None:
    with pytest.raises(ValueError, match=r"<stream>: row 3, column 'q1': expected a number"):
        logs.read_log(io.StringIO(HEADER + "\n" + _rows(1) + "\n0.005,x,0,0,0,0,0,0,0,0\n"))


def test_bad_arguments() -> None:
    log = synthetic.land_water_experiment(cycles=0.5, seed=0)
    with pytest.raises(ValueError, match="per"):
        fit.hydro_coefficients(log, per="joint")
    with pytest.raises(ValueError, match="joints"):
        fit.hydro_coefficients(log, joints=(3,))
    with pytest.raises(ValueError, match="sigma"):
        fit.hydro_coefficients(log, sigma=-1.0)
    with pytest.raises(ValueError, match="tau_land"):
        fit.hydro_coefficients(log.water())


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
