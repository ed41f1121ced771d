"""A robot's validated model as source code for firmware (``uwml export``): Rust constants of the
core's plain types, or C initializers of the C ABI's structs, every number written so that it
reads back to the same float (``f64``: Python's shortest repr; ``f32``: numpy's for float32).

Rust::

    mod arm { include!("arm.rs"); }
    let robot = uwml_core::Robot::<f64, { arm::N_JOINTS }, { arm::N_SEGMENTS }>::new(
        &arm::JOINTS, &arm::LINKS, arm::BASE, &arm::SEGMENTS)?;

C (with the C ABI's header ``uwml.h``: in the folder :func:`get_include` names, or
``crates/uwml-ffi/include``)::

    #include "arm.h"
    static UwmlRobotF64 robot;
    uwml_robot_new_f64(&robot, ROBOT_JOINTS, ROBOT_N_JOINTS, ROBOT_LINKS, ROBOT_BASE, ROBOT_SEGMENTS,
                       ROBOT_N_SEGMENTS, 1025.0, 9.81, &err);

(``ROBOT_BASE`` is ``NULL`` for a robot without a base body.)

Joint and link names and the source's path are untrusted text: they appear only in comments,
every character outside a small safe set written as ``\\u{HEX}`` (docs/firmware.md, "The model
as source"); the C prefix must be an upper-case ASCII identifier outside the header's own
``UWML_`` names.

What is written is what the firmware's constructor takes (docs/firmware.md, "The model as
source"): C within the C API's capacities (:data:`C_MAX_JOINTS`, :data:`C_MAX_SEGMENTS`,
:data:`C_MAX_LUMPED`), and in either language every number finite and, unless zero, a normal
number of the precision (none rounds to zero, to a subnormal or to infinity; the error names the
number and the range); in f32, each lumped model as rounded is one the core takes.
"""

from __future__ import annotations

import math
import os
import re
import sys
from collections.abc import Iterable, Iterator, Sequence
from types import SimpleNamespace
from typing import Any

import numpy as np

from .._checks import shown
from ..model.lumped import LumpedModel
from ..model.parts import AXIS_TOLERANCE, Link, Segment
from ._robot_like import RobotLike

__all__ = ["C_MAX_JOINTS", "C_MAX_LUMPED", "C_MAX_SEGMENTS", "get_include", "to_c", "to_rust"]

PRECISIONS = ("f64", "f32")

#: The C API's robot's capacities: ``UWML_ROBOT_MAX_JOINTS``, ``UWML_ROBOT_MAX_SEGMENTS`` and
#: ``UWML_ROBOT_MAX_LUMPED`` of uwml.h (tests/test_export.py holds these to it).
C_MAX_JOINTS = 16
C_MAX_SEGMENTS = 32
C_MAX_LUMPED = 4

#: Per precision: the smallest normal number and the largest finite one. A nonzero number below
#: the first rounds to zero or to a subnormal (which firmware built to flush subnormals reads as
#: zero: a positive length becomes none); above the second, to infinity.
_RANGE = {
    "f64": (sys.float_info.min, sys.float_info.max),
    "f32": (float(np.finfo(np.float32).tiny), float(np.finfo(np.float32).max)),
}
#: How far from a rotation a lumped model's axes may be when written in f32: the core allows
#: AXIS_TOLERANCE, and f32's rounding of the entries and its arithmetic in the check take up to
#: about 2e-7 of it.
_F32_AXES_TOLERANCE = 0.5 * AXIS_TOLERANCE


def get_include() -> str:
    """The folder, inside the installed package, that holds ``uwml.h``: the header of the C ABI
    (crates/uwml-ffi/include/uwml.h, which the package ships as it is), as ``numpy.get_include()``
    does for numpy's. The static library is not in the package: it comes from the firmware
    package of ``make dist`` (docs/firmware.md, "Without Rust").

    Examples
    --------
    A host C program next to a pip install:

    ```sh
    cc -I"$(python -c 'import uwml; print(uwml.get_include())')" app.c libuwml.a -lm
    ```
    """
    return os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "include")


def _literal(x: float, precision: str, suffix: str = "") -> str:
    """The shortest decimal that reads back to ``x`` in ``precision`` (a float literal in both
    languages: it always has a point or an exponent)."""
    text = repr(float(x)) if precision == "f64" else str(np.float32(x))
    if "." not in text and "e" not in text:
        text += ".0"
    return text + suffix


