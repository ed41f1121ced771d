"""What one run of a study is (:mod:`uwml.study`): each scenario's parameters, their domains and
defaults, and its metrics.

``paper_leg``: the paper's leg on its stand following the walking gait in sea water under a
controller, simulated in MuJoCo with uwml's forces (:func:`uwml.paper.control_study.run`, whose docstring
states the plant and the controllers). Parameters: ``depth`` [m, 0 to 11000; default 0],
``controller`` (one of :data:`uwml.paper.control_study.CONTROLLERS`; default ``hydro``), ``cycles`` (gait
cycles, 0.001 to 100; default 0.5), ``coefficient_scale`` (the controller's Cd and Cm over the
plant's, 0 to 10; default 1, or 1.3 for the ``_wrong`` controllers), ``payload`` [kg the foot
carries, unknown to the controller, 0 to 100; default 0]. Metrics over the last gait cycle (or
the whole run if shorter): ``rms_error_<j>`` and ``peak_error_<j>`` [rad] per joint ``j`` from 1,
``positive_work`` (the motors' positive work, ``∫ Σ max(τ q̇, 0) dt``) and ``energy``
(``∫ Σ |τ q̇| dt``) [J].

``robot``: any robot from its description (``robot``: a URDF or MJCF file, ``hydro``: its hydro
file; paths relative to the study file), on a fixed base, its joints following sines
(``amplitude`` [rad or m, 0 to 3.14; default 0.3] and ``period`` [s, 0.1 to 100; default 2],
joint ``j`` shifted by ``j·π/3``) for ``duration`` [s, 0.01 to 3600; default 4] in a ``current``
along x [m/s, 0 to 5; default 0] at ``depth`` [m], simulated in MuJoCo with uwml's forces under
PD (a critically damped ``kp_hz`` loop on each joint's rigid inertia at the start, 0.1 to 50
Hz; default 4) plus the rigid body's inverse dynamics (``land``), plus uwml's hydrodynamic
feedforward in the current (``hydro``), plus the robot's joint losses' (``hydro_losses``), the
feedforward's Cd and Cm ``coefficient_scale`` times the robot's own. Metrics over the last
period (or the whole run if shorter): ``rms_error_<j>``, ``peak_error_<j>`` per joint,
``positive_work``, ``energy``, as for ``paper_leg``; the metrics' joints are the robot's.

``rov``: an arm moving on a free-floating ROV in a current while a station-keeping PD holds the
vehicle (:func:`uwml.sim.control.rov_drift`): ``station_keeping`` (``pd``, or ``pd_uwml`` with
the feedforward of uwml's predicted wrench on the vehicle; default ``pd_uwml``), ``duration``
[s, 0.1 to 600; default 4], ``current`` [m/s along x, 0 to 3; default 0.5]. Metrics: the
vehicle's drift from its start, ``rms_drift`` and ``max_drift`` [m], and ``rms_attitude`` [°].

``vehicle``: any floating vehicle from its description holding station through its thrusters
while its arm moves (:mod:`uwml.study.vehicle`, whose docstring states the run): ``robot``,
``hydro`` and ``trajectory`` (a log of joint angles instead of the sines) files; ``duration`` [s,
0.01 to 600; default 4], ``amplitude`` [rad or m, 0 to 3.14; default 0.3], ``period`` [s, 0.1 to
100; default 4], ``current`` [m/s, 0 to 5; default 0], ``current_heading`` [°, -180 to 180;
default 0], ``depth`` [m; default 0], ``station_keeping`` (``off``, ``pd``, ``pid``, or ``log``:
the thrusters driven by the recorded commands of the file ``commands``; default ``pid``), ``feedforward`` (``none``, ``uwml``; default ``uwml``), ``bandwidth_hz`` [0.01 to 10;
default 0.5], ``coefficient_scale`` [0 to 10; default 1], ``payload`` [kg, 0 to 100; default 0].
Metrics: ``rms_drift``, ``max_drift`` [m], ``rms_roll``, ``max_roll``, ``rms_pitch``,
``max_pitch`` [°], ``mean_thrust``, ``peak_thrust`` [N], ``thrust_energy`` [N^1.5·s],
``saturation`` (:meth:`uwml.sim.station_keeping.StationRecord.metrics`).

``custom``: a function of one's own, ``function = "package.module:function"``, called with each
run's parameters and returning the ``metrics`` the study file declares (:mod:`uwml.study.custom`):
its parameters are any names, numbers or strings.
"""

from __future__ import annotations

from typing import Any

from ..paper.control_study import CONTROLLERS, MAX_CYCLES
from .vehicle import METRICS as VEHICLE_METRICS

