"""Plain descriptions of a robot: joints, links, their hydrodynamic geometry, the water.

These classes only hold and check numbers; the physics lives in the Rust core (``uwml._core``)
and, independently, in :mod:`uwml.reference`.

Frames (URDF style, without fixed rotations; docs/model.md sections 2 and 10): every link frame is
parallel to the base frame (the world frame for a fixed, upright base) when all joint positions
are zero. Joint ``i`` sits at ``origin`` in the frame of its parent (link ``parent``, or the base
for ``-1``; by default the previous link, so that a list of joints is a serial chain) and moves
link ``i``: a revolute joint turns it about ``axis`` (a unit vector in the parent's frame) by
``q[i]``, a prismatic joint slides it along ``axis`` by ``q[i]``. Link ``i``'s geometry is given
in its own frame, whose origin is joint ``i``. World z points up, against gravity.
"""

from __future__ import annotations

import math
from collections.abc import Iterable
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from .._checks import Vec3
from .._checks import check_name as _check_name
from .._checks import scalar as _scalar
from .._checks import vec3 as _vec3
from ..domains import MAX_COEFFICIENT, MAX_DENSITY, MAX_GRAVITY
from ..plausibility import check_density
from ..sea.conditions import SEA_WATER_DENSITY
from .lumped import LumpedModel
from .thrusters import Thruster

__all__ = ["CIRCULAR_DEFAULTS", "FRESH_WATER", "RECTANGULAR_DEFAULTS", "SEA_WATER", "SECTIONS", "Joint", "Link", "Segment", "Vec3", "Water"]

#: Tolerance on unit length and orthogonality of the axes and normals given by users.
AXIS_TOLERANCE = 1e-6

#: How far from 1 the computed norm of a normalized vector can be (a few ulps).
_UNIT_ROUNDING = 4.0 * 2.0**-52

#: The section kinds of a :class:`Segment` (docs/model.md section 10, "Describing a robot").
SECTIONS = ("rectangular", "circular")
#: The joint kinds of a :class:`Joint`.
JOINT_KINDS = ("revolute", "prismatic")

#: Default ``(Cd, Cm)`` of a rectangular section: the paper's fitted values, rounded (Cd =
#: 2.19747 ± 0.00551, Cm = 0.50025 ± 0.00344 on the UWML's box-section links; those of
#: :func:`uwml.paper_leg`).
RECTANGULAR_DEFAULTS = (2.2, 0.5)
#: Default ``(Cd, Cm)`` of a circular section: Cm = 1 is the potential-flow added-mass
#: coefficient of a circular cylinder in cross-flow (exact; DNV-RP-C205, appendix D, the
#: added-mass table of two-dimensional bodies: circle, ``C_A = 1``); Cd = 1.2 is the steady
#: cross-flow drag coefficient of a smooth circular cylinder at subcritical Reynolds numbers
#: (roughly 1e3 < Re < 2e5: a 0.1 m link at 0.1-2 m/s in cold water), the plateau of the
#: drag-versus-Reynolds curve of DNV-RP-C205 section 6.7 and of Hoerner, *Fluid-Dynamic Drag*
#: (1965), ch. 3. Past the drag crisis (Re above about 3e5) a smooth cylinder's Cd falls to
#: about 0.65 (rough: about 1.05): give the segment's own ``cd`` there.
CIRCULAR_DEFAULTS = (1.2, 1.0)


def _pair(value: object, name: str) -> tuple[object, ...]:
    try:
        if not isinstance(value, Iterable):
            raise TypeError(f"{type(value).__name__!r} object is not iterable")
        items = tuple(value)
    except TypeError:
        raise TypeError(f"{name} must be a pair (two items), got {value!r}") from None
    if len(items) != 2:
        raise ValueError(f"{name} must hold 2 items, got {len(items)}")
    return items


