"""Robot descriptions (URDF, MJCF, a MuJoCo model) to a :class:`uwml.Robot` (docs/model.md section 10).

``urdf_parts(path, hydro=None)``, ``mjcf_parts(path, hydro=None)`` and ``mujoco_parts(model,
hydro=None)`` (the classmethods ``uwml.Robot.from_urdf`` and so on, which assemble the robot of
these parts: :class:`DescriptionParts`) read a description
with MuJoCo (``pip install "uwml[mujoco]"``), which parses both formats into one model, and map it
by the fixed rules of docs/model.md section 10 ("From URDF and MJCF"):

- The root body is the base: its own mass, COM and collision geometry become the base body. A
  free joint on the root makes it the moving base (no uwml joint; the motion is a
  :class:`uwml.BaseMotion`). An MJCF root carrying hinge or slide joints hangs from the world: the
  base is then the world, without a body of its own. The world body's own geoms (a floor) are
  scenery and ignored; the world must hold exactly one root body. ``world`` is not a link of the
  robot: a hydro file's ``[links.world]`` is an error, and so is a URDF link named ``world`` with
  an ``<inertial>`` or a ``<collision>`` (MuJoCo takes it for the world and drops both).
- Fixed joints (URDF ``fixed``; MJCF bodies without joints) are fused into their parent:
  geometry, mass with the COM mass-weighted, volume with the COB volume-weighted.
- URDF revolute and continuous, MJCF hinge: revolute; URDF prismatic, MJCF slide: prismatic;
  anything else (ball, planar, a floating or free joint other than the root's, several joints in
  one body, a joint with a nonzero ``ref``, a URDF ``<mimic>``: uwml has no coupled joints) is a
  :class:`DescriptionError` naming the joint. Every joint and link name is given once.
- Masses. A URDF link without ``<inertial>`` is massless (URDF's rule; MuJoCo would compute a
  mass from its collision geometry, and does not here); a link moved by a joint with no mass,
  neither its own nor a fixed child's, is an error naming it (MuJoCo cannot move it). An MJCF
  body without ``<inertial>`` takes its mass from its geoms, as MuJoCo does. A negative mass is an
  error (MuJoCo would clamp it to 0). A hydro file's mass override and point items are written
  into the body's inertial before the final compile (:mod:`uwml.io._description_masses`).
- Frames. uwml's link frames are parallel to the base frame at ``q = 0``; a description's body
  frames may be rotated (URDF ``rpy``, MJCF ``quat``/``euler``/``axisangle``/...). With ``R_i``
  the orientation of body ``i`` relative to the base at ``q = 0`` (the product of the fixed
  rotations from the root down to it) and ``p_i`` its origin in the base frame, a point ``v`` of
  the body's own frame is at ``p_i + R_i v`` in the base frame and a direction ``d`` is ``R_i d``.
  The uwml link frame of a body moved by a joint has its origin at the joint's anchor,
  ``o_i = p_i + R_i a_i`` (``a_i`` the anchor in the body frame: the origin for URDF, ``pos`` of
  the MJCF joint), axes parallel to the base. So the uwml joint has ``axis = R_i axis_local``,
  ``origin = o_i − o_parent`` (in the parent's base-parallel frame), and every point of the
  body's (and its fused children's) geometry, COM and COB is ``p_b + R_b v − o_i``. At ``q`` the
  description's body turns by the same rotation about the same line as uwml's frame, so the two
  stay rigidly attached: the same robot.
- Geometry from collision geoms only (MuJoCo's convention: a geom with ``contype`` or
  ``conaffinity`` nonzero; URDF ``<collision>``); visuals are dropped before MuJoCo compiles, so
  missing visual mesh files do not stop the load. Box: a rectangular segment along its longest
  edge, centred, ``n0`` along the second-longest, ``n1`` along the shortest (ties: x, y, z),
  ``widths = (extent along n1, extent along n0)``, area the product of the two shorter edges,
  volume the product of all three. Cylinder: a circular segment along its axis, centred,
  ``D = 2r``, volume ``πr²L``. Capsule: the cylinder part as a circular segment, volume
  ``πr²L + 4/3 πr³``. Sphere, ellipsoid: volume only. Mesh (or any other kind): an error naming
  the link, unless the hydro file describes the link (``volume`` or ``dry``; its mesh geoms are
  then ignored). A link's volume is the sum of its primitives', its COB their volume-weighted
  centroid; mass and COM come from the inertial description.
- Names: URDF link and joint names, MJCF body and joint names, are kept (``Link.name``,
  ``Joint.name``; an unnamed MJCF joint has none). Links are in MuJoCo's body order (depth first,
  as written), so ``q`` is in the order of the description's moving joints.
- The files: regular files only (a directory, a named pipe or a device is refused, not waited
  on), the description and every file it names or includes; at most
  :data:`MAX_DESCRIPTION_BODIES` bodies, ``uwml.MAX_ROBOT_JOINTS`` moving joints (and a free
  root) and :data:`MAX_DESCRIPTION_GEOMS` geoms, counted as written (``<replicate>`` multiplied,
  ``<include>`` added) before MuJoCo reads the file; numbers finite. See
  :mod:`uwml.io._description_xml`, which reads the XML as written for these checks before MuJoCo
  does.

What MuJoCo loses, and how this module keeps it. ``mujoco.MjModel.from_xml_path`` on a URDF
fuses every body without a joint into its parent (``fusestatic``, on by default for URDF): the
root link is merged into the world body, whose mass MuJoCo does not keep (``body_mass[0]`` is 0),
so the base body's mass, COM and geometry would be lost. So the description is read as an
``mujoco.MjSpec``, with ``fusestatic`` turned off (and, for URDF, ``inertiafromgeom``), the
non-collision geoms (and the meshes only they use) deleted, then compiled: the root stays a body
with its own inertial and geoms, fixed links stay bodies (fused here, by the rules above), and the
compiled model supplies what the spec leaves implicit (MJCF default classes, ``fromto``, Euler
sequences and degrees, inertia from geoms where MJCF has no ``<inertial>``). What MuJoCo changes
without a word (a repeated joint name, a ``<mimic>``, a negative mass) is refused from the XML as
written or from the spec before compiling. ``from_mujoco`` takes a model already compiled: if it
was compiled from a URDF with ``fusestatic`` on, the root's mass is already gone (the base is then
the world, without a body); load the file with :func:`from_urdf` instead.

The hydro file (TOML): what the descriptions lack, per link and per joint by name, and the water;
its format is :mod:`uwml.io.hydrofile`'s (:func:`read_hydro`, :class:`HydroFile`).
"""

