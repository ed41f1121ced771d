"""Synthetic data of the paper's three-configuration joint experiment, from known parameters.

**Synthetic**: for tests, demos and planning an experiment, never a stand-in for measurements.
The paper (Section IV) measured motor current in three configurations of its hip-roll joint;
:func:`three_configuration_experiment` reproduces that experiment from given loss models
(:mod:`uwml.model.losses`), so that the identification in :mod:`uwml.fit` can be checked against the
truth. Its model of a measurement (every current in A, ω the output speed in rad/s, p the
pressure in MPa, θ the oil temperature in °C, noise Gaussian with standard deviation
``noise_a``, independent between rows):

* ``dry`` (housing dry, no output-shaft seal): ``I_dry(ω) = i0 + i1·|ω|``, the rest of the
  drive's losses (gear, bearings, motor), independent of pressure and temperature. Dry rows are
  written at pressure 0 (a dry housing is not pressurised).
* ``oil`` (oil-filled, no seal): ``I_dry(ω) + T_oil(N ω, p, θ)/K_t``.
* ``oil_seal`` (oil-filled, with the seal): ``I_oil + T_seal(ω, p)/(N η K_t)``.

Start-up rows (``startup = 1``) are the current peak when the joint breaks away from rest
toward the slowest grid speed. They are evaluated at ``ω → 0⁺`` with the hard sign: the seal
gives its breakaway level ``S(p)`` (``T_seal(0⁺) = S(p)``), the oil nothing
(``T_oil(0⁺) = 0``: the oil has not been sheared yet), the dry drive its base ``i0``. So a
start-up row of ``dry`` or ``oil`` reads ``i0`` and one of ``oil_seal`` reads
``i0 + S(p)/(N η K_t)``, plus noise. The inertial part of a real start-up peak is the same in
all configurations and cancels in the differences that :mod:`uwml.fit` takes, so it is left
out. Their ``speed_rpm`` is the commanded speed (the slowest grid speed), which the model does
not use.

Steady rows use the hard sign (ε = 0), as the fits do.

:func:`land_water_experiment` reproduces the paper's hydrodynamic experiment (Section III): the
leg follows one trajectory on land and in water, and the motor torques of both runs are logged
(:mod:`uwml.io.logs`), so that :func:`uwml.fit.hydro_coefficients` can be checked against known
Cd and Cm. With a :class:`uwml.Robot` (any tree) and a :class:`uwml.sim.prescribed.SineTrajectory`
(or anything with ``joint_states(t)``) it does the same for any robot on a fixed base.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..io.logs import Log
from ..model.joint_losses import JointLosses
from ..model.losses import RPM, Drive, OilDrag, Seal
from ..model.parts import Water
from ..robot.presets import paper_leg
from ..robot.results import Torques
from ..robot.tree import Robot
from ..sim.prescribed import SineTrajectory
from .gait import WalkingGait

FloatArray = NDArray[np.float64]

__all__ = [
    "CONFIGURATIONS",
    "LAND_COULOMB",
    "LAND_INERTIA",
    "LAND_VISCOUS",
    "PAPER_LIKE_ERROR",
    "PAPER_LIKE_NOISE",
    "PAPER_LIKE_PERIOD",
    "YAW_STEP_FOOT",
    "ModelDiscrepancy",
    "land_water_experiment",
    "paper_like_experiment",
    "three_configuration_experiment",
]

#: The paper's three configurations, in its order.
CONFIGURATIONS = ("dry", "oil", "oil_seal")
#: The illustrative defaults of :mod:`uwml.model.losses`.
_OIL, _SEAL, _DRIVE = OilDrag(), Seal(), Drive()


def _grid(values: Sequence[float], name: str, *, low: float, strict: bool) -> NDArray[np.float64]:
    """Distinct finite numbers ``>= low`` (``> low`` if ``strict``), as a 1-D array."""
    try:
        a = np.asarray(values, dtype=np.float64)
    except (TypeError, ValueError) as exc:
        raise ValueError(f"{name} must be a sequence of numbers, got {values!r}") from exc
    if a.ndim != 1 or a.size == 0 or not np.all(np.isfinite(a)):
        raise ValueError(f"{name} must be a non-empty sequence of finite numbers, got {values!r}")
    if np.any(a <= low if strict else a < low):
        raise ValueError(f"{name} must be {'>' if strict else '>='} {low}, got {values!r}")
    if np.unique(a).size != a.size:
        raise ValueError(f"{name} must not repeat a value, got {values!r}")
    return a


def three_configuration_experiment(
    oil: OilDrag = _OIL,
    seal: Seal = _SEAL,
    drive: Drive = _DRIVE,
    *,
    speeds_rpm: Sequence[float] = (1.0, 2.0, 4.0, 6.0, 8.0, 10.0),
    pressures_mpa: Sequence[float] = (0.0, 2.0, 4.0, 6.0, 8.0, 10.0),
    temperatures_c: Sequence[float] | None = None,
    repeats: int = 5,
    startup: int = 0,
    noise_a: float = 0.02,
    dry_current_a: tuple[float, float] = (0.6, 0.3),
    rng: np.random.Generator | int | None = None,
) -> dict[str, NDArray[Any]]:
    """Synthetic motor currents of the three-configuration experiment (see the module docstring).

    Parameters
    ----------
    oil, seal, drive
        The true loss models and drive.
    speeds_rpm : sequence of float
        Output speeds [r/min], > 0, distinct.
    pressures_mpa : sequence of float
        Ambient pressures [MPa], ≥ 0, distinct (the ``oil`` and ``oil_seal`` runs).
    temperatures_c : sequence of float, optional
        Oil temperatures [°C] of the runs (every speed and pressure at each); None: all runs at
        ``oil.reference_temperature_c`` and no ``temperature_c`` column.
    repeats : int
        Steady rows per grid point and configuration, ≥ 1.
    startup : int
        Start-up rows per configuration, pressure and temperature, ≥ 0.
    noise_a : float
        Standard deviation of the current noise [A], ≥ 0.
    dry_current_a : (float, float)
        ``(i0, i1)`` of the dry current ``i0 + i1 |ω|`` [A, A·s/rad].
    rng : numpy.random.Generator or int or None
        Random generator, or a seed for ``numpy.random.default_rng``.

    Returns
    -------
    dict of ndarray
        Columns of equal length: ``configuration`` (str), ``speed_rpm``, ``pressure_mpa``,
        ``current_a``, ``startup`` (int, 0 or 1), and ``temperature_c`` when
        ``temperatures_c`` is given; the layout of :func:`uwml.fit.write_loss_csv`.

    Raises
    ------
    ValueError
        On empty, repeated, negative or non-finite grids, ``repeats < 1``, ``startup < 0``,
        negative noise or a negative dry current.
    """
    speeds = _grid(speeds_rpm, "speeds_rpm", low=0.0, strict=True)
    pressures = _grid(pressures_mpa, "pressures_mpa", low=0.0, strict=False)
    temperatures = None if temperatures_c is None else _grid(temperatures_c, "temperatures_c", low=-273.15, strict=True)
    if int(repeats) != repeats or repeats < 1:
        raise ValueError(f"repeats must be an integer >= 1, got {repeats!r}")
    if int(startup) != startup or startup < 0:
        raise ValueError(f"startup must be an integer >= 0, got {startup!r}")
    if not np.isfinite(noise_a) or noise_a < 0.0:
        raise ValueError(f"noise_a must be finite and >= 0, got {noise_a!r}")
    i0, i1 = (float(x) for x in dry_current_a)
    if not (np.isfinite(i0) and np.isfinite(i1)) or i0 < 0.0 or i1 < 0.0:
        raise ValueError(f"dry_current_a must be two finite numbers >= 0, got {dry_current_a!r}")
    generator = rng if isinstance(rng, np.random.Generator) else np.random.default_rng(rng)

    thetas = np.array([oil.reference_temperature_c]) if temperatures is None else temperatures
    rows: list[tuple[str, float, float, float, int]] = []  # configuration, speed, pressure, θ, startup
    for theta in thetas:
        for speed in speeds:
            rows += [("dry", speed, 0.0, theta, 0)] * int(repeats)
        rows += [("dry", speeds.min(), 0.0, theta, 1)] * int(startup)
        for configuration in CONFIGURATIONS[1:]:
            for pressure in pressures:
                for speed in speeds:
                    rows += [(configuration, speed, pressure, theta, 0)] * int(repeats)
                rows += [(configuration, speeds.min(), pressure, theta, 1)] * int(startup)

    configurations = np.array([r[0] for r in rows])
    speed_rpm, pressure_mpa, temperature_c = (np.array([r[k] for r in rows], dtype=np.float64) for k in (1, 2, 3))
    is_startup = np.array([r[4] for r in rows], dtype=np.int64)
    # Start-up rows are evaluated at ω → 0⁺: speed 0 with the sign forced to +1.
    omega = np.where(is_startup == 1, 0.0, speed_rpm * RPM)
    # The oil's loss current T_oil/K_t and the seal's T_seal/(N η K_t), by the core (hard sign):
    # the oil gives nothing at rest, as at ω → 0⁺.
    oil_current = JointLosses(drive=drive, oil=oil, seal=None, epsilon=0.0).torques(omega, pressure_mpa, temperature_c).current
    seal_steady = JointLosses(drive=drive, oil=None, seal=seal, epsilon=0.0).torques(omega, pressure_mpa, temperature_c).current
    # At ω → 0⁺ the seal gives its breakaway level S(p) (the hard sign is 0 at rest itself).
    breakaway = seal.s0 + seal.s1_per_mpa * pressure_mpa
    seal_current = np.where(is_startup == 1, breakaway / (drive.ratio * drive.efficiency * drive.torque_constant), seal_steady)
    current = i0 + i1 * np.abs(omega)
    current = current + np.where(configurations != "dry", oil_current, 0.0)
    current = current + np.where(configurations == "oil_seal", seal_current, 0.0)
    current = current + generator.normal(0.0, noise_a, size=current.shape)

    columns: dict[str, NDArray[Any]] = {
        "configuration": configurations,
        "speed_rpm": speed_rpm,
        "pressure_mpa": pressure_mpa,
        "current_a": current,
        "startup": is_startup,
    }
    if temperatures is not None:
        columns["temperature_c"] = temperature_c
    return columns


#: The land torque's illustrative rigid-body and friction terms (every joint): an effective
#: inertia [kg·m²], a viscous friction [N·m·s/rad] and a Coulomb friction [N·m].
LAND_INERTIA, LAND_VISCOUS, LAND_COULOMB = 0.3, 2.0, 1.5
#: Speed scale of the Coulomb friction's smooth sign ``tanh(q̇ / 0.05 rad/s)``.
_COULOMB_SPEED = 0.05
#: Nominal foot of the default gait of :func:`land_water_experiment` [m]: beside the hip, so
#: that stepping along x swings the hip-yaw joint (joint 1) by ±13° as in the paper's
#: experiment. (:class:`uwml.WalkingGait`'s own default steps radially, which leaves joint 1 at
#: rest: nothing to identify on it.)
YAW_STEP_FOOT = (0.1, 0.7, -0.6)


@dataclass(frozen=True)
class ModelDiscrepancy:
    """What a real land/water experiment has and the identification's model does not.

    **Synthetic**, and illustrative: each field is one of the reasons the paper gives (Section
    III.B) for its fit's COD of 0.826, in the simplest form that has its effect. All zero (the
    default) is the model itself. In water, at the water run's joint states ``q, q̇, q̈``:

    * ``damping`` [N·m·s/rad, ≥ 0]: an unmodelled linear damping ``−damping · q̇`` on every
      joint (the paper's reason 1: shapes the strips leave out, skin friction, cables);
    * ``water_lag`` [s, ≥ 0]: in water the leg follows the trajectory this much later than on
      land, ``q_water(t) = q_land(t − water_lag)``, while the log keeps the land run's states
      (reason 2: the two environments' responses differ; the paper assumes they do not);
    * ``cd_speed`` [in (−1, 1)]: a drag coefficient that varies with the flow (reason 4),
      ``Cd(t) = cd · (1 + cd_speed · (ω_ref − ‖q̇‖) / (ω_ref + ‖q̇‖))`` with ``ω_ref =
      reference_speed`` [rad/s, > 0] and ``‖q̇‖`` the norm of the joint velocities: ``cd`` at
      ``ω_ref``, up to ``cd (1 + cd_speed)`` near rest and down toward ``cd (1 − cd_speed)``
      fast, as a drag coefficient falls with the Reynolds number;
    * ``buoyancy`` [> −1]: the real buoyancy is ``(1 + buoyancy)`` times the computed one
      (reason 3: volumes and centres of buoyancy off). It leaves joint 1 of the paper's leg
      alone (its axis is vertical), which is why the paper fits on joint 1.
    """

    damping: float = 0.0
    water_lag: float = 0.0
    cd_speed: float = 0.0
    reference_speed: float = 0.3
    buoyancy: float = 0.0

    def __post_init__(self) -> None:
        domains: tuple[tuple[str, Callable[[float], bool], str], ...] = (
            ("damping", lambda x: x >= 0.0, ">= 0 [N·m·s/rad]"),
            ("water_lag", lambda x: x >= 0.0, ">= 0 [s]"),
            ("cd_speed", lambda x: -1.0 < x < 1.0, "in (-1, 1)"),
            ("reference_speed", lambda x: x > 0.0, "> 0 [rad/s]"),
            ("buoyancy", lambda x: x > -1.0, "> -1 (a relative error)"),
        )
        for name, inside, allowed in domains:
            value = getattr(self, name)
            if isinstance(value, bool) or not isinstance(value, (int, float, np.floating, np.integer)):
                raise TypeError(f"ModelDiscrepancy.{name} must be a number, got {value!r}")
            if not (np.isfinite(value) and inside(float(value))):
                raise ValueError(f"ModelDiscrepancy.{name} must be finite and {allowed}, got {value!r}")


#: The model error of :func:`paper_like_experiment`: 0.5 N·m·s/rad of unmodelled damping, the
#: water run 50 ms behind the land run, and a drag coefficient 30 % above ``cd`` near rest
#: (``cd`` at 0.3 rad/s). Chosen, with :data:`PAPER_LIKE_NOISE`, so that the fit's unweighted
#: COD and reduced χ² come near the paper's 0.826 and 2.425 N·m²; each part's effect on the
#: recovered coefficients is in ``uwml paper``'s report.
PAPER_LIKE_ERROR = ModelDiscrepancy(damping=0.5, water_lag=0.05, cd_speed=0.3, reference_speed=0.3)
#: Noise on each measured torque of :func:`paper_like_experiment` [N·m].
PAPER_LIKE_NOISE = 1.08
#: Period of the gait of :func:`paper_like_experiment` [s]: slow enough that joint 1's
#: hydrodynamic torque varies as the paper's does (a variance near 14 N·m², which its statistics
#: imply: 2.425 / (1 − 0.826)); our 2 s gait gives about 800 N·m².
PAPER_LIKE_PERIOD = 5.65


def paper_like_experiment(leg: Robot | None = None, seed: np.random.Generator | int | None = None) -> Log:
    """A synthetic land/water experiment sized and spoiled like the paper's (**synthetic**).

    :func:`land_water_experiment` of the paper's leg (default) over 3 cycles of
    ``WalkingGait(nominal_foot=YAW_STEP_FOOT, period=PAPER_LIKE_PERIOD)`` at 200 Hz, true Cd = 2.2
    and Cm = 0.5, ``torque_noise=PAPER_LIKE_NOISE`` and ``model_error=PAPER_LIKE_ERROR``.
    """
    gait = WalkingGait(nominal_foot=YAW_STEP_FOOT, period=PAPER_LIKE_PERIOD)
    return land_water_experiment(leg, gait, torque_noise=PAPER_LIKE_NOISE, model_error=PAPER_LIKE_ERROR, seed=seed)


def land_water_experiment(
    leg: Robot | None = None,
    gait: WalkingGait | SineTrajectory | None = None,
    cycles: float = 3,
    rate_hz: float = 200.0,
    cd: ArrayLike = 2.2,
    cm: ArrayLike = 0.5,
    torque_noise: float = 0.5,
    model_error: float | ModelDiscrepancy = 0.0,
    water: Water | None = None,
    seed: np.random.Generator | int | None = None,
    *,
    derivatives: bool = True,
    start_time: float = 0.0,
) -> Log:
    """A synthetic land/water experiment: the motor torques of one trajectory on land and in water.

    **Synthetic**: for tests and demos. The model of the measurement, per joint, at the gait's
    joint states ``q, q̇, q̈`` (analytic) sampled at ``rate_hz`` from ``start_time``:

    * land: ``τ_land = −τ_gravity + I q̈ + b q̇ + c tanh(q̇ / 0.05)`` with ``τ_gravity`` the
      weight's torque (:meth:`uwml.Robot.hydro`'s ``gravity``, which the motor holds) and the
      illustrative ``I = LAND_INERTIA``, ``b = LAND_VISCOUS``, ``c = LAND_COULOMB`` on every
      joint: an arbitrary but deterministic rigid-body-like torque, identical in both runs, that
      the difference cancels;
    * water: ``τ_water = τ_land − τ_hydro``: the motor also supplies minus the water's torque,
      ``τ_hydro = buoyancy + drag(cd) + added mass(cm)`` (docs/model.md section 4), spoiled by
      ``model_error`` (:class:`ModelDiscrepancy`: what the identification's model does not contain;
      a number is an unmodelled linear damping ``model_error · q̇`` in N·m·s/rad, 0 by default);
    * each measured torque gets independent Gaussian noise of standard deviation
      ``torque_noise`` [N·m] (so their difference has ``√2 · torque_noise``).

    Parameters
    ----------
    leg : Robot, optional
        Default :func:`uwml.paper_leg`. The robot is on a fixed, upright base in still water.
    gait : WalkingGait or SineTrajectory, optional
        Anything with ``joint_states(t)``; default ``WalkingGait(nominal_foot=YAW_STEP_FOOT)``
        (the paper leg's: a robot needs its own).
    cycles : float
        Duration in gait periods (``gait.period``) (or in seconds, if the gait has no period).
    rate_hz : float
        Sample rate [Hz].
    cd, cm : array_like
        True coefficients, in any layout :class:`uwml.Conditions` accepts (None for the
        segments' own).
    torque_noise : float
        See above [N·m]; ≥ 0.
    model_error : float or ModelDiscrepancy
        See above; a number is ``ModelDiscrepancy(damping=model_error)``.
    water : Water, optional
        The fluid; default fresh water (a robot: its own).
    seed : numpy.random.Generator or int or None
        Random generator, or a seed for ``numpy.random.default_rng``.
    derivatives : bool
        Write the analytic ``qd`` and ``qdd`` into the log (else only ``q``, and the fit
        estimates them).
    start_time : float
        Time of the first sample [s].

    Returns
    -------
    Log
        A log of the whole experiment (``tau_land`` and ``tau_water``), source ``"<synthetic>"``.
    """
    leg = paper_leg() if leg is None else leg
    gait = WalkingGait(nominal_foot=YAW_STEP_FOOT) if gait is None else gait
    for name, value in (("cycles", cycles), ("rate_hz", rate_hz)):
        if not (np.isfinite(value) and value > 0.0):
            raise ValueError(f"{name} must be finite and > 0, got {value!r}")
    if not (np.isfinite(torque_noise) and torque_noise >= 0.0):
        raise ValueError(f"torque_noise must be finite and >= 0, got {torque_noise!r}")
    if not isinstance(model_error, ModelDiscrepancy):
        if not (np.isfinite(model_error) and model_error >= 0.0):
            raise ValueError(f"model_error must be a ModelDiscrepancy or a damping finite and >= 0, got {model_error!r}")
        model_error = ModelDiscrepancy(damping=float(model_error))
    generator = seed if isinstance(seed, np.random.Generator) else np.random.default_rng(seed)
    duration = float(cycles) * float(getattr(gait, "period", 1.0))
    t = float(start_time) + np.arange(round(duration * rate_hz)) / float(rate_hz)
    q, qd, qdd = (np.asarray(a, dtype=np.float64) for a in gait.joint_states(t))
    if q.shape[-1] != leg.n_joints:
        raise ValueError(f"the gait gives {q.shape[-1]} joints, the robot has {leg.n_joints}")
    land = _hydro(leg, q, qd, qdd, cd, cm, water)
    tau_land = _motor_torque(land.gravity, qd, qdd)
    # The water run: the same trajectory, model_error.water_lag later; the log keeps the land's.
    if model_error.water_lag == 0.0:
        qw, qdw, qddw, hydro = q, qd, qdd, land
    else:
        qw, qdw, qddw = (np.asarray(a, dtype=np.float64) for a in gait.joint_states(t - model_error.water_lag))
        hydro = _hydro(leg, qw, qdw, qddw, cd, cm, water)
    speed = np.linalg.norm(qdw, axis=-1, keepdims=True)
    omega = model_error.reference_speed
    drag_factor = 1.0 + model_error.cd_speed * (omega - speed) / (omega + speed)
    water_hydro = drag_factor * hydro.drag + hydro.added_mass + (1.0 + model_error.buoyancy) * hydro.buoyancy
    tau_water = _motor_torque(hydro.gravity, qdw, qddw) - water_hydro + model_error.damping * qdw
    tau_land = tau_land + generator.normal(0.0, torque_noise, size=q.shape)
    tau_water = tau_water + generator.normal(0.0, torque_noise, size=q.shape)
    return Log(
        time=t,
        q=q,
        qd=qd if derivatives else None,
        qdd=qdd if derivatives else None,
        tau_land=tau_land,
        tau_water=tau_water,
        source="<synthetic>",
    )


def _hydro(leg: Robot, q: FloatArray, qd: FloatArray, qdd: FloatArray, cd: ArrayLike, cm: ArrayLike, water: Water | None) -> Torques:
    return leg.hydro(q, qd, qdd, cd=cd, cm=cm) if water is None else leg.hydro(q, qd, qdd, cd=cd, cm=cm, water=water)


def _motor_torque(gravity: FloatArray, qd: FloatArray, qdd: FloatArray) -> FloatArray:
    """The motor torque of a run without water: it holds the weight (``gravity``, the weight's
    torque) and drives the illustrative rigid-body and friction terms."""
    return -gravity + LAND_INERTIA * qdd + LAND_VISCOUS * qd + LAND_COULOMB * np.tanh(qd / _COULOMB_SPEED)