def _items(value: object, kind: type, name: str) -> tuple[Any, ...]:
    """``value`` as a tuple of ``kind`` (``uwml.Segment``, ``uwml.Thruster``), or a TypeError
    naming ``name`` and the item that is not one."""
    try:
        items: tuple[Any, ...] = tuple(value)  # type: ignore[arg-type]
    except TypeError:
        raise TypeError(f"{name} must be a sequence of uwml.{kind.__name__}, got {type(value).__name__}") from None
    for index, item in enumerate(items):
        if not isinstance(item, kind):
            raise TypeError(f"{name}[{index}] must be a uwml.{kind.__name__}, got {type(item).__name__}")
    return items


def _dot(a: Vec3, b: Vec3) -> float:
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def _unit(value: object, name: str) -> Vec3:
    v = _vec3(value, name)
    norm = math.sqrt(_dot(v, v))
    if abs(norm - 1.0) > AXIS_TOLERANCE:
        raise ValueError(f"{name} must be a unit vector (|{name}| = 1 within {AXIS_TOLERANCE}), got norm {norm}")
    if abs(norm - 1.0) <= _UNIT_ROUNDING:
        # Unit to rounding already (a normalized vector, e.g. one read back from a model file):
        # kept as it is, so that normalizing twice changes nothing.
        return v
    return (v[0] / norm, v[1] / norm, v[2] / norm)


@dataclass(frozen=True)
class Joint:
    """A joint: its origin and unit axis in the parent's frame at q = 0, its parent and kind.

    ``parent`` is the index of the parent link, ``-1`` for the base, or ``None`` (the default)
    for the previous link (the base for the first joint), so that a list of joints without
    parents is a serial chain. ``kind`` is ``"revolute"`` (turns about ``axis`` by ``q``, the
    generalized force is a torque [N·m]) or ``"prismatic"`` (slides along ``axis`` by ``q``, the
    generalized force is a force [N]).

    The limits a description gives (URDF ``<limit lower upper velocity effort>``, MJCF ``range``
    and ``actuatorfrcrange``), each optional: ``range`` ``(lower, upper)`` [rad or m],
    ``velocity_limit`` [rad/s or m/s] and ``effort_limit`` [N·m or N], positive. uwml does not
    enforce them (its evaluations take any state); they set the bounds of its
    :class:`uwml.PlausibilityWarning` (:mod:`uwml.plausibility`).
    """

    origin: Vec3
    axis: Vec3
    parent: int | None = None
    kind: str = "revolute"
    #: A name (a URDF or MJCF joint's), or None.
    name: str | None = None
    #: ``(lower, upper)`` positions the description allows [rad or m], or None.
    range: tuple[float, float] | None = None
    #: The description's largest speed [rad/s or m/s], or None.
    velocity_limit: float | None = None
    #: The description's largest torque [N·m] or force [N], or None.
    effort_limit: float | None = None

    def __post_init__(self) -> None:
        _check_name(self.name, "joint.name")
        object.__setattr__(self, "origin", _vec3(self.origin, "joint.origin"))
        object.__setattr__(self, "axis", _unit(self.axis, "joint.axis"))
        if self.parent is not None:
            if isinstance(self.parent, bool) or not isinstance(self.parent, (int, np.integer)):
                raise TypeError(f"joint.parent must be a link index (int), -1 for the base, or None; got {self.parent!r}")
            if self.parent < -1:
                raise ValueError(f"joint.parent must be -1 (the base) or a link index >= 0, got {self.parent}")
            object.__setattr__(self, "parent", int(self.parent))
        if self.kind not in JOINT_KINDS:
            raise ValueError(f"joint.kind must be one of {JOINT_KINDS}, got {self.kind!r}")
        if self.range is not None:
            lower, upper = (_scalar(x, "joint.range", positive=False, signed=True) for x in _pair(self.range, "joint.range"))
            if not lower < upper:
                raise ValueError(f"joint.range must be (lower, upper) with lower < upper, got ({lower}, {upper})")
            object.__setattr__(self, "range", (lower, upper))
        for limit in ("velocity_limit", "effort_limit"):
            if getattr(self, limit) is not None:
                object.__setattr__(self, limit, _scalar(getattr(self, limit), f"joint.{limit}", positive=True))


