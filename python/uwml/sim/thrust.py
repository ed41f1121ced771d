"""The robot's thrusters in a :class:`uwml.sim.mujoco.Simulation` (docs/model.md section 13.1).

Each thruster's command is held until the next (:meth:`Simulation.command_thrusters`), as an ESC
holds it. Its steady thrust is its curve's, within its limits; the thrust it gives lags it by
its time constant, advanced exactly over each step (``T ← f + (T − f) e^{−h/τ}``). Every forward
pass of a step applies the thrust of the step's start as a wrench on the thruster's body, at the
body's pose of that pass (each stage's, with RK4): force ``Σ R T d`` and moment
``Σ R T (r − c) × d`` about the body's centre of mass ``c`` in world components (MuJoCo's
``xfrc_applied``, added to what is there and restored after the step).

Thrusters are given in their body's uwml frame (a link's frame is parallel to the base's at
q = 0, docs/model.md section 10), which a description's MuJoCo body frame need not be: the two are
related once, at the model's ``qpos0`` (every joint at 0), and the thrusters placed in the MuJoCo
body's frame.
"""

from __future__ import annotations

from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..robot.tree import Robot

__all__ = ["SimulatedThrusters"]

FloatArray = NDArray[np.float64]


class SimulatedThrusters:
    """The thrusters of ``robot`` on the MuJoCo model ``m``: the base is the body ``root`` (None:
    the base is the world, where thrusters push nothing), link ``i`` the body of degree of
    freedom ``joint_dofs[i]``. Not thread-safe by itself: the simulation's lock guards it."""

    def __init__(self, mj: Any, m: Any, robot: Robot, root: int | None, joint_dofs: NDArray[np.int64]) -> None:
        placed = robot.thrusters
        self._thrusters = tuple(t for _, t in placed)
        n = len(placed)
        body_of = [root if body < 0 else int(m.dof_bodyid[joint_dofs[body]]) for body, _ in placed]
        in_body = _uwml_to_body_frames(mj, m, robot, root, body_of, placed)
        #: The bodies that carry thrusters that move something, and each one's rows of
        #: ``local``: force then moment about its centre of mass, per newton of each thruster.
        self._bodies = np.array(sorted({b for b in body_of if b is not None}), dtype=np.int64)
        self._local = np.zeros((len(self._bodies), 6, n))
        for k, (body, thruster) in enumerate(zip(body_of, self._thrusters, strict=True)):
            if body is None:
                continue
            row = int(np.searchsorted(self._bodies, body))
            turn, shift = in_body[k]
            d = turn @ np.asarray(thruster.direction)
            arm = turn @ np.asarray(thruster.position) + shift - np.asarray(m.body_ipos[body])
            self._local[row, :3, k] = d
            self._local[row, 3:, k] = np.cross(arm, d)
        self._flat = self._local.reshape(6 * len(self._bodies), n)
        #: The rows of ``xfrc_applied`` pushed: a slice where the bodies are consecutive (a
        #: view, cheaper to copy and write than an index array).
        b = self._bodies
        consecutive = len(b) > 0 and np.array_equal(b, np.arange(b[0], b[0] + len(b)))
        self.rows: slice | NDArray[np.int64] = slice(int(b[0]), int(b[0]) + len(b)) if consecutive else b
        self._time_constants = np.array([t.time_constant for t in self._thrusters])
        self._command = np.zeros(n)
        self._steady = self._steady_thrust(self._command)
        self._thrust = self._steady.copy()
        self._lags = bool(np.any(self._time_constants > 0.0))
        self._columns = self._body_columns()
        self._world = np.zeros((len(self._bodies), 2, 3))
        self._flat_world = self._world.reshape(len(self._bodies), 6)
        self._decay: tuple[float, FloatArray] | None = None
        self._idle = self._no_thrust()

    def __len__(self) -> int:
        return len(self._thrusters)

    def _steady_thrust(self, command: FloatArray) -> FloatArray:
        return np.array([t.thrust(u) for t, u in zip(self._thrusters, command, strict=True)], dtype=np.float64)

    @property
    def command(self) -> FloatArray:
        """The commands held (a copy)."""
        return self._command.copy()

    @property
    def thrust(self) -> FloatArray:
        """Each thruster's thrust [N] now (a copy)."""
        return self._thrust.copy()

    def set_command(self, command: ArrayLike) -> None:
        """Hold ``command`` (one number per thruster, finite) from now on."""
        n = len(self._thrusters)
        try:
            u = np.asarray(command, dtype=np.float64).reshape(-1)
        except (TypeError, ValueError) as exc:
            raise TypeError(f"thruster commands must be {n} numbers, got {command!r}") from exc
        if u.shape != (n,) or not np.all(np.isfinite(u)):
            raise ValueError(f"thruster commands must be {n} finite numbers (one per thruster of robot.thrusters), got {u.tolist()}")
        self._command = u.copy()
        self._steady = self._steady_thrust(u)
        # A thruster without a lag gives its new thrust at once (with a lag: from the next step on).
        self._thrust = np.where(self._time_constants > 0.0, self._thrust, self._steady)
        self._columns = self._body_columns()
        self._idle = self._no_thrust()

    def _body_columns(self) -> FloatArray:
        """The thrust now as each body's force and moment (about its centre of mass) in its
        frame, ``(n_bodies, 2, 3)``."""
        local: FloatArray = (self._flat @ self._thrust).reshape(len(self._bodies), 2, 3)
        return local

    def wrenches(self, xmat: FloatArray) -> FloatArray:
        """The world wrenches ``(n_bodies, 6)`` on :attr:`bodies` of the thrust now, the bodies
        turned by ``xmat`` (MuJoCo's ``data.xmat``): rows ``f Rᵀ`` (the same buffer each call)."""
        turns = xmat[self.rows].reshape(-1, 3, 3).transpose(0, 2, 1)
        np.matmul(self._columns, turns, out=self._world)
        return self._flat_world

    def push(self, xfrc_applied: FloatArray, xmat: FloatArray, under: FloatArray) -> None:
        """The pushed bodies' rows of ``xfrc_applied`` made ``under`` (their rows without thrust)
        plus :meth:`wrenches`."""
        if isinstance(self.rows, slice):  # a view: written in place
            np.add(under, self.wrenches(xmat), out=xfrc_applied[self.rows])
        else:
            xfrc_applied[self.rows] = under + self.wrenches(xmat)

    @property
    def bodies(self) -> NDArray[np.int64]:
        """The MuJoCo bodies pushed."""
        return self._bodies

    def _no_thrust(self) -> bool:
        """Whether no thrust acts now nor will without a new command (or no body is pushed):
        kept as :attr:`idle`, which every step reads."""
        return len(self._bodies) == 0 or (not np.any(self._thrust) and not np.any(self._steady))

    @property
    def idle(self) -> bool:
        """Whether no thrust acts (nothing to apply in a step)."""
        return self._idle

    def advance(self, h: float) -> None:
        """The thrust ``h`` seconds on (the lag's exact solution under the held command)."""
        if not self._lags:
            return
        if self._decay is None or self._decay[0] != h:
            with np.errstate(divide="ignore", over="ignore"):
                decay = np.where(
                    self._time_constants > 0.0, np.exp(-h / np.where(self._time_constants > 0.0, self._time_constants, 1.0)), 0.0
                )
            self._decay = (h, decay)
        self._thrust = self._steady + (self._thrust - self._steady) * self._decay[1]
        self._columns = self._body_columns()
        self._idle = self._no_thrust()


