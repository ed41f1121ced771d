"""The hydro file: what a robot description (URDF, MJCF) lacks, for :mod:`uwml.io.descriptions`.

TOML, read with ``tomllib``: per link by name (a URDF link's, an MJCF body's; a link fused into
its parent may have its own entry), per joint by name, and the water. Every vector is in that
link's own description frame, as in the URDF/MJCF (:mod:`uwml.io.descriptions` turns it into uwml's
frames)::

    # uwml hydro file: SI units
    [links.thigh]
    cd = 2.2                  # every segment of this link: one number, or [along n0, along n1]
    cm = [0.5, 0.6]
    cd_axial = 0.1            # every segment's axial drag (docs/model.md section 12.2; default none)
    volume = 0.00713          # m³, displaced volume (instead of the primitives' sum)
    cob = [0.506, 0.0, 0.0]   # m, centre of buoyancy (default: the primitives' centroid, or the COM)

    [links.camera]
    dry = true                # no segments, no volume (a link out of the water, or to ignore)

    [links.vehicle]           # a bluff body: Fossen's lumped model (uwml.LumpedModel, docs/model.md
    strips = false            # section 12.1) instead of strips from its collision geometry (which
                              # still gives its volume); strips = true keeps both
    [links.vehicle.lumped]    # the keys of a model file's lumped table (uwml.io.modelfile), in the
    point = [0.0, 0.0, 0.02]  # link's description frame; point defaults to the link's centre of
    added_mass = [[6.36, 0, 0, 0, 0, 0], ...]   # buoyancy. Magnitudes: SNAME's X_u̇ = −6.36
    linear_damping = [[13.7, 0, 0, 0, 0, 0], ...]
    quadratic_damping = [141.0, 217.0, 190.0, 1.19, 0.47, 1.5]

    [links.hull]              # a link drawn as a mesh: give its volume and segments
    volume = 0.29
    cob = [0.0, 0.0, 0.05]
    segment_cd = [0.9, [1.1, 1.3]]   # per segment, in order (primitives, then the segments below)

    [[links.hull.segments]]   # the keys of a uwml model file's segments (uwml.io.modelfile)
    section = "circular"
    start = [-0.9, 0.0, 0.0]
    axis = [1.0, 0.0, 0.0]
    length = 1.8
    diameter = 0.6
    area = 0.283
    cd = [0.9, 0.9]
    cm = [1.0, 1.0]

    [[links.hull.segments]]
    section = "rectangular"
    start = [0.0, -0.3, 0.0]
    axis = [0.0, 1.0, 0.0]
    length = 0.6
    normals = [[1.0, 0.0, 0.0], [0.0, 0.0, 1.0]]
    widths = [0.2, 0.4]
    area = 0.08
    cd = [1.1, 1.3]
    cm = [1.0, 1.0]

    [links.frame]             # masses (docs/model.md section 13), also on a dry link
    mass = 11.2               # kg, the link's mass in place of the description's inertial
    com = [0.0, 0.0, -0.02]   # m, its centre of mass (default: the description's)
    inertia = [0.21, 0.25, 0.3]   # kg·m², principal moments about the COM along the frame's axes
                              # (default: the description's inertia scaled by the new mass)

    [[links.frame.items]]     # a point item: lead, foam, a DVL, a battery can
    name = "lead"             # optional: a label for messages and uwml describe
    mass = 0.8                # kg, at least 0: its mass at position (parallel axis theorem)
    volume = 0.00007          # m³, at least 0: ρ V of buoyancy at position
    position = [0.1, 0.0, -0.1]
    inertia = [1e-4, 1e-4, 1e-4]  # optional: its own moments about position (a point has none)

    [[links.frame.thrusters]] # a thruster (docs/model.md section 13.1): up to 64 per link
    name = "t1"               # optional
    position = [0.156, -0.111, 0.085]   # m, where it pushes
    direction = [0.7071, -0.7071, 0.0]  # its positive thrust's direction (normalized)
    max_forward = 51.5        # N, optional limits on |thrust| (default none)
    max_reverse = 40.2
    time_constant = 0.05      # s, optional first-order lag (default none)
    [links.frame.thrusters.curve]       # optional; default uwml.ThrustCurve.t200()
    kind = "table"            # linear interpolation; or kind = "polynomial" with forward,
    commands = [-1.0, 0.0, 1.0]         # reverse (coefficients in u − dead_band, lowest degree
    thrusts = [-40.2, 0.0, 51.5]        # first) and dead_band

A segment's coefficients: ``segment_cd``/``segment_cm`` of its link if given, else the link's
``cd``/``cm``, else its own (hydro segments), else the documented defaults per section
(:data:`uwml.model.RECTANGULAR_DEFAULTS`, :data:`uwml.model.CIRCULAR_DEFAULTS`). A circular
segment takes one number (a pair must have two equal entries); every coefficient is between 0
and ``MAX_COEFFICIENT`` (1e3: measured ones are of order 1), a ``volume`` at most ``MAX_VOLUME``
(1e6 m³), a ``cob`` coordinate at most ``MAX_LENGTH`` (1e4 m): the model's own bounds
(``uwml._core``), checked here so that the error names the key. A link takes at most
:data:`uwml.MAX_SEGMENTS` segments (and as many per-segment coefficients) and :data:`MAX_ITEMS`
(64) items.

Masses. ``mass`` (above 0; ``com`` and ``inertia`` need it) replaces the description's inertial
of that link before its items are added; ``inertia``'s moments are positive and each at most the
sum of the other two; a link the description leaves massless needs ``inertia`` with its mass.
Each item adds its mass at its position to the link's rigid-body inertia (the parallel axis
theorem; its own ``inertia`` besides) and ``ρ V`` of buoyancy there: the link's volume and centre
of buoyancy become the volume-weighted combination of its own and its items'. Items add nothing
to drag or added mass (a lumped model's point, when not given, stays the centre of buoyancy
without them). The robot's link masses, centres of mass, volumes and centres of buoyancy include
them, and so does the MuJoCo model compiled from the description
(:func:`uwml.robot.files.model_and_robot`, a simulation's); a compiled ``mujoco.MjModel``
(``from_mujoco``) keeps its own masses, so a mass override or items with mass are refused there.
A link fused into a body with a lumped model whose table says nothing of its water (no ``dry``,
``strips``, ``volume``, segments or coefficients) adds its collision geometry's volume and strips
beside the model: a :class:`uwml.DescriptionWarning` names it, what it adds and the fix. Unknown link names
(``world`` too: the world is not a link of the robot), unknown keys, missing values and wrong
types are :class:`DescriptionError`\\ s naming the file, the table and the key. Per joint by
name, ``[joints.NAME]`` gives that joint's losses (``uwml.JointLosses``: the same tables as the
model file's ``[joints.losses]``: ``epsilon``, ``[joints.NAME.drive]``, ``[joints.NAME.oil]``,
``[joints.NAME.seal]`` with their dataclasses' fields), kept as the robot's own
(``Robot.losses``). ``[water]`` gives the robot's water (``Robot.water``, which every evaluation
uses unless given another)::

    [water]
    density = 1025.0   # kg/m³, 900 to 1300 (default 1000, fresh water)
    gravity = 9.81     # m/s², 9.7 to 9.9 (default 9.81)

A density or gravity outside those ranges is taken for a unit mistake (g/cm³, g, ft/s²) and is an
error; another fluid or planet is a :class:`uwml.Water` given in code. ``[base]`` says how a
simulation holds the robot's base (:meth:`uwml.sim.mujoco.Simulation.from_file`)::

    [base]
    floating = true    # the root body on a free joint: a vehicle floating freely (default false)

The file itself: UTF-8 text (other bytes are an error naming the offset), a regular file (a
directory, a named pipe or a device is refused, not waited on), valid TOML (arrays nested too
deeply to read are an error too). Quoted values in messages are cut short.
"""