def _check(precision: str, robot: RobotLike) -> None:
    """What both languages check before writing: the precision, every number, and in f32 the
    lumped models as rounded."""
    if precision not in PRECISIONS:
        raise ValueError(f"precision must be one of {PRECISIONS}, got {shown(precision)}")
    smallest, largest = _RANGE[precision]
    for label, x in _numbers(robot):
        written = float(np.float32(x)) if precision == "f32" else float(x)
        if not math.isfinite(written) or (x != 0.0 and not smallest <= abs(written) <= largest):
            raise ValueError(
                f"{label} = {x!r} cannot be written in {precision}: a number must be finite and, unless zero, "
                f"between {smallest:.6g} and {largest:.6g} in magnitude ({_why(precision)})"
            )
    if precision == "f32":
        for k, (owner, model) in enumerate(_lumped_owned(robot)):
            _check_lumped_f32(k, _owner_name(owner), model)


def _why(precision: str) -> str:
    if precision == "f32":
        return "f32 holds a smaller one only as zero or a subnormal, which firmware may flush to zero, and a larger one not at all"
    return "a smaller one is a subnormal, which firmware may flush to zero"


def _owner_name(owner: int) -> str:
    return "base" if owner < 0 else f"link {owner}"


def _numbers(robot: RobotLike) -> Iterator[tuple[str, float]]:
    """Every number the exporters write, with the name an error gives it."""

    def each(label: str, values: Iterable[float]) -> Iterator[tuple[str, float]]:
        for c, x in enumerate(values):
            yield f"{label}[{c}]", float(x)

    for i, joint in enumerate(robot.joints):
        yield from each(f"joint {i}: origin", joint.origin)
        yield from each(f"joint {i}: axis", joint.axis)
    bodies = [("base", robot.base)] if robot.base is not None else []
    for where, body in [*bodies, *((f"link {i}", link) for i, link in enumerate(robot.links))]:
        yield f"{where}: mass", float(body.mass)
        yield from each(f"{where}: com", body.com)
        yield f"{where}: volume", float(body.volume)
        yield from each(f"{where}: cob", body.cob if body.cob is not None else body.com)
    for k, (owner, s) in enumerate(_owned(robot)):
        where = f"segment {k} ({_owner_name(owner)})"
        yield from each(f"{where}: start", s.start)
        yield from each(f"{where}: axis", s.axis)
        yield f"{where}: length", float(s.length)
        yield f"{where}: area", float(s.area or 0.0)
        for n, normal in enumerate(s.normals or ()):
            yield from each(f"{where}: normals[{n}]", normal)
        yield from each(f"{where}: widths", s.widths or ())
        yield f"{where}: diameter", float(s.diameter or 0.0)
        yield from each(f"{where}: cd", s.cd)
        yield from each(f"{where}: cm", s.cm)
        yield f"{where}: cd_axial", float(s.cd_axial)
        yield f"{where}: axial_area", float(s.axial_area)
    for k, (owner, model) in enumerate(_lumped_owned(robot)):
        where = f"lumped model {k} ({_owner_name(owner)})"
        yield from each(f"{where}: point", model.point if model.point is not None else (0.0, 0.0, 0.0))
        for name in ("axes", "added_mass", "linear_damping"):
            for r, row in enumerate(getattr(model, name)):
                yield from each(f"{where}: {name}[{r}]", row)
        yield from each(f"{where}: quadratic_damping", model.quadratic_damping)  # type: ignore[arg-type]
    yield "water: density", float(robot.water.density)
    yield "water: gravity", float(robot.water.gravity)


