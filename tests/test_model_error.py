"""The synthetic experiment's model error (``uwml.paper.synthetic.ModelDiscrepancy``) and the paper-like
experiment built with it: each part does what its docstring says, checked against torques
computed independently (other calls, other time bases), and the paper-like fit's statistics
come near the paper's 2.425 N·m² and 0.826."""

from __future__ import annotations

import numpy as np
import pytest
import uwml
from uwml import WalkingGait, fit
from uwml.paper import synthetic

LEG = uwml.paper_leg()
GAIT = WalkingGait(nominal_foot=synthetic.YAW_STEP_FOOT, period=3.0)
QUIET = {"leg": LEG, "gait": GAIT, "cycles": 1, "rate_hz": 100.0, "torque_noise": 0.0}


def _experiment(error: synthetic.ModelDiscrepancy | float = 0.0, **kwargs):
    return synthetic.land_water_experiment(**{**QUIET, "model_error": error, **kwargs})


def test_no_model_error_is_the_plain_experiment_bit_for_bit() -> None:
    plain = synthetic.land_water_experiment(seed=3)
    for error in (synthetic.ModelDiscrepancy(), 0.0):
        spoiled = synthetic.land_water_experiment(seed=3, model_error=error)
        np.testing.assert_array_equal(spoiled.tau_water, plain.tau_water)
        np.testing.assert_array_equal(spoiled.tau_land, plain.tau_land)


def test_a_number_is_an_unmodelled_damping() -> None:
    plain = _experiment()
    damped = _experiment(2.5)
    np.testing.assert_array_equal(damped.tau_water, _experiment(synthetic.ModelDiscrepancy(damping=2.5)).tau_water)
    np.testing.assert_allclose(damped.tau_water - plain.tau_water, 2.5 * plain.qd, rtol=1e-12, atol=1e-12)
    np.testing.assert_array_equal(damped.tau_land, plain.tau_land)


def test_a_late_water_run_is_the_whole_water_run_shifted_in_time() -> None:
    """The water torque at t is the lag-free water torque at t − lag (an experiment started lag
    earlier); the land torque and the logged states are the land run's."""
    lag = 0.07
    late = _experiment(synthetic.ModelDiscrepancy(water_lag=lag))
    early = _experiment(start_time=-lag)
    plain = _experiment()
    np.testing.assert_allclose(late.tau_water, early.tau_water, rtol=1e-12, atol=1e-10)
    np.testing.assert_array_equal(late.tau_land, plain.tau_land)
    np.testing.assert_array_equal(late.q, plain.q)


def test_a_drag_coefficient_that_varies_with_speed() -> None:
    """Cd(t) = cd (1 + a (ω_ref − ‖q̇‖)/(ω_ref + ‖q̇‖)): each sample's water torque is that of
    the model evaluated alone at that sample's Cd."""
    a, omega = 0.4, 0.5
    log = _experiment(synthetic.ModelDiscrepancy(cd_speed=a, reference_speed=omega))
    plain = _experiment()
    for i in range(0, log.n_samples, 37):
        speed = float(np.linalg.norm(log.qd[i]))
        cd_here = 2.2 * (1.0 + a * (omega - speed) / (omega + speed))
        here = LEG.hydro(log.q[i], log.qd[i], log.qdd[i], cd=cd_here, cm=0.5)
        there = LEG.hydro(log.q[i], log.qd[i], log.qdd[i], cd=2.2, cm=0.5)
        np.testing.assert_allclose(log.tau_water[i] - plain.tau_water[i], there.total - here.total, rtol=1e-10, atol=1e-12)


def test_buoyancy_computed_wrong_spares_joint_1() -> None:
    """A real buoyancy 10 % above the computed one: joints 2 and 3 feel it, joint 1 (vertical
    axis) does not."""
    log = _experiment(synthetic.ModelDiscrepancy(buoyancy=0.1))
    plain = _experiment()
    buoyancy = LEG.hydro(plain.q, plain.qd, plain.qdd).buoyancy
    np.testing.assert_allclose(log.tau_water - plain.tau_water, -0.1 * buoyancy, rtol=1e-10, atol=1e-12)
    np.testing.assert_allclose(log.tau_water[:, 0], plain.tau_water[:, 0], atol=1e-12)
    assert np.max(np.abs(buoyancy[:, 1])) > 1.0


