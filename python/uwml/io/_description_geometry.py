"""How a description body becomes part of a uwml link (:mod:`uwml.io.descriptions`): its collision
primitives as segments and volume, moved into the link's frame, with a hydro file's entry
(:class:`~uwml.io.hydrofile.HydroLink`) applied."""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import NDArray

from ..model.lumped import LumpedModel
from ..model.parts import Segment
from ._description_io import DescriptionError, quoted
from .hydrofile import HydroLink

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
) -> _Body:
    """Body ``i``'s mass, volume and segments in its uwml link's frame (points ``R v + offset``)."""
    body = _Body(name=name, mass=float(model.body_mass[i]), com=rotation @ model.body_ipos[i] + offset)
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
    if entry is not None:
        segments += [_moved(s, rotation, offset) for s in entry.segments]
        if entry.volume is not None:
            if entry.cob is not None:
                cob = rotation @ np.asarray(entry.cob) + offset
            elif volume > 0.0:
                cob = moment / volume
            else:
                cob = body.com
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