def _check_lumped_f32(k: int, owner: str, model: LumpedModel) -> None:
    """Lumped model ``k`` as written in f32 is one the core takes. Its matrices are judged as
    rounded (in f64 on the exact values, as the core does in either precision: the compiled core
    itself judges them here), which may make a singular semi-definite matrix slightly indefinite;
    its axes, which the core checks in f32 arithmetic, must be a rotation within
    ``_F32_AXES_TOLERANCE``."""
    from .._core import Robot as CoreRobot

    def rounded(value: Any) -> list[Any]:
        return np.asarray(value, dtype=np.float32).astype(np.float64).tolist()  # type: ignore[no-any-return]

    where = f"lumped model {k} ({owner}) cannot be written in f32"
    axes = np.asarray(rounded(model.axes))
    columns = axes / np.linalg.norm(axes, axis=0)
    off = max(
        float(np.max(np.abs(np.linalg.norm(axes, axis=0) - 1.0))),
        float(np.max(np.abs(np.triu(columns.T @ columns, 1)))),
        float(np.max(np.abs(np.cross(columns[:, 0], columns[:, 1]) - columns[:, 2]))),
    )
    if off > _F32_AXES_TOLERANCE:
        raise ValueError(
            f"{where}: its axes, rounded to f32, are a rotation only within {off:.3g}, and f32's arithmetic needs them within "
            f"{_F32_AXES_TOLERANCE:g} of one (the core allows {AXIS_TOLERANCE:g}); give them orthonormal to rounding, or export in f64"
        )
    lumped = SimpleNamespace(
        point=rounded(model.point if model.point is not None else (0.0, 0.0, 0.0)),
        axes=axes.tolist(),
        added_mass=rounded(model.added_mass),
        linear_damping=rounded(model.linear_damping),
        quadratic_damping=rounded(model.quadratic_damping),
    )
    zero = (0.0, 0.0, 0.0)
    joint = SimpleNamespace(parent=-1, kind="revolute", origin=zero, axis=(0.0, 0.0, 1.0))
    body = SimpleNamespace(mass=0.0, com=zero, volume=0.0, cob=zero, lumped=None)
    base = SimpleNamespace(mass=0.0, com=zero, volume=0.0, cob=zero, lumped=lumped)
    try:
        CoreRobot([joint], [body], base, [], [(math.inf, math.inf, math.inf)])  # type: ignore[arg-type, list-item]  # duck-typed parts
    except ValueError as exc:
        message = str(exc).removeprefix("lumped model 0: ")
        raise ValueError(f"{where}: rounded to f32, {message}; export it in f64, or give it a margin above rounding") from None


# Names (a URDF's or MJCF's) and the source's path are untrusted text: they go only into
# comments, where these characters cannot end the comment, start a line, or mean anything to a
# compiler, rustdoc or a terminal. Every other character is written as \u{HEX}: so `*/`, `/*`,
# newlines, backslashes, control characters and non-ASCII text never reach the source as such.
_COMMENT_SAFE = frozenset("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789 _-.,:;/+=()#@!?'\"$%^|~{}")
# The C names are PREFIX_...: an ASCII identifier in upper case, outside the header's UWML_
# names (PREFIX UWML would redefine UWML_BASE; UWML_ROBOT_MAX could one day be a header's name).
_C_PREFIX = re.compile(r"[A-Z_][A-Z0-9_]*")
_HEADER_NAMES = re.compile(r"UWML(_.*)?")


def _comment(text: str) -> str:
    """``text`` as inert comment text in C and Rust (see ``_COMMENT_SAFE``)."""
    return "".join(c if c in _COMMENT_SAFE else f"\\u{{{ord(c):x}}}" for c in text)


def _names(names: Iterable[str]) -> str:
    return ", ".join(_comment(name) for name in names)


def _from(source: str | None) -> str:
    return f" from {_comment(source)}" if source else ""


def _owned(robot: RobotLike) -> list[tuple[int, Segment]]:
    base = [] if robot.base is None else [(-1, s) for s in robot.base.segments]
    return base + [(i, s) for i, link in enumerate(robot.links) for s in link.segments]


def _lumped_owned(robot: RobotLike) -> list[tuple[int, LumpedModel]]:
    """Each body's lumped model (docs/model.md section 12.1) with its owner (-1: the base)."""
    bodies = [(-1, robot.base)] if robot.base is not None else []
    bodies += list(enumerate(robot.links))
    return [(owner, body.lumped) for owner, body in bodies if body.lumped is not None]


def _rust_matrix(rows: Sequence[Sequence[float]], p: str, kind: str) -> str:
    return f"{kind}::new(" + ", ".join(_literal(x, p) for row in rows for x in row) + ")"


def _rust_vector(v: Sequence[float], p: str) -> str:
    return "Vector3::new(" + ", ".join(_literal(x, p) for x in v) + ")"


