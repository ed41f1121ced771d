"""Robots from files, as functions: a uwml model file (:func:`load`, :func:`loads`) and the robot
descriptions URDF and MJCF with a hydro file (:func:`from_urdf`, :func:`from_mjcf`,
:func:`from_mujoco`, :func:`model_and_robot`). :mod:`uwml.io` reads the files into parts; the
:class:`uwml.Robot` is assembled here (as by its classmethods ``Robot.load``, ``Robot.from_urdf``
and so on)."""

from __future__ import annotations

import os
from typing import Any

from ..io import descriptions, modelfile
from .tree import Robot

__all__ = ["from_mjcf", "from_mujoco", "from_urdf", "load", "loads", "model_and_robot"]


def loads(text: str, source: str = "<string>") -> Robot:
    """The robot of a uwml model file given as text (``source`` names it in errors)."""
    return modelfile.parse(text, source).build(Robot)


def load(path: str | os.PathLike[str]) -> Robot:
    """The robot of the uwml model file at ``path``."""
    return Robot.load(path)


def from_urdf(path: str | os.PathLike[str], hydro: str | os.PathLike[str] | None = None) -> Robot:
    """The :class:`uwml.Robot` of the URDF file at ``path``, with the hydro file ``hydro``."""
    return Robot.from_urdf(path, hydro)


def from_mjcf(path: str | os.PathLike[str], hydro: str | os.PathLike[str] | None = None) -> Robot:
    """The :class:`uwml.Robot` of the MJCF file at ``path``, with the hydro file ``hydro``."""
    return Robot.from_mjcf(path, hydro)


def from_mujoco(model: Any, hydro: str | os.PathLike[str] | None = None) -> Robot:
    """The :class:`uwml.Robot` of a compiled ``mujoco.MjModel`` (see :mod:`uwml.io.descriptions`
    for what a URDF compiled with ``fusestatic`` has already lost)."""
    return Robot.from_mujoco(model, hydro)


def model_and_robot(
    path: str | os.PathLike[str], hydro: str | os.PathLike[str] | None = None, floating: bool | None = None
) -> tuple[Any, Robot]:
    """The compiled ``mujoco.MjModel`` of a URDF (``.urdf``) or MJCF (any other suffix) file, as
    :mod:`uwml.io.descriptions` reads it (visual geoms and their meshes removed, so absent visual
    mesh files do not matter; fixed links kept as bodies; the root kept with its inertial), and
    its :class:`uwml.Robot`: what a simulation of the description needs (:mod:`uwml.sim.mujoco`).
    ``floating``: the root on a free joint (None: the hydro file's ``[base] floating``)."""
    model, parts = descriptions.model_and_parts(path, hydro, floating)
    return model, parts.build(Robot)
