"""The uwml model file: a robot's whole validated model as readable TOML, read back exactly.

``Robot.save(path)`` writes it, ``Robot.load(path)`` reads it. Here, :func:`dumps` and :func:`save`
write any robot (:class:`~uwml.io._robot_like.RobotLike`); :func:`parse` and :func:`read` give its
parts (:class:`ModelParts`), which :mod:`uwml.robot` assembles into a :class:`uwml.Robot`
(``uwml.robot.files.loads`` and ``load`` return the robot of a string and of a file). Every
number is written as Python's shortest repr of the float, which reads back to the same float, so
a saved model loads equal to itself, names too (any text; control characters are escaped, a
lone surrogate, which UTF-8 cannot hold, is refused). ``save`` writes the whole file to a
temporary file beside it and renames it over the old one, so a failed save leaves the old file
as it was. The file is read with the standard library's ``tomllib``; every error names the file,
the table and the key, and quotes at most a short part of a value. The water must be within
900-1300 kg/m³ and 9.7-9.9 m/s² (anything else is taken for a unit mistake, as in a hydro file;
docs/domains.md); another fluid or planet is a :class:`uwml.Water` in code.

Layout (SI units; vectors as arrays of 3 numbers; every link frame parallel to the base frame
at ``q = 0``, as in :mod:`uwml.model.parts`)::

    format = "uwml-robot"
    version = 1

    [water]                      # optional: the robot's water (uwml.Water); default fresh water
    density = 1025.0             # kg/m³, 900 to 1300
    gravity = 9.81               # m/s², 9.7 to 9.9

    [base]                       # optional: the base's own body, in the base frame
    mass = 300.0                 # kg
    com = [0.0, 0.0, -0.05]      # m
    volume = 0.29                # m³
    cob = [0.0, 0.0, 0.05]       # m

    [[base.segments]]            # any number, for the base and for every link
    section = "circular"         # or "rectangular" (then normals, widths, area)
    start = [-0.9, 0.0, 0.0]
    axis = [1.0, 0.0, 0.0]
    length = 1.8
    diameter = 0.6
    area = 0.283
    cd = [0.9, 0.9]              # per normal direction (a circular section's two are equal)
    cm = [1.0, 1.0]
    cd_axial = 0.8               # optional: axial drag (docs/model.md section 12.2), along the
    axial_area = 0.283           # axis; its area defaults to the section area

    [base.lumped]                # optional, for the base and for every link: Fossen's lumped
    point = [0.0, 0.0, 0.05]     # model (uwml.LumpedModel, docs/model.md section 12.1), about
    axes = [[1, 0, 0], [0, 1, 0], [0, 0, 1]]  # `point`, in `axes` (a rotation, optional; its
    added_mass = [[...6...], ...]      # columns the model's axes in the body frame): 6 rows of 6
    linear_damping = [[...6...], ...]  # (x, y, z, roll, pitch, yaw); magnitudes (SNAME's X_u̇
    quadratic_damping = [...6...]      # is −added_mass[0][0])

    [[joints]]                   # in the order of q, parents first
    name = "shoulder_yaw"        # optional
    parent = -1                  # an earlier link's index, or -1 for the base
    kind = "revolute"            # or "prismatic"
    origin = [0.9, 0.0, -0.3]
    axis = [0.0, 0.0, 1.0]
    range = [-2.6, 2.6]          # optional: the description's limits (uwml.Joint's fields; they
    velocity_limit = 2.0         # set the bounds of uwml.PlausibilityWarning, nothing else)
    effort_limit = 80.0

    [joints.losses]              # optional: the joint's own losses (uwml.JointLosses)
    epsilon = 0.001              # smooth-sign width [rad/s]
    [joints.losses.drive]        # uwml.Drive's fields
    torque_constant = 0.4
    ratio = 160.0
    efficiency = 0.8
    rated_current = 10.4
    [joints.losses.oil]          # uwml.OilDrag's fields; absent: no oil drag
    k_oil = ...
    [joints.losses.seal]         # uwml.Seal's fields; absent: no seal
    c0 = 16.0

    [[links]]                    # link i is moved by joint i
    name = "upper_arm"           # optional
    mass = 12.0
    com = [0.075, 0.0, 0.0]
    volume = 0.004
    cob = [0.075, 0.0, 0.01]

    [[links.segments]]
    section = "rectangular"
    start = [0.0, 0.0, -0.05]
    axis = [1.0, 0.0, 0.0]
    length = 0.09
    normals = [[0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]
    widths = [0.05, 0.08]
    area = 0.004
    cd = [2.0, 2.1]
    cm = [1.2, 1.5]
"""

from __future__ import annotations

