"""A :class:`uwml.Robot` compiled for JAX (:func:`compile_robot`): its numbers as a pytree of
arrays, :class:`RobotModel`, and its shape (the tree, the joints' kinds, which body carries each
segment and lumped model, the sections, the added-mass form) as static structure.

The model is the robot's own description, read from the same objects the Rust core reads (its
joints, links, base, segments and lumped models, its water and joint losses, or those of a
:class:`uwml.Conditions`): there is no second description to keep in step. Its arrays are
float64 numpy arrays as compiled; an evaluation takes them in the dtype of its joint state. Every
array is a leaf of the pytree, so ``jax.grad`` differentiates with respect to any of them (a
segment's ``cd``, a lumped model's damping, the water's density) and returns a :class:`RobotModel`
of gradients.
"""

from __future__ import annotations

import dataclasses
from typing import TYPE_CHECKING, Any, NamedTuple

import jax
import numpy as np
from numpy.typing import NDArray

from ..model.joint_losses import JointLosses
from ..model.parts import Segment
from ..robot.evaluation_conditions import Conditions
from ..robot.tree import Robot

if TYPE_CHECKING:
    from numpy.typing import ArrayLike

__all__ = ["Bodies", "JointLossParameters", "Joints", "LumpedModels", "RobotModel", "Segments", "Structure", "compile_robot"]

FloatArray = NDArray[np.float64]
#: A leaf of the model: a float64 numpy array as compiled, a JAX array (of any float dtype)
#: inside an evaluation or a transformation.
Leaf = Any


class Joints(NamedTuple):
    """Each joint's origin in its parent's frame and its unit axis there, ``(N, 3)`` each."""

    origin: Leaf
    axis: Leaf


class Bodies(NamedTuple):
    """Each body's mass, centre of mass, volume and centre of buoyancy in its own frame: the base
    (row 0; zeros for a base without a body) and link ``i`` (row ``i + 1``)."""

    mass: Leaf
    com: Leaf
    volume: Leaf
    cob: Leaf


class Segments(NamedTuple):
    """Every segment (base first, then link by link: :attr:`uwml.Robot.segments`), in its body's
    frame, with the evaluation's coefficients ``cd``, ``cm`` ``(S, 2)`` (a circular segment uses
    column 0) and its axial drag. ``widths`` of a circular segment are its diameter twice."""

    start: Leaf
    axis: Leaf
    length: Leaf
    normals: Leaf
    widths: Leaf
    area: Leaf
    cd: Leaf
    cm: Leaf
    cd_axial: Leaf
    axial_area: Leaf


class LumpedModels(NamedTuple):
    """Every lumped model (:attr:`uwml.Robot.lumped_models`' order): its point in its body's
    frame, its axes (body from model, an exact rotation), ``M_A``, ``D_L`` and ``d`` in its axes."""

    point: Leaf
    axes: Leaf
    added_mass: Leaf
    linear_damping: Leaf
    quadratic_damping: Leaf


class JointLossParameters(NamedTuple):
    """Each joint's losses, ``(N,)`` per field, named and in the units of :class:`uwml.Drive`,
    :class:`uwml.OilDrag` and :class:`uwml.Seal` (pressures in MPa). A joint without oil, seal or
    losses has neutral values (zero torque scale and levels, unit drive), which give exactly zero."""

    torque_constant: Leaf
    ratio: Leaf
    efficiency: Leaf
    k_oil: Leaf
    exponent: Leaf
    pressure_sensitivity_per_mpa: Leaf
    temperature_sensitivity_per_k: Leaf
    reference_pressure_mpa: Leaf
    reference_temperature_c: Leaf
    c0: Leaf
    c1_per_mpa: Leaf
    s0: Leaf
    s1_per_mpa: Leaf
    d0: Leaf
    d1_per_mpa: Leaf
    stribeck_speed: Leaf
    epsilon: Leaf


