"""A robot made in code, beyond the paper's leg (:func:`uwml.paper_leg`), for documentation,
benchmarks and first experiments: its numbers are illustrative, not a vehicle's datasheet."""

from __future__ import annotations

import math

from ..model.parts import Joint, Link, Segment
from ..robot.tree import Robot

__all__ = ["arm_on_rov"]


def arm_on_rov() -> Robot:
    """A 7-joint manipulator at the front of a 300 kg work-class ROV hull.

    Joints: shoulder yaw (z), shoulder pitch, elbow pitch (y), wrist roll (x), wrist pitch (y),
    wrist roll (x), and a prismatic gripper slide (x), in a chain from the base. Every link is a
    circular tube along its x axis plus a rectangular housing below it (14 segments); the hull is
    one circular segment 1.8 m long, 0.6 m across, with its centre of buoyancy 0.1 m above its
    centre of mass. The same robot as the Rust benchmarks' (``crates/uwml-core/benches/common/arm.rs``).
    """
    axes = [(0, 0, 1), (0, 1, 0), (0, 1, 0), (1, 0, 0), (0, 1, 0), (1, 0, 0), (1, 0, 0)]
    origins = [(0.9, 0, -0.3), (0, 0, -0.15), (0.6, 0, 0), (0.5, 0, 0), (0.15, 0, 0), (0.2, 0, 0), (0.1, 0, 0)]
    lengths = [0.15, 0.6, 0.5, 0.15, 0.2, 0.1, 0.15]
    joints = [Joint(origin, axis, kind="prismatic" if i == 6 else "revolute") for i, (origin, axis) in enumerate(zip(origins, axes))]
    links = []
    for i, length in enumerate(lengths):
        mass, diameter = 12.0 - 1.5 * i, 0.12 - 0.01 * i
        tube = Segment((0, 0, 0), (1, 0, 0), length, section="circular", diameter=diameter, area=math.pi * diameter**2 / 4, cd=1.2, cm=1.0)
        housing = Segment(
            (0, 0, -0.05),
            (1, 0, 0),
            0.6 * length,
            normals=((0, 1, 0), (0, 0, 1)),
            widths=(0.05, 0.08),
            area=0.004,
            cd=(2.0, 2.1),
            cm=(1.2, 1.5),
        )
        links.append(Link(mass, (length / 2, 0, 0), mass / 3000.0, cob=(length / 2, 0, 0.01), segments=(tube, housing)))
    hull = Link(
        300.0,
        (0, 0, -0.05),
        0.29,
        cob=(0, 0, 0.05),
        segments=(Segment((-0.9, 0, 0), (1, 0, 0), 1.8, section="circular", diameter=0.6, area=0.283, cd=0.9, cm=1.0),),
    )
    return Robot(joints, links, base=hull)