import dataclasses
import functools
import math
import os
import tomllib
import unicodedata
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import Any, TypeVar

from .._checks import shown
from ..errors import ModelFileError
from ..model.joint_losses import JointLosses
from ..model.lumped import LumpedModel
from ..model.parts import Joint, Link, Segment, Water
from ..model.thrusters import Thruster
from ._file_access import read_regular, write_atomically
from ._model_tables import (
    _DENSITY_HINT,
    _GRAVITY_HINT,
    WATER_DENSITY_RANGE,
    WATER_GRAVITY_RANGE,
    _body,
    _clipped,
    _fail_type,
    _float,
    _integer,
    _losses,
    _pair,
    _Reader,
    _text,
    _vec3,
    _water,
)
from ._robot_like import RobotLike

__all__ = [
    "FORMAT",
    "VERSION",
    "WATER_DENSITY_RANGE",
    "WATER_GRAVITY_RANGE",
    "ModelFileError",
    "ModelParts",
    "dumps",
    "parse",
    "read",
    "save",
]

#: The ``format`` key of a uwml model file.
FORMAT = "uwml-robot"
#: The version this module writes and reads.
VERSION = 1


def _number(x: float) -> str:
    # repr is the shortest string that reads back to the same float; TOML wants a decimal
    # point or an exponent, which repr of a float always has.
    return repr(float(x))


def _vector(v: Sequence[float]) -> str:
    return "[" + ", ".join(_number(x) for x in v) + "]"


_ESCAPES = {'"': '\\"', "\\": "\\\\", "\b": "\\b", "\t": "\\t", "\n": "\\n", "\f": "\\f", "\r": "\\r"}


def _escaped(c: str) -> str:
    if c in _ESCAPES:
        return _ESCAPES[c]
    # TOML requires U+0000-U+001F and U+007F escaped; the other control and format characters
    # (C1 controls, text-direction marks, line separators) are escaped too, so the file shows them.
    if unicodedata.category(c) in ("Cc", "Cf", "Zl", "Zp"):
        return f"\\u{ord(c):04X}" if ord(c) <= 0xFFFF else f"\\U{ord(c):08X}"
    return c


def _string(text: str, what: str = "a string") -> str:
    """``text`` as a TOML basic string that reads back exactly; a lone surrogate (which no UTF-8
    file can hold) is a ValueError naming ``what``."""
    surrogate = next((c for c in text if "\ud800" <= c <= "\udfff"), None)
    if surrogate is not None:
        raise ValueError(
            f"{what} {shown(text)} cannot be written to a model file: it holds a lone surrogate "
            f"(U+{ord(surrogate):04X}), which is not a character UTF-8 can encode"
        )
    return '"' + "".join(_escaped(c) for c in text) + '"'


def _body_lines(body: Link, where: str) -> list[str]:
    lines = [] if body.name is None else [f"name = {_string(body.name, f'{where}.name')}"]
    cob = body.cob if body.cob is not None else body.com
    return [
        *lines,
        f"mass = {_number(body.mass)}",
        f"com = {_vector(body.com)}",
        f"volume = {_number(body.volume)}",
        f"cob = {_vector(cob)}",
    ]


def _lumped_lines(lumped: LumpedModel) -> list[str]:
    point = lumped.point if lumped.point is not None else (0.0, 0.0, 0.0)

    def matrix(rows: Any) -> str:
        return "[" + ", ".join(_vector(row) for row in rows) + "]"

    axes = [] if lumped.axes == ((1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0)) else [f"axes = {matrix(lumped.axes)}"]
    return [
        f"point = {_vector(point)}",
        *axes,
        f"added_mass = {matrix(lumped.added_mass)}",
        f"linear_damping = {matrix(lumped.linear_damping)}",
        f"quadratic_damping = {_vector(lumped.quadratic_damping)}",  # type: ignore[arg-type]
    ]


def _thruster_lines(thruster: Thruster, table: str, where: str) -> list[str]:
    lines = ["", f"[[{table}]]"]
    if thruster.name is not None:
        lines.append(f"name = {_string(thruster.name, f'{where}.name')}")
    lines += [f"position = {_vector(thruster.position)}", f"direction = {_vector(thruster.direction)}"]
    lines += [f"{key} = {_number(value)}" for key in ("max_forward", "max_reverse") if math.isfinite(value := getattr(thruster, key))]
    if thruster.time_constant:
        lines.append(f"time_constant = {_number(thruster.time_constant)}")
    curve = thruster.curve
    lines += ["", f"[{table}.curve]", f"kind = {_string(curve.kind)}"]
    if curve.kind == "table":
        return [*lines, f"commands = {_vector(curve.commands)}", f"thrusts = {_vector(curve.thrusts)}"]
    return [*lines, f"forward = {_vector(curve.forward)}", f"reverse = {_vector(curve.reverse)}", f"dead_band = {_number(curve.dead_band)}"]