from __future__ import annotations

import os
import re
import warnings
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any, NoReturn, TypeVar

import numpy as np

from ..domains import MAX_MASS
from ..model.parts import Joint, Link, Water
from ..plausibility import PlausibilityWarning
from ._description_geometry import Outline, _assembled, _Body, _body, _records, _rotation, _t, outlines_of
from ._description_io import DescriptionError, clipped, quoted
from ._description_masses import MassOverride, OwnInertial, PlacedItem, _changes_mass, apply_masses, massless_overrides
from ._description_xml import MAX_DESCRIPTION_BODIES, MAX_DESCRIPTION_GEOMS, limits_exceeded, scan
from ._robot_like import RobotLike
from .hydrofile import HydroFile, HydroLink, _table, read_hydro

__all__ = [
    "MAX_DESCRIPTION_BODIES",
    "MAX_DESCRIPTION_GEOMS",
    "DescriptionError",
    "DescriptionParts",
    "HydroFile",
    "HydroLink",
    "MassOverride",
    "Outline",
    "PlacedItem",
    "mjcf_parts",
    "model_and_parts",
    "mujoco_parts",
    "read_hydro",
    "urdf_parts",
]

_R = TypeVar("_R", bound=RobotLike)


def _mujoco() -> Any:
    try:
        import mujoco
    except ImportError:
        raise ImportError('reading URDF and MJCF needs MuJoCo: pip install "uwml[mujoco]" (or pip install mujoco)') from None
    return mujoco


