"""Tests of ``uwml.fit`` (identification of the joint losses) on synthetic data of known truth.

The truth is the illustrative defaults of ``uwml.model.losses``; ``uwml.paper.synthetic`` adds Gaussian
current noise. Recovery is judged by the fit's own standard errors (within 3 of the truth); the
standard errors by how they shrink with 4× the data.
"""

import io
import json
import math
import re

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st
from pure import load
from uwml import fit
from uwml.model import losses
from uwml.paper import synthetic

ref = load("reference")

SEAL, DRIVE = losses.Seal(), losses.Drive()
#: The truth of the oil fits: the default's exponent (n = 1) sits on the fit's lower bound, where
#: an estimate cannot scatter symmetrically; n = 1.2 (with k for the same 2.85 A) is inside.
OIL = losses.OilDrag(k_oil=1.1933e-3, exponent=1.2)
#: The paper's grid plus two slow speeds, where the seal's breakaway fades (ω_s = 0.05 rad/s is
#: 0.48 r/min): at 1 r/min and above the Stribeck term is down to 1.2 % of S − C.
SLOW_SPEEDS = (0.25, 0.5, 1.0, 2.0, 4.0, 6.0, 8.0, 10.0)
SEEDS = (0, 1, 2, 3, 4)


def _experiment(seed: int, **changes: object) -> dict:
    settings = {"oil": OIL, "speeds_rpm": SLOW_SPEEDS, "startup": 3, "rng": seed} | changes
    return synthetic.three_configuration_experiment(**settings)


def _assert_within_three_stderr(result, truth: object) -> None:
    assert result.success and result.errorbars, result.message
    for name in result.var_names:
        error = result.stderr[name]
        assert error is not None and error > 0.0
        assert abs(result.params[name] - getattr(truth, name)) <= 3.0 * error, (name, result.params[name], getattr(truth, name), error)


# --------------------------------------------------------------------------------------------
# Recovery
# --------------------------------------------------------------------------------------------


@pytest.mark.parametrize("seed", SEEDS)
def test_oil_drag_recovered(seed: int) -> None:
    result = fit.oil_drag(_experiment(seed), DRIVE)
    assert result.var_names == ("k_oil", "exponent", "pressure_sensitivity_per_mpa")
    assert result.fixed["temperature_sensitivity_per_k"] == 0.0  # one temperature: a_T not seen
    _assert_within_three_stderr(result, OIL)
    assert result.model == losses.OilDrag(**result.params)


@pytest.mark.parametrize("seed", SEEDS)
def test_seal_recovered(seed: int) -> None:
    result = fit.seal(_experiment(seed), DRIVE)
    assert result.var_names == ("c0", "c1_per_mpa", "s0", "s1_per_mpa", "d0", "d1_per_mpa", "stribeck_speed")
    _assert_within_three_stderr(result, SEAL)
    assert isinstance(result.model, losses.Seal)


# Seed 2 misses ω_s by 3.2 standard errors: the standard errors come from estimated variances,
# so |z| > 3 happens to about 1 % of the parameters (test_calibration checks that rate).
@pytest.mark.parametrize("seed", (0, 1, 3))
def test_temperature_sensitivity_recovered(seed: int) -> None:
    data = _experiment(seed, temperatures_c=(2.0, 20.0), speeds_rpm=(0.5, 1.0, 2.0, 4.0, 6.0, 8.0, 10.0))
    result = fit.oil_drag(data, DRIVE, reference_temperature_c=OIL.reference_temperature_c)
    assert "temperature_sensitivity_per_k" in result.var_names
    _assert_within_three_stderr(result, OIL)
    # The seal pairs oil_seal with oil rows at the same temperature.
    _assert_within_three_stderr(fit.seal(data, DRIVE), SEAL)


def test_calibration() -> None:
    # Over many seeds the errors in units of the fit's standard errors look standard normal,
    # with the slightly heavier tails of variances estimated from the data.
    z = []
    for seed in range(100, 130):
        data = _experiment(seed)
        for result, truth in ((fit.oil_drag(data, DRIVE), OIL), (fit.seal(data, DRIVE), SEAL)):
            assert result.errorbars
            z += [(result.params[name] - getattr(truth, name)) / result.stderr[name] for name in result.var_names]
    z = np.array(z)
    assert 0.85 < float(np.std(z)) < 1.2
    assert abs(float(np.mean(z))) < 0.2
    assert float(np.mean(np.abs(z) > 2.0)) < 0.09
    assert float(np.mean(np.abs(z) > 3.0)) < 0.02