__all__ = ["DEFAULTS", "METRICS", "PARAMETERS", "PARAMETER_UNITS", "SCENARIOS", "metric_names", "metric_units", "run_one"]

SCENARIOS = ("paper_leg", "robot", "rov", "vehicle", "custom")
#: The kind of a setting that names a file (relative to the study file).
PATH = "path"
#: Each scenario's parameters: a number's (low, high) bounds, or the allowed strings.
PARAMETERS: dict[str, dict[str, Any]] = {
    "paper_leg": {
        "depth": (0.0, 11_000.0),
        "controller": CONTROLLERS,
        "cycles": (1e-3, float(MAX_CYCLES)),
        "coefficient_scale": (0.0, 10.0),
        "payload": (0.0, 100.0),
    },
    "robot": {
        "robot": PATH,
        "hydro": PATH,
        "depth": (0.0, 11_000.0),
        "controller": ("land", "hydro", "hydro_losses"),
        "duration": (0.01, 3600.0),
        "amplitude": (0.0, 3.14),
        "period": (0.1, 100.0),
        "current": (0.0, 5.0),
        "coefficient_scale": (0.0, 10.0),
        "kp_hz": (0.1, 50.0),
    },
    "rov": {
        "station_keeping": ("pd", "pd_uwml"),
        "duration": (0.1, 600.0),
        "current": (0.0, 3.0),
    },
    "vehicle": {
        "robot": PATH,
        "hydro": PATH,
        "trajectory": PATH,
        "duration": (0.01, 600.0),
        "amplitude": (0.0, 3.14),
        "period": (0.1, 100.0),
        "current": (0.0, 5.0),
        "current_heading": (-180.0, 180.0),
        "depth": (0.0, 11_000.0),
        "station_keeping": ("off", "pd", "pid", "log"),
        "commands": PATH,
        "feedforward": ("none", "uwml"),
        "bandwidth_hz": (0.01, 10.0),
        "coefficient_scale": (0.0, 10.0),
        "payload": (0.0, 100.0),
    },
    # Any names (uwml.study.custom): checked by the configuration, not listed here.
    "custom": {},
}
#: The units of the scenarios' numeric parameters (the x axes of a study's figures), by name.
PARAMETER_UNITS: dict[str, str] = {
    "depth": "m",
    "cycles": "gait cycles",
    "coefficient_scale": "ratio",
    "payload": "kg",
    "duration": "s",
    "amplitude": "rad or m",
    "period": "s",
    "current": "m/s",
    "current_heading": "°",
    "kp_hz": "Hz",
    "bandwidth_hz": "Hz",
}
#: Settings a scenario cannot run without.
REQUIRED: dict[str, tuple[str, ...]] = {
    "paper_leg": (),
    "robot": ("robot",),
    "rov": (),
    "vehicle": ("robot",),
    "custom": ("function", "metrics"),
}
DEFAULTS: dict[str, dict[str, Any]] = {
    "paper_leg": {"depth": 0.0, "controller": "hydro", "cycles": 0.5, "payload": 0.0},
    "robot": {
        "hydro": None,
        "depth": 0.0,
        "controller": "hydro",
        "duration": 4.0,
        "amplitude": 0.3,
        "period": 2.0,
        "current": 0.0,
        "coefficient_scale": 1.0,
        "kp_hz": 4.0,
    },
    "rov": {"station_keeping": "pd_uwml", "duration": 4.0, "current": 0.5},
    "vehicle": {
        "hydro": None,
        "trajectory": None,
        "duration": 4.0,
        "amplitude": 0.3,
        "period": 4.0,
        "current": 0.0,
        "current_heading": 0.0,
        "depth": 0.0,
        "station_keeping": "pid",
        "feedforward": "uwml",
        "bandwidth_hz": 0.5,
        "coefficient_scale": 1.0,
        "payload": 0.0,
    },
    "custom": {},
}
#: Each scenario's metrics, the columns of a study's results, and each metric's unit (the axes
#: of a study's figures, its summary): ``{name: unit}``. The ``robot`` scenario's depend on its
#: joints and a ``custom`` one's are declared by its file (:func:`metric_units`).
METRICS: dict[str, dict[str, str]] = {
    "paper_leg": {
        **{f"rms_error_{j}": "rad" for j in (1, 2, 3)},
        **{f"peak_error_{j}": "rad" for j in (1, 2, 3)},
        "positive_work": "J",
        "energy": "J",
    },
    "rov": {"rms_drift": "m", "max_drift": "m", "rms_attitude": "°"},
    "vehicle": VEHICLE_METRICS,
}


def metric_names(kind: str, settings: dict[str, Any]) -> tuple[str, ...]:
    """The metrics of a scenario's runs (the ``robot`` scenario's depend on its joints, a
    ``custom`` one's are its settings'): :func:`metric_units`' names."""
    return tuple(metric_units(kind, settings))


