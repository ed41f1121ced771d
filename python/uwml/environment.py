"""Joint losses evaluated by the Rust core, and the environment torque of a whole leg.

:class:`JointLosses` bundles one joint's :class:`~uwml.losses.Drive` with its optional
:class:`~uwml.losses.OilDrag` and :class:`~uwml.losses.Seal`; :meth:`uwml.Leg.environment`
adds the losses of every joint to the hydrodynamic torques at a depth and temperature.
"""

from __future__ import annotations

import math
import numbers
import warnings
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from . import _core
from ._checks import real_array as _real_array
from ._checks import to_float
from .domains import ABSOLUTE_ZERO_C, MAX_DEPTH, MAX_PRESSURE, OIL_TEMPERATURE_RANGE_C
from .losses import Drive, OilDrag, Seal

__all__ = [
    "ABSOLUTE_ZERO_C",
    "MAX_DEPTH",
    "OIL_TEMPERATURE_RANGE_C",
    "SEA_WATER_DENSITY",
    "EnvironmentTorques",
    "ExtrapolationWarning",
    "JointLosses",
    "LossTorques",
    "hydrostatic_pressure_mpa",
]

FloatArray = NDArray[np.float64]

#: Default sea-water density for the hydrostatic pressure [kg/m³].
SEA_WATER_DENSITY = 1025.0
_MPA = 1e6


#: The largest ambient (gauge) pressure taken [MPa]: the deepest ocean's 110 MPa, with margin.
MAX_PRESSURE_MPA: float = MAX_PRESSURE / _MPA
# MAX_DEPTH, ABSOLUTE_ZERO_C and OIL_TEMPERATURE_RANGE_C (outside which the losses are still
# evaluated, the exponential temperature law extrapolating, with an ExtrapolationWarning) come
# from uwml.domains.


class ExtrapolationWarning(UserWarning):
    """An input outside the range a model is meant for, though inside the physics' domain: the
    result is the model's extrapolation (e.g. an oil temperature outside
    :data:`OIL_TEMPERATURE_RANGE_C`)."""


def _positive_number(value: object, name: str) -> float:
    real = isinstance(value, numbers.Real) or (isinstance(value, np.ndarray) and value.ndim == 0 and value.dtype.kind in "fiu")
    if not real or isinstance(value, (bool, np.bool_)):
        raise TypeError(f"{name} must be a real number, got {value!r}")
    x = to_float(value)
    if not (math.isfinite(x) and x > 0.0):
        raise ValueError(f"{name} must be finite and positive, got {value!r}")
    return x


def check_depths(depth: FloatArray, name: str = "depth") -> None:
    """Every depth finite and from 0 to :data:`MAX_DEPTH`; else a ValueError naming the first."""
    flat = np.ravel(depth)
    bad = np.flatnonzero(~np.isfinite(flat) | (flat < 0.0) | (flat > MAX_DEPTH))
    if bad.size:
        where = f"{name}[{bad[0]}]" if np.ndim(depth) else name
        raise ValueError(f"{where} is {float(flat[bad[0]])!r} m: {name} must be finite and from 0 to {MAX_DEPTH:g} m (the deepest ocean)")


def check_temperatures(temperature: FloatArray, name: str = "temperature_c", stacklevel: int = 3) -> None:
    """Every temperature finite and above absolute zero (else a ValueError naming the first); an
    :class:`ExtrapolationWarning` when one is outside :data:`OIL_TEMPERATURE_RANGE_C`."""
    flat = np.ravel(temperature)
    bad = np.flatnonzero(~np.isfinite(flat) | (flat <= ABSOLUTE_ZERO_C))
    if bad.size:
        where = f"{name}[{bad[0]}]" if np.ndim(temperature) else name
        raise ValueError(f"{where} is {float(flat[bad[0]])!r} °C: {name} must be finite and above absolute zero ({ABSOLUTE_ZERO_C} °C)")
    low, high = OIL_TEMPERATURE_RANGE_C
    outside = np.flatnonzero((flat < low) | (flat > high))
    if outside.size:
        where = f"{name}[{outside[0]}]" if np.ndim(temperature) else name
        warnings.warn(
            f"{where} is {float(flat[outside[0]])!r} °C, outside the oil model's range ({low:g} to {high:g} °C, the sea's): "
            "its temperature law extrapolates there",
            ExtrapolationWarning,
            stacklevel=stacklevel,
        )