@dataclass(frozen=True, eq=False)
class DescriptionParts:
    """The robot of a description, in parts: its joints, links and base as mapped, and the hydro
    file's joint losses and water. :meth:`build` puts them together, the errors of the whole
    naming the description's joints and links (``refused``)."""

    joints: tuple[Joint, ...]
    links: tuple[Link, ...]
    base: Link | None
    hydro: HydroFile
    #: Raises the DescriptionError of a failed assembly (called while handling its exception).
    refused: Callable[[Exception], NoReturn]
    #: The hydro file's point items and mass overrides as the robot carries them (in its links'
    #: frames), for ``uwml describe`` (:func:`uwml.viz.describe.describe`).
    items: tuple[PlacedItem, ...] = ()
    overrides: tuple[MassOverride, ...] = ()
    #: The collision shapes of the bodies described by lumped models, for ``uwml describe``.
    outlines: tuple[Outline, ...] = ()

    def build(self, make: Callable[..., _R]) -> _R:
        """``make(joints, links, base=)`` (the class :class:`uwml.Robot`), then with the hydro
        file's joint losses (by joint name) and water; a DescriptionError naming the element."""
        # As where the parts were mapped: a huge coordinate's inf is the model's checks' to refuse.
        with np.errstate(all="ignore"):
            try:
                robot = make(self.joints, self.links, base=self.base)
            except (TypeError, ValueError) as exc:
                self.refused(exc)
        return _with_joints_and_water(robot, self.hydro, make)


def _with_joints_and_water(robot: _R, hydro: HydroFile, make: Callable[..., _R]) -> _R:
    """``robot`` with the joint losses (by joint name) and the water of the hydro file."""
    names = robot.joint_names
    for name in hydro.joints:
        if name not in names:
            known = clipped(", ".join(names) or "none")
            raise DescriptionError(
                f"{hydro.source}: {_table('joints', name)}: no joint of that name in the description (its joints: {known})"
            )
    if not hydro.joints and hydro.water is None:
        return robot
    losses = [hydro.joints.get(name) for name in names] if hydro.joints else robot.losses
    return make(robot.joints, robot.links, base=robot.base, losses=losses, water=hydro.water)


# --- reading ----------------------------------------------------------------------------------


def _is_collision(geom: Any) -> bool:
    return bool(geom.contype) or bool(geom.conaffinity)


def _unknown_link(hydro_source: str, name: str, source: str, names: set[str]) -> DescriptionError:
    known = clipped(", ".join(sorted(n for n in names if n and n != "world")))
    if name == "world":
        return DescriptionError(
            f"{hydro_source}: [links.world]: 'world' is the world (MuJoCo's world body; a URDF link named 'world' becomes it), "
            f"not a link of the robot: {source}'s links are {known}"
        )
    return DescriptionError(
        f"{hydro_source}: {_table('links', name)}: {source} has no link (body) named {quoted(name)} (its links: {known})"
    )


