"""A reusable result for one state of one robot, written in place call after call, as
Pinocchio's ``Data`` is: :meth:`uwml.Robot.workspace`, given as ``workspace=`` to
:meth:`uwml.Robot.hydro` and :meth:`uwml.Robot.environment`.

A controller stepping one state at a time gets each call's forces without the call making
result objects and arrays: the core writes them into the workspace's one float64 array, whose
parts the workspace's :class:`uwml.Torques` (and :class:`uwml.BaseWrench`) view. Every call
returns the same result object, holding the last call's values.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from .results import BaseWrench, Torques

if TYPE_CHECKING:
    from .tree import Robot

__all__ = ["Workspace"]


class Workspace:
    """One state's results of one robot, written in place by each evaluation given it
    (``robot.hydro(q, qd, qdd, conditions, workspace=w)``), which returns the workspace's result:
    the same :class:`uwml.Torques` every call (one with ``base`` None where the call does not
    evaluate the base wrench).

    Made by :meth:`uwml.Robot.workspace`. The result's arrays are views of one array: each call
    overwrites them (copy what is to be kept). :meth:`uwml.Robot.hydro` leaves zeros in the
    losses' arrays. A workspace takes one state (1-D ``q``, ``qd``, ``qdd`` and
    conditions without a sample axis) of the robot that made it. A call that raises leaves its
    values unspecified.

    Threads: the native evaluation writes the array whole with the GIL held, so no thread sees
    a call's values half written; but the result is shared, so a thread that evaluates while
    another reads gets the other's values under it: use one workspace per thread.
    """

    __slots__ = ("_core", "_values", "_with_base", "_without_base")

    def __init__(self, robot: Robot) -> None:
        n = robot.n_joints
        self._core = robot._core
        # The joints' seven parts (n each), then the base's four (6 each): the core's layout.
        self._values = np.zeros(7 * n + 24)
        drag, added_mass, buoyancy, gravity, visc, seal, current = (self._values[k * n : (k + 1) * n] for k in range(7))
        joints = {"drag": drag, "added_mass": added_mass, "buoyancy": buoyancy, "gravity": gravity}
        losses = {"visc": visc, "seal": seal, "current": current}
        base_drag, base_added_mass, base_buoyancy, base_gravity = (self._values[7 * n + 6 * k : 7 * n + 6 * (k + 1)] for k in range(4))
        base = BaseWrench(drag=base_drag, added_mass=base_added_mass, buoyancy=base_buoyancy, gravity=base_gravity)
        self._with_base = Torques(**joints, **losses, base=base)
        self._without_base = Torques(**joints, **losses, base=None)

    def __repr__(self) -> str:
        return f"Workspace(n_joints={self._with_base.drag.size})"

    def _check(self, core: object) -> None:
        """A ValueError unless the workspace is the robot ``core``'s."""
        if core is not self._core:
            raise ValueError("this workspace is another robot's: make one with this robot's workspace()")

    def _store(self, result: Torques) -> Torques:
        """``result`` (of one state) written into the workspace, in one assignment; its view."""
        n = self._with_base.drag.size
        if result.drag.shape != (n,):
            raise ValueError(
                f"a workspace holds one state's results: give q, qd, qdd of shape ({n},) and conditions "
                f"without a sample axis (the forces have shape {result.drag.shape})"
            )
        parts = [result.drag, result.added_mass, result.buoyancy, result.gravity, result.visc, result.seal, result.current]
        if result.base is None:
            parts.append(np.zeros(24))
        else:
            parts += [result.base.drag, result.base.added_mass, result.base.buoyancy, result.base.gravity]
        self._values[:] = np.concatenate(parts)
        return self._without_base if result.base is None else self._with_base