@pytest.mark.parametrize(
    ("field", "value"),
    [
        ("damping", -0.1),
        ("water_lag", -1e-3),
        ("cd_speed", 1.0),
        ("cd_speed", -1.0),
        ("reference_speed", 0.0),
        ("buoyancy", -1.0),
        ("damping", float("nan")),
        ("water_lag", float("inf")),
    ],
)
def test_model_error_out_of_its_domain_is_a_value_error(field: str, value: float) -> None:
    with pytest.raises(ValueError, match=f"ModelDiscrepancy.{field} must be finite and"):
        synthetic.ModelDiscrepancy(**{field: value})


@pytest.mark.parametrize("value", [True, "0.5", None])
def test_model_error_fields_are_numbers(value: object) -> None:
    with pytest.raises(TypeError, match="ModelDiscrepancy.damping must be a number"):
        synthetic.ModelDiscrepancy(damping=value)  # type: ignore[arg-type]


def test_the_discrepancy_is_no_exception_and_hides_none() -> None:
    """Not :class:`uwml.ModelError` (an exception), nor a name that would hide it."""
    assert "ModelDiscrepancy" in synthetic.__all__ and not hasattr(synthetic, "ModelError")
    assert not issubclass(synthetic.ModelDiscrepancy, BaseException)


def test_land_water_experiment_refuses_a_bad_model_error() -> None:
    for bad in (-1.0, float("nan")):
        with pytest.raises(ValueError, match="model_error must be a ModelDiscrepancy or a damping"):
            synthetic.land_water_experiment(model_error=bad)


# --------------------------------------------------------------------------------------------
# The paper-like experiment (uwml paper's)
# --------------------------------------------------------------------------------------------


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_paper_like_fit_has_the_papers_statistics(seed: int) -> None:
    """Unweighted reduced χ² near the paper's 2.425 N·m², COD near its 0.826, and a measured
    torque whose variance is the paper's (≈ 2.425 / (1 − 0.826) ≈ 14 N·m²)."""
    result = fit.hydro_coefficients(synthetic.paper_like_experiment(seed=seed))
    assert 2.0 < result.redchi_unweighted < 2.9, result.redchi_unweighted
    assert 0.79 < result.cod < 0.86, result.cod
    assert 11.0 < np.var(result.data) < 17.0, np.var(result.data)


def test_structured_errors_bias_the_coefficients_beyond_their_standard_errors() -> None:
    """What the report says: noise alone leaves Cd and Cm within their standard errors; the
    late water run pulls Cm down and the unmodelled damping pulls Cd up, by more than five of
    the fit's own standard errors, while the COD barely moves."""
    error = synthetic.PAPER_LIKE_ERROR
    gait = WalkingGait(nominal_foot=synthetic.YAW_STEP_FOOT, period=synthetic.PAPER_LIKE_PERIOD)

    def fitted(part: synthetic.ModelDiscrepancy, noise: float = synthetic.PAPER_LIKE_NOISE):
        log = synthetic.land_water_experiment(LEG, gait, torque_noise=noise, model_error=part, seed=5)
        return fit.hydro_coefficients(log, LEG)

    noise_only = fitted(synthetic.ModelDiscrepancy())
    for name, truth in (("cd", 2.2), ("cm", 0.5)):
        assert abs(noise_only.params[name] - truth) < 3.0 * noise_only.stderr[name]
    late = fitted(synthetic.ModelDiscrepancy(water_lag=error.water_lag))
    assert late.params["cm"] < 0.5 - 5.0 * late.stderr["cm"]
    damped = fitted(synthetic.ModelDiscrepancy(damping=4.0 * error.damping))
    assert damped.params["cd"] > 2.2 + 5.0 * damped.stderr["cd"]
    everything = fitted(error)
    assert abs(everything.cod - noise_only.cod) < 0.05
    # Without noise the model error alone leaves a high COD: the fit absorbs it.
    assert fitted(error, noise=0.0).cod > 0.97