def _check_masses(spec: Any, fmt: str, source: str) -> None:
    """Refuses what MuJoCo's compile would change without a word: a negative mass (clamped to 0),
    a URDF link named 'world' with mass or geometry (taken for the world), and a URDF link moved
    by a joint with no mass (massless by URDF's rules; MuJoCo cannot move it); and a mass beyond
    ``MAX_MASS``, which the model refuses, before MuJoCo's compile warns of it (a singular
    inertia matrix) in words that do not name the link."""
    noun = "link" if fmt == "URDF" else "body"
    world, bodies = spec.bodies[0], spec.bodies[1:]
    for body in bodies:
        if body.explicitinertial and not body.mass >= 0.0:
            raise DescriptionError(f"{source}: {noun} {quoted(body.name)} has mass {body.mass:g} kg in its <inertial>, which is negative")
        if body.explicitinertial and body.mass > MAX_MASS:
            raise DescriptionError(
                f"{source}: {noun} {quoted(body.name)} has mass {body.mass:g} kg in its <inertial>, beyond {MAX_MASS:g} kg "
                "(uwml.domains.MAX_MASS, docs/domains.md)"
            )
        if body.explicitinertial and not np.all(np.asarray(body.inertia) >= 0.0):
            raise DescriptionError(
                f"{source}: {noun} {quoted(body.name)} has a negative moment of inertia in its <inertial> ({', '.join(f'{x:g}' for x in body.inertia)})"
            )
    if fmt != "URDF":
        return
    if world.explicitinertial or world.mass != 0.0 or any(_is_collision(g) for g in world.geoms):
        raise DescriptionError(
            f"{source}: link 'world' has an <inertial> or a <collision>; MuJoCo takes a URDF link named 'world' for the world itself "
            "(fixed, without mass, its geometry scenery): rename the link if it is the robot's base"
        )

    def massive(body: Any) -> bool:
        return (body.explicitinertial and body.mass > 0.0) or any(massive(child) for child in body.bodies if not child.joints)

    for body in bodies:
        if body.joints and not massive(body):
            raise DescriptionError(
                f"{source}: link {quoted(body.name)} is moved by joint {quoted(body.joints[0].name)} but has no <inertial> with a mass "
                "(nor has a link fixed to it): URDF makes it massless, and a link moved by a joint needs a mass and inertia"
            )


_ELEMENT = re.compile(r"Element name '([^']*)', id (\d+)")
_ELEMENT_KINDS = ("geom", "joint", "mesh", "site", "material", "texture", "hfield", "skin", "tendon", "actuator", "sensor", "equality")


def _compile_error(exc: ValueError, spec: Any, fmt: str, source: str) -> DescriptionError:
    """MuJoCo's compile error, with the element it names ("Element name '', id 3") as uwml names
    it: the geom's link, the body or joint by name."""
    text = " ".join(str(exc).split()).removeprefix("Error: ")
    found = _ELEMENT.search(text)
    if found is None:
        return DescriptionError(f"{source}: MuJoCo cannot compile this {fmt} file: {clipped(text)}")
    message, name, index = text[: found.start()].strip(), found.group(1), int(found.group(2))
    kind = message.rsplit(" in ", 1)[1] if " in " in message else "body"
    kind = kind if kind in _ELEMENT_KINDS else "body"  # "... in fullinertia": the body's
    noun = "link" if fmt == "URDF" else "body"
    if kind == "geom" and index < len(spec.geoms):
        where = (
            f"{noun} {quoted(spec.geoms[index].parent.name)}, its geom {quoted(name)}"
            if name
            else f"{noun} {quoted(spec.geoms[index].parent.name)}"
        )
    else:
        where = f"{noun if kind == 'body' else kind} {quoted(name)}" if name else f"{kind} {index}"
    line = re.search(r"line (\d+)", text[found.end() :])
    if line is not None:
        where += f" (line {line.group(1)})"
    if "moving bodies" in message:
        message += " (a body moved by a joint needs a positive mass and inertia)"
    return DescriptionError(f"{source}: {where}: MuJoCo cannot compile this {fmt} file: {clipped(message)}")