@dataclasses.dataclass(frozen=True)
class Structure:
    """What an evaluation branches on, fixed when the robot is compiled (hashable: it is part of
    the pytree's static structure, so a change compiles anew)."""

    #: Each joint's parent body: 0 the base, ``i + 1`` link ``i``.
    parents: tuple[int, ...]
    prismatic: tuple[bool, ...]
    #: Each segment's body and section.
    segment_bodies: tuple[int, ...]
    circular: tuple[bool, ...]
    lumped_bodies: tuple[int, ...]
    #: The segments' added-mass form, ``"morison"`` or ``"kirchhoff"``.
    form: str

    @property
    def n_joints(self) -> int:
        return len(self.parents)

    @property
    def n_bodies(self) -> int:
        return len(self.parents) + 1

    def moves(self) -> NDArray[np.bool_]:
        """``(B, N)``: whether joint ``j`` moves body ``b``."""
        moves = np.zeros((self.n_bodies, self.n_joints), dtype=bool)
        for j, parent in enumerate(self.parents):
            moves[j + 1] = moves[parent]
            moves[j + 1, j] = True
        return moves


@jax.tree_util.register_dataclass
@dataclasses.dataclass(frozen=True)
class RobotModel:
    """A robot compiled for :mod:`uwml.jax` (:func:`compile_robot`): a pytree whose leaves are
    the arrays below and whose static part is :attr:`structure`."""

    joints: Joints
    bodies: Bodies
    segments: Segments
    lumped: LumpedModels
    losses: JointLossParameters
    #: The water's density [kg/m³] and gravity [m/s²], and the density of the water column for
    #: the joint losses' pressure at depth.
    density: Leaf
    gravity: Leaf
    sea_density: Leaf
    structure: Structure = dataclasses.field(metadata={"static": True})


def _rows(values: list[ArrayLike], shape: tuple[int, ...]) -> FloatArray:
    return np.array(values, dtype=np.float64).reshape((len(values), *shape))


def _table(value: FloatArray | None, own: FloatArray, name: str) -> FloatArray:
    """Coefficients per segment and direction ``(S, 2)``: the segments' own (None), one number,
    one per segment or one per segment and direction."""
    if value is None:
        return own
    count = len(own)
    if value.ndim == 0:
        return np.full((count, 2), float(value))
    if value.shape == (count,):
        return np.repeat(value[:, None], 2, axis=1)
    if value.shape == (count, 2):
        return np.array(value, dtype=np.float64)
    raise ValueError(f"{name} must be a scalar, ({count},) or ({count}, 2) for this robot's {count} segments; got shape {value.shape}")


def _rotation(axes: ArrayLike) -> FloatArray:
    """A lumped model's axes made an exact rotation as the core makes them: its first column
    normalized, the second made perpendicular to it and normalized, the third their cross product."""
    m = np.asarray(axes, dtype=np.float64)
    x = m[:, 0] / np.linalg.norm(m[:, 0])
    y = m[:, 1] / np.linalg.norm(m[:, 1])
    y = y - x * float(x @ y)
    y = y / np.linalg.norm(y)
    return np.stack([x, y, np.cross(x, y)], axis=1)


def _losses(per_joint: tuple[JointLosses | None, ...]) -> JointLossParameters:
    columns: dict[str, list[float]] = {name: [] for name in JointLossParameters._fields}
    for losses in per_joint:
        drive, oil, seal = (None, None, None) if losses is None else (losses.drive, losses.oil, losses.seal)
        values = {
            "torque_constant": 1.0 if drive is None else drive.torque_constant,
            "ratio": 1.0 if drive is None else drive.ratio,
            "efficiency": 1.0 if drive is None else drive.efficiency,
            "epsilon": 0.0 if losses is None else losses.epsilon,
            "exponent": 1.0 if oil is None else oil.exponent,
            "reference_temperature_c": 20.0 if oil is None else oil.reference_temperature_c,
            "stribeck_speed": 1.0 if seal is None else seal.stribeck_speed,
        }
        for name in ("k_oil", "pressure_sensitivity_per_mpa", "temperature_sensitivity_per_k", "reference_pressure_mpa"):
            values[name] = 0.0 if oil is None else getattr(oil, name)
        for name in ("c0", "c1_per_mpa", "s0", "s1_per_mpa", "d0", "d1_per_mpa"):
            values[name] = 0.0 if seal is None else getattr(seal, name)
        for name, value in values.items():
            columns[name].append(float(value))
    return JointLossParameters(**{name: np.array(values, dtype=np.float64) for name, values in columns.items()})


