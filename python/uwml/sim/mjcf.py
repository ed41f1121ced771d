"""An MJCF model of a :class:`uwml.Robot` for :class:`uwml.sim.mujoco.Simulation`
(:func:`mjcf_of`): one MuJoCo body per link in uwml's frames, each with its mass and an inertia
spread over its segments' solids, for a robot built in code rather than read from a description."""

from __future__ import annotations

import math
from typing import Any

import numpy as np
from numpy.typing import NDArray

from ..robot.tree import Robot

__all__ = ["mjcf_of"]

FloatArray = NDArray[np.float64]


def _segment_solid(segment: Any) -> tuple[float, FloatArray, FloatArray]:
    """A segment as a uniform solid: its volume, centre and unit-mass inertia about the centre."""
    u = np.asarray(segment.axis, dtype=np.float64)
    centre = np.asarray(segment.start, dtype=np.float64) + u * (segment.length / 2.0)
    length = segment.length
    if segment.section == "circular":
        radius = segment.diameter / 2.0
        axial, across = radius**2 / 2.0, (3.0 * radius**2 + length**2) / 12.0
        inertia = across * (np.eye(3) - np.outer(u, u)) + axial * np.outer(u, u)
        return math.pi * radius**2 * length, centre, inertia
    n0, n1 = (np.asarray(n, dtype=np.float64) for n in segment.normals)
    # Drag along n_k uses the extent along the other normal: widths = (along n1, along n0).
    a, b, c = length, segment.widths[1], segment.widths[0]
    frame = np.column_stack([u, n0, n1])
    inertia = frame @ np.diag([b * b + c * c, a * a + c * c, a * a + b * b]) @ frame.T / 12.0
    return a * b * c, centre, inertia


def _body_inertia(body: Any) -> FloatArray:
    """A body's inertia about its centre of mass [kg·m²], its mass spread uniformly over its
    segments' solids (a sphere of its volume, or of 0.05 m radius, without segments)."""
    com = np.asarray(body.com, dtype=np.float64)
    solids = [_segment_solid(s) for s in body.segments]
    total = sum(volume for volume, _, _ in solids)
    if not solids or total <= 0.0:
        radius = (3.0 * body.volume / (4.0 * math.pi)) ** (1.0 / 3.0) if body.volume > 0.0 else 0.05
        sphere: FloatArray = np.eye(3) * (0.4 * body.mass * radius**2)
        return sphere
    inertia = np.zeros((3, 3))
    for volume, centre, unit in solids:
        mass = body.mass * volume / total
        d = centre - com
        inertia += mass * unit + mass * (d @ d * np.eye(3) - np.outer(d, d))
    return inertia


def mjcf_of(robot: Robot, *, floating: bool = False, timestep: float = 1e-3, gravity: float | None = None) -> str:
    """An MJCF model of ``robot`` for :class:`Simulation`: one body per link in uwml's frames
    (parallel to the base at ``q = 0``), hinge and slide joints, each body's mass and centre of
    mass, its inertia that of its mass spread uniformly over its segments' solids (boxes and
    cylinders; without segments, a sphere of its volume), and its segments as geoms without
    contacts. ``floating``: the base on a free joint (it then needs a mass). Gravity: the
    robot's water's."""
    g = robot.water.gravity if gravity is None else gravity
    base = robot.base
    lines = [
        '<mujoco model="uwml_robot">',
        f'  <option timestep="{timestep!r}" gravity="0 0 {-g!r}"/>',
        "  <worldbody>",
        '    <body name="base">',
    ]
    if floating:
        if base is None or base.mass <= 0.0:
            raise ValueError("a floating base needs a base body with a mass")
        lines.append('      <freejoint name="base_free"/>')

    def number(values: Any) -> str:
        return " ".join(repr(float(x)) for x in values)

    def body_lines(body: Any, indent: str) -> list[str]:
        out = []
        if body.mass > 0.0:
            inertia = _body_inertia(body)
            full = [inertia[0, 0], inertia[1, 1], inertia[2, 2], inertia[0, 1], inertia[0, 2], inertia[1, 2]]
            out.append(f'{indent}<inertial pos="{number(body.com)}" mass="{body.mass!r}" fullinertia="{number(full)}"/>')
        for segment in body.segments:
            _, centre, _ = _segment_solid(segment)
            u = np.asarray(segment.axis, dtype=np.float64)
            if segment.section == "circular":
                ends = np.concatenate([centre - u * segment.length / 2.0, centre + u * segment.length / 2.0])
                out.append(
                    f'{indent}<geom type="cylinder" fromto="{number(ends)}" size="{segment.diameter / 2.0!r}" contype="0" conaffinity="0"/>'
                )
            else:
                n0 = np.asarray(segment.normals[0], dtype=np.float64)
                size = [segment.length / 2.0, segment.widths[1] / 2.0, segment.widths[0] / 2.0]
                axes = number(np.concatenate([u, n0]))
                out.append(
                    f'{indent}<geom type="box" pos="{number(centre)}" xyaxes="{axes}" size="{number(size)}" contype="0" conaffinity="0"/>'
                )
        return out

    if base is not None:
        lines += body_lines(base, "      ")
    children: dict[int, list[int]] = {}
    for i, joint in enumerate(robot.joints):
        children.setdefault(-1 if joint.parent is None else joint.parent, []).append(i)

    def emit(parent: int, depth: int) -> None:
        for i in children.get(parent, []):
            joint, link, pad = robot.joints[i], robot.links[i], "  " * depth
            lines.append(f'{pad}<body name="{link.name or f"link{i}"}" pos="{number(joint.origin)}">')
            kind = "slide" if joint.kind == "prismatic" else "hinge"
            lines.append(f'{pad}  <joint name="{joint.name or f"joint{i}"}" type="{kind}" axis="{number(joint.axis)}"/>')
            if link.mass <= 0.0:
                raise ValueError(f"link {i} needs a mass > 0 to move in a simulation")
            lines.extend(body_lines(link, pad + "  "))
            emit(i, depth + 1)
            lines.append(f"{pad}</body>")

    emit(-1, 3)
    lines += ["    </body>", "  </worldbody>", "</mujoco>"]
    return "\n".join(lines)