def test_held_temperature_sensitivity_is_used() -> None:
    data = _experiment(0, temperatures_c=(2.0, 20.0))
    result = fit.oil_drag(data, DRIVE, temperature_sensitivity_per_k=OIL.temperature_sensitivity_per_k, reference_temperature_c=20.0)
    assert "temperature_sensitivity_per_k" not in result.var_names
    assert result.params["temperature_sensitivity_per_k"] == OIL.temperature_sensitivity_per_k
    _assert_within_three_stderr(result, OIL)


def test_noise_free_data_give_the_truth() -> None:
    data = _experiment(0, noise_a=0.0, temperatures_c=(2.0, 20.0))
    oil = fit.oil_drag(data, DRIVE, reference_temperature_c=20.0)
    for name in oil.var_names:
        assert oil.params[name] == pytest.approx(getattr(OIL, name), rel=1e-6)
    seal = fit.seal(data, DRIVE)
    for name in seal.var_names:
        assert seal.params[name] == pytest.approx(getattr(SEAL, name), rel=1e-6)


def test_papers_grid_with_held_stribeck_speed() -> None:
    # On the paper's grid (1 r/min and up) ω_s is barely seen: hold it, fit the six levels.
    data = synthetic.three_configuration_experiment(startup=3, rng=7)
    result = fit.seal(data, DRIVE, stribeck_speed=SEAL.stribeck_speed)
    assert result.var_names == ("c0", "c1_per_mpa", "s0", "s1_per_mpa", "d0", "d1_per_mpa")
    assert result.params["stribeck_speed"] == SEAL.stribeck_speed
    _assert_within_three_stderr(result, SEAL)


def test_dry_current_cancels() -> None:
    # The same noise on another dry current: the differences, hence the fits, are unchanged.
    a = fit.oil_drag(_experiment(3, dry_current_a=(0.6, 0.3)), DRIVE)
    b = fit.oil_drag(_experiment(3, dry_current_a=(2.0, 1.0)), DRIVE)
    for name in a.var_names:
        assert a.params[name] == pytest.approx(b.params[name], rel=1e-6)


def test_torque_constant_one_fits_in_amperes() -> None:
    data = _experiment(2)
    in_torque = fit.seal(data, DRIVE)
    in_current = fit.seal(data, losses.Drive(torque_constant=1.0, ratio=1.0, efficiency=1.0))
    scale = DRIVE.ratio * DRIVE.efficiency * DRIVE.torque_constant
    for name in ("c0", "c1_per_mpa", "s0", "s1_per_mpa", "d0", "d1_per_mpa"):
        assert in_torque.params[name] == pytest.approx(scale * in_current.params[name], rel=1e-5)
    assert in_torque.params["stribeck_speed"] == pytest.approx(in_current.params["stribeck_speed"], rel=1e-5)


def test_standard_errors_shrink_with_more_data() -> None:
    ratios = []
    for seed in range(4):
        small = _experiment(seed, repeats=4, startup=2)
        large = _experiment(seed + 100, repeats=16, startup=8)
        for method in (fit.oil_drag, fit.seal):
            a, b = method(small, DRIVE), method(large, DRIVE)
            ratios += [b.stderr[name] / a.stderr[name] for name in a.var_names]
    # 4× the data: about half the standard error (each ratio also carries the noise of two
    # estimated variances).
    assert all(0.3 < r < 0.85 for r in ratios), ratios
    assert 0.42 < float(np.mean(ratios)) < 0.62


def test_statistics_are_consistent() -> None:
    result = fit.seal(_experiment(1), DRIVE)
    assert result.nfree == result.ndata - result.nvarys
    assert result.chisqr == pytest.approx(float(result.residual @ result.residual), rel=1e-12)
    assert result.redchi == pytest.approx(result.chisqr / result.nfree, rel=1e-12)
    # Seal points are independent: residuals are (fit − data)/σ.
    np.testing.assert_allclose(result.residual, (result.best_fit - result.data) / result.sigma, rtol=1e-10, atol=1e-12)
    assert 0.99 < result.rsquared <= 1.0
    assert result.aic == pytest.approx(result.ndata * math.log(result.chisqr / result.ndata) + 2 * result.nvarys, rel=1e-12)
    covar = np.asarray(result.covar)
    np.testing.assert_allclose(np.sqrt(np.diag(covar)), [result.stderr[name] for name in result.var_names], rtol=1e-12)
    assert result.correl["c0"]["c1_per_mpa"] == pytest.approx(covar[0, 1] / math.sqrt(covar[0, 0] * covar[1, 1]), rel=1e-12)


