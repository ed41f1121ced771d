"""Robots that uwml carries as presets, built from the Rust core's own (``uwml_core::presets``):
the paper's 3-DOF leg (:func:`paper_leg`)."""

from __future__ import annotations

from .. import _core
from ..model.parts import Joint, Link, Segment
from .tree import Robot

__all__ = ["paper_leg"]


def paper_leg() -> Robot:
    """The 3-DOF leg of the paper (Table II; docs/model.md section 2): hip yaw, hip roll, knee
    roll, in series on a fixed base; links 1 and 2 with a rectangular segment each, Cd 2.2 and
    Cm 0.5 (the paper's fitted values, rounded), the normals ordered out of the leg plane (yaw)
    then in it (roll). The numbers are the core's preset (``presets::paper_leg``), so that the
    Rust, C and Python legs are one."""
    joints, links, _base, segments = _core.Robot.paper_leg().parts()
    by_link: dict[int, list[Segment]] = {}
    for owner, start, axis, length, area, section, normals, widths, _diameter, cd, cm, cd_axial, axial_area in segments:
        assert section == "rectangular" and normals is not None and widths is not None
        segment = Segment(
            start=start, axis=axis, length=length, normals=normals, widths=widths, area=area,
            cd=cd, cm=cm, cd_axial=cd_axial, axial_area=axial_area,
        )  # fmt: skip
        by_link.setdefault(owner, []).append(segment)
    return Robot(
        joints=[Joint(origin=origin, axis=axis) for _parent, _kind, origin, axis in joints],
        links=[
            Link(mass=mass, com=com, volume=volume, cob=cob, segments=tuple(by_link.get(i, ())))
            for i, (mass, com, volume, cob) in enumerate(links)
        ],
    )
