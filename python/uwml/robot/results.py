"""What a robot's evaluations give (one family): the forces on every joint and, where asked
for, the wrench on the base (:class:`Torques`, with a :class:`BaseWrench`), their regressors in
the coefficients (:class:`Regressors`) and their derivatives (:class:`Jacobians`). The
evaluations are :class:`uwml.Robot`'s; the core builds these objects directly."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from .._checks import real_array as _real_array

__all__ = ["BaseWrench", "Jacobians", "Regressors", "Torques"]

FloatArray = NDArray[np.float64]


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
class Torques:
    """Generalized forces of the environment on every joint (N·m, or N for a prismatic joint),
    shaped like the ``q`` given: ``(n_joints,)`` or ``(n_samples, n_joints)``; and, where asked
    for, the wrench on the base. Sign: the force exerted by the environment on the joint, in the
    joint's positive direction.

    ``visc``, ``seal`` and ``current`` (the joint losses: oil drag reflected to the output, seal
    friction [N·m], loss current [A]; zero for a joint without) are those of
    :meth:`uwml.Robot.environment`; :meth:`uwml.Robot.hydro` evaluates none (zeros, one
    read-only array). ``base``: the wrench on the base (:class:`BaseWrench`), None where not
    evaluated (``base=False``). Joint losses act between a link and its parent, inside the
    robot: they add nothing to the base wrench.
    """

    drag: FloatArray
    added_mass: FloatArray
    #: Buoyancy and Froude-Krylov.
    buoyancy: FloatArray
    #: Weight of the links at their centres of mass; not part of ``total``.
    gravity: FloatArray
    visc: FloatArray
    seal: FloatArray
    current: FloatArray
    base: BaseWrench | None = None

    @property
    def hydro(self) -> FloatArray:
        """``drag + added_mass + buoyancy``: the water's torque, the paper's ``τ_w``; the
        links' weight (``gravity``) is not in it."""
        return self.drag + self.added_mass + self.buoyancy

    @property
    def total(self) -> FloatArray:
        """Everything the environment exerts but the weight: ``τ_env = τ_hydro + τ_visc +
        τ_seal`` (from :meth:`uwml.Robot.hydro`, ``hydro``)."""
        return self.hydro + self.visc + self.seal


@dataclass(frozen=True)
class Regressors:
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

    def torques(self, cd: ArrayLike, cm: ArrayLike, cd_axial: ArrayLike = 0.0, lumped: ArrayLike | None = None) -> Torques:
        """The forces at coefficients ``cd``, ``cm``: scalars, ``(n_segments,)`` or
        ``(n_segments, 2)``; ``cd_axial``: a scalar or ``(n_segments,)`` (a robot's own:
        ``[s.cd_axial for s in robot.segments]``); ``lumped``: ``(n_lumped, 63)`` (a robot's own:
        ``[m.coefficients() for _, m in robot.lumped_models]``), None for none."""
        n_segments = self.drag.shape[-2]
        n_lumped = self.lumped.shape[-2]

        def table(value: ArrayLike, name: str) -> FloatArray:
            array = _real_array(value, name, "a scalar or an array per segment")
            if not np.all(np.isfinite(array)) or np.any(array < 0.0):
                raise ValueError(f"{name} must be finite and non-negative, got {array.tolist()}")
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
        none = np.zeros_like(self.buoyancy)
        none.flags.writeable = False
        return Torques(
            drag=drag(self.drag, self.axial_drag, self.lumped),
            added_mass=added_mass(self.added_mass, self.lumped),
            buoyancy=self.buoyancy,
            gravity=self.gravity,
            visc=none,
            seal=none,
            current=none,
            base=base,
        )


@dataclass(frozen=True)
class Jacobians:
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
