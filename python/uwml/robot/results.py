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
        """``drag + added_mass + buoyancy``: the water's torque, the paper's ``τ_w``; the
        links' weight (``gravity``) is not in it."""
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
        """``drag + added_mass + buoyancy``: the water's wrench (``buoyancy`` the gross
        ``ρ V``, with Froude-Krylov); the weight (``gravity``) is not in it."""
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
    section 10, "What is computed"; lumped models and axial drag, section 12): the force of each
    coefficient at unit value, the others zero.

    ``drag[..., j, k, d]`` is the generalized force on joint ``j`` of segment ``k``'s drag along
    its normal direction ``d`` at unit coefficient (a circular segment: all in ``d = 0``), shape
    ``(..., n_joints, n_segments, 2)``; ``base_drag[..., i, k, d]`` the same for the base wrench's
    component ``i`` (force xyz, moment xyz), ``(..., 6, n_segments, 2)``; likewise
    ``added_mass`` and ``base_added_mass``. ``axial_drag[..., j, k]`` is segment ``k``'s axial
    drag at ``cd_axial = 1`` (zero where its ``axial_area`` is), ``(..., n_joints, n_segments)``,
    and ``base_axial_drag`` ``(..., 6, n_segments)``. ``lumped[..., j, b, i]`` is coefficient
    ``i`` of lumped model ``b`` (:attr:`Robot.lumped_models`; coefficients named and ordered as
    :data:`uwml.model.lumped.LUMPED_COEFFICIENTS`, in the model's own axes), ``(..., n_joints,
    n_lumped, 63)``, and ``base_lumped`` ``(..., 6, n_lumped, 63)``: its first 21 are added
    mass, the rest damping (drag).

    So ``total = buoyancy + einsum("...jkd,kd->...j", drag, cd) + (same for added mass) +
    axial_drag @ cd_axial + einsum("...jbi,bi->...j", lumped, coefficients)``: linear least
    squares for an arm on a moving vehicle, and for a hull (:meth:`torques`). Segments are ordered
    as :attr:`Robot.segments`.
    """

    buoyancy: FloatArray
    gravity: FloatArray
    drag: FloatArray
    added_mass: FloatArray
    base_buoyancy: FloatArray
    base_gravity: FloatArray
    base_drag: FloatArray
    base_added_mass: FloatArray
    axial_drag: FloatArray
    base_axial_drag: FloatArray
    lumped: FloatArray
    base_lumped: FloatArray

    def torques(self, cd: ArrayLike, cm: ArrayLike, cd_axial: ArrayLike = 0.0, lumped: ArrayLike | None = None) -> RobotTorques:
        """The forces at coefficients ``cd``, ``cm``: scalars, ``(n_segments,)`` or
        ``(n_segments, 2)``; ``cd_axial``: a scalar or ``(n_segments,)`` (a robot's own:
        ``[s.cd_axial for s in robot.segments]``); ``lumped``: ``(n_lumped, 63)`` (a robot's own:
        ``[m.coefficients() for _, m in robot.lumped_models]``), None for none."""
        n_segments = self.drag.shape[-2]
        n_lumped = self.lumped.shape[-2]

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
        axial = _real_array(cd_axial, "cd_axial", "a scalar or an array per segment")
        if axial.ndim == 0:
            axial = np.full(n_segments, float(axial))
        if axial.shape != (n_segments,):
            raise ValueError(f"cd_axial must be a scalar or ({n_segments},); got shape {axial.shape}")
        models = np.zeros((n_lumped, 63)) if lumped is None else _real_array(lumped, "lumped", "an array of 63 coefficients per model")
        if models.shape != (n_lumped, 63):
            raise ValueError(f"lumped must have shape ({n_lumped}, 63), one row of 63 coefficients per lumped model; got {models.shape}")
        # The lumped models' added-mass coefficients, then their damping ones.
        mass_part = np.zeros_like(models)
        mass_part[:, :21] = models[:, :21]
        damping_part = models - mass_part

        def apply(columns: FloatArray, coefficients: FloatArray) -> FloatArray:
            forces: FloatArray = np.einsum("...jkd,kd->...j", columns, coefficients)
            return forces

        def drag(segments: FloatArray, axial_columns: FloatArray, lumped_columns: FloatArray) -> FloatArray:
            return apply(segments, cd_table) + axial_columns @ axial + apply(lumped_columns, damping_part)

        def added_mass(segments: FloatArray, lumped_columns: FloatArray) -> FloatArray:
            return apply(segments, cm_table) + apply(lumped_columns, mass_part)

        base = BaseWrench(
            drag=drag(self.base_drag, self.base_axial_drag, self.base_lumped),
            added_mass=added_mass(self.base_added_mass, self.base_lumped),
            buoyancy=self.base_buoyancy,
            gravity=self.base_gravity,
        )
        return RobotTorques(
            drag=drag(self.drag, self.axial_drag, self.lumped),
            added_mass=added_mass(self.added_mass, self.lumped),
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
