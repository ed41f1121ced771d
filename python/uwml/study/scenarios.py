"""What one run of a study is (:mod:`uwml.study`): each scenario's parameters, their domains and
defaults, and its metrics.

``paper_leg``: the paper's leg on its stand following the walking gait in sea water under a
controller, simulated in MuJoCo with uwml's forces (:func:`uwml.sim.studies.run`, whose docstring
states the plant and the controllers). Parameters: ``depth`` [m, 0 to 11000; default 0],
``controller`` (one of :data:`uwml.sim.studies.CONTROLLERS`; default ``hydro``), ``cycles`` (gait
cycles, 0.001 to 100; default 0.5), ``coefficient_scale`` (the controller's Cd and Cm over the
plant's, 0 to 10; default 1, or 1.3 for the ``_wrong`` controllers), ``payload`` [kg the foot
carries, unknown to the controller, 0 to 100; default 0]. Metrics over the last gait cycle (or
the whole run if shorter): ``rms_error_<j>`` and ``peak_error_<j>`` [rad] per joint ``j`` from 1,
``positive_work`` (the motors' positive work, ``∫ Σ max(τ q̇, 0) dt``) and ``energy``
(``∫ Σ |τ q̇| dt``) [J].
"""

from __future__ import annotations

from typing import Any

from ..sim.studies import CONTROLLERS, MAX_CYCLES

__all__ = ["DEFAULTS", "METRICS", "PARAMETERS", "SCENARIOS", "run_one"]

SCENARIOS = ("paper_leg",)
#: Each scenario's parameters: a number's (low, high) bounds, or the allowed strings.
PARAMETERS: dict[str, dict[str, Any]] = {
    "paper_leg": {
        "depth": (0.0, 11_000.0),
        "controller": CONTROLLERS,
        "cycles": (1e-3, float(MAX_CYCLES)),
        "coefficient_scale": (0.0, 10.0),
        "payload": (0.0, 100.0),
    }
}
DEFAULTS: dict[str, dict[str, Any]] = {"paper_leg": {"depth": 0.0, "controller": "hydro", "cycles": 0.5, "payload": 0.0}}
#: Each scenario's metrics, the columns of a study's results.
METRICS: dict[str, tuple[str, ...]] = {
    "paper_leg": (
        *(f"rms_error_{j}" for j in (1, 2, 3)),
        *(f"peak_error_{j}" for j in (1, 2, 3)),
        "positive_work",
        "energy",
    )
}


def run_one(kind: str, settings: dict[str, Any], parameters: dict[str, Any]) -> dict[str, float]:
    """One run's metrics (module docstring): the scenario's defaults, then ``settings``, then
    ``parameters``."""
    from ..sim.studies import run

    values = DEFAULTS[kind] | settings | parameters
    result = run(
        str(values["controller"]),
        float(values["depth"]),
        float(values["cycles"]),
        coefficient_scale=None if values.get("coefficient_scale") is None else float(values["coefficient_scale"]),
        payload=float(values["payload"]),
    )
    rms, peak = result.rms_error(), result.peak_error()
    metrics = {f"rms_error_{j + 1}": float(rms[j]) for j in range(3)}
    metrics |= {f"peak_error_{j + 1}": float(peak[j]) for j in range(3)}
    return metrics | {"positive_work": result.positive_work(), "energy": result.energy()}