def _spec(
    path: str | os.PathLike[str], what: str, hydro: dict[str, HydroLink], hydro_source: str, floating: bool = False
) -> tuple[Any, dict[str, dict[str, float]], dict[str, OwnInertial]]:
    """The compiled model of the description (with the hydro file's masses: mass overrides and
    items, :mod:`uwml.io._description_masses`), its joints' limits by name as written (URDF), and
    the inertial before the items of each body whose masses the hydro file changed."""
    mujoco = _mujoco()
    source = str(path)
    fmt, written_limits = scan(path, what)  # the XML as written: files, sizes, names, numbers (uwml.io._description_xml)
    try:
        spec = mujoco.MjSpec.from_file(source)
    except ValueError as exc:
        raise DescriptionError(f"{source}: not a readable {fmt} file: {clipped(str(exc))}") from None
    spec.compiler.fusestatic = False
    if fmt == "URDF":  # URDF's rule: no <inertial>, no mass (MuJoCo would compute one from the geoms)
        spec.compiler.inertiafromgeom = mujoco.mjtInertiaFromGeom.mjINERTIAFROMGEOM_FALSE
    names = {body.name for body in spec.bodies[1:]}
    for name in hydro:
        if name not in names:
            raise _unknown_link(hydro_source, name, source, names)
    massless_overrides(mujoco, spec, hydro, fmt, hydro_source)
    _check_masses(spec, fmt, source)
    kept_meshes: set[str] = set()
    for geom in list(spec.geoms):
        body = geom.parent
        if not _is_collision(geom):
            spec.delete(geom)
            continue
        if geom.type == mujoco.mjtGeom.mjGEOM_MESH:
            entry = hydro.get(body.name)
            if entry is None or not entry.describes_geometry:
                raise DescriptionError(
                    f"{source}: link {quoted(body.name)} has a collision mesh ({quoted(geom.meshname) if geom.meshname else 'unnamed'}), "
                    f"which uwml cannot turn into segments: describe the link in a hydro file ({_table('links', body.name)} with volume "
                    "and segments, or dry = true)"
                )
            if not entry.dry and not entry.segments and entry.lumped is None and (entry.volume or 0.0) > 0.0:
                warnings.warn(
                    f"{hydro_source}: {_table('links', body.name)} gives the mesh link {quoted(body.name)} a volume but no "
                    "segments and no lumped model: it has buoyancy, but no drag and no added mass; give it segments or a "
                    "lumped model if it moves through the water (or dry = true if it is out of it)",
                    PlausibilityWarning,
                    stacklevel=4,
                )
            if body.explicitinertial or fmt == "URDF":
                spec.delete(geom)  # its geometry is the hydro file's; its mass is the inertial's
                continue
            kept_meshes.add(geom.meshname)
    for mesh in list(spec.meshes):
        if mesh.name not in kept_meshes:
            spec.delete(mesh)
    if floating:
        _float_root(spec, source)
    model = _compiled(spec, fmt, source)
    own = apply_masses(mujoco, spec, model, hydro, hydro_source)
    if own:  # the same spec with the hydro file's masses in its bodies' inertials
        model = _compiled(spec, fmt, source)
    return model, written_limits, own


def _compiled(spec: Any, fmt: str, source: str) -> Any:
    """``spec`` compiled; its errors and warnings DescriptionErrors naming the element."""
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        try:
            model = spec.compile()
        except ValueError as exc:
            raise _compile_error(exc, spec, fmt, source) from None
    if caught:  # MuJoCo's warnings while compiling ("inertia matrix too close to singular"): a broken model
        raise DescriptionError(f"{source}: MuJoCo warns while compiling this {fmt} file: {clipped(str(caught[0].message))}")
    return model


def _float_root(spec: Any, source: str) -> None:
    """The root body on a free joint (unless it has one already)."""
    mujoco = _mujoco()
    roots = [body for body in spec.worldbody.bodies]
    if len(roots) != 1:
        raise DescriptionError(f"{source}: the world must hold exactly one root body (the robot's base) to float it")
    joints = list(roots[0].joints)
    if any(joint.type == mujoco.mjtJoint.mjJNT_FREE for joint in joints):
        return
    if joints:
        raise DescriptionError(f"{source}: the root body {quoted(roots[0].name)} hangs from the world by a joint: it cannot also float")
    roots[0].add_freejoint()


def urdf_parts(path: str | os.PathLike[str], hydro: str | os.PathLike[str] | None = None) -> DescriptionParts:
    """The robot of the URDF file at ``path`` with the hydro file ``hydro``, in parts."""
    file = HydroFile() if hydro is None else read_hydro(hydro)
    model, written_limits, own = _spec(path, "URDF", file.links, str(hydro))
    return _from_model(model, written_limits, file, str(path), str(hydro), own)