def metric_units(kind: str, settings: dict[str, Any], declared: dict[str, str] | None = None) -> dict[str, str]:
    """Each metric of a scenario's runs with its unit (:data:`METRICS`): the ``robot``
    scenario's errors in rad for a revolute joint and m for a prismatic one; a ``custom``
    scenario's as its file declares them (``declared``; ``""`` where it gives none)."""
    if kind == "custom":
        return {name: (declared or {}).get(name, "") for name in settings["metrics"]}
    if kind != "robot":
        return dict(METRICS[kind])
    from ..robot.files import model_and_robot

    _, robot = model_and_robot(settings["robot"], settings.get("hydro"), floating=False)
    units = ["m" if joint.kind == "prismatic" else "rad" for joint in robot.joints]
    return {
        **{f"rms_error_{j}": unit for j, unit in enumerate(units, 1)},
        **{f"peak_error_{j}": unit for j, unit in enumerate(units, 1)},
        "positive_work": "J",
        "energy": "J",
    }


def run_one(kind: str, settings: dict[str, Any], parameters: dict[str, Any]) -> dict[str, float]:
    """One run's metrics (module docstring): the scenario's defaults, then ``settings``, then
    ``parameters``."""
    from ..paper.control_study import run

    if kind == "custom":
        from .custom import custom_run

        return custom_run(settings, parameters)
    values = DEFAULTS[kind] | settings | parameters
    if kind == "robot":
        return _robot_run(values)
    if kind == "vehicle":
        from .vehicle import vehicle_run

        return vehicle_run(values)
    if kind == "rov":
        from ..sim.control import rov_drift

        drift = rov_drift(values["station_keeping"] == "pd_uwml", float(values["duration"]), current=float(values["current"])).summary()
        return {"rms_drift": drift["rms_drift_m"], "max_drift": drift["max_drift_m"], "rms_attitude": drift["rms_attitude_deg"]}
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


def _robot_run(values: dict[str, Any]) -> dict[str, float]:
    """One run of the ``robot`` scenario (module docstring)."""
    import math

    import numpy as np

    from ..robot.files import model_and_robot
    from ..sim.control import track
    from ..sim.mujoco import Simulation

    model, robot = model_and_robot(values["robot"], values["hydro"], floating=False)
    n = robot.n_joints
    if model.nq != n or model.nv != n:
        raise ValueError(f"{values['robot']}: the robot scenario takes a fixed base and hinge or slide joints only")
    current = (float(values["current"]), 0.0, 0.0)
    depth = float(values["depth"])
    sim = Simulation(model, robot, depth=depth, current=current)
    dt = float(model.opt.timestep)
    steps = max(1, round(float(values["duration"]) / dt))
    time = np.arange(steps + 1) * dt
    omega = 2.0 * math.pi / float(values["period"])
    phase = np.arange(n) * math.pi / 3.0
    amplitude = float(values["amplitude"])
    q_d = amplitude * np.sin(omega * time[:, None] + phase)
    qd_d = amplitude * omega * np.cos(omega * time[:, None] + phase)
    qdd_d = -amplitude * omega**2 * np.sin(omega * time[:, None] + phase)
    controller = values["controller"]
    feedforward = np.zeros_like(q_d)
    if controller != "land":
        scale = float(values["coefficient_scale"])
        cd = np.array([s.cd for s in robot.segments], dtype=np.float64).reshape(-1, 2) * scale
        cm = np.array([s.cm for s in robot.segments], dtype=np.float64).reshape(-1, 2) * scale
        forces = robot.environment(q_d, qd_d, qdd_d, depth=depth, cd=cd if cd.size else None, cm=cm if cm.size else None, current=current)
        feedforward -= forces.hydro
        if controller == "hydro_losses":
            feedforward -= forces.visc + forces.seal
    q, qd, torque = track(sim, model, (q_d, qd_d, qdd_d), feedforward, float(values["kp_hz"]))
    window = slice(max(0, steps + 1 - round(float(values["period"]) / dt)), None)
    error = (q - q_d)[window]
    power = (torque * qd)[window]
    if not np.all(np.isfinite(error)):
        raise FloatingPointError("the simulation diverged (a non-finite joint state)")
    metrics = {f"rms_error_{j + 1}": float(np.sqrt(np.mean(error[:, j] ** 2))) for j in range(n)}
    metrics |= {f"peak_error_{j + 1}": float(np.max(np.abs(error[:, j]))) for j in range(n)}
    return metrics | {"positive_work": float(np.sum(np.maximum(power, 0.0)) * dt), "energy": float(np.sum(np.abs(power)) * dt)}