def _rust_body(body: Link, p: str) -> str:
    cob = body.cob if body.cob is not None else body.com
    return (
        f"RigidBody {{ mass: {_literal(body.mass, p)}, com: {_rust_vector(body.com, p)}, "
        f"volume: {_literal(body.volume, p)}, cob: {_rust_vector(cob, p)} }}"
    )


def _rust_pair(values: Sequence[float], p: str) -> str:
    return "[" + ", ".join(_literal(x, p) for x in values) + "]"


def to_rust(robot: RobotLike, precision: str = "f64", source: str | None = None) -> str:
    """Rust constants `N_JOINTS`, `N_SEGMENTS`, `JOINTS`, `LINKS`, `BASE`, `SEGMENTS` of
    `uwml_core`'s plain types for ``robot`` (``precision`` "f64" or "f32"), and its water,
    `WATER_DENSITY` and `GRAVITY`."""
    _check(precision, robot)
    p, t = precision, precision
    owned = _owned(robot)
    out = [
        f"// Generated by `uwml export --rust`{_from(source)}: the robot's validated model as",
        f"// plain data; build it with `Robot::<{t}, N_JOINTS, N_SEGMENTS>::new(&JOINTS, &LINKS, BASE, &SEGMENTS)`.",
        "use uwml_core::nalgebra::Vector3;",
        "use uwml_core::{JointKind, Owner, RigidBody, RobotSegment, Section, TreeJoint};",
        "",
        f"/// Joints (and links) of the robot: {robot.n_joints}.",
        f"pub const N_JOINTS: usize = {robot.n_joints};",
        f"/// Segments of the robot, base first: {len(owned)}.",
        f"pub const N_SEGMENTS: usize = {len(owned)};",
        f"/// The joints, in the order of q: {_names(robot.joint_names)}.",
        f"pub const JOINTS: [TreeJoint<{t}>; N_JOINTS] = [",
    ]
    for joint in robot.joints:
        parent = "None" if joint.parent is None or joint.parent < 0 else f"Some({joint.parent})"
        kind = "JointKind::Prismatic" if joint.kind == "prismatic" else "JointKind::Revolute"
        out.append(
            f"    TreeJoint {{ parent: {parent}, kind: {kind}, origin: {_rust_vector(joint.origin, p)}, axis: {_rust_vector(joint.axis, p)} }},"
        )
    out += ["];", f"/// The links: {_names(robot.link_names)}.", f"pub const LINKS: [RigidBody<{t}>; N_JOINTS] = ["]
    out += [f"    {_rust_body(link, p)}," for link in robot.links]
    base = robot.base if robot.base is not None else Link(0.0, (0.0, 0.0, 0.0), 0.0)
    out += ["];", "/// The base's own body (empty: none).", f"pub const BASE: RigidBody<{t}> = {_rust_body(base, p)};"]
    out += ["/// The segments, base first, then link by link.", f"pub const SEGMENTS: [RobotSegment<{t}>; N_SEGMENTS] = ["]
    for owner, s in owned:
        owner_text = "Owner::Base" if owner < 0 else f"Owner::Link({owner})"
        if s.section == "circular":
            section = f"Section::Circular {{ diameter: {_literal(s.diameter or 0.0, p)} }}"
        else:
            normals = s.normals or ((0.0, 0.0, 0.0), (0.0, 0.0, 0.0))
            widths = s.widths or (0.0, 0.0)
            section = f"Section::Rectangular {{ normals: [{_rust_vector(normals[0], p)}, {_rust_vector(normals[1], p)}], widths: {_rust_pair(widths, p)} }}"
        out.append(
            f"    RobotSegment {{ owner: {owner_text}, start: {_rust_vector(s.start, p)}, axis: {_rust_vector(s.axis, p)}, "
            f"length: {_literal(s.length, p)}, area: {_literal(s.area or 0.0, p)}, section: {section}, "
            f"cd: {_rust_pair(s.cd, p)}, cm: {_rust_pair(s.cm, p)}, cd_axial: {_literal(s.cd_axial, p)}, "
            f"axial_area: {_literal(s.axial_area, p)} }},"
        )
    out.append("];")
    lumped = _lumped_owned(robot)
    if lumped:
        out += [
            "/// The bodies' lumped models (docs/model.md section 12.1): `.with_lumped(&LUMPED)` on the robot.",
            f"pub const N_LUMPED: usize = {len(lumped)};",
            f"pub const LUMPED: [LumpedBody<{t}>; N_LUMPED] = [",
        ]
        for owner, model in lumped:
            owner_text = "Owner::Base" if owner < 0 else f"Owner::Link({owner})"
            point = model.point if model.point is not None else (0.0, 0.0, 0.0)
            out.append(
                f"    LumpedBody {{ owner: {owner_text}, point: {_rust_vector(point, p)}, "
                f"axes: {_rust_matrix(model.axes, p, 'Matrix3')}, added_mass: {_rust_matrix(model.added_mass, p, 'Matrix6')}, "  # type: ignore[arg-type]
                f"linear_damping: {_rust_matrix(model.linear_damping, p, 'Matrix6')}, "  # type: ignore[arg-type]
                f"quadratic_damping: {_rust_pair(model.quadratic_damping, p)} }},"  # type: ignore[arg-type]
            )
        out.append("];")
        out[2] = "use uwml_core::nalgebra::{Matrix3, Matrix6, Vector3};"
        out[3] = "use uwml_core::{JointKind, LumpedBody, Owner, RigidBody, RobotSegment, Section, TreeJoint};"
    out += [
        "/// The robot's water: density [kg/m³] and gravity [m/s²], the evaluation's `density` and `gravity`.",
        f"pub const WATER_DENSITY: {t} = {_literal(robot.water.density, p)};",
        f"pub const GRAVITY: {t} = {_literal(robot.water.gravity, p)};",
    ]
    return "\n".join(out) + "\n"