from __future__ import annotations

import math
import os
import re
import tomllib
from dataclasses import dataclass, field
from typing import Any

from .._checks import shown
from .._core import MAX_COEFFICIENT, MAX_SEGMENTS, MAX_VOLUME
from ..model.joint_losses import JointLosses
from ..model.lumped import LumpedModel
from ..model.parts import Segment, Water
from ..model.thrusters import Thruster
from ._description_io import DescriptionError, clipped, read_regular
from ._hydro_masses import MAX_ITEMS, HydroItem, _point, _volume, read_items, read_override
from ._model_tables import WATER_DENSITY_RANGE, WATER_GRAVITY_RANGE, _float, _losses, _lumped, _pair, _Reader, _segment, _water, thrusters

__all__ = [
    "MAX_ITEMS",
    "WATER_DENSITY_RANGE",
    "WATER_GRAVITY_RANGE",
    "DescriptionError",
    "HydroFile",
    "HydroItem",
    "HydroLink",
    "read_hydro",
]

_LINK_KEYS = (
    "cd",
    "cm",
    "cd_axial",
    "segment_cd",
    "segment_cm",
    "volume",
    "cob",
    "dry",
    "segments",
    "strips",
    "lumped",
    "mass",
    "com",
    "inertia",
    "items",
    "thrusters",
)
#: The keys that say how a link meets the water (a link fused into a lumped body without any of
#: them adds its collision geometry unasked, and is warned of).
_WATER_KEYS = ("cd", "cm", "cd_axial", "segment_cd", "segment_cm", "volume", "dry", "segments", "strips", "lumped")