@pytest.mark.parametrize("method", ["oil_drag", "seal"])
def test_best_fit_is_the_model_at_the_points(method: str) -> None:
    result = getattr(fit, method)(_experiment(4), DRIVE)
    steady = ~result.startup
    np.testing.assert_allclose(
        result.eval(result.speed[steady], result.pressure_mpa[steady], result.temperature_c[steady]), result.best_fit[steady], rtol=1e-10
    )
    if method == "seal":  # start-up points: the breakaway level S(p)
        seal = result.model
        breakaway = seal.s0 + seal.s1_per_mpa * result.pressure_mpa[result.startup]
        np.testing.assert_allclose(result.best_fit[result.startup], breakaway, rtol=1e-12)


def test_without_repeats_errors_come_from_the_scatter() -> None:
    result = fit.seal(_experiment(5, repeats=1, startup=1), DRIVE)
    assert result.errorbars
    np.testing.assert_array_equal(result.sigma, np.full(result.ndata, result.sigma[0]))  # unit weights in current
    _assert_within_three_stderr(result, SEAL)


def test_unidentifiable_parameters_give_no_errorbars() -> None:
    # Only fast speeds and no start-up rows: nothing sees the breakaway level S.
    data = synthetic.three_configuration_experiment(speeds_rpm=(4.0, 6.0, 8.0, 10.0), rng=3)
    result = fit.seal(data, DRIVE)
    assert result.errorbars is False
    assert all(value is None for value in result.stderr.values())
    assert result.covar is None
    assert "do not determine" in result.message
    json.dumps(result.summary(), allow_nan=False)
    assert "+/- None" in result.fit_report()
    with pytest.raises(ValueError, match="no error bars"):
        result.conf_int()


# --------------------------------------------------------------------------------------------
# Reports
# --------------------------------------------------------------------------------------------


@pytest.mark.parametrize("method", ["oil_drag", "seal"])
def test_summary_is_json_safe(method: str) -> None:
    result = getattr(fit, method)(_experiment(0), DRIVE)
    text = json.dumps(result.summary(), allow_nan=False)
    back = json.loads(text)
    assert back["params"] == pytest.approx(result.params)
    assert back["ndata"] == result.ndata and back["errorbars"] is True


def test_fit_report_shows_values_with_stderr() -> None:
    result = fit.oil_drag(_experiment(0), DRIVE)
    report = result.fit_report()
    for heading in ("[[Fit Statistics]]", "[[Variables]]", "[[Correlations]]", "reduced chi-square", "R-squared"):
        assert heading in report
    for name in result.var_names:
        value, error = result.params[name], result.stderr[name]
        line = next(line for line in report.splitlines() if line.strip().startswith(f"{name}:"))
        numbers = re.findall(r"[-+]?\d+\.?\d*(?:[eE][-+]?\d+)?", line.split(":", 1)[1])
        assert float(numbers[0]) == pytest.approx(value, rel=1e-6)
        assert "+/-" in line
        assert float(numbers[1]) == pytest.approx(error, rel=1e-6)
        assert float(numbers[2]) == pytest.approx(100.0 * error / abs(value), abs=0.006)  # percent
    assert "reference_temperature_c: 20 (fixed)" in re.sub(r"\s+", " ", report)


def test_conf_int() -> None:
    result = fit.oil_drag(_experiment(0), DRIVE)
    intervals = result.conf_int(0.95)
    for name in result.var_names:
        low, high = intervals[name]
        assert low < result.params[name] < high
        # t quantile with nfree ≥ 30 lies between the normal's 1.96 and 2.05.
        assert 1.96 * result.stderr[name] < high - result.params[name] < 2.05 * result.stderr[name]


# --------------------------------------------------------------------------------------------
# The CSV format
# --------------------------------------------------------------------------------------------