def _segment_lines(segment: Segment) -> list[str]:
    lines = [f"section = {_string(segment.section)}", f"start = {_vector(segment.start)}", f"axis = {_vector(segment.axis)}"]
    lines.append(f"length = {_number(segment.length)}")
    if segment.section == "circular":
        lines.append(f"diameter = {_number(segment.diameter or 0.0)}")
    else:
        normals = segment.normals or ((0.0, 0.0, 0.0), (0.0, 0.0, 0.0))
        lines.append(f"normals = [{_vector(normals[0])}, {_vector(normals[1])}]")
        lines.append(f"widths = {_vector(segment.widths or (0.0, 0.0))}")
    lines.append(f"area = {_number(segment.area or 0.0)}")
    lines.append(f"cd = {_vector(segment.cd)}")
    lines.append(f"cm = {_vector(segment.cm)}")
    # The axial drag (docs/model.md section 12.2), when there is one; its area unless the default.
    if segment.cd_axial != 0.0:
        lines.append(f"cd_axial = {_number(segment.cd_axial)}")
    if segment.axial_area != segment.area:
        lines.append(f"axial_area = {_number(segment.axial_area)}")
    return lines


def _losses_lines(losses: JointLosses) -> list[str]:
    lines = ["", "[joints.losses]", f"epsilon = {_number(losses.epsilon)}"]
    for name, part in (("drive", losses.drive), ("oil", losses.oil), ("seal", losses.seal)):
        if part is not None:
            lines += ["", f"[joints.losses.{name}]"]
            lines += [f"{f.name} = {_number(getattr(part, f.name))}" for f in dataclasses.fields(part)]
    return lines


def dumps(robot: RobotLike) -> str:
    """The uwml model file of ``robot``, as a string."""
    out = [
        f"# uwml model file: {robot.n_joints} joints, {len(robot.segments)} segments (SI units)",
        f"format = {_string(FORMAT)}",
        f"version = {VERSION}",
    ]
    for key, value, (low, high), unit, hint in (
        ("density", robot.water.density, WATER_DENSITY_RANGE, "kg/m³", _DENSITY_HINT),
        ("gravity", robot.water.gravity, WATER_GRAVITY_RANGE, "m/s²", _GRAVITY_HINT),
    ):
        if not low <= value <= high:
            raise ValueError(
                f"water.{key} {value:g} {unit} cannot be written to a model file, which holds {low:g} to {high:g} {unit} "
                f"(docs/domains.md; {hint}): another fluid or planet is a uwml.Water given in code"
            )
    out += ["", "[water]", f"density = {_number(robot.water.density)}", f"gravity = {_number(robot.water.gravity)}"]
    if robot.base is not None:
        out += ["", "[base]", *_body_lines(robot.base, "base")]
        if robot.base.lumped is not None:
            out += ["", "[base.lumped]", *_lumped_lines(robot.base.lumped)]
        for segment in robot.base.segments:
            out += ["", "[[base.segments]]", *_segment_lines(segment)]
        for k, thruster in enumerate(robot.base.thrusters):
            out += _thruster_lines(thruster, "base.thrusters", f"base.thrusters[{k}]")
    for i, (joint, losses) in enumerate(zip(robot.joints, robot.losses)):
        out += ["", "[[joints]]"]
        if joint.name is not None:
            out.append(f"name = {_string(joint.name, f'joints[{i}].name')}")
        out += [
            # A joint without a parent follows the previous link (a uwml.Joint's default).
            f"parent = {i - 1 if joint.parent is None else joint.parent}",
            f"kind = {_string(joint.kind)}",
            f"origin = {_vector(joint.origin)}",
            f"axis = {_vector(joint.axis)}",
        ]
        if joint.range is not None:
            out.append(f"range = [{_number(joint.range[0])}, {_number(joint.range[1])}]")
        out += [f"{key} = {_number(value)}" for key in ("velocity_limit", "effort_limit") if (value := getattr(joint, key)) is not None]
        if losses is not None:
            out += _losses_lines(losses)
    for i, link in enumerate(robot.links):
        out += ["", "[[links]]", *_body_lines(link, f"links[{i}]")]
        if link.lumped is not None:
            out += ["", "[links.lumped]", *_lumped_lines(link.lumped)]
        for segment in link.segments:
            out += ["", "[[links.segments]]", *_segment_lines(segment)]
        for k, thruster in enumerate(link.thrusters):
            out += _thruster_lines(thruster, "links.thrusters", f"links[{i}].thrusters[{k}]")
    return "\n".join(out) + "\n"