def check_overflow(outputs: Sequence[FloatArray], n_samples: int, velocities: FloatArray, accelerations: FloatArray) -> None:
    """A ValueError naming the first sample whose outputs are not finite although its state is
    (the states are checked before): forces beyond float64's range, from speeds or accelerations
    far beyond any robot's. Cheap when nothing overflows (one sum per output array)."""
    with np.errstate(over="ignore", invalid="ignore"):
        if all(math.isfinite(float(np.sum(a))) for a in outputs):
            return
    bad = np.zeros(n_samples, dtype=bool)
    for a in outputs:
        bad |= ~np.all(np.isfinite(np.reshape(a, (n_samples, -1))), axis=1)
    if not bad.any():
        return  # only the sums overflowed
    i = int(np.flatnonzero(bad)[0])
    speed = float(np.max(np.abs(np.reshape(velocities, (n_samples, -1))[i])))
    acceleration = float(np.max(np.abs(np.reshape(accelerations, (n_samples, -1))[i])))
    where = f"sample {i}" if n_samples > 1 else "the state"
    raise ValueError(
        f"the forces of {where} overflow float64 (joint speeds up to {speed:.3g}, accelerations up to {acceleration:.3g}; "
        "or the base's motion, the current or the coefficients): the inputs are outside the physics' domain"
    )


def hydrostatic_pressure_mpa(depth_m: ArrayLike, *, sea_density: float = SEA_WATER_DENSITY, gravity: float = 9.81) -> FloatArray:
    """Gauge pressure ``ρ g z`` [MPa] at depth [m] (0 to :data:`MAX_DEPTH`), the formula the core
    uses; ``sea_density`` [kg/m³] and ``gravity`` [m/s²] finite and positive, keyword-only.

    :func:`uwml.seawater.pressure_at_depth_mpa` gives the oceanographers' TEOS-10 value (its second
    argument is a latitude); the two agree within the bound documented in docs/losses.md.
    """
    depth = _real_array(depth_m, "depth_m", "a real number or array")
    check_depths(depth, "depth_m")
    density = _positive_number(sea_density, "sea_density")
    g = _positive_number(gravity, "gravity")
    with np.errstate(over="ignore", invalid="ignore"):
        pressure = density * g * depth / _MPA
    if not np.all(pressure <= MAX_PRESSURE_MPA):
        raise ValueError(
            f"the pressure of sea_density {density:g} kg/m³ and gravity {g:g} m/s² reaches {float(np.max(pressure)):g} MPa, "
            f"beyond the deepest ocean's ({MAX_PRESSURE_MPA:g} MPa): a water far from the sea's"
        )
    return pressure


@dataclass(frozen=True)
class LossTorques:
    """One joint's losses [environment sign: they oppose motion]."""

    #: Oil drag reflected to the output, ``−N η T_oil`` [N·m].
    visc: FloatArray
    #: Seal friction, ``−T_seal`` [N·m].
    seal: FloatArray
    #: Loss current ``T_oil/K_t + T_seal/(N η K_t)`` [A], signed like the motion.
    current: FloatArray