@dataclass(frozen=True)
class HydroLink:
    """One link's entry of a hydro file (vectors in the link's description frame)."""

    cd: float | tuple[float, float] | None = None
    cm: float | tuple[float, float] | None = None
    #: Every segment's axial drag coefficient (docs/model.md section 12.2), its area the section's.
    cd_axial: float | None = None
    segment_cd: tuple[float | tuple[float, float], ...] | None = None
    segment_cm: tuple[float | tuple[float, float], ...] | None = None
    volume: float | None = None
    cob: tuple[float, float, float] | None = None
    dry: bool = False
    segments: tuple[Segment, ...] = field(default=())
    #: Whether the link's collision geometry gives strip segments (false: its volume only, for a
    #: body described by its lumped model, so that nothing is counted twice).
    strips: bool = True
    #: Fossen's lumped model, in the link's description frame.
    lumped: LumpedModel | None = None
    #: The link's mass [kg] in place of the description's (None: the description's), its centre
    #: of mass [m] and principal moments about it along the frame's axes [kg·m²] (None: the
    #: description's centre of mass; its inertia scaled by the new mass).
    mass: float | None = None
    com: tuple[float, float, float] | None = None
    inertia: tuple[float, float, float] | None = None
    #: Point items (lead, foam, a DVL): mass and buoyancy at a point (docs/model.md section 13).
    items: tuple[HydroItem, ...] = field(default=())
    #: Thrusters (docs/model.md section 13.1), in the link's description frame.
    thrusters: tuple[Thruster, ...] = field(default=())
    #: Whether the table says how the link meets the water (any of the keys that set its
    #: segments, coefficients or volume, or ``dry``), not only its masses.
    describes_water: bool = False

    @property
    def describes_geometry(self) -> bool:
        """Whether the entry stands in for the link's geometry (a mesh link may then load)."""
        return self.dry or self.volume is not None


@dataclass(frozen=True)
class HydroFile:
    """A hydro file: per link by name (:class:`HydroLink`), per joint by name (its
    :class:`uwml.JointLosses`), and the water (None: not given)."""

    links: dict[str, HydroLink] = field(default_factory=dict)
    joints: dict[str, JointLosses] = field(default_factory=dict)
    water: Water | None = None
    source: str = "<string>"
    #: ``[base] floating``: simulate the description's root body on a free joint.
    floating: bool = False


def _coefficient(value: Any) -> float | tuple[float, float]:
    if isinstance(value, list):
        first, second = _pair(value)
        return _in_coefficient_range(first, "each "), _in_coefficient_range(second, "each ")
    return _in_coefficient_range(_float(value), "each ")


def _axial(value: Any) -> float:
    return _in_coefficient_range(_float(value), "")


def _in_coefficient_range(x: float, each: str) -> float:
    if not (math.isfinite(x) and 0.0 <= x <= MAX_COEFFICIENT):
        raise ValueError(f"{each}between 0 and {MAX_COEFFICIENT:g}")
    return x


def _coefficients(value: Any) -> tuple[float | tuple[float, float], ...]:
    if not isinstance(value, list):
        raise TypeError("not an array")
    return tuple(_coefficient(v) for v in value)


def _boolean(value: Any) -> bool:
    if not isinstance(value, bool):
        raise TypeError("not true or false")
    return value


def _hydro_lumped(source: str, where: str, table: object) -> LumpedModel:
    """A ``lumped`` table of a link, its ``point`` within ``MAX_LENGTH`` (the model refuses it
    later, naming the description, not this file)."""
    if isinstance(table, dict) and "point" in table:
        _Reader(source, where, table, DescriptionError).get("point", _point, "an array of 3 numbers [m]")
    return _lumped(source, where, table, DescriptionError)


def _not(what: str) -> Any:
    raise TypeError(f"not {what}")


def _table(kind: str, name: str) -> str:
    """``[links.NAME]`` as it would be written, the name quoted short if it is not a bare key."""
    return f"[{kind}.{name}]" if re.fullmatch(r"[A-Za-z0-9_-]{1,60}", name) else f"[{kind}.{shown(name, 40)}]"


def _hydro_water(source: str, table: object) -> Water:
    # The model file's rule: uwml.io.modelfile.WATER_DENSITY_RANGE and WATER_GRAVITY_RANGE.
    return _water(source, "[water]", table, DescriptionError)


def _toml(text: str, source: str) -> dict[str, Any]:
    try:
        return tomllib.loads(text)
    except RecursionError:
        raise DescriptionError(f"{source}: not a hydro file: arrays or tables nested too deeply to read") from None
    except (ValueError, TypeError, OverflowError) as exc:  # tomllib.TOMLDecodeError is a ValueError
        raise DescriptionError(f"{source}: not valid TOML: {clipped(str(exc))}") from None