def _coefficient_pair(value: object, name: str, section: str, default: float) -> tuple[float, float]:
    """A coefficient given as ``None`` (the section's default), one number, or one per normal."""
    if value is None:
        return (default, default)
    if isinstance(value, (int, float, np.floating, np.integer)) and not isinstance(value, bool):
        x = _scalar(value, name, positive=False)
        return (x, x)
    if section == "circular":
        raise TypeError(f"{name} of a circular segment must be one number (the cross-flow principle has one coefficient), got {value!r}")
    pair = _pair(value, name)
    return (_scalar(pair[0], f"{name}[0]", positive=False), _scalar(pair[1], f"{name}[1]", positive=False))


@dataclass(frozen=True, init=False)
class Segment:
    """Hydrodynamic geometry of a straight piece of a link (strip theory), in the link's frame.

    A slice at arc length ``s`` in ``[0, length]`` lies at ``start + s * axis``.

    ``section="rectangular"`` (the paper's links; independence principle, docs/model.md section 3): ``normals``
    are the two principal directions of cross-flow (orthonormal, perpendicular to ``axis``);
    ``widths[k]`` is the frontal width seen by flow along ``normals[k]`` (the drag reference
    width); ``area`` is the cross-section area used for added mass.

    ``section="circular"`` (a cylinder; cross-flow principle on the whole normal velocity,
    docs/model.md section 10, "Describing a robot"): give ``diameter``; ``area`` defaults to
    ``π diameter² / 4``; ``normals`` and ``widths`` are not used (they are set to a pair of
    normals and ``(diameter, diameter)``).

    ``cd`` and ``cm``: the segment's own drag and added-mass coefficients, used when an evaluation
    is not given coefficients. One number, or (rectangular only) one per normal direction;
    ``None`` takes the section's documented default (:data:`RECTANGULAR_DEFAULTS`,
    :data:`CIRCULAR_DEFAULTS`).

    ``cd_axial``: the optional axial drag (docs/model.md section 12.2), ``−½ ρ cd_axial
    axial_area |u·v| (u·v) u`` along the axis at the midpoint (strips have no force along their
    axis); 0 (default): none. ``axial_area`` [m²]: its reference area, default the section area.

    Construction validates every value and stores it normalized: ``normals``, ``widths``,
    ``area``, ``cd`` and ``cm`` always hold their final form (pairs and numbers, the section's
    defaults filled in), whatever form they were given in; ``diameter`` is None for a
    rectangular section.
    """

    start: Vec3
    axis: Vec3
    length: float
    normals: tuple[Vec3, Vec3]
    widths: tuple[float, float]
    area: float
    section: str
    diameter: float | None
    cd: tuple[float, float]
    cm: tuple[float, float]
    cd_axial: float
    axial_area: float

    def __init__(
        self,
        start: Iterable[float],
        axis: Iterable[float],
        length: float,
        normals: Iterable[Iterable[float]] | None = None,
        widths: Iterable[float] | None = None,
        area: float | None = None,
        section: str = "rectangular",
        diameter: float | None = None,
        cd: float | Iterable[float] | None = None,
        cm: float | Iterable[float] | None = None,
        cd_axial: float = 0.0,
        axial_area: float | None = None,
    ) -> None:
        if section not in SECTIONS:
            raise ValueError(f"segment.section must be one of {SECTIONS}, got {section!r}")
        object.__setattr__(self, "section", section)
        object.__setattr__(self, "start", _vec3(start, "segment.start"))
        unit_axis = _unit(axis, "segment.axis")
        object.__setattr__(self, "axis", unit_axis)
        object.__setattr__(self, "length", _scalar(length, "segment.length", positive=True))
        if section == "circular":
            self._circular(unit_axis, widths, area, diameter)
        else:
            self._rectangular(unit_axis, normals, widths, area, diameter)
        cd_default, cm_default = RECTANGULAR_DEFAULTS if section == "rectangular" else CIRCULAR_DEFAULTS
        object.__setattr__(self, "cd", _coefficient_pair(cd, "segment.cd", section, cd_default))
        object.__setattr__(self, "cm", _coefficient_pair(cm, "segment.cm", section, cm_default))
        axial = _scalar(cd_axial, "segment.cd_axial", positive=False)
        if axial > MAX_COEFFICIENT:
            raise ValueError(f"segment.cd_axial must be at most {MAX_COEFFICIENT:g} (measured coefficients are of order 1), got {axial}")
        object.__setattr__(self, "cd_axial", axial)
        reference = self.area if axial_area is None else _scalar(axial_area, "segment.axial_area", positive=False)
        object.__setattr__(self, "axial_area", reference)

    def _rectangular(self, axis: Vec3, normals: object, widths: object, area: object, diameter: object) -> None:
        for name, value in (("normals", normals), ("widths", widths), ("area", area)):
            if value is None:
                raise ValueError(f"a rectangular segment needs segment.{name}")
        if diameter is not None:
            raise ValueError("segment.diameter is for circular sections; a rectangular segment takes widths and area")
        normal_pair = _pair(normals, "segment.normals")
        n1 = _unit(normal_pair[0], "segment.normals[0]")
        n2 = _unit(normal_pair[1], "segment.normals[1]")
        for name, a, b in (("normals[0]·axis", n1, axis), ("normals[1]·axis", n2, axis), ("normals[0]·normals[1]", n1, n2)):
            if abs(_dot(a, b)) > AXIS_TOLERANCE:
                raise ValueError(f"segment.{name} must be 0 (orthonormal normals perpendicular to the axis), got {_dot(a, b)}")
        object.__setattr__(self, "normals", _exact_frame(axis, n1, n2))
        width_pair = _pair(widths, "segment.widths")
        object.__setattr__(
            self,
            "widths",
            (_scalar(width_pair[0], "segment.widths[0]", positive=True), _scalar(width_pair[1], "segment.widths[1]", positive=True)),
        )
        object.__setattr__(self, "area", _scalar(area, "segment.area", positive=True))
        object.__setattr__(self, "diameter", None)

    def _circular(self, axis: Vec3, widths: Iterable[float] | None, area: object, diameter: object) -> None:
        if diameter is None:
            raise ValueError("a circular segment needs segment.diameter")
        d = _scalar(diameter, "segment.diameter", positive=True)
        object.__setattr__(self, "diameter", d)
        section_area = math.pi * d * d / 4.0 if area is None else _scalar(area, "segment.area", positive=True)
        object.__setattr__(self, "area", section_area)
        if widths is not None and tuple(widths) != (d, d):
            raise ValueError(f"segment.widths of a circular segment are (diameter, diameter); got {widths!r}")
        object.__setattr__(self, "widths", (d, d))
        object.__setattr__(self, "normals", _normals_of(axis))