@dataclass(frozen=True)
class JointLosses:
    """The losses of one joint: its drive, and optionally oil drag and a dynamic seal.

    ``epsilon`` [rad/s, output speed] is the smooth sign's width (a few times the velocity
    noise; 0 for the hard sign). The defaults are the illustrative ones of :mod:`uwml.losses`.
    """

    drive: Drive = field(default_factory=Drive)
    oil: OilDrag | None = field(default_factory=OilDrag)
    seal: Seal | None = field(default_factory=Seal)
    epsilon: float = 1e-3

    def __post_init__(self) -> None:
        if not isinstance(self.drive, Drive):
            raise TypeError(f"drive must be a uwml.Drive, got {type(self.drive).__name__}")
        if self.oil is not None and not isinstance(self.oil, OilDrag):
            raise TypeError(f"oil must be a uwml.OilDrag or None, got {type(self.oil).__name__}")
        if self.seal is not None and not isinstance(self.seal, Seal):
            raise TypeError(f"seal must be a uwml.Seal or None, got {type(self.seal).__name__}")
        epsilon = float(self.epsilon)
        if not np.isfinite(epsilon) or epsilon < 0:
            raise ValueError(f"epsilon must be finite and >= 0, got {self.epsilon!r}")
        object.__setattr__(self, "epsilon", epsilon)

    def packed(self) -> list[float]:
        """The core's packed layout (SI: pressures in Pa)."""
        o, s, d = self.oil, self.seal, self.drive
        oil = (
            [0.0] * 7
            if o is None
            else [
                1.0,
                o.k_oil,
                o.exponent,
                o.pressure_sensitivity_per_mpa / _MPA,
                o.temperature_sensitivity_per_k,
                o.reference_pressure_mpa * _MPA,
                o.reference_temperature_c,
            ]
        )
        seal = (
            [0.0] * 8
            if s is None
            else [
                1.0,
                s.c0,
                s.c1_per_mpa / _MPA,
                s.s0,
                s.s1_per_mpa / _MPA,
                s.d0,
                s.d1_per_mpa / _MPA,
                s.stribeck_speed,
            ]
        )
        return [*oil, *seal, d.torque_constant, d.ratio, d.efficiency, d.rated_current, self.epsilon, 1.0]

    def torques(self, speed: ArrayLike, pressure_mpa: ArrayLike = 0.0, temperature_c: ArrayLike = 20.0) -> LossTorques:
        """Losses at output speed [rad/s], ambient pressure [MPa] and oil temperature [°C].

        The three arguments broadcast against each other; the results have their common shape.
        """
        arrays = [
            _real_array(value, name, "a real number or array")
            for name, value in (("speed", speed), ("pressure_mpa", pressure_mpa), ("temperature_c", temperature_c))
        ]
        try:
            speed_b, pressure_b, temperature_b = np.broadcast_arrays(*arrays)
        except ValueError:
            raise ValueError(f"speed, pressure_mpa and temperature_c must broadcast, got shapes {[a.shape for a in arrays]}") from None
        bad = np.flatnonzero(~np.isfinite(np.ravel(speed_b)))
        if bad.size:
            raise ValueError(f"speed[{bad[0]}] is {float(np.ravel(speed_b)[bad[0]])!r}: speed must be finite")
        pressures = np.ravel(pressure_b)
        bad = np.flatnonzero(~np.isfinite(pressures) | (pressures < 0.0) | (pressures > MAX_PRESSURE_MPA))
        if bad.size:
            raise ValueError(
                f"pressure_mpa[{bad[0]}] is {float(pressures[bad[0]])!r}: pressure_mpa must be finite, >= 0 (gauge pressure) "
                f"and at most {MAX_PRESSURE_MPA:g} MPa (the deepest ocean's, with margin)"
            )
        check_temperatures(temperature_b)
        shape = speed_b.shape
        flat = [np.ascontiguousarray(a.ravel()) for a in (speed_b, pressure_b * _MPA, temperature_b)]
        packed = np.array([self.packed()], dtype=np.float64)
        visc, seal, current = _core.joint_losses(packed, *flat)
        check_overflow((visc, seal, current), len(flat[0]), flat[0], np.zeros_like(flat[0]))
        return LossTorques(visc=visc.reshape(shape), seal=seal.reshape(shape), current=current.reshape(shape))


