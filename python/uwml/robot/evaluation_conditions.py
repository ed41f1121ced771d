"""What an evaluation of a robot takes besides the robot and its joint state, in one value
(:class:`Conditions`; docs/model.md sections 7 and 10, the core's ``Conditions``): the water, other
coefficients than the segments' own, the added-mass form, the base's motion, the current, and
the depth, temperature and joint losses of :meth:`uwml.Robot.environment`.

A ``Conditions`` is frozen and checked once, when it is made; every evaluation of
:class:`uwml.Robot` takes ``(q, qd, qdd, conditions)``, and the keywords of its fields as
shortcuts (``robot.hydro(q, qd, qdd, current=(0.2, 0, 0))`` evaluates in ``Conditions(current=(0.2,
0, 0))``; given with a ``conditions``, they replace its fields). Made once and passed to every
call, the conditions are read by the core once per robot: what a controller stepping one state
at a time does.
"""

from __future__ import annotations

import numbers
from collections.abc import Iterable
from dataclasses import dataclass, fields
from typing import TYPE_CHECKING, Any, Literal, TypedDict

import numpy as np
from numpy.typing import ArrayLike, NDArray

from .._checks import real_array as _real_array
from .._checks import to_float
from ..model.joint_losses import JointLosses
from ..model.parts import Water
from ..sea.conditions import check_depths, check_temperatures, positive_number
from .base_motion import BaseMotion

if TYPE_CHECKING:
    from typing_extensions import Unpack

__all__ = ["ADDED_MASS_FORMS", "ConditionFields", "Conditions"]

FloatArray = NDArray[np.float64]

#: The forms of the added-mass forces: the paper's Morison form, and Kirchhoff's
#: (docs/simulation.md, "Energy-consistent added mass").
ADDED_MASS_FORMS = ("morison", "kirchhoff")


def _frozen(array: FloatArray) -> FloatArray:
    """``array`` C-contiguous and read-only (a copy where it was not)."""
    array = np.array(array, dtype=np.float64, order="C", copy=True)
    array.flags.writeable = False
    return array


_STILL = _frozen(np.zeros(3))


def _flow(value: ArrayLike, name: str) -> FloatArray:
    """A current's velocity or acceleration: ``(3,)`` or ``(n_samples, 3)``, finite."""
    if value is _STILL:
        return _STILL
    array = _real_array(value, name, "a 3-vector or an (n, 3) array")
    if array.ndim not in (1, 2) or array.shape[-1] != 3 or (array.ndim == 2 and array.shape[0] == 0):
        raise ValueError(f"{name} must have shape (3,) or (n_samples, 3), got {array.shape}")
    if not np.all(np.isfinite(array)):
        raise ValueError(f"{name} must be finite, got {array.tolist()}")
    return _frozen(array)


def _coefficient(value: ArrayLike | None, name: str) -> FloatArray | None:
    """``cd`` or ``cm``: None (the segments' own), a number for all, one per segment, or one per
    segment and direction; finite and non-negative (their count is checked by the robot)."""
    if value is None:
        return None
    array = _real_array(value, name, "None, a real number, or an array per segment")
    if array.ndim > 2 or (array.ndim == 2 and array.shape[1] != 2):
        raise ValueError(
            f"{name} must be None, a scalar, shape (n_segments,) per segment, or (n_segments, 2) per segment and direction; "
            f"got shape {array.shape}"
        )
    if not np.all(np.isfinite(array)) or np.any(array < 0.0):
        raise ValueError(f"{name} must be finite and non-negative, got {array.tolist()}")
    return _frozen(array)


def _per_sample(value: ArrayLike, name: str) -> float | FloatArray:
    """``depth`` or ``temperature_c``: a number for every sample, or a 1-D array, one per sample."""
    if isinstance(value, numbers.Real) and not isinstance(value, bool):
        return to_float(value)
    array = _real_array(value, name, "a real number or one per sample")
    if array.ndim == 0:
        return float(array)
    if array.ndim != 1 or array.shape[0] == 0:
        raise ValueError(f"{name} must be a scalar or have one entry per sample, got shape {array.shape}")
    return _frozen(array)


def _losses(losses: object) -> JointLosses | tuple[JointLosses | None, ...] | None:
    """None (the robot's own), one :class:`uwml.JointLosses` for every joint, or one (or None)
    per joint, as a tuple (its length is checked by the robot)."""
    if losses is None or isinstance(losses, JointLosses):
        return losses
    if not isinstance(losses, Iterable) or isinstance(losses, (str, bytes)):
        raise TypeError(f"losses must be a uwml.JointLosses, a sequence of them (or None), or None; got {type(losses).__name__}")
    items = tuple(losses)
    for index, item in enumerate(items):
        if item is not None and not isinstance(item, JointLosses):
            raise TypeError(f"losses[{index}] must be a uwml.JointLosses or None, got {type(item).__name__}")
    return items