def mjcf_parts(path: str | os.PathLike[str], hydro: str | os.PathLike[str] | None = None) -> DescriptionParts:
    """The robot of the MJCF file at ``path`` with the hydro file ``hydro``, in parts."""
    file = HydroFile() if hydro is None else read_hydro(hydro)
    model, written_limits, own = _spec(path, "MJCF", file.links, str(hydro))
    return _from_model(model, written_limits, file, str(path), str(hydro), own)


def model_and_parts(
    path: str | os.PathLike[str], hydro: str | os.PathLike[str] | None = None, floating: bool | None = None
) -> tuple[Any, DescriptionParts]:
    """The compiled ``mujoco.MjModel`` of a URDF (``.urdf``) or MJCF (any other suffix) file, as
    this module reads it (visual geoms and their meshes removed, so absent visual mesh files do
    not matter; fixed links kept as bodies; the root kept with its inertial), and its robot in
    parts: what a simulation of the description needs (:mod:`uwml.sim.mujoco`). ``floating``:
    the root body on a free joint (a vehicle floating freely), keeping the description's own
    masses and inertias; None (default): the hydro file's ``[base] floating`` (default false).
    A root that is already free stays so."""
    what = "URDF" if str(path).lower().endswith(".urdf") else "MJCF"
    file = HydroFile() if hydro is None else read_hydro(hydro)
    if floating is not None and not isinstance(floating, bool):
        raise TypeError(f"floating must be true, false or None, got {type(floating).__name__}")
    model, written_limits, own = _spec(path, what, file.links, str(hydro), file.floating if floating is None else floating)
    return model, _from_model(model, written_limits, file, str(path), str(hydro), own)


def mujoco_parts(model: Any, hydro: str | os.PathLike[str] | None = None) -> DescriptionParts:
    """The robot of a compiled ``mujoco.MjModel``, in parts (see the module docstring for what a
    URDF compiled with ``fusestatic`` has already lost)."""
    mujoco = _mujoco()
    if not isinstance(model, mujoco.MjModel):
        raise TypeError(f"model must be a mujoco.MjModel, got {type(model).__name__}")
    source = "<mujoco.MjModel>"
    error = limits_exceeded(source, model.nbody - 1, model.njnt, model.ngeom, urdf=False, counted="in the compiled model")
    if error is not None:
        raise error
    file = HydroFile() if hydro is None else read_hydro(hydro)
    names = {model.body(i).name for i in range(1, model.nbody)}
    for name, entry in file.links.items():
        if name not in names:
            raise _unknown_link(str(hydro), name, "the MuJoCo model", names)
        if _changes_mass(entry):
            what = "a mass override" if entry.mass is not None else "items with mass"
            raise DescriptionError(
                f"{hydro}: {_table('links', name)} gives {what}, which a compiled mujoco.MjModel cannot take (its masses are "
                "compiled in, and a simulation of it would not carry them): read the description with uwml.Robot.from_urdf, "
                "from_mjcf or uwml.robot.files.model_and_robot"
            )
    return _from_model(model, {}, file, source, str(hydro), {})


def _from_model(
    model: Any, written_limits: dict[str, dict[str, float]], file: HydroFile, source: str, hydro_source: str, own: dict[str, OwnInertial]
) -> DescriptionParts:
    # A huge coordinate overflows to inf in the frames' products: the model's checks then refuse
    # it by name (a numpy warning would say nothing of where).
    with np.errstate(all="ignore"):
        return _mapped(model, written_limits, file, source, hydro_source, own)


def _split_joint(first: str, second: str) -> str | None:
    """The URDF joint that MuJoCo split into ``first`` and ``second`` (its planar and floating
    joints become ``NAME_TX``, ``NAME_TY``, ``NAME_RZ``, …), or None."""
    suffixes = ("_TX", "_TY", "_TZ", "_RX", "_RY", "_RZ")
    for a in suffixes:
        for b in suffixes:
            if first.endswith(a) and second.endswith(b) and first[: -len(a)] == second[: -len(b)] and first[: -len(a)]:
                return first[: -len(a)]
    return None


