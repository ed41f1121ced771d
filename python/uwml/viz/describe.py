"""What a robot is made of, in words and in a picture: joints, links, segments, volumes, masses and
the net buoyancy of every body, and a 3-D drawing of the robot at ``q = 0`` with its segments
(``uwml describe``)."""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path

import numpy as np

from ..io.descriptions import MassOverride, Outline, PlacedItem
from ..model.parts import Joint, Link, Segment, Water
from ..robot.tree import Robot

__all__ = ["describe", "draw", "figure", "frame_origins"]


def frame_origins(robot: Robot) -> np.ndarray:
    """Every link frame's origin (its joint) at ``q = 0`` in the base frame, ``(n_joints, 3)``:
    frames are parallel to the base there, so a joint's origin adds to its parent's."""
    origins = np.zeros((robot.n_joints, 3))
    for i, joint in enumerate(robot.joints):
        parent = np.zeros(3) if joint.parent is None or joint.parent < 0 else origins[joint.parent]
        origins[i] = parent + np.asarray(joint.origin)
    return origins


def _bodies(robot: Robot) -> list[tuple[str, Link, np.ndarray]]:
    """(name, body, frame origin at q = 0) of the base (if it has a body) and every link."""
    out: list[tuple[str, Link, np.ndarray]] = []
    if robot.base is not None:
        out.append((robot.base.name or "base", robot.base, np.zeros(3)))
    out += [(name, link, origin) for name, link, origin in zip(robot.link_names, robot.links, frame_origins(robot))]
    return out


def _section(segment: Segment) -> str:
    if segment.section == "circular":
        return f"circular, D {segment.diameter:.4g} m"
    widths = segment.widths or (0.0, 0.0)
    return f"rectangular, widths {widths[0]:.4g} × {widths[1]:.4g} m"


def _limits(joint: Joint) -> str:
    """A joint's limits as the description gives them (uwml warns beyond them, nothing else)."""
    unit, force = ("rad", "N·m") if joint.kind == "revolute" else ("m", "N")
    parts = []
    if joint.range is not None:
        parts.append(f"range [{joint.range[0]:.4g}, {joint.range[1]:.4g}] {unit}")
    if joint.velocity_limit is not None:
        parts.append(f"velocity {joint.velocity_limit:.4g} {unit}/s")
    if joint.effort_limit is not None:
        parts.append(f"effort {joint.effort_limit:.4g} {force}")
    return f"  limits: {', '.join(parts)}" if parts else ""


def describe(robot: Robot, water: Water | None = None, *, items: Sequence[PlacedItem] = (), overrides: Sequence[MassOverride] = ()) -> str:
    """A plain-text account of ``robot``: joints, bodies (mass, volume, net buoyancy in
    ``water``, fresh water by default), segments with their coefficients, and lumped models;
    with a description's hydro file's point items and mass overrides (``items``, ``overrides``:
    :class:`uwml.io.descriptions.DescriptionParts`' own), what each contributes."""
    water = water if water is not None else Water()
    lines = [
        f"{robot.n_joints} joints, {len(robot.segments)} segments; water {water.density:g} kg/m³, g = {water.gravity:g} m/s²",
        "",
        "joints",
    ]
    parent_names = ("base", *robot.link_names)
    for name, joint in zip(robot.joint_names, robot.joints):
        parent = parent_names[0 if joint.parent is None or joint.parent < 0 else joint.parent + 1]
        lines.append(
            f"  {name:16s} {joint.kind:9s} parent {parent:16s} origin {_fmt(joint.origin)}  axis {_fmt(joint.axis)}{_limits(joint)}"
        )
    lines += ["", "bodies (buoyancy = ρ V g, the water's; net = ρ V g − m g, with the weight; both upwards)"]
    total_mass = total_volume = 0.0
    for name, body, _ in _bodies(robot):
        gross = water.density * body.volume * water.gravity
        net = gross - body.mass * water.gravity
        total_mass += body.mass
        total_volume += body.volume
        lines.append(
            f"  {name:16s} mass {body.mass:9.4g} kg  volume {body.volume:9.4g} m³  buoyancy {gross:9.4g} N  net {_number(net, '+10.4g')} N  "
            f"COM {_fmt(body.com)}  COB {_fmt(body.cob or body.com)}  segments {len(body.segments)}"
        )
    gross_total = water.density * total_volume * water.gravity
    net_total = gross_total - total_mass * water.gravity
    lines.append(
        f"  {'all':16s} mass {total_mass:9.4g} kg  volume {total_volume:9.4g} m³  buoyancy {gross_total:9.4g} N  net {_number(net_total, '+10.4g')} N"
    )
    dragless = [name for name, body, _ in _bodies(robot) if body.volume > 0.0 and not body.segments and body.lumped is None]
    if dragless:
        lines.append(
            f"  in the water without drag or added mass (a volume, no segment, no lumped model): {', '.join(dragless)}; "
            "give them segments or a lumped model (a hydro file's [links.NAME]) if they move through the water"
        )
    lines += _masses(robot, water, items, overrides)
    lines += ["", "segments (in their body's frame)"]
    index = 0
    for name, body, _ in _bodies(robot):
        for segment in body.segments:
            cd, cm = segment.cd, segment.cm
            lines.append(
                f"  {index:3d} {name:16s} {_section(segment):34s} length {segment.length:.4g} m  area {segment.area:.4g} m²  "
                f"start {_fmt(segment.start)}  axis {_fmt(segment.axis)}  Cd {_pair(cd)}  Cm {_pair(cm)}"
            )
            index += 1
    lumped = [(name, body.lumped) for name, body, _ in _bodies(robot) if body.lumped is not None]
    if lumped:
        lines += ["", "lumped models (docs/model.md section 12.1; magnitudes: SNAME's X_u̇ = −M_A[0][0])"]
    for name, model in lumped:
        added, damping = np.asarray(model.added_mass), np.asarray(model.linear_damping)
        coupled = (
            " (and off-diagonal terms)" if np.any(added - np.diag(np.diag(added))) or np.any(damping - np.diag(np.diag(damping))) else ""
        )
        turned = "" if np.array_equal(np.asarray(model.axes), np.eye(3)) else " in turned axes"
        lines.append(
            f"  {name:16s} at {_fmt(model.point)}{turned}  M_A diag {_fmt(np.diag(added))}  D_L diag {_fmt(np.diag(damping))}  "
            f"D_Q {_fmt(model.quadratic_damping)}{coupled}"
        )
    return "\n".join(lines)