@dataclass(frozen=True)
class EnvironmentTorques:
    """Everything the environment does to every joint [N·m, A], shaped like ``q``."""

    drag: FloatArray
    added_mass: FloatArray
    buoyancy: FloatArray
    #: Weight of the links; not part of ``total``.
    gravity: FloatArray
    #: Oil drag reflected to the output (0 for joints without oil).
    visc: FloatArray
    #: Seal friction (0 for joints without a seal).
    seal: FloatArray
    #: Loss current [A].
    current: FloatArray

    @property
    def hydro(self) -> FloatArray:
        """``drag + added_mass + buoyancy``."""
        return self.drag + self.added_mass + self.buoyancy

    @property
    def total(self) -> FloatArray:
        """``τ_env = τ_hydro + τ_visc + τ_seal``."""
        return self.hydro + self.visc + self.seal


def loss_conditions(
    depth: ArrayLike, temperature_c: ArrayLike, sea_density: float, gravity: float, n_samples: int
) -> tuple[FloatArray, FloatArray]:
    """The hydrostatic pressure [Pa] (``sea_density · gravity · depth``) and the temperature
    [°C] of every sample, checked: depth and temperature a scalar or one per sample, finite,
    depth ≥ 0, ``sea_density`` positive."""
    conditions, given = [], []
    for name, value in (("depth", depth), ("temperature_c", temperature_c)):
        array = _real_array(value, name, "a real number or one per sample")
        if array.ndim > 1 or (array.ndim == 1 and array.shape[0] != n_samples):
            raise ValueError(f"{name} must be a scalar or have one entry per sample ({n_samples}), got shape {array.shape}")
        given.append(array)
        conditions.append(np.ascontiguousarray(np.broadcast_to(array, (n_samples,))))
    depth_m, temperature = conditions
    sea_density = _positive_number(sea_density, "sea_density")
    check_depths(given[0])
    check_temperatures(given[1], stacklevel=4)
    return np.ascontiguousarray(sea_density * gravity * depth_m), temperature


def one_state_losses(owner: Any, losses: object, n_joints: int) -> FloatArray | bool:
    """``losses`` (not None) for a one-state native call: one :class:`JointLosses` packed for
    every joint, kept on ``owner`` (its ``_losses_cache``) for the next call with the same object
    (it is frozen), or ``False`` (which the native calls do not take) for anything else, left to
    the general path."""
    cached: tuple[JointLosses, FloatArray] | None = owner._losses_cache
    if cached is not None and cached[0] is losses:
        return cached[1]
    if type(losses) is not JointLosses:
        return False
    packed = pack_leg_losses(losses, n_joints)
    packed.flags.writeable = False
    owner._losses_cache = (losses, packed)
    return packed


def pack_leg_losses(losses: JointLosses | Sequence[JointLosses | None] | None, n_joints: int) -> FloatArray:
    """Per-joint packed losses ``(n_joints, LOSS_WIDTH)``: one ``JointLosses`` for every joint,
    a sequence with one entry (or None) per joint, or None for no losses."""
    if losses is None or isinstance(losses, JointLosses):
        per_joint: list[JointLosses | None] = [losses] * n_joints
    else:
        try:
            per_joint = list(losses)
        except TypeError:
            raise TypeError(
                f"losses must be a uwml.JointLosses, a sequence of them (or None), or None; got {type(losses).__name__}"
            ) from None
        if len(per_joint) != n_joints:
            raise ValueError(f"losses must have one entry per joint ({n_joints}), got {len(per_joint)}")
    rows = []
    for i, item in enumerate(per_joint):
        if item is None:
            rows.append([0.0] * _core.LOSS_WIDTH)
        elif isinstance(item, JointLosses):
            rows.append(item.packed())
        else:
            raise TypeError(f"losses[{i}] must be a uwml.JointLosses or None, got {type(item).__name__}")
    return np.array(rows, dtype=np.float64).reshape(n_joints, _core.LOSS_WIDTH)