def _exact_frame(axis: Vec3, n1: Vec3, n2: Vec3) -> tuple[Vec3, Vec3]:
    """The normals made an exact orthonormal frame with the unit ``axis`` (Gram-Schmidt, as the
    core does): ``n1`` without its component along the axis, renormalized; ``n2 = ±axis × n1`` on
    the side it was given. The strip integrals' identities assume an exact frame; normals within
    :data:`AXIS_TOLERANCE` of one would otherwise be used as given. A frame exact to rounding
    already (one read back from a model file) is kept as it is, so that this is idempotent."""
    along = _dot(n1, axis)
    if abs(along) > _UNIT_ROUNDING:
        n1 = _unit(tuple(n - along * a for n, a in zip(n1, axis, strict=True)), "segment.normals[0]")
    cross = (axis[1] * n1[2] - axis[2] * n1[1], axis[2] * n1[0] - axis[0] * n1[2], axis[0] * n1[1] - axis[1] * n1[0])
    if max(abs(c - n) for c, n in zip(cross, n2, strict=True)) <= _UNIT_ROUNDING:
        return n1, n2
    sign = 1.0 if _dot(cross, n2) >= 0.0 else -1.0
    return n1, (sign * cross[0], sign * cross[1], sign * cross[2])


def _normals_of(axis: Vec3) -> tuple[Vec3, Vec3]:
    """Two unit normals that make ``(axis, n0, n1)`` orthonormal (any pair: a circular section
    does not depend on them)."""
    a = np.asarray(axis)
    helper = np.eye(3)[int(np.argmin(np.abs(a)))]
    n0 = helper - a * float(a @ helper)
    n0 /= np.linalg.norm(n0)
    n1 = np.cross(a, n0)
    return ((float(n0[0]), float(n0[1]), float(n0[2])), (float(n1[0]), float(n1[1]), float(n1[2])))