def _c_array(values: Sequence[float], p: str) -> str:
    suffix = "f" if p == "f32" else ""
    return "{" + ", ".join(_literal(x, p, suffix) for x in values) + "}"


def _c_body(body: Link, p: str) -> str:
    suffix = "f" if p == "f32" else ""
    cob = body.cob if body.cob is not None else body.com
    return f"{{ .mass = {_literal(body.mass, p, suffix)}, .com = {_c_array(body.com, p)}, .volume = {_literal(body.volume, p, suffix)}, .cob = {_c_array(cob, p)} }}"


def to_c(robot: RobotLike, precision: str = "f64", prefix: str = "ROBOT", source: str | None = None) -> str:
    """C initializers of the C ABI's structs for ``robot``: ``PREFIX_N_JOINTS``,
    ``PREFIX_N_SEGMENTS``, ``PREFIX_JOINTS``, ``PREFIX_LINKS``, ``PREFIX_BASE`` (a pointer, NULL
    without a base body) and ``PREFIX_SEGMENTS``, for ``uwml_robot_new_f64`` (or ``_f32``), and
    the robot's water, ``PREFIX_WATER_DENSITY`` and ``PREFIX_GRAVITY``."""
    if not isinstance(prefix, str) or not _C_PREFIX.fullmatch(prefix) or not prefix.isupper():
        raise ValueError(f"prefix must be an upper-case C identifier (ASCII: A-Z, 0-9, _, not first a digit), got {shown(prefix)}")
    if _HEADER_NAMES.fullmatch(prefix):
        raise ValueError(
            f"prefix must not be UWML or start with UWML_: uwml.h's own names are UWML_... (PREFIX_BASE would redefine UWML_BASE), got {prefix}"
        )
    owned = _owned(robot)
    for what, count, cap, name in (
        ("joints", robot.n_joints, C_MAX_JOINTS, "UWML_ROBOT_MAX_JOINTS"),
        ("segments", len(owned), C_MAX_SEGMENTS, "UWML_ROBOT_MAX_SEGMENTS"),
        ("lumped models", len(_lumped_owned(robot)), C_MAX_LUMPED, "UWML_ROBOT_MAX_LUMPED"),
    ):
        if count > cap:
            raise ValueError(f"the C API's robot carries at most {cap} {what} ({name}), this one {count}")
    _check(precision, robot)
    p = precision
    t = "F64" if p == "f64" else "F32"
    suffix = "f" if p == "f32" else ""
    guard = f"UWML_EXPORT_{prefix}_H"
    out = [
        f"/* Generated by `uwml export --c`{_from(source)}: the robot's validated model as C",
        f" * initializers for uwml_robot_new_{p} (crates/uwml-ffi/include/uwml.h). */",
        f"#ifndef {guard}",
        f"#define {guard}",
        "#include <stddef.h> /* NULL */",
        '#include "uwml.h"',
        "",
        f"#define {prefix}_N_JOINTS {robot.n_joints}u",
        f"#define {prefix}_N_SEGMENTS {len(owned)}u",
        "",
        f"/* joints, in the order of q: {_names(robot.joint_names)} */",
        f"static const UwmlTreeJoint{t} {prefix}_JOINTS[{max(robot.n_joints, 1)}] = {{",
    ]
    for joint in robot.joints:
        parent = "UWML_BASE" if joint.parent is None or joint.parent < 0 else str(joint.parent)
        kind = "UWML_JOINT_PRISMATIC" if joint.kind == "prismatic" else "UWML_JOINT_REVOLUTE"
        out.append(
            f"    {{ .parent = {parent}, .kind = {kind}, .origin = {_c_array(joint.origin, p)}, .axis = {_c_array(joint.axis, p)} }},"
        )
    out += ["};", f"/* links: {_names(robot.link_names)} */", f"static const UwmlBody{t} {prefix}_LINKS[{max(robot.n_joints, 1)}] = {{"]
    out += [f"    {_c_body(link, p)}," for link in robot.links]
    out.append("};")
    if robot.base is not None:
        out += [f"static const UwmlBody{t} {prefix}_BASE_BODY = {_c_body(robot.base, p)};", f"#define {prefix}_BASE (&{prefix}_BASE_BODY)"]
    else:
        out.append(f"#define {prefix}_BASE NULL")
    out += [
        "/* segments, base first, then link by link */",
        f"static const UwmlRobotSegment{t} {prefix}_SEGMENTS[{max(len(owned), 1)}] = {{",
    ]
    if not owned:
        out.append("    { 0 }, /* none: ISO C has no empty initializer (the count is 0) */")
    for owner, s in owned:
        owner_text = "UWML_BASE" if owner < 0 else str(owner)
        section = "UWML_SECTION_CIRCULAR" if s.section == "circular" else "UWML_SECTION_RECTANGULAR"
        normals = s.normals or ((0.0, 0.0, 0.0), (0.0, 0.0, 0.0))
        widths = s.widths or (0.0, 0.0)
        out.append(
            f"    {{ .owner = {owner_text}, .section = {section}, .start = {_c_array(s.start, p)}, .axis = {_c_array(s.axis, p)}, "
            f".length = {_literal(s.length, p, suffix)}, .area = {_literal(s.area or 0.0, p, suffix)}, "
            f".normals = {{{_c_array(normals[0], p)}, {_c_array(normals[1], p)}}}, .widths = {_c_array(widths, p)}, "
            f".diameter = {_literal(s.diameter or 0.0, p, suffix)}, .cd = {_c_array(s.cd, p)}, .cm = {_c_array(s.cm, p)}, "
            f".cd_axial = {_literal(s.cd_axial, p, suffix)}, .axial_area = {_literal(s.axial_area, p, suffix)} }},"
        )
    lumped = _lumped_owned(robot)
    if lumped:
        out += [
            "};",
            "/* the bodies' lumped models (docs/model.md section 12.1), for uwml_robot_set_lumped */",
            f"#define {prefix}_N_LUMPED {len(lumped)}u",
            f"static const UwmlLumped{t} {prefix}_LUMPED[{len(lumped)}] = {{",
        ]
        for owner, model in lumped:
            owner_text = "UWML_BASE" if owner < 0 else str(owner)
            point = model.point if model.point is not None else (0.0, 0.0, 0.0)

            def rows(matrix: Any) -> str:
                return "{" + ", ".join(_c_array(row, p) for row in matrix) + "}"

            out.append(
                f"    {{ .owner = {owner_text}, .point = {_c_array(point, p)}, .axes = {rows(model.axes)}, "
                f".added_mass = {rows(model.added_mass)}, .linear_damping = {rows(model.linear_damping)}, "
                f".quadratic_damping = {_c_array(model.quadratic_damping, p)} }},"  # type: ignore[arg-type]
            )
    out += [
        "};",
        "/* the robot's water: density [kg/m^3] and gravity [m/s^2], for the evaluation's density and gravity */",
        f"#define {prefix}_WATER_DENSITY {_literal(robot.water.density, p, suffix)}",
        f"#define {prefix}_GRAVITY {_literal(robot.water.gravity, p, suffix)}",
        "",
        f"#endif /* {guard} */",
    ]
    return "\n".join(out) + "\n"