def compile_robot(robot: Robot, conditions: Conditions | None = None) -> RobotModel:
    """``robot`` as a :class:`RobotModel` for :mod:`uwml.jax`'s evaluations.

    Of ``conditions`` (:class:`uwml.Conditions`; None: the defaults), what does not change from
    sample to sample is compiled in: the water (else the robot's), the coefficients ``cd`` and
    ``cm`` (else the segments' own), the added-mass form, the joint losses (else the robot's own)
    and ``sea_density`` (else the water's). The base motion, the current, the depth and the
    temperature are arguments of each evaluation (:class:`uwml.jax.Motion`, :func:`uwml.jax.motion`).
    """
    if not isinstance(robot, Robot):
        raise TypeError(f"robot must be a uwml.Robot, got {type(robot).__name__}")
    conditions = Conditions() if conditions is None else conditions
    if not isinstance(conditions, Conditions):
        raise TypeError(f"conditions must be a uwml.Conditions or None, got {type(conditions).__name__}")
    bodies = (robot.base, *robot.links)
    owned: list[tuple[int, Segment]] = [(b, s) for b, body in enumerate(bodies) if body is not None for s in body.segments]
    segments = [s for _, s in owned]
    own_cd = _rows([s.cd for s in segments], (2,))
    own_cm = _rows([s.cm for s in segments], (2,))
    lumped = robot.lumped_models
    water = robot.water if conditions.water is None else conditions.water
    losses = conditions.losses if conditions.losses is not None else robot.losses
    per_joint = (losses,) * robot.n_joints if losses is None or isinstance(losses, JointLosses) else tuple(losses)
    if len(per_joint) != robot.n_joints:
        raise ValueError(f"losses must have one entry per joint ({robot.n_joints}), got {len(per_joint)}")
    structure = Structure(
        parents=tuple(0 if j.parent is None or j.parent < 0 else j.parent + 1 for j in robot.joints),
        prismatic=tuple(j.kind == "prismatic" for j in robot.joints),
        segment_bodies=tuple(b for b, _ in owned),
        circular=tuple(s.section == "circular" for s in segments),
        lumped_bodies=tuple(b + 1 for b, _ in lumped),
        form=conditions.added_mass,
    )
    zero = np.zeros(3)
    return RobotModel(
        joints=Joints(origin=_rows([j.origin for j in robot.joints], (3,)), axis=_rows([j.axis for j in robot.joints], (3,))),
        bodies=Bodies(
            mass=_rows([0.0 if b is None else b.mass for b in bodies], ()),
            com=_rows([zero if b is None else b.com for b in bodies], (3,)),
            volume=_rows([0.0 if b is None else b.volume for b in bodies], ()),
            cob=_rows([zero if b is None or b.cob is None else b.cob for b in bodies], (3,)),
        ),
        segments=Segments(
            start=_rows([s.start for s in segments], (3,)),
            axis=_rows([s.axis for s in segments], (3,)),
            length=_rows([s.length for s in segments], ()),
            normals=_rows([s.normals for s in segments], (2, 3)),
            widths=_rows([s.widths for s in segments], (2,)),
            area=_rows([s.area for s in segments], ()),
            cd=_table(conditions.cd, own_cd, "cd"),
            cm=_table(conditions.cm, own_cm, "cm"),
            cd_axial=_rows([s.cd_axial for s in segments], ()),
            axial_area=_rows([s.axial_area for s in segments], ()),
        ),
        lumped=LumpedModels(
            point=_rows([zero if m.point is None else m.point for _, m in lumped], (3,)),
            axes=_rows([_rotation(m.axes) for _, m in lumped], (3, 3)),
            added_mass=_rows([m.added_mass for _, m in lumped], (6, 6)),
            linear_damping=_rows([m.linear_damping for _, m in lumped], (6, 6)),
            quadratic_damping=_rows([m.quadratic_damping for _, m in lumped], (6,)),
        ),
        losses=_losses(per_joint),
        density=np.array(water.density),
        gravity=np.array(water.gravity),
        sea_density=np.array(water.density if conditions.sea_density is None else conditions.sea_density),
        structure=structure,
    )