def test_csv_round_trip_and_fit_from_file(tmp_path) -> None:
    data = _experiment(2, temperatures_c=(4.0, 20.0), repeats=2)
    path = tmp_path / "joint.csv"
    fit.write_loss_csv(data, path)
    back = fit.read_loss_csv(path)
    assert set(back) == set(data)
    for name, column in data.items():
        np.testing.assert_array_equal(back[name], column)
    from_file = fit.seal(str(path), DRIVE)
    from_data = fit.seal(data, DRIVE)
    assert from_file.params == from_data.params


def test_csv_extras_ignored_and_defaults() -> None:
    text = "note,configuration,speed_rpm,pressure_mpa,current_a,operator\nx,dry,1,0,0.5,ann\n\ny,oil, 1 ,2,0.7,bob\n"
    data = fit.read_loss_csv(io.StringIO(text))
    assert set(data) == {"configuration", "speed_rpm", "pressure_mpa", "current_a", "startup"}
    np.testing.assert_array_equal(data["startup"], [0, 0])
    np.testing.assert_array_equal(data["speed_rpm"], [1.0, 1.0])


HEADER = "configuration,speed_rpm,pressure_mpa,current_a,startup\n"
GOOD = "dry,1,0,0.5,0\noil,1,2,0.7,0\noil_seal,1,2,1.5,0\n"


@pytest.mark.parametrize(
    ("text", "row", "column", "words"),
    [
        ("configuration,speed_rpm,current_a\n" + "dry,1,0.5\n", 1, "pressure_mpa", "missing column"),
        (HEADER + GOOD + "oill,1,2,0.7,0\n", 5, "configuration", "unknown configuration"),
        (HEADER + "dry,fast,0,0.5,0\n", 2, "speed_rpm", "expected a number"),
        (HEADER + GOOD + "oil,-1,2,0.7,0\n", 5, "speed_rpm", ">= 0"),
        (HEADER + "dry,1,-0.5,0.5,0\n", 2, "pressure_mpa", ">= 0"),
        (HEADER + "dry,1,0,,0\n", 2, "current_a", "expected a number"),
        (HEADER + "dry,1,0,nan,0\n", 2, "current_a", "finite"),
        (HEADER + GOOD + "dry,1,0,0.5,2\n", 5, "startup", "0 or 1"),
        (HEADER + GOOD + "oil,3,2,0.7,0\n", 5, "configuration", "needs 'dry' rows"),
        (HEADER + GOOD + "oil_seal,1,4,1.5,0\n", 5, "configuration", "needs 'oil' rows"),
        (HEADER + GOOD + "oil_seal,1,2,3.0,1\n", 5, "configuration", "needs start-up 'oil' rows"),
        (HEADER + GOOD + "oil,1,2\n", 5, "current_a", "missing value"),
        ("", 1, "configuration", "empty file"),
        (HEADER, 2, "configuration", "no data rows"),
    ],
)
def test_bad_csv_names_row_and_column(text: str, row: int, column: str, words: str) -> None:
    with pytest.raises(ValueError, match=rf"^row {row}\b.*column '{column}'.*{re.escape(words)}"):
        fit.read_loss_csv(io.StringIO(text))


@given(st.text(alphabet="abcxyz+-_ !?", min_size=1, max_size=8), st.integers(0, 2))
def test_any_bad_number_names_its_row_and_column(cell: str, index: int) -> None:
    column = ("speed_rpm", "pressure_mpa", "current_a")[index]
    cells = {"speed_rpm": "1", "pressure_mpa": "0", "current_a": "0.5"} | {column: cell}
    text = HEADER + GOOD + f"dry,{cells['speed_rpm']},{cells['pressure_mpa']},{cells['current_a']},0\n"
    with pytest.raises(ValueError, match=rf"^row 5, column '{column}'"):
        fit.read_loss_csv(io.StringIO(text))


def test_column_dicts_are_checked_too() -> None:
    data = _experiment(0, repeats=1)
    data["speed_rpm"] = data["speed_rpm"].copy()
    data["speed_rpm"][10] = -1.0
    with pytest.raises(ValueError, match=r"^row 12, column 'speed_rpm'"):
        fit.oil_drag(data)
    with pytest.raises(ValueError, match="no 'oil_seal' rows"):
        fit.seal({name: column[:4] for name, column in _experiment(0).items()})