@dataclass(frozen=True, init=False, eq=False)
class Conditions:
    """The conditions of an evaluation (module docstring), checked once.

    Any input with a sample axis gives results with one (all such inputs, and the joint states,
    agree on the number of samples); the others are broadcast.

    Parameters
    ----------
    water
        Density and gravity (:class:`uwml.Water`); None (default): the robot's own
        (:attr:`uwml.Robot.water`).
    cd, cm
        Drag and added-mass coefficients instead of the segments' own: a number for all, an array
        ``(n_segments,)`` per segment or ``(n_segments, 2)`` per segment and normal direction (a
        circular segment takes one: its two entries equal), in the order of
        :attr:`uwml.Robot.segments`. None (default): each segment's own; one given, the other is
        the segments' own. Not used by :meth:`uwml.Robot.hydro_regressors` (which gives the
        forces at unit coefficients).
    added_mass
        ``"morison"`` (default): the paper's form, added mass on the normal components of each
        slice's acceleration. ``"kirchhoff"``: the form derived from the water's kinetic energy
        (docs/simulation.md, "Energy-consistent added mass"): the same added-mass matrix, other
        velocity terms, energy-consistent.
    base_motion
        How the base moves (:class:`uwml.BaseMotion`); None (default): a fixed, upright base.
    current, current_acceleration
        The water's velocity [m/s] and acceleration [m/s²], WORLD frame: ``(3,)`` or
        ``(n_samples, 3)``. Drag acts on the velocity relative to the water, added mass on the
        acceleration relative to it, and every body's centre of buoyancy carries
        ``ρ V (current_acceleration − g)``.
    depth, temperature_c
        Depth [m], 0 to 11000, and oil temperature [°C] of :meth:`uwml.Robot.environment`'s joint
        losses: a number or one per sample. The pressure is the hydrostatic
        ``sea_density · g · depth`` (the core's ``pressure_at_depth``).
    losses
        The joints' losses: one :class:`uwml.JointLosses` for every joint, a sequence with one
        (or None) per joint; None (default): the robot's own (:attr:`uwml.Robot.losses`;
        ``[None] * n_joints`` for none).
    sea_density
        The density of the water column above, for the pressure [kg/m³]; None (default): the
        water's, so that one water is used for both.

    Examples
    --------
    A controller of the paper's leg at 1000 m, stepping one state at a time:

    >>> import uwml
    >>> leg = uwml.paper_leg()
    >>> at_depth = uwml.Conditions(water=uwml.Water(1025.0), depth=1000.0, temperature_c=4.0, losses=uwml.JointLosses())
    >>> for q, qd, qdd in [([0.1, -0.4, 0.7], [0.5, -1.0, 2.0], [1.0, 3.0, -2.0])]:
    ...     tau = leg.environment(q, qd, qdd, at_depth).total   # read by the core once, for every call
    """

    water: Water | None
    cd: FloatArray | None
    cm: FloatArray | None
    added_mass: Literal["morison", "kirchhoff"]
    base_motion: BaseMotion | None
    current: FloatArray
    current_acceleration: FloatArray
    depth: float | FloatArray
    temperature_c: float | FloatArray
    losses: JointLosses | tuple[JointLosses | None, ...] | None
    sea_density: float | None

    def __init__(
        self,
        *,
        water: Water | None = None,
        cd: ArrayLike | None = None,
        cm: ArrayLike | None = None,
        added_mass: Literal["morison", "kirchhoff"] = "morison",
        base_motion: BaseMotion | None = None,
        current: ArrayLike = _STILL,
        current_acceleration: ArrayLike = _STILL,
        depth: ArrayLike = 0.0,
        temperature_c: ArrayLike = 20.0,
        losses: JointLosses | Iterable[JointLosses | None] | None = None,
        sea_density: float | None = None,
    ) -> None:
        if water is not None and not isinstance(water, Water):
            raise TypeError(f"water must be a uwml.Water or None, got {type(water).__name__}")
        if added_mass not in ADDED_MASS_FORMS:
            raise ValueError(f"added_mass must be one of {', '.join(ADDED_MASS_FORMS)}, got {added_mass!r}")
        if base_motion is not None and not isinstance(base_motion, BaseMotion):
            raise TypeError(f"base_motion must be a uwml.BaseMotion or None, got {type(base_motion).__name__}")
        values: dict[str, Any] = {
            "water": water,
            "cd": _coefficient(cd, "cd"),
            "cm": _coefficient(cm, "cm"),
            "added_mass": added_mass,
            "base_motion": base_motion,
            "current": _flow(current, "current"),
            "current_acceleration": _flow(current_acceleration, "current_acceleration"),
            "depth": _per_sample(depth, "depth"),
            "temperature_c": _per_sample(temperature_c, "temperature_c"),
            "losses": _losses(losses),
            "sea_density": None if sea_density is None else positive_number(sea_density, "sea_density"),
        }
        check_depths(np.asarray(values["depth"]))
        check_temperatures(np.asarray(values["temperature_c"]), stacklevel=_caller_level())
        per_sample = {
            name: len(array)
            for name, array in (
                *((f"base_motion.{f}", getattr(base_motion, f)) for f in _MOTION_FIELDS if base_motion is not None),
                ("current", values["current"]),
                ("current_acceleration", values["current_acceleration"]),
                ("depth", values["depth"]),
                ("temperature_c", values["temperature_c"]),
            )
            if np.ndim(array) == (2 if name.startswith(("base_motion", "current")) else 1)
        }
        if len(set(per_sample.values())) > 1:
            sizes = ", ".join(f"{k}: {v}" for k, v in per_sample.items())
            raise ValueError(f"arguments given per sample must agree on the number of samples; got {sizes}")
        for name, value in values.items():
            object.__setattr__(self, name, value)

    @property
    def n_samples(self) -> int | None:
        """The number of samples of the inputs given per sample, or None when each is one value
        for every sample."""
        counts = [len(a) for a in (self.current, self.current_acceleration) if a.ndim == 2]
        counts += [len(a) for a in (self.depth, self.temperature_c) if np.ndim(a) == 1]  # type: ignore[arg-type]
        if self.base_motion is not None:
            counts += [len(getattr(self.base_motion, f)) for f in _MOTION_FIELDS if getattr(self.base_motion, f).ndim == 2]
        return counts[0] if counts else None

    def replace(self, **changes: Unpack[ConditionFields]) -> Conditions:
        """These conditions with the fields ``changes`` (keywords of :class:`Conditions`) changed,
        checked again."""
        unknown = sorted(set(changes) - _FIELD_NAMES)
        if unknown:
            raise TypeError(
                f"unknown conditions {', '.join(map(repr, unknown))}: the fields of uwml.Conditions are {', '.join(sorted(_FIELD_NAMES))}"
            )
        current: dict[str, Any] = {name: getattr(self, name) for name in _FIELD_NAMES}
        return Conditions(**(current | dict(changes)))

    def _moved(self, base_motion: BaseMotion) -> Conditions:
        """These conditions with the base motion ``base_motion`` (one for every sample, checked
        already: a simulator's state), without checking the rest again."""
        moved = object.__new__(Conditions)
        for name in _FIELD_NAMES:
            object.__setattr__(moved, name, getattr(self, name))
        object.__setattr__(moved, "base_motion", base_motion)
        return moved

    def __repr__(self) -> str:
        given = [f"{name}={_short(getattr(self, name))}" for name in _FIELD_NAMES_IN_ORDER if _differs(self, name)]
        return f"Conditions({', '.join(given)})"

    def __getstate__(self) -> dict[str, Any]:
        # The native conditions kept for a robot (`uwml.Robot`) are not pickled: made again.
        return {name: getattr(self, name) for name in _FIELD_NAMES}

    def __setstate__(self, state: dict[str, Any]) -> None:
        for name, value in state.items():
            object.__setattr__(self, name, value)


