"""How a description body becomes part of a uwml link (:mod:`uwml.io.descriptions`): its collision
primitives as segments and volume, moved into the link's frame, with a hydro file's entry
(:class:`~uwml.io.hydrofile.HydroLink`) applied."""

from __future__ import annotations

import dataclasses
import math
import warnings
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import NDArray

from ..model.lumped import LumpedModel
from ..model.parts import Segment
from ..model.thrusters import Thruster
from ..plausibility import DescriptionWarning
from ._description_io import DescriptionError, quoted
from ._description_masses import MassOverride, OwnInertial, PlacedItem
from .hydrofile import HydroItem, HydroLink, _table

FloatArray = NDArray[np.float64]


def _rotation(quat: FloatArray) -> FloatArray:
    """The rotation matrix of a unit quaternion (w, x, y, z)."""
    w, x, y, z = np.asarray(quat, dtype=np.float64) / np.linalg.norm(quat)
    return np.array(
        [
            [1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
            [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
            [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)],
        ]
    )


def _t(v: FloatArray) -> tuple[float, float, float]:
    return (float(v[0]), float(v[1]), float(v[2]))


@dataclass(frozen=True)
class Outline:
    """A collision geom of a body the hydro file describes by its lumped model (``strips =
    false``): its shape only drawn (``uwml describe``), in its uwml link's frame."""

    #: The link (its description body's name, the base's too).
    link: str
    #: ``"box"`` (``size`` its half-extents), ``"sphere"``, ``"ellipsoid"``, ``"cylinder"`` or
    #: ``"capsule"`` (``size`` as MuJoCo's: radius, half-length), along ``rotation``'s columns.
    kind: str
    size: tuple[float, float, float]
    rotation: tuple[tuple[float, ...], ...]
    position: tuple[float, float, float]


@dataclass
class _Body:
    """What one description body contributes to its uwml link, in that link's frame."""

    name: str
    mass: float
    com: FloatArray
    volume: float = 0.0
    cob_moment: FloatArray = field(default_factory=lambda: np.zeros(3))
    segments: list[Segment] = field(default_factory=list)
    #: Its lumped model (hydro file), in the link's frame.
    lumped: LumpedModel | None = None
    #: Its point items (hydro file) in the link's frame: (item, position); their mass is in
    #: ``mass`` and ``com`` (the compiled model's), their volume not in ``volume``.
    items: list[tuple[HydroItem, FloatArray]] = field(default_factory=list)
    #: Its thrusters (hydro file), in the link's frame.
    thrusters: list[Thruster] = field(default_factory=list)
    #: Its collision geoms' shapes when the hydro file describes it by a lumped model:
    #: (kind, size, rotation, position) in the link's frame.
    outlines: list[tuple[str, FloatArray, FloatArray, FloatArray]] = field(default_factory=list)
    #: Mass and centre of mass before the items (the description's, or the hydro file's override).
    own_mass: float = 0.0
    own_com: FloatArray = field(default_factory=lambda: np.zeros(3))


def _with_coefficients(segment: Segment, cd: Any, cm: Any, where: str) -> Segment:
    def one(value: Any, name: str) -> Any:
        if value is None or segment.section != "circular" or not isinstance(value, tuple):
            return value
        if value[0] != value[1]:
            raise DescriptionError(f"{where}: {name} of a circular segment must be one number (or two equal), got {list(value)}")
        return value[0]

    changes = {key: one(value, key) for key, value in (("cd", cd), ("cm", cm)) if value is not None}
    try:
        return _segment_copy(segment, **changes)
    except (TypeError, ValueError) as exc:
        raise DescriptionError(f"{where}: {exc}") from None


def _segment_copy(segment: Segment, **changes: Any) -> Segment:
    fields: dict[str, Any] = {
        "start": segment.start,
        "axis": segment.axis,
        "length": segment.length,
        "section": segment.section,
        "area": segment.area,
        "cd": segment.cd if segment.section == "rectangular" else segment.cd[0],
        "cm": segment.cm if segment.section == "rectangular" else segment.cm[0],
        "cd_axial": segment.cd_axial,
        "axial_area": segment.axial_area,
    }
    if segment.section == "circular":
        fields["diameter"] = segment.diameter
    else:
        fields["normals"], fields["widths"] = segment.normals, segment.widths
    fields.update(changes)
    return Segment(**fields)


def _moved(segment: Segment, rotation: FloatArray, offset: FloatArray) -> Segment:
    """``segment`` (given in a body frame) in the uwml link frame: points ``R v + offset``."""
    changes: dict[str, Any] = {
        "start": _t(rotation @ np.asarray(segment.start) + offset),
        "axis": _t(rotation @ np.asarray(segment.axis)),
    }
    if segment.section == "rectangular":
        n0, n1 = segment.normals
        changes["normals"] = (_t(rotation @ np.asarray(n0)), _t(rotation @ np.asarray(n1)))
    return _segment_copy(segment, **changes)


def _primitive(mujoco: Any, kind: int, size: FloatArray) -> tuple[Segment | None, float]:
    """The segment (in the geom's own frame) and volume of a box, cylinder, capsule, sphere or
    ellipsoid, or ``(None, -1)`` for any other kind."""
    g = mujoco.mjtGeom
    if kind == g.mjGEOM_BOX:
        edges = 2.0 * np.asarray(size[:3], dtype=np.float64)
        order = sorted(range(3), key=lambda k: -edges[k])  # stable: ties x, y, z
        e = np.eye(3)
        along, n0, n1 = order
        length = float(edges[along])
        segment = Segment(
            start=_t(-0.5 * length * e[along]),
            axis=_t(e[along]),
            length=length,
            normals=(_t(e[n0]), _t(e[n1])),
            widths=(float(edges[n1]), float(edges[n0])),
            area=float(edges[n0] * edges[n1]),
        )
        return segment, float(edges[0] * edges[1] * edges[2])
    if kind in (g.mjGEOM_CYLINDER, g.mjGEOM_CAPSULE):
        r, length = float(size[0]), 2.0 * float(size[1])
        segment = Segment(
            start=(0.0, 0.0, -0.5 * length), axis=(0.0, 0.0, 1.0), length=length, section="circular", diameter=2.0 * r, area=math.pi * r * r
        )
        volume = math.pi * r * r * length + (4.0 / 3.0 * math.pi * r * r * r if kind == g.mjGEOM_CAPSULE else 0.0)
        return segment, volume
    if kind == g.mjGEOM_SPHERE:
        r = float(size[0])
        return None, 4.0 / 3.0 * math.pi * r * r * r
    if kind == g.mjGEOM_ELLIPSOID:
        return None, 4.0 / 3.0 * math.pi * float(size[0]) * float(size[1]) * float(size[2])
    return None, -1.0


def _body(
    mujoco: Any,
    model: Any,
    i: int,
    rotation: FloatArray,
    offset: FloatArray,
    name: str,
    entry: HydroLink | None,
    source: str,
    hydro_source: str,
    own: OwnInertial | None = None,
) -> _Body:
    """Body ``i``'s mass, volume, segments and items in its uwml link's frame (points ``R v +
    offset``); ``own``: its inertial before the items, where the hydro file changed it."""
    mass, com = float(model.body_mass[i]), rotation @ model.body_ipos[i] + offset
    own_mass, own_com = (mass, com) if own is None else (own.mass, rotation @ own.com + offset)
    body = _Body(name=name, mass=mass, com=com, own_mass=own_mass, own_com=own_com)
    if entry is not None:
        body.items = [(item, rotation @ np.asarray(item.position) + offset) for item in entry.items]
        body.thrusters = [
            dataclasses.replace(
                t, position=_t(rotation @ np.asarray(t.position) + offset), direction=_t(rotation @ np.asarray(t.direction))
            )
            for t in entry.thrusters
        ]
    if entry is not None and entry.dry:
        return body
    if entry is not None and entry.lumped is not None:
        # From the description's body frame into the link's: the point moved, the axes turned.
        lumped = entry.lumped
        point = None if lumped.point is None else _t(rotation @ np.asarray(lumped.point) + offset)
        axes = rotation @ np.asarray(lumped.axes, dtype=np.float64)
        body.lumped = dataclasses.replace(lumped, point=point, axes=axes)
    segments: list[Segment] = []
    volume, moment = 0.0, np.zeros(3)
    first = int(model.body_geomadr[i])
    for g in range(first, first + int(model.body_geomnum[i])):
        if not (model.geom_contype[g] or model.geom_conaffinity[g]):
            continue
        kind = int(model.geom_type[g])
        segment, v = _primitive(mujoco, kind, model.geom_size[g])
        if v < 0.0:
            if entry is not None and entry.describes_geometry:
                continue
            what = "mesh" if kind == mujoco.mjtGeom.mjGEOM_MESH else f"geom of type {mujoco.mjtGeom(kind).name}"
            raise DescriptionError(
                f"{source}: link {quoted(name)} has a collision {what}, which uwml cannot turn into segments: describe the link in a hydro file"
            )
        geom_rotation = rotation @ _rotation(model.geom_quat[g])
        geom_offset = rotation @ model.geom_pos[g] + offset
        volume += v
        moment += v * geom_offset
        if segment is not None and (entry is None or entry.strips):
            segments.append(_moved(segment, geom_rotation, geom_offset))
        elif entry is not None and entry.lumped is not None:
            shape = mujoco.mjtGeom(kind).name.removeprefix("mjGEOM_").lower()
            body.outlines.append((shape, np.array(model.geom_size[g]), geom_rotation, geom_offset))
    if entry is not None:
        segments += [_moved(s, rotation, offset) for s in entry.segments]
        if entry.volume is not None:
            if entry.cob is not None:
                cob = rotation @ np.asarray(entry.cob) + offset
            elif volume > 0.0:
                cob = moment / volume
            else:
                cob = body.own_com
            volume, moment = entry.volume, entry.volume * cob
        where = f"{hydro_source}: [links.{name}]"
        for key, per_segment in (("segment_cd", entry.segment_cd), ("segment_cm", entry.segment_cm)):
            if per_segment is not None and len(per_segment) != len(segments):
                raise DescriptionError(
                    f"{where}, key '{key}': must have one entry per segment of the link ({len(segments)}), got {len(per_segment)}"
                )
        if entry.cd_axial is not None:
            segments = [_segment_copy(segment, cd_axial=entry.cd_axial) for segment in segments]
        coefficients = []
        for index, segment in enumerate(segments):
            cd = entry.segment_cd[index] if entry.segment_cd is not None else entry.cd
            cm = entry.segment_cm[index] if entry.segment_cm is not None else entry.cm
            if cd is None and cm is None:
                coefficients.append(segment)
                continue
            coefficients.append(_with_coefficients(segment, cd, cm, where))
        segments = coefficients
    body.volume, body.cob_moment, body.segments = volume, moment, segments
    return body


def _assembled(
    bodies: list[_Body], link: str, hydro: dict[str, HydroLink], hydro_source: str, density: float, gravity: float
) -> dict[str, Any]:
    """The :class:`uwml.Link` fields (``mass``, ``com``, ``volume``, ``cob``, ``segments``,
    ``lumped``) of the description bodies fused into link ``link`` (``bodies[0]`` its own): masses
    with their centres mass-weighted, volumes (items' too) with their centres volume-weighted; a
    lumped model's point, when not given, the centre of buoyancy without the items (they add
    nothing to its hydrodynamics). Warns of bodies that add geometry beside a lumped model."""
    mass = sum(x.mass for x in bodies)
    com = sum((x.mass * x.com for x in bodies), np.zeros(3)) / mass if mass > 0.0 else np.zeros(3)
    items = [(item, position) for x in bodies for item, position in x.items]
    own_volume = sum(x.volume for x in bodies)
    own_moment = sum((x.cob_moment for x in bodies), np.zeros(3))
    volume = own_volume + sum(item.volume for item, _ in items)
    moment = own_moment + sum((item.volume * position for item, position in items), np.zeros(3))
    cob = _t(moment / volume) if volume > 0.0 else None
    segments = tuple(s for x in bodies for s in x.segments)
    lumped_bodies = [x for x in bodies if x.lumped is not None]
    if len(lumped_bodies) > 1:
        names = ", ".join(_table("links", x.name) for x in lumped_bodies)
        raise DescriptionError(
            f"{hydro_source}: {names} give lumped models to bodies fused into one link ({quoted(link)}); "
            "a link takes one lumped model: give it once, on one of them"
        )
    lumped = lumped_bodies[0].lumped if lumped_bodies else None
    if lumped is not None and lumped.point is None and items:
        own_mass = sum(x.own_mass for x in bodies)
        own_com = sum((x.own_mass * x.own_com for x in bodies), np.zeros(3)) / own_mass if own_mass > 0.0 else np.zeros(3)
        lumped = dataclasses.replace(lumped, point=_t(own_moment / own_volume if own_volume > 0.0 else own_com))
    if lumped_bodies:
        _warn_fused(bodies, lumped_bodies[0], link, hydro, hydro_source, density * gravity)
    thrusters = tuple(t for x in bodies for t in x.thrusters)
    return {"mass": mass, "com": _t(com), "volume": volume, "cob": cob, "segments": segments, "lumped": lumped, "thrusters": thrusters}


def _warn_fused(bodies: list[_Body], lumped: _Body, link: str, hydro: dict[str, HydroLink], hydro_source: str, weight: float) -> None:
    """A :class:`uwml.DescriptionWarning` for each body of a link with a lumped model that adds
    collision geometry (volume, strips) beside it while its hydro table (if any) says nothing of
    its water: the model most likely counts it already."""
    for x in bodies:
        entry = hydro.get(x.name)
        if x is lumped or (entry is not None and entry.describes_water) or (x.volume <= 0.0 and not x.segments):
            continue
        if x is bodies[0]:
            where = f"link {quoted(x.name)} has collision geometry beside the lumped model of link {quoted(lumped.name)}, fused into it"
        else:
            where = f"link {quoted(x.name)} is fused into link {quoted(link)} (a fixed joint), whose lumped model ({_table('links', lumped.name)}) describes the body"
        strips = f"{len(x.segments)} strip segment{'s' if len(x.segments) != 1 else ''} with the default coefficients"
        warnings.warn(
            f"{hydro_source}: {where}; its collision geometry adds {1000.0 * x.volume:.4g} L ({x.volume:.4g} m³, "
            f"{weight * x.volume:.4g} N of buoyancy) and {strips} beside that model, which most likely counts them already. "
            f"Set dry = true in {_table('links', x.name)} if the lumped model covers it, or strips = false there to keep its volume "
            "without strips",
            DescriptionWarning,
            stacklevel=5,
        )


def outlines_of(parts: dict[int, list[_Body]], body_name: list[str]) -> tuple[Outline, ...]:
    """The drawn shapes of the bodies described by their lumped models (``uwml describe``)."""
    return tuple(
        Outline(body_name[b], kind, _t(size), tuple(tuple(float(x) for x in row) for row in turn), _t(at))
        for b, bodies in parts.items()
        for x in bodies
        for kind, size, turn, at in x.outlines
    )


def _records(
    parts: dict[int, list[_Body]], body_name: list[str], own: dict[str, OwnInertial]
) -> tuple[tuple[PlacedItem, ...], tuple[MassOverride, ...]]:
    """The hydro file's items and mass overrides as the robot carries them (``uwml describe``)."""
    items, overrides = [], []
    for b, bodies in parts.items():
        link = body_name[b]
        for x in bodies:
            items += [PlacedItem(x.name, link, item.name, item.mass, item.volume, _t(position)) for item, position in x.items]
            inertial = own.get(x.name)
            if inertial is not None and inertial.overridden:
                overrides.append(MassOverride(x.name, link, inertial.described_mass, inertial.mass, _t(x.own_com), inertial.inertia_given))
    return tuple(items), tuple(overrides)