def _masses(robot: Robot, water: Water, items: Sequence[PlacedItem], overrides: Sequence[MassOverride]) -> list[str]:
    """The hydro file's point items (each one's mass, buoyancy and net force, upwards, at its
    place) and mass overrides, their bodies named as in the bodies' listing."""

    def label(link: str) -> str:
        return "base" if robot.base is not None and robot.base.name == link else link

    def source(body: str, link: str) -> str:
        return "" if body == link else f"  (of {body}, fused into {link})"

    lines = []
    if overrides:
        lines += ["", "mass overrides (the hydro file's mass, in place of the description's inertial; before items)"]
    for o in overrides:
        inertia = "its inertia given" if o.inertia_given else "its inertia the description's, scaled"
        lines.append(
            f"  {label(o.link):16s} mass {o.mass:9.4g} kg (the description's {o.described_mass:.4g} kg)  COM {_fmt(o.com)}  "
            f"{inertia}{source(o.body, o.link)}"
        )
    if items:
        lines += ["", "point items (the hydro file's; in their body's frame; buoyancy = ρ V g, net = ρ V g − m g, upwards)"]
    for index, item in enumerate(items):
        gross = water.density * item.volume * water.gravity
        net = gross - item.mass * water.gravity
        lines.append(
            f"  {label(item.link):16s} {item.name or f'item {index}':16s} mass {item.mass:9.4g} kg  volume {item.volume:9.4g} m³  "
            f"buoyancy {gross:9.4g} N  net {_number(net, '+10.4g')} N  at {_fmt(item.position)}{source(item.body, item.link)}"
        )
    return lines


def _fmt(v: object) -> str:
    """A vector with its rounding residue (below 1e-12 of its largest entry, or of 1) shown as 0."""
    values = np.asarray(v, dtype=float)
    scale = max(1.0, float(np.max(np.abs(values)))) if values.size else 1.0
    return "(" + ", ".join(_number(x, ".4g", scale) for x in values) + ")"


def _number(x: float, spec: str, scale: float = 1.0) -> str:
    """``x`` formatted, a rounding residue (below 1e-12 of ``scale``) as 0."""
    return format(0.0 if abs(x) < 1e-12 * scale else float(x), spec)


def _pair(values: tuple[float, float]) -> str:
    a, b = values
    return f"{a:g}" if a == b else f"({a:g}, {b:g})"


#: The twelve edges of a box, as pairs of corner indices of :func:`_box`.
_BOX_EDGES = ((0, 1), (1, 3), (3, 2), (2, 0), (4, 5), (5, 7), (7, 6), (6, 4), (0, 4), (1, 5), (2, 6), (3, 7))