def _limits(model: Any, j: int, written_limits: dict[str, dict[str, float]]) -> dict[str, Any]:
    """Joint ``j``'s limits as :class:`uwml.Joint` takes them: its range (where limited), its
    velocity and effort limits as the URDF writes them, else the larger magnitude of its
    ``actuatorfrcrange`` (MJCF; where limited and nonzero)."""
    written = written_limits.get(model.joint(j).name, {})
    limits: dict[str, Any] = {"velocity_limit": written.get("velocity"), "effort_limit": written.get("effort")}
    lower, upper = (float(x) for x in model.jnt_range[j])
    if model.jnt_limited[j] and lower < upper:
        limits["range"] = (lower, upper)
    effort = max(abs(float(x)) for x in model.jnt_actfrcrange[j])
    if limits["effort_limit"] is None and model.jnt_actfrclimited[j] and effort > 0.0:
        limits["effort_limit"] = effort
    return limits


def _mapped(
    model: Any, written_limits: dict[str, dict[str, float]], file: HydroFile, source: str, hydro_source: str, own: dict[str, OwnInertial]
) -> DescriptionParts:
    hydro = file.links
    mujoco = _mujoco()
    jt = mujoco.mjtJoint
    body_name = [model.body(i).name for i in range(model.nbody)]
    joint_name = [model.joint(j).name for j in range(model.njnt)]
    parent = [int(p) for p in model.body_parentid]
    roots = [i for i in range(1, model.nbody) if parent[i] == 0]
    if len(roots) != 1:
        listed = ", ".join(f"'{body_name[i]}'" for i in roots) or "none"
        raise DescriptionError(f"{source}: the world must hold exactly one root body (the robot's base), got {listed}")
    root = roots[0]

    def joint_label(j: int) -> str:
        return (
            f"joint {quoted(joint_name[j])}"
            if joint_name[j]
            else f"the unnamed joint of body {quoted(body_name[int(model.jnt_bodyid[j])])}"
        )

    moving: dict[int, int] = {}  # body -> its hinge/slide joint
    free_root = False
    for j in range(model.njnt):
        b, kind = int(model.jnt_bodyid[j]), int(model.jnt_type[j])
        if kind == jt.mjJNT_FREE:
            if b != root or model.body_jntnum[b] != 1:
                raise DescriptionError(
                    f"{source}: {joint_label(j)} is a free (floating) joint; only the root body may be free (the moving base)"
                )
            free_root = True
            continue
        if kind not in (jt.mjJNT_HINGE, jt.mjJNT_SLIDE):
            what = {int(jt.mjJNT_BALL): "ball"}.get(kind, str(kind))
            raise DescriptionError(
                f"{source}: {joint_label(j)} is a {what} joint; uwml takes revolute/continuous/hinge and prismatic/slide joints (and a free root)"
            )
        if b in moving:
            split = _split_joint(model.joint(moving[b]).name, model.joint(j).name)
            if split is not None:
                raise DescriptionError(
                    f"{source}: joint {quoted(split)} is a planar or floating joint (MuJoCo reads it as the joints "
                    f"{joint_label(moving[b])}, {joint_label(j)}, …); uwml takes revolute, continuous and prismatic joints (and a free root)"
                )
            raise DescriptionError(
                f"{source}: body {quoted(body_name[b])} has several joints ({joint_label(moving[b])}, {joint_label(j)}); uwml takes one per link"
            )
        if model.qpos0[model.jnt_qposadr[j]] != 0.0:
            raise DescriptionError(f"{source}: {joint_label(j)} has a nonzero ref; uwml's q = 0 is the pose as written")
        moving[b] = j
    # The base: the root body, unless the root itself hangs from the world by a joint.
    base_body = 0 if root in moving else root

    rotation = {base_body: np.eye(3)}
    position = {base_body: np.zeros(3)}
    owner = {base_body: base_body}
    origin = {base_body: np.zeros(3)}
    order = [base_body]
    for i in range(1, model.nbody):
        if i == base_body:
            continue
        p = parent[i]
        rotation[i] = rotation[p] @ _rotation(model.body_quat[i])
        position[i] = position[p] + rotation[p] @ model.body_pos[i]
        if i in moving:
            owner[i] = i
            origin[i] = position[i] + rotation[i] @ model.jnt_pos[moving[i]]
            order.append(i)
        else:
            owner[i] = owner[p]

    link_index = {b: k for k, b in enumerate(order[1:])}
    joints = []
    for b in order[1:]:
        j = moving[b]
        axis = rotation[b] @ model.jnt_axis[j]
        axis = axis / np.linalg.norm(axis)
        parent_owner = owner[parent[b]]
        try:
            joints.append(
                Joint(
                    _t(origin[b] - origin[parent_owner]),
                    _t(axis),
                    parent=link_index.get(parent_owner, -1),
                    kind="revolute" if model.jnt_type[j] == jt.mjJNT_HINGE else "prismatic",
                    name=joint_name[j] or None,
                    **_limits(model, j, written_limits),
                )
            )
        except (TypeError, ValueError) as exc:
            raise DescriptionError(f"{source}: {joint_label(j)}: {clipped(str(exc))}") from None

    parts: dict[int, list[_Body]] = {b: [] for b in order}
    for i in range(1, model.nbody):
        k = owner[i]
        try:
            parts[k].append(
                _body(
                    mujoco,
                    model,
                    i,
                    rotation[i],
                    position[i] - origin[k],
                    body_name[i],
                    hydro.get(body_name[i]),
                    source,
                    hydro_source,
                    own.get(body_name[i]),
                )
            )
        except DescriptionError:
            raise
        except (TypeError, ValueError) as exc:  # a segment of non-finite numbers
            raise DescriptionError(f"{source}: link {quoted(body_name[i])}: {clipped(str(exc))}") from None

    def with_hydro(b: int) -> str:
        """Where the hydro file describes link ``b`` (its own body or one fused into it), if it does."""
        tables = [_table("links", x.name) for x in parts.get(b, ()) if x.name in hydro]
        return f" (with {hydro_source} {', '.join(tables)})" if tables else ""

    water = file.water if file.water is not None else Water()

    def link(b: int) -> Link:
        fields = _assembled(parts[b], body_name[b], hydro, hydro_source, water.density, water.gravity)
        try:
            return Link(name=body_name[b] or None, **fields)
        except (TypeError, ValueError) as exc:
            raise DescriptionError(f"{source}: link {quoted(body_name[b])}{with_hydro(b)}: {clipped(str(exc))}") from None

    links = [link(b) for b in order[1:]]
    base = link(base_body) if base_body != 0 else None
    del free_root  # a free root and a fixed root give the same robot: the motion is an argument

    def refused(exc: Exception) -> NoReturn:
        # The model's checks number joints and links ("joint 0: ..."); the description names them.
        message = clipped(str(exc))
        numbered = re.match(r"(joint|link|segment) (\d+): ", message)
        # Segments are numbered over the base's, then each link's (uwml.Robot.segments).
        owners = [base_body] * len(base.segments if base is not None else ()) + [b for b, x in zip(order[1:], links) for _ in x.segments]
        if numbered is not None and numbered.group(1) == "segment" and int(numbered.group(2)) < len(owners):
            b = owners[int(numbered.group(2))]
            message = f"link {quoted(body_name[b])}{with_hydro(b)}, {message}"
        elif numbered is not None and numbered.group(1) != "segment" and int(numbered.group(2)) < len(order) - 1:
            b = order[1 + int(numbered.group(2))]
            named = joint_label(moving[b]) if numbered.group(1) == "joint" else f"link {quoted(body_name[b])}{with_hydro(b)}"
            message = f"{named}: {message[numbered.end() :]}"
        elif message.startswith("base.") and base_body != 0:
            message = f"link {quoted(body_name[base_body])} (the base){with_hydro(base_body)}: {message}"
        raise DescriptionError(f"{source}: {message}") from None

    items, overrides = _records(parts, body_name, own)
    return DescriptionParts(tuple(joints), tuple(links), base, file, refused, items, overrides, outlines_of(parts, body_name))
