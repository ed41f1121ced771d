"""The logs a hydrodynamic fit reads (``uwml.io.logs``, ``uwml.fit``): derivatives estimated by the
documented window rule, CSV and Parquet round trips, two logs aligned by time, and bad files named
by file, row and column.

Nothing expected here is produced by the code under test: derivatives against the gait's analytic
ones; window lengths typed from the documented rule; bad files written by hand.
"""

import io
import math
from dataclasses import replace

import numpy as np
import pytest
from uwml import WalkingGait, fit
from uwml.io import logs
from uwml.paper import synthetic

CD, CM = 2.2, 0.5
GAIT = WalkingGait(nominal_foot=synthetic.YAW_STEP_FOOT)


def _take(log: logs.Log, index) -> logs.Log:
    """The rows ``index`` of a log."""
    arrays = {name: getattr(log, name) for name in ("time", "q", "qd", "qdd", "tau_land", "tau_water", "tau")}
    return replace(log, **{name: None if a is None else a[index] for name, a in arrays.items()})


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
