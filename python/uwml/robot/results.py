"""What the robots' evaluations give: the torques on the joints (:class:`HydroTorques`,
:class:`EnvironmentTorques`), the wrench on the base (:class:`BaseWrench`) and a robot's torques
with it (:class:`RobotTorques`, :class:`RobotEnvironment`), their regressors
(:class:`HydroRegressors`, :class:`RobotRegressors`) and derivatives
(:class:`EnvironmentJacobians`, :class:`RobotJacobians`). The evaluations are
:class:`uwml.Leg`'s and :class:`uwml.Robot`'s."""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
from numpy.typing import ArrayLike, NDArray

from .._checks import real_array as _real_array
from ._arguments import _coefficients

__all__ = [
    "BaseWrench",
    "EnvironmentJacobians",
    "EnvironmentTorques",
    "HydroRegressors",
    "HydroTorques",
    "RobotEnvironment",
    "RobotJacobians",
    "RobotRegressors",
    "RobotTorques",
]

FloatArray = NDArray[np.float64]


@dataclass(frozen=True)
class HydroTorques:
    """Generalized forces of the water (and of gravity) on every joint [N·m].

    Every array is shaped like the ``q`` given: ``(n_joints,)`` or ``(n_samples, n_joints)``.
    Sign: the force exerted by the environment on the joint, in the joint's positive direction.
    """

    drag: FloatArray
    added_mass: FloatArray
    buoyancy: FloatArray
    #: Weight of the links at their centres of mass; not part of ``total``.
    gravity: FloatArray

    @property
    def total(self) -> FloatArray:
        """``drag + added_mass + buoyancy``: the paper's ``τ_w``."""
        return self.drag + self.added_mass + self.buoyancy


@dataclass(frozen=True)
class HydroRegressors:
    """Regressors of the hydrodynamic torques (docs/model.md section 4).

    With ``per="leg"``, ``drag`` and ``added_mass`` are shaped like ``q`` (the torques at Cd = 1
    and Cm = 1 everywhere) and ``total = buoyancy + cd * drag + cm * added_mass``. With
    ``per="direction"`` they have two more axes, ``(..., n_joints, n_links, 2)``: entry
    ``[..., j, l, k]`` is the torque on joint ``j`` of link ``l``'s drag (or added mass) along its
    normal ``k`` at unit coefficient, and ``total = buoyancy + einsum("...jlk,lk->...j", drag, cd)
    + (same for added mass)``.
    """

    buoyancy: FloatArray
    gravity: FloatArray
    drag: FloatArray
    added_mass: FloatArray
    #: The links that carry a segment (None: all), whose coefficients the torques use: a link
    #: without one ignores its ``cd`` and ``cm``, as in :meth:`Leg.hydro`.
    links_with_segments: tuple[int, ...] | None = field(default=None, repr=False, compare=False)

    def torques(self, cd: ArrayLike = 2.2, cm: ArrayLike = 0.5) -> HydroTorques:
        """The torques for the given coefficients (same layout rules as :meth:`Leg.hydro`; with
        ``per="leg"`` regressors, per-link or per-direction coefficients must be one value over
        the links that carry a segment, since the regressors sum over links)."""
        n_joints = self.buoyancy.shape[-1]
        per_direction = self.drag.ndim == self.buoyancy.ndim + 2
        n_links = self.drag.shape[-2] if per_direction else n_joints
        cd_table = _coefficients(cd, "cd", n_links)
        cm_table = _coefficients(cm, "cm", n_links)
        if per_direction:
            drag = np.einsum("...jlk,lk->...j", self.drag, cd_table)
            added_mass = np.einsum("...jlk,lk->...j", self.added_mass, cm_table)
        else:
            used = slice(None) if self.links_with_segments is None else list(self.links_with_segments)
            values = []
            for name, table in (("cd", cd_table), ("cm", cm_table)):
                rows = table[used]
                if rows.size and not np.all(rows == rows.flat[0]):
                    raise ValueError(
                        f"{name} differs between links that carry a segment (or between directions); "
                        "that needs regressors computed with per='direction'"
                    )
                values.append(rows.flat[0] if rows.size else 0.0)
            drag = values[0] * self.drag
            added_mass = values[1] * self.added_mass
        return HydroTorques(drag=drag, added_mass=added_mass, buoyancy=self.buoyancy, gravity=self.gravity)


@dataclass(frozen=True)
class EnvironmentJacobians:
    """The environment torque ``τ_env`` of :meth:`Leg.environment` and its derivatives, for control.

    Shapes: ``value`` like ``q``, ``(n_joints,)`` or ``(n_samples, n_joints)``; the matrices
    ``(n_joints, n_joints)`` or ``(n_samples, n_joints, n_joints)``, entry ``[..., i, j]`` being
    ``∂τ_i/∂q_j`` (``d_q`` [N·m/rad]), ``∂τ_i/∂q̇_j`` (``d_qd`` [N·m·s/rad]) or ``M_A[i, j]``
    [kg·m²]. Sign: environment torques, as everywhere in uwml. The added-mass torque is
    ``−M_A(q) q̈`` plus terms in ``q̇``, so ``∂τ_env/∂q̈ = −added_mass_matrix``, and a simulator adds
    ``added_mass_matrix`` (symmetric, positive semi-definite) to the rigid-body inertia.
    """

    value: FloatArray
    d_q: FloatArray
    d_qd: FloatArray
    added_mass_matrix: FloatArray


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
