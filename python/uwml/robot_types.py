"""What a robot evaluation takes and gives: the base's motion (:class:`BaseMotion`), and the
forces on joints and base (:class:`RobotTorques`, :class:`RobotEnvironment`, :class:`BaseWrench`),
their regressors (:class:`RobotRegressors`) and derivatives (:class:`RobotJacobians`). The
evaluations are :class:`uwml.Robot`'s (:mod:`uwml.robot`)."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ._checks import real_array as _real_array
from .environment import EnvironmentTorques
from .leg import HydroTorques

__all__ = ["BaseMotion", "BaseWrench", "RobotEnvironment", "RobotJacobians", "RobotRegressors", "RobotTorques"]

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
    of the right shapes, the quaternion a unit one (a simulator's state, :mod:`uwml.mujoco`):
    without the checks, which cost more than the evaluation. The native call checks again."""
    motion = object.__new__(BaseMotion)
    for name, array in zip(_MOTION_FIELDS, arrays, strict=True):
        object.__setattr__(motion, name, array)
    object.__setattr__(motion, "_one", arrays)
    return motion


@dataclass(frozen=True)
class BaseWrench:
    """The environment's wrench on the whole robot, per component, at the base (docs/model.md
    section 10, "What is computed").

    Each array is ``(..., 6)``: force ``[0:3]`` [N] and moment ``[3:6]`` [N·m] about the base
    origin, in base-frame components: the generalized force of the base's six degrees of freedom.
    """

    drag: FloatArray
    added_mass: FloatArray
    buoyancy: FloatArray
    #: Weight of all bodies; not part of ``total``.
    gravity: FloatArray

    @property
    def total(self) -> FloatArray:
        """``drag + added_mass + buoyancy``."""
        return self.drag + self.added_mass + self.buoyancy


@dataclass(frozen=True)
class RobotTorques(HydroTorques):
    """Generalized forces on every joint (shaped like ``q``; N·m, or N for prismatic joints),
    and ``base``, the wrench on the base (:class:`BaseWrench`)."""

    base: BaseWrench


@dataclass(frozen=True)
class RobotEnvironment(EnvironmentTorques):
    """Everything the environment does to every joint (hydrodynamics and joint losses, shaped
    like ``q``), and ``base``, the hydrodynamic wrench on the base (:class:`BaseWrench`). Joint
    losses act between a link and its parent, inside the robot: they add nothing to the base
    wrench."""

    base: BaseWrench


@dataclass(frozen=True)
class RobotRegressors:
    """Regressors of a robot's hydrodynamic forces (docs/model.md section 4; for whole robots,
    docs/model.md section 10, "What is computed").

    ``drag[..., j, k, d]`` is the generalized force on joint ``j`` of segment ``k``'s drag along
    its normal direction ``d`` at unit coefficient (a circular segment: all in ``d = 0``), shape
    ``(..., n_joints, n_segments, 2)``; ``base_drag[..., i, k, d]`` the same for the base wrench's
    component ``i`` (force xyz, moment xyz), ``(..., 6, n_segments, 2)``; likewise
    ``added_mass`` and ``base_added_mass``. So for coefficients ``cd``, ``cm`` per segment and
    direction, ``total = buoyancy + einsum("...jkd,kd->...j", drag, cd) + (same for added
    mass)``: linear least squares for an arm on a moving vehicle. Segments are ordered as
    :attr:`Robot.segments`.
    """

    buoyancy: FloatArray
    gravity: FloatArray
    drag: FloatArray
    added_mass: FloatArray
    base_buoyancy: FloatArray
    base_gravity: FloatArray
    base_drag: FloatArray
    base_added_mass: FloatArray

    def torques(self, cd: ArrayLike, cm: ArrayLike) -> RobotTorques:
        """The forces at coefficients ``cd``, ``cm``: scalars, ``(n_segments,)`` or ``(n_segments, 2)``."""
        n_segments = self.drag.shape[-2]

        def table(value: ArrayLike, name: str) -> FloatArray:
            array = _real_array(value, name, "a scalar or an array per segment")
            if array.ndim == 0:
                return np.full((n_segments, 2), float(array))
            if array.shape == (n_segments,):
                return np.repeat(array[:, None], 2, axis=1)
            if array.shape == (n_segments, 2):
                return array
            raise ValueError(f"{name} must be a scalar, ({n_segments},) or ({n_segments}, 2); got shape {array.shape}")

        cd_table, cm_table = table(cd, "cd"), table(cm, "cm")

        def apply(columns: FloatArray, coefficients: FloatArray) -> FloatArray:
            forces: FloatArray = np.einsum("...jkd,kd->...j", columns, coefficients)
            return forces

        base = BaseWrench(
            drag=apply(self.base_drag, cd_table),
            added_mass=apply(self.base_added_mass, cm_table),
            buoyancy=self.base_buoyancy,
            gravity=self.base_gravity,
        )
        return RobotTorques(
            drag=apply(self.drag, cd_table),
            added_mass=apply(self.added_mass, cm_table),
            buoyancy=self.buoyancy,
            gravity=self.gravity,
            base=base,
        )


@dataclass(frozen=True)
class RobotJacobians:
    """The environment's forces on base and joints and their derivatives, for control.

    With ``m = 6 + n_joints`` (rows: the base wrench's force and moment, base frame, then the
    joints): ``value`` ``(..., m)`` is ``(base.total, total)`` of :meth:`Robot.environment`;
    ``d_q`` ``(..., m, n_joints)`` is ``∂value/∂q``; ``d_velocity`` ``(..., m, m)`` is
    ``∂value/∂(ν, q̇)``, columns the base twist (``v``, ``ω``, base components) then the joint
    rates; ``added_mass_matrix`` ``(..., m, m)`` is ``M_A`` (:meth:`Robot.added_mass_matrix`), so
    ``∂value/∂(ν̇, q̈) = −M_A``. Exact derivatives (dual numbers through the same Rust code).
    """

    value: FloatArray
    d_q: FloatArray
    d_velocity: FloatArray
    added_mass_matrix: FloatArray