def save(robot: RobotLike, path: str | os.PathLike[str]) -> None:
    """Writes :func:`dumps` of ``robot`` to ``path`` (UTF-8), whole or not at all: the text is
    written to a temporary file in the same folder, synced, and renamed over ``path``; on any
    failure the temporary file is removed and an existing file at ``path`` is left as it was."""
    write_atomically(path, dumps(robot).encode("utf-8"))


_R = TypeVar("_R")


@dataclass(frozen=True, eq=False)
class ModelParts:
    """The parts of the robot of a model file, read and checked one by one; :meth:`build` puts them
    together, with the errors of the whole (a parent that is not an earlier link, too many
    segments, ...) naming the file."""

    joints: tuple[Joint, ...]
    links: tuple[Link, ...]
    base: Link | None
    losses: tuple[JointLosses | None, ...]
    water: Water | None
    _top: _Reader

    def build(self, make: Callable[..., _R]) -> _R:
        """``make(joints, links, base=, losses=, water=)`` (the class :class:`uwml.Robot`); its
        ValueError or TypeError as a :class:`ModelFileError` naming the file."""
        return self._top.build(lambda: make(self.joints, self.links, base=self.base, losses=self.losses, water=self.water))


def parse(text: str, source: str = "<string>") -> ModelParts:
    """The robot's parts of a uwml model file given as text (``source`` names it in errors)."""
    try:
        document = tomllib.loads(text)
    except RecursionError:
        raise ModelFileError(f"{source}: not a model file: arrays or tables nested too deeply to read") from None
    except (ValueError, TypeError, OverflowError) as exc:  # tomllib.TOMLDecodeError is a ValueError
        raise ModelFileError(f"{source}: not valid TOML: {_clipped(str(exc))}") from None
    top = _Reader(source, "top level", document)
    top.check_keys(("format", "version", "water", "base", "joints", "links"))
    if top.get("format", _text, f'"{FORMAT}"') != FORMAT:
        top.fail("format", f'must be "{FORMAT}" (a uwml model file), got {shown(document["format"])}')
    if top.get("version", _integer, f"the integer {VERSION}") != VERSION:
        top.fail("version", f"must be {VERSION} (this uwml reads version {VERSION}), got {shown(document['version'])}")
    as_list = lambda v: v if isinstance(v, list) else _fail_type("an array of tables")
    joint_tables = top.get("joints", as_list, "an array of tables [[joints]]")
    link_tables = top.get("links", as_list, "an array of tables [[links]]")
    joints, losses = [], []
    for i, table in enumerate(joint_tables):
        r = _Reader(source, f"joints[{i}]", table)
        r.check_keys(("name", "parent", "kind", "origin", "axis", "range", "velocity_limit", "effort_limit", "losses"))
        losses.append(_losses(source, f"joints[{i}], losses", table["losses"]) if "losses" in table else None)
        name = r.get("name", _text, "a string", required=False)
        parent = r.get("parent", _integer, "an integer: an earlier link's index, or -1 for the base")
        kind = r.get("kind", _text, 'a string, "revolute" or "prismatic"')
        origin = r.get("origin", _vec3, "an array of 3 numbers [m]")
        axis = r.get("axis", _vec3, "a unit vector")
        joint_range = r.get("range", _pair, "an array of 2 numbers, lower < upper [rad or m]", required=False)
        velocity = r.get("velocity_limit", _float, "a positive number [rad/s or m/s]", required=False)
        effort = r.get("effort_limit", _float, "a positive number [N·m or N]", required=False)
        make = functools.partial(
            Joint, origin, axis, parent=parent, kind=kind, name=name, range=joint_range, velocity_limit=velocity, effort_limit=effort
        )
        joints.append(r.build(make))
    links = [_body(source, f"links[{i}]", table) for i, table in enumerate(link_tables)]
    base = _body(source, "base", document["base"]) if "base" in document else None
    water = _water(source, "water", document["water"]) if "water" in document else None
    return ModelParts(tuple(joints), tuple(links), base, tuple(losses), water, top)


def read(path: str | os.PathLike[str]) -> ModelParts:
    """The robot's parts of the uwml model file at ``path``."""
    data = read_regular(path, "model file", ModelFileError)  # a named pipe is refused, not waited on
    try:
        text = data.decode("utf-8")
    except UnicodeDecodeError as exc:
        line = data.count(b"\n", 0, exc.start) + 1
        raise ModelFileError(
            f"{path}: not UTF-8 text: byte 0x{data[exc.start]:02x} at offset {exc.start} (line {line}) cannot be decoded ({exc.reason})"
        ) from None
    return parse(text, str(path))