def _uwml_to_body_frames(
    mj: Any, m: Any, robot: Robot, root: int | None, body_of: list[int | None], placed: tuple[tuple[int, Any], ...]
) -> list[tuple[FloatArray, FloatArray]]:
    """For each thruster, the map ``x ↦ turn x + shift`` from its uwml body frame to its MuJoCo
    body's frame, found at ``qpos0``: both frames ride the same body, and there a link's uwml
    frame is parallel to the base's, at the link's joint."""
    d = mj.MjData(m)
    mj.mj_kinematics(m, d)
    base = root if root is not None else 0
    base_turn, base_at = d.xmat[base].reshape(3, 3), d.xpos[base]
    zeros = np.zeros(robot.n_joints)
    out = []
    for (link, _), body in zip(placed, body_of, strict=True):
        if body is None:
            out.append((np.eye(3), np.zeros(3)))
            continue
        # The MuJoCo body's pose in the base frame, and the uwml frame's origin there.
        turn = base_turn.T @ d.xmat[body].reshape(3, 3)
        at = base_turn.T @ (d.xpos[body] - base_at)
        origin = np.zeros(3) if link < 0 else robot.forward_kinematics(zeros, link, (0.0, 0.0, 0.0))
        out.append((turn.T, turn.T @ (origin - at)))
    return out
