"""What the writers of :mod:`uwml.io` take of a robot (:class:`RobotLike`): a :class:`uwml.Robot`,
or anything with its attributes, so that io need not know the class (the robots are built on top
of io, :mod:`uwml.robot`)."""

from __future__ import annotations

from typing import Protocol

from ..model.joint_losses import JointLosses
from ..model.parts import Joint, Link, Segment, Water


class RobotLike(Protocol):
    """The attributes of a :class:`uwml.Robot` that a writer reads (model files, exported code)."""

    @property
    def joints(self) -> tuple[Joint, ...]: ...
    @property
    def links(self) -> tuple[Link, ...]: ...
    @property
    def base(self) -> Link | None: ...
    @property
    def losses(self) -> tuple[JointLosses | None, ...]: ...
    @property
    def water(self) -> Water: ...
    @property
    def segments(self) -> tuple[Segment, ...]: ...
    @property
    def n_joints(self) -> int: ...
    @property
    def joint_names(self) -> tuple[str, ...]: ...
    @property
    def link_names(self) -> tuple[str, ...]: ...
