"""A hydro file's masses in a description (docs/model.md section 13): each link's mass override and
point items, written into the description's MuJoCo spec as its body's inertial, so that the
compiled model (what a simulation steps) and the robot read from it (its link masses and centres
of mass) carry them alike; and the records ``uwml describe`` lists.

The spec is compiled once as written, to read each body's inertial as MuJoCo makes it (MJCF
bodies without ``<inertial>`` take it from their geoms), then the changed bodies' inertials are
set (mass, centre of mass, principal moments and axes) and the spec compiled again. A body the
description leaves massless gets its override before the first compile (MuJoCo refuses a moving
body without mass), and needs ``inertia`` with it (there is none to scale)."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

from .._checks import Vec3
from ._description_io import DescriptionError
from .hydrofile import HydroLink, _table

__all__ = ["MassOverride", "OwnInertial", "PlacedItem", "apply_masses", "massless_overrides"]

FloatArray = NDArray[np.float64]


@dataclass(frozen=True)
class OwnInertial:
    """A description body's inertial before its items (body frame): the description's mass, and
    the mass and centre of mass after the hydro file's override (the description's if none)."""

    described_mass: float
    mass: float
    com: FloatArray
    overridden: bool
    inertia_given: bool


@dataclass(frozen=True)
class PlacedItem:
    """A point item of the hydro file as the robot carries it."""

    #: The description body whose ``[links.NAME]`` gives it.
    body: str
    #: The uwml link it is part of (the body, or the one it is fused into; the base's is its body's).
    link: str
    name: str | None
    mass: float
    volume: float
    #: In the uwml link's frame [m].
    position: Vec3


@dataclass(frozen=True)
class MassOverride:
    """A link's mass override of the hydro file as the robot carries it."""

    body: str
    link: str
    described_mass: float
    mass: float
    #: The centre of mass before items, in the uwml link's frame [m].
    com: Vec3
    inertia_given: bool


def _point(mass: float, d: FloatArray) -> FloatArray:
    """The inertia of a point mass at ``d`` about the origin: ``m (|d|² E − d dᵀ)``."""
    return mass * (float(d @ d) * np.eye(3) - np.outer(d, d))


def _body_frame_inertia(mujoco: Any, model: Any, i: int) -> FloatArray:
    """Body ``i``'s inertia about its centre of mass in its own frame: ``R diag(I) Rᵀ``."""
    rotation = np.zeros(9)
    mujoco.mju_quat2Mat(rotation, model.body_iquat[i])
    r = rotation.reshape(3, 3)
    return np.asarray(r @ np.diag(model.body_inertia[i]) @ r.T)


def _changes_mass(entry: HydroLink | None) -> bool:
    return entry is not None and (entry.mass is not None or any(item.mass > 0.0 for item in entry.items))


def _no_inertia_to_scale(hydro_source: str, name: str) -> DescriptionError:
    return DescriptionError(
        f"{hydro_source}: {_table('links', name)}, key 'mass': the description gives this link no mass (and so no inertia "
        "to scale to the new mass): give inertia = [ixx, iyy, izz] with it"
    )


def _massless_as_written(body: Any, fmt: str) -> bool:
    return (body.explicitinertial and body.mass == 0.0) or (fmt == "URDF" and not body.explicitinertial)


def _set_inertial(mujoco: Any, body: Any, mass: float, com: FloatArray, inertia: FloatArray) -> None:
    """The spec body's explicit inertial: mass, centre of mass and inertia (body frame) as its
    principal moments and axes (a proper rotation)."""
    moments, axes = np.linalg.eigh(0.5 * (inertia + inertia.T))
    if np.linalg.det(axes) < 0.0:
        axes[:, 0] = -axes[:, 0]
    quat = np.zeros(4)
    mujoco.mju_mat2Quat(quat, np.ascontiguousarray(axes).reshape(9))
    body.explicitinertial = True
    body.mass = float(mass)
    body.ipos = com
    body.iquat = quat
    body.inertia = np.maximum(moments, 0.0)  # a point's zero moments round to ±1e-18
    body.fullinertia = [np.nan, 0.0, 0.0, 0.0, 0.0, 0.0]  # unset: iquat and inertia hold it
    body.ialt.type = mujoco.mjtOrientation.mjORIENTATION_QUAT


def massless_overrides(mujoco: Any, spec: Any, hydro: dict[str, HydroLink], fmt: str, hydro_source: str) -> None:
    """Before the first compile: the override of a body the description leaves massless (a URDF
    link without ``<inertial>``, an ``<inertial>`` of mass 0), which needs ``inertia``."""
    for body in spec.bodies[1:]:
        entry = hydro.get(body.name)
        if entry is None or entry.mass is None or not _massless_as_written(body, fmt):
            continue
        if entry.inertia is None:
            raise _no_inertia_to_scale(hydro_source, body.name)
        com = np.asarray(entry.com if entry.com is not None else (body.ipos if body.explicitinertial else np.zeros(3)), dtype=np.float64)
        _set_inertial(mujoco, body, entry.mass, com, np.diag(entry.inertia))


def apply_masses(mujoco: Any, spec: Any, model: Any, hydro: dict[str, HydroLink], hydro_source: str) -> dict[str, OwnInertial]:
    """Each body's override and items written into ``spec`` (``model``: the spec compiled as
    written); its inertial before the items, by body name, for each body changed."""
    own: dict[str, OwnInertial] = {}
    for i in range(1, model.nbody):
        name = model.body(i).name
        entry = hydro.get(name)
        if entry is None or not _changes_mass(entry):
            continue
        described, com, inertia = (
            float(model.body_mass[i]),
            np.array(model.body_ipos[i], dtype=np.float64),
            _body_frame_inertia(mujoco, model, i),
        )
        mass = described
        if entry.mass is not None:
            mass = entry.mass
            if entry.com is not None:
                com = np.asarray(entry.com, dtype=np.float64)
            if entry.inertia is not None:
                inertia = np.diag(entry.inertia)
            elif described > 0.0:
                inertia = inertia * (mass / described)  # the same distribution of mass, scaled
            else:
                raise _no_inertia_to_scale(hydro_source, name)
        own[name] = OwnInertial(described, mass, com, entry.mass is not None, entry.inertia is not None)
        total = mass + sum(item.mass for item in entry.items)
        centre = (mass * com + sum((item.mass * np.asarray(item.position) for item in entry.items), np.zeros(3))) / total
        combined = inertia + _point(mass, com - centre)
        for item in entry.items:
            combined = combined + _point(item.mass, np.asarray(item.position) - centre)
            if item.inertia is not None:
                combined = combined + np.diag(item.inertia)
        _set_inertial(mujoco, spec.body(name), total, centre, combined)
    return own