class ConditionFields(TypedDict, total=False):
    """The keywords of :class:`Conditions`, as evaluations take them (``robot.hydro(q, qd, qdd,
    cd=2.2, water=...)``)."""

    water: Water | None
    cd: ArrayLike | None
    cm: ArrayLike | None
    added_mass: Literal["morison", "kirchhoff"]
    base_motion: BaseMotion | None
    current: ArrayLike
    current_acceleration: ArrayLike
    depth: ArrayLike
    temperature_c: ArrayLike
    losses: JointLosses | Iterable[JointLosses | None] | None
    sea_density: float | None


_MOTION_FIELDS = ("orientation", "velocity", "angular_velocity", "acceleration", "angular_acceleration")
_FIELD_NAMES_IN_ORDER = tuple(f.name for f in fields(Conditions))
_FIELD_NAMES = frozenset(_FIELD_NAMES_IN_ORDER)


def _differs(conditions: Conditions, name: str) -> bool:
    value, default = getattr(conditions, name), getattr(_DEFAULTS, name)
    if isinstance(value, np.ndarray) or isinstance(default, np.ndarray):
        return not (np.shape(value) == np.shape(default) and np.array_equal(value, default))
    return bool(value != default)


def _short(value: object) -> str:
    if isinstance(value, np.ndarray):
        return repr(value.tolist()) if value.size <= 6 else f"<array {value.shape}>"
    return repr(value)


def _caller_level() -> int:
    """The ``stacklevel`` of a warning about an argument, for the code that made the conditions:
    past the frames of this module and of :mod:`uwml.robot` (an evaluation's shortcuts)."""
    import sys

    frame, level = sys._getframe(1), 1
    while frame is not None and frame.f_globals.get("__name__", "").startswith("uwml.robot"):
        frame, level = frame.f_back, level + 1  # type: ignore[assignment]
    # One more: the warning is issued one frame below the caller of this function.
    return level + 1


_DEFAULTS = Conditions()