def _hydro_loads(text: str, source: str) -> HydroFile:
    document = _toml(text, source)
    top = _Reader(source, "top level", document, DescriptionError)
    top.check_keys(("links", "joints", "water", "base"))
    links: dict[str, Any] = top.get(
        "links",
        lambda v: v if isinstance(v, dict) else _not("a table [links.NAME]"),
        "a table of links by name",
        required=False,
        default={},
    )
    out: dict[str, HydroLink] = {}
    for name, table in links.items():
        where = _table("links", name)
        r = _Reader(source, where, table, DescriptionError)
        r.check_keys(_LINK_KEYS)
        for key in ("segments", "segment_cd", "segment_cm"):  # refused before reading a thousand of them
            if isinstance(r.table.get(key), list) and len(r.table[key]) > MAX_SEGMENTS:
                r.fail(key, f"has {len(r.table[key])} entries; a link has at most {MAX_SEGMENTS} segments (uwml.MAX_SEGMENTS)")
        mass, com, inertia = read_override(r)
        raw_segments: list[Any] = r.get(
            "segments", lambda v: v if isinstance(v, list) else _not("an array of tables"), "[[...segments]]", required=False, default=[]
        )
        segments = tuple(_segment(source, f"{where}, segments[{i}]", s, DescriptionError) for i, s in enumerate(raw_segments))
        entry = HydroLink(
            cd=r.get("cd", _coefficient, "a number or [along n0, along n1]", required=False),
            cm=r.get("cm", _coefficient, "a number or [along n0, along n1]", required=False),
            cd_axial=r.get("cd_axial", _axial, f"a number, 0 to {MAX_COEFFICIENT:g}", required=False),
            segment_cd=r.get("segment_cd", _coefficients, "an array, one number or pair per segment", required=False),
            segment_cm=r.get("segment_cm", _coefficients, "an array, one number or pair per segment", required=False),
            volume=r.get("volume", _volume, f"a volume [m³], 0 to {MAX_VOLUME:g}", required=False),
            cob=r.get("cob", _point, "an array of 3 numbers [m]", required=False),
            dry=r.get("dry", _boolean, "true or false", required=False, default=False),
            segments=segments,
            strips=r.get("strips", _boolean, "true or false", required=False, default=True),
            lumped=None if "lumped" not in r.table else _hydro_lumped(source, f"{where}, lumped", r.table["lumped"]),
            mass=mass,
            com=com,
            inertia=inertia,
            items=read_items(r, source, where),
            thrusters=thrusters(source, where, r.table["thrusters"], DescriptionError) if "thrusters" in r.table else (),
            describes_water=any(key in r.table for key in _WATER_KEYS),
        )
        if entry.dry:
            for key in ("volume", "cob", "segments", "segment_cd", "segment_cm", "cd", "cm", "cd_axial", "strips", "lumped"):
                if key in r.table:
                    r.fail(key, "a dry link has no segments and no volume: remove this key or dry = true")
            for index, item in enumerate(entry.items):
                if item.volume > 0.0:
                    r.fail("items", f"items[{index}] has a volume, but a dry link has none: give it volume = 0, or remove dry = true")
        if entry.cob is not None and entry.volume is None:
            r.fail("cob", "needs volume (give the displaced volume with its centre of buoyancy)")
        out[name] = entry
    joints: dict[str, Any] = top.get(
        "joints",
        lambda v: v if isinstance(v, dict) else _not("a table [joints.NAME]"),
        "a table of joints by name",
        required=False,
        default={},
    )
    losses = {name: _losses(source, _table("joints", name), table, DescriptionError) for name, table in joints.items()}
    water = _hydro_water(source, document["water"]) if "water" in document else None
    floating = False
    if "base" in document:
        base = _Reader(source, "[base]", document["base"], DescriptionError)
        base.check_keys(("floating",))
        floating = base.get("floating", _boolean, "true or false", required=False, default=False)
    return HydroFile(links=out, joints=losses, water=water, source=source, floating=floating)


def read_hydro(path: str | os.PathLike[str]) -> HydroFile:
    """The hydro file at ``path`` (see the module docstring)."""
    data = read_regular(path, "hydro file")
    source = str(path)
    try:
        text = data.decode("utf-8")
    except UnicodeDecodeError as exc:
        line = data.count(b"\n", 0, exc.start) + 1
        raise DescriptionError(
            f"{source}: not UTF-8 text: byte 0x{data[exc.start]:02x} at offset {exc.start} (line {line}) cannot be decoded "
            f"({exc.reason}); a hydro file is TOML, which is UTF-8"
        ) from None
    return _hydro_loads(text.removeprefix("\ufeff"), source)  # a byte-order mark (Windows editors) is not content