def _box(start: np.ndarray, axis: np.ndarray, segment: Segment) -> np.ndarray:
    """The eight corners of a rectangular segment's box: along its axis from ``start``, its
    widths across (``widths[0]`` along ``normals[1]``, ``widths[1]`` along ``normals[0]``, the
    widths that face the flow along ``normals[0]`` and ``normals[1]``)."""
    n0, n1 = (np.asarray(n, dtype=float) for n in (segment.normals or ((0.0, 1.0, 0.0), (0.0, 0.0, 1.0))))
    w0, w1 = segment.widths or (0.0, 0.0)
    corners = []
    for along in (0.0, segment.length):
        for a in (-0.5, 0.5):
            for b in (-0.5, 0.5):
                corners.append(start + along * axis + a * w1 * n0 + b * w0 * n1)
    return np.asarray(corners)


def _lumped_surface(body: Link, origin: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """A lumped body's drawing: the sphere of its volume (the model has no shape of its own) about
    the model's reference point, as three ``(12, 12)`` grids of x, y, z."""
    assert body.lumped is not None
    radius = (3.0 * max(body.volume, 1e-9) / (4.0 * np.pi)) ** (1.0 / 3.0)
    centre = origin + np.asarray(body.lumped.point if body.lumped.point is not None else body.cob or body.com)
    u, v = np.meshgrid(np.linspace(0.0, 2.0 * np.pi, 12), np.linspace(0.0, np.pi, 12))
    return centre[0] + radius * np.cos(u) * np.sin(v), centre[1] + radius * np.sin(u) * np.sin(v), centre[2] + radius * np.cos(v)


def _outline_lines(outline: Outline, origin: np.ndarray) -> list[np.ndarray]:
    """An outline's lines in the base frame at q = 0: a box's twelve edges; any other shape as
    the ellipsoid of its extents (three rings)."""
    turn, centre = np.asarray(outline.rotation), origin + np.asarray(outline.position)
    a, b, c = outline.size
    if outline.kind == "box":
        corners = np.array([[x, y, z] for x in (-a, a) for y in (-b, b) for z in (-c, c)]) @ turn.T + centre
        edges = ((0, 1), (0, 2), (0, 4), (1, 3), (1, 5), (2, 3), (2, 6), (3, 7), (4, 5), (4, 6), (5, 7), (6, 7))
        return [corners[[i, j]] for i, j in edges]
    # MuJoCo's sizes: a sphere r; an ellipsoid its three semi-axes; a cylinder and a capsule r and
    # the half-length (a capsule's caps added).
    axes = {"sphere": (a, a, a), "ellipsoid": (a, b, c), "cylinder": (a, a, b), "capsule": (a, a, b + a)}.get(outline.kind, (a, a, a))
    t = np.linspace(0.0, 2.0 * np.pi, 37)
    zero = np.zeros_like(t)
    rings = [
        np.stack([np.cos(t), np.sin(t), zero], 1),
        np.stack([np.cos(t), zero, np.sin(t)], 1),
        np.stack([zero, np.cos(t), np.sin(t)], 1),
    ]
    return [(ring * np.asarray(axes)) @ turn.T + centre for ring in rings]


def figure(robot: Robot, title: str | None = None, outlines: Sequence[Outline] = ()) -> object:
    """The matplotlib figure of :func:`draw`: a ``matplotlib.figure.Figure`` made without pyplot,
    so that drawing it neither changes the backend nor opens a window."""
    from matplotlib.figure import Figure

    fig = Figure(figsize=(7, 6))
    ax = fig.add_subplot(projection="3d")
    points = [np.zeros(3)]
    scale = max((s.length for s in robot.segments), default=0.5)
    # Thrusters' arrows: a quarter of the largest part (a segment, or a lumped body's sphere).
    sizes = [2.0 * (3.0 * body.volume / (4.0 * np.pi)) ** (1.0 / 3.0) for _, body, _ in _bodies(robot) if body.lumped is not None]
    push_length = 0.25 * max([scale, *sizes])
    shapes = {outline.link for outline in outlines}
    for name, body, origin in _bodies(robot):
        for outline in (o for o in outlines if o.link == name):
            for line in _outline_lines(outline, origin):
                ax.plot(*line.T, color="tab:purple", linewidth=0.9, gid=f"outline {name}")
                points += [line.min(axis=0), line.max(axis=0)]
        if body.lumped is not None and name not in shapes:
            x, y, z = _lumped_surface(body, origin)
            ax.plot_wireframe(x, y, z, color="tab:purple", linewidth=0.5, alpha=0.6, gid=f"lumped {name}")
            points += [np.array([x.min(), y.min(), z.min()]), np.array([x.max(), y.max(), z.max()])]
        label_at = origin + np.asarray(body.com)
        ax.text(*label_at, f" {name}", fontsize=7, color="0.2")
        for thruster in body.thrusters:
            at, push = origin + np.asarray(thruster.position), push_length * np.asarray(thruster.direction)
            ax.quiver(*at, *push, color="tab:red", linewidth=1.0, arrow_length_ratio=0.3, gid=f"thruster {thruster.name or ''}")
            points += [at]
        for segment in body.segments:
            start = origin + np.asarray(segment.start)
            end = start + segment.length * np.asarray(segment.axis)
            if segment.section == "circular":
                ax.plot(*np.stack([start, end]).T, color="tab:blue", linewidth=max(1.5, 40.0 * float(segment.diameter or 0.0)), alpha=0.8)
                points += [start, end]
            else:
                corners = _box(start, np.asarray(segment.axis), segment)
                for a, b in _BOX_EDGES:
                    ax.plot(*np.stack([corners[a], corners[b]]).T, color="tab:orange", linewidth=1.2)
                points += list(corners)
        com, cob = origin + np.asarray(body.com), origin + np.asarray(body.cob or body.com)
        ax.scatter(*com, marker="x", color="k", s=25)
        ax.scatter(*cob, marker="o", facecolors="none", edgecolors="tab:green", s=30)
        points += [com, cob]
    for origin, joint in zip(frame_origins(robot), robot.joints):
        tip = origin + 0.15 * scale * np.asarray(joint.axis)
        ax.scatter(*origin, color="k", s=18)
        ax.plot(*np.stack([origin, tip]).T, color="k", linewidth=1.0)
        points.append(origin)
    cloud = np.asarray(points)
    centre, half = (cloud.max(axis=0) + cloud.min(axis=0)) / 2, max(float(np.ptp(cloud, axis=0).max()) / 2, 0.1)
    ax.set_xlim(centre[0] - half, centre[0] + half)
    ax.set_ylim(centre[1] - half, centre[1] + half)
    ax.set_zlim(centre[2] - half, centre[2] + half)
    ax.set_box_aspect((1.0, 1.0, 1.0))  # a metre as long on every axis: a sphere drawn round
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    ax.set_zlabel("z [m]")
    from matplotlib.lines import Line2D

    legend = [
        Line2D([], [], color="tab:blue", linewidth=4, label="circular segment (width ∝ diameter)"),
        Line2D([], [], color="tab:orange", linewidth=1.2, label="rectangular segment (its box)"),
        Line2D([], [], color="k", marker="o", markersize=4, linewidth=1.0, label="joint and its axis"),
        Line2D([], [], color="k", marker="x", linestyle="none", label="centre of mass"),
        Line2D([], [], markeredgecolor="tab:green", markerfacecolor="none", marker="o", linestyle="none", label="centre of buoyancy"),
    ]
    if robot.lumped_models:
        what = "its collision shape" if outlines else "the sphere of its volume"
        legend.append(Line2D([], [], color="tab:purple", linewidth=0.8, label=f"lumped body ({what})"))
    if robot.thrusters:
        legend.append(Line2D([], [], color="tab:red", marker=">", linewidth=1.0, label="thruster (its push)"))
    ax.legend(handles=legend, loc="upper left", fontsize=7)
    ax.set_title(title or f"{robot.n_joints} joints, {len(robot.segments)} segments at q = 0", fontsize=9)
    fig.tight_layout()
    return fig


def draw(robot: Robot, path: str | Path, title: str | None = None, outlines: Sequence[Outline] = ()) -> None:
    """A 3-D picture of ``robot`` at ``q = 0`` (base frame, z up), with a legend: circular
    segments as thick blue lines (width by their diameter), rectangular ones as their boxes'
    outlines (orange), lumped bodies as their description's collision shapes (``outlines``, a
    description's :attr:`uwml.io.descriptions.DescriptionParts.outlines`) or, without them, as
    the sphere of their volume about their reference point (purple wireframe), thrusters as arrows along their push (red), joints as black dots with
    their axes, centres of mass (x) and buoyancy (o), each body named at its centre of mass.
    Written to ``path`` (format from the extension)."""
    fig = figure(robot, title, outlines)
    fig.savefig(path, dpi=110)  # type: ignore[attr-defined]