@dataclass(frozen=True)
class Link:
    """A rigid body: mass and centre of mass, displaced volume and centre of buoyancy, and the
    straight segments that meet the water.

    ``cob`` defaults to ``com`` (as the paper assumes). ``segments``: any number of them, in the
    link's frame. ``lumped``: Fossen's lumped model of the body (:class:`uwml.LumpedModel`,
    docs/model.md section 12.1), for what is not slender; its reference point defaults to
    ``cob``. ``thrusters``: the :class:`uwml.Thruster` s it carries, in its frame (docs/model.md
    section 13.1).
    """

    mass: float
    com: Vec3
    volume: float
    cob: Vec3 | None = None
    segments: tuple[Segment, ...] = field(default=())
    #: A name (a URDF link's, an MJCF body's), or None.
    name: str | None = None
    lumped: LumpedModel | None = None
    thrusters: tuple[Thruster, ...] = field(default=())

    def __post_init__(self) -> None:
        _check_name(self.name, "link.name")
        object.__setattr__(self, "mass", _scalar(self.mass, "link.mass", positive=False))
        object.__setattr__(self, "com", _vec3(self.com, "link.com"))
        object.__setattr__(self, "volume", _scalar(self.volume, "link.volume", positive=False))
        cob = self.com if self.cob is None else self.cob
        object.__setattr__(self, "cob", _vec3(cob, "link.cob"))
        object.__setattr__(self, "segments", _items(self.segments, Segment, "link.segments"))
        object.__setattr__(self, "thrusters", _items(self.thrusters, Thruster, "link.thrusters"))
        if self.lumped is not None:
            if not isinstance(self.lumped, LumpedModel):
                raise TypeError(f"link.lumped must be a uwml.LumpedModel or None, got {type(self.lumped).__name__}")
            object.__setattr__(self, "lumped", self.lumped.at(self.cob if self.cob is not None else self.com))


@dataclass(frozen=True)
class Water:
    """The fluid: density [kg/m³] and gravitational acceleration [m/s²]."""

    density: float = 1000.0
    gravity: float = 9.81

    def __post_init__(self) -> None:
        object.__setattr__(self, "density", _scalar(self.density, "water.density", positive=True))
        object.__setattr__(self, "gravity", _scalar(self.gravity, "water.gravity", positive=False))
        # docs/domains.md, "Model values": beyond these, forces of ordinary states overflow.
        for name, limit, unit in (("density", MAX_DENSITY, "kg/m³"), ("gravity", MAX_GRAVITY, "m/s²")):
            if getattr(self, name) > limit:
                raise ValueError(f"water.{name} must be at most {limit:g} {unit}, got {getattr(self, name)!r}")
        check_density(self.density)


#: The default fluid: fresh water as in the paper, 1000 kg/m³ under g = 9.81 m/s² (immutable).
FRESH_WATER = Water()
#: Sea water (1025 kg/m³), for the hydrodynamics and the pressure at depth alike.
SEA_WATER = Water(density=SEA_WATER_DENSITY)
