"""Plain descriptions of a serial chain: joints, links, their hydrodynamic geometry, the water.

These classes only hold and check numbers; the physics lives in the Rust core (``uwml._core``)
and, independently, in :mod:`uwml.reference`.

Frames (URDF style, without fixed rotations): every link frame is parallel to the world frame
when all joint angles are zero. Joint ``i`` sits at ``origin`` in the frame of link ``i - 1``
(the world frame for the first joint) and turns link ``i`` about ``axis`` (a unit vector in the
same frame) by ``q[i]``. Link ``i``'s geometry is given in its own frame, whose origin is joint
``i``. World z points up, against gravity.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

Vec3 = tuple[float, float, float]

__all__ = ["Joint", "Link", "Segment", "Vec3", "Water"]

#: Tolerance on unit length and orthogonality of the axes and normals given by users.
AXIS_TOLERANCE = 1e-6


def _vec3(value: object, name: str) -> Vec3:
    try:
        items = tuple(float(v) for v in value)  # type: ignore[union-attr]
    except TypeError as exc:
        raise TypeError(f"{name} must be a sequence of 3 numbers, got {value!r}") from exc
    except ValueError as exc:
        raise ValueError(f"{name} must be a sequence of 3 numbers, got {value!r}") from exc
    if len(items) != 3:
        raise ValueError(f"{name} must have 3 components, got {len(items)}")
    if not all(math.isfinite(v) for v in items):
        raise ValueError(f"{name} must be finite, got {items}")
    return (items[0], items[1], items[2])


def _scalar(value: object, name: str, *, positive: bool) -> float:
    try:
        x = float(value)  # type: ignore[arg-type]
    except (TypeError, ValueError) as exc:
        raise TypeError(f"{name} must be a number, got {value!r}") from exc
    if not math.isfinite(x):
        raise ValueError(f"{name} must be finite, got {x}")
    if positive and not x > 0.0:
        raise ValueError(f"{name} must be positive, got {x}")
    if not positive and x < 0.0:
        raise ValueError(f"{name} must be non-negative, got {x}")
    return x


def _pair(value: object, name: str) -> tuple:
    try:
        items = tuple(value)  # type: ignore[arg-type]
    except TypeError:
        raise TypeError(f"{name} must be a pair (two items), got {value!r}") from None
    if len(items) != 2:
        raise ValueError(f"{name} must hold 2 items, got {len(items)}")
    return items


def _dot(a: Vec3, b: Vec3) -> float:
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def _unit(value: object, name: str) -> Vec3:
    v = _vec3(value, name)
    norm = math.sqrt(_dot(v, v))
    if abs(norm - 1.0) > AXIS_TOLERANCE:
        raise ValueError(f"{name} must be a unit vector (|{name}| = 1 within {AXIS_TOLERANCE}), got norm {norm}")
    return (v[0] / norm, v[1] / norm, v[2] / norm)


@dataclass(frozen=True)
class Joint:
    """A revolute joint: its origin and unit axis in the parent link's frame at q = 0."""

    origin: Vec3
    axis: Vec3

    def __post_init__(self) -> None:
        object.__setattr__(self, "origin", _vec3(self.origin, "joint.origin"))
        object.__setattr__(self, "axis", _unit(self.axis, "joint.axis"))


@dataclass(frozen=True)
class Segment:
    """Hydrodynamic geometry of a straight link (strip theory), in the link's frame.

    A slice at arc length ``s`` in ``[0, length]`` lies at ``start + s * axis``. ``normals`` are
    the two principal directions of cross-flow (orthonormal, perpendicular to ``axis``);
    ``widths[k]`` is the frontal width seen by flow along ``normals[k]`` (the drag reference
    width); ``area`` is the cross-section area used for added mass.
    """

    start: Vec3
    axis: Vec3
    length: float
    normals: tuple[Vec3, Vec3]
    widths: tuple[float, float]
    area: float

    def __post_init__(self) -> None:
        object.__setattr__(self, "start", _vec3(self.start, "segment.start"))
        axis = _unit(self.axis, "segment.axis")
        object.__setattr__(self, "axis", axis)
        object.__setattr__(self, "length", _scalar(self.length, "segment.length", positive=True))
        normals = _pair(self.normals, "segment.normals")
        n1 = _unit(normals[0], "segment.normals[0]")
        n2 = _unit(normals[1], "segment.normals[1]")
        for name, a, b in (("normals[0]·axis", n1, axis), ("normals[1]·axis", n2, axis), ("normals[0]·normals[1]", n1, n2)):
            if abs(_dot(a, b)) > AXIS_TOLERANCE:
                raise ValueError(f"segment.{name} must be 0 (orthonormal normals perpendicular to the axis), got {_dot(a, b)}")
        object.__setattr__(self, "normals", (n1, n2))
        widths = _pair(self.widths, "segment.widths")
        object.__setattr__(
            self,
            "widths",
            (_scalar(widths[0], "segment.widths[0]", positive=True), _scalar(widths[1], "segment.widths[1]", positive=True)),
        )
        object.__setattr__(self, "area", _scalar(self.area, "segment.area", positive=True))


@dataclass(frozen=True)
class Link:
    """A rigid link: mass and centre of mass, displaced volume and centre of buoyancy, and
    optionally a straight segment that meets the water (``None``: no drag or added mass).

    ``cob`` defaults to ``com`` (as the paper assumes).
    """

    mass: float
    com: Vec3
    volume: float
    cob: Vec3 | None = None
    segment: Segment | None = None

    def __post_init__(self) -> None:
        object.__setattr__(self, "mass", _scalar(self.mass, "link.mass", positive=False))
        object.__setattr__(self, "com", _vec3(self.com, "link.com"))
        object.__setattr__(self, "volume", _scalar(self.volume, "link.volume", positive=False))
        cob = self.com if self.cob is None else self.cob
        object.__setattr__(self, "cob", _vec3(cob, "link.cob"))
        if self.segment is not None and not isinstance(self.segment, Segment):
            raise TypeError(f"link.segment must be a uwml.Segment or None, got {type(self.segment).__name__}")


@dataclass(frozen=True)
class Water:
    """The fluid: density [kg/m³] and gravitational acceleration [m/s²]."""

    density: float = 1000.0
    gravity: float = 9.81

    def __post_init__(self) -> None:
        object.__setattr__(self, "density", _scalar(self.density, "water.density", positive=True))
        object.__setattr__(self, "gravity", _scalar(self.gravity, "water.gravity", positive=False))
