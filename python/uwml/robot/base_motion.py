"""How a robot's base moves (:class:`BaseMotion`): its orientation, velocities and
accelerations at each sample (docs/model.md section 10, "Base motion and current")."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from .._checks import real_array as _real_array

__all__ = ["BaseMotion"]

FloatArray = NDArray[np.float64]


def _quaternion(value: Any) -> FloatArray:
    """A scalar-first quaternion array from numbers or a ``scipy.spatial.transform.Rotation``."""
    as_quat = getattr(value, "as_quat", None)
    if callable(as_quat):
        return np.asarray(as_quat(scalar_first=True), dtype=np.float64)
    return _real_array(value, "orientation", "a quaternion (w, x, y, z), an (n, 4) array of them, or a scipy Rotation")


@dataclass(frozen=True, init=False)
class BaseMotion:
    """How the base moves at each sample (docs/model.md section 10, "Base motion and current").

    ``orientation``: world from base, a unit quaternion ``(w, x, y, z)`` scalar first (MuJoCo's
    order), or a ``scipy.spatial.transform.Rotation``. ``velocity`` and ``angular_velocity``:
    the base origin's velocity [m/s] and the angular velocity [rad/s], in BASE-frame components
    (Fossen's ν; Pinocchio's free-flyer ``v`` in the LOCAL frame). ``acceleration`` and
    ``angular_acceleration``: the time derivatives of those components (Fossen's ν̇), so the base
    origin's classical acceleration is ``acceleration + angular_velocity × velocity``.

    Each is one value for every sample, or one per sample: ``(n, 4)`` and ``(n, 3)``.
    The default is a fixed, upright base.
    """

    orientation: FloatArray
    velocity: FloatArray
    angular_velocity: FloatArray
    acceleration: FloatArray
    angular_acceleration: FloatArray

    def __init__(
        self,
        orientation: Any = (1.0, 0.0, 0.0, 0.0),
        velocity: ArrayLike = (0.0, 0.0, 0.0),
        angular_velocity: ArrayLike = (0.0, 0.0, 0.0),
        acceleration: ArrayLike = (0.0, 0.0, 0.0),
        angular_acceleration: ArrayLike = (0.0, 0.0, 0.0),
    ) -> None:
        given = (velocity, angular_velocity, acceleration, angular_acceleration)
        arrays = {"orientation": _quaternion(orientation)}
        for name, value in zip(_MOTION_FIELDS[1:], given, strict=True):
            arrays[name] = _real_array(value, name, "a 3-vector or an (n, 3) array")
        for name, width in (("orientation", 4), ("velocity", 3), ("angular_velocity", 3), ("acceleration", 3), ("angular_acceleration", 3)):
            array = arrays[name]
            if array.ndim not in (1, 2) or array.shape[-1] != width:
                raise ValueError(f"base_motion.{name} must have shape ({width},) or (n_samples, {width}), got {array.shape}")
            if not np.all(np.isfinite(array)):
                raise ValueError(f"base_motion.{name} must be finite, got {array.tolist()}")
        for name in _MOTION_FIELDS:
            object.__setattr__(self, name, arrays[name])
        single = all(arrays[name].ndim == 1 for name in _MOTION_FIELDS)
        object.__setattr__(self, "_one", tuple(arrays[name] for name in _MOTION_FIELDS) if single else None)
        with np.errstate(over="ignore"):  # a huge quaternion's norm overflows: not a unit one
            norms = np.linalg.norm(np.atleast_2d(self.orientation), axis=1)
        bad = np.flatnonzero(np.abs(norms - 1.0) > 1e-6)
        if bad.size:
            raise ValueError(
                f"base_motion.orientation must be a unit quaternion (w, x, y, z) (norm 1 within 1e-6); sample {bad[0]} has norm {norms[bad[0]]}"
            )

    def _single(self) -> tuple[FloatArray, ...] | None:
        """The five arrays, if this is one motion for every sample (else None)."""
        one: tuple[FloatArray, ...] | None = self.__dict__["_one"]
        return one


_MOTION_FIELDS = ("orientation", "velocity", "angular_velocity", "acceleration", "angular_acceleration")


def _trusted_motion(*arrays: FloatArray) -> BaseMotion:
    """A :class:`BaseMotion` of one state from five float64 arrays already known to be finite,
    of the right shapes, the quaternion a unit one (a simulator's state, :mod:`uwml.sim.mujoco`):
    without the checks, which cost more than the evaluation. The native call checks again."""
    motion = object.__new__(BaseMotion)
    for name, array in zip(_MOTION_FIELDS, arrays, strict=True):
        object.__setattr__(motion, name, array)
    object.__setattr__(motion, "_one", arrays)
    return motion
