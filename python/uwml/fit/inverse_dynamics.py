"""The description's rigid-body inverse dynamics ``ID_RB(q, q̇, q̈)`` at a log's states, from
MuJoCo's ``mj_inverse`` (docs/model.md section 13, "13.3 Identifying a vehicle"): what the joints'
motors and the base's wrench must supply to move the rigid bodies as the log says, with gravity
and without the water. MuJoCo's own fluid model is off (``opt.density`` and ``opt.viscosity`` 0)
and so are its constraints (``mjDSBL_CONSTRAINT``: contacts, joint limits and MuJoCo's friction
loss, which a robot swimming free does not meet, and which ``mj_inverse`` would otherwise solve
for); the description's passive forces (joint damping and springs) are kept.

A floating base (the root body on a free joint) moves as the log's vehicle columns say: its
orientation ``qw … qz`` (upright where absent), its twist ``ν = (u, v, w, p, q, r)`` and rate
``ν̇`` (at rest where absent), in MuJoCo's coordinates ``v_world = R ν_lin``, ``ω`` as it is,
``v̇_world = R (ν̇_lin + ω × ν_lin)``. Its generalized force comes back as the wrench on the base
about its origin in its own axes (the linear rows turned by ``Rᵀ``; the angular ones already
are), the frame of :meth:`uwml.Robot.thruster_allocation` and of the regressors' base rows.
"""

from __future__ import annotations

import copy
import os
from typing import Any

import numpy as np

from ..io.logs import Log
from ..robot.files import model_and_robot
from ..robot.tree import Robot
from ._types import Array

__all__ = ["RigidBodyInverse", "load_description"]


def load_description(description: Any, hydro: Any = None, floating: bool | None = None) -> tuple[Any, Robot]:
    """``(mujoco.MjModel, Robot)`` of a URDF or MJCF file (with its hydro file, read as
    :func:`uwml.robot.files.model_and_robot` reads it), or of such a pair given as it is."""
    if isinstance(description, tuple) and len(description) == 2 and isinstance(description[1], Robot):
        return description[0], description[1]
    if not isinstance(description, str | os.PathLike):
        raise TypeError(
            "the description must be a URDF or MJCF file (with hydro=), or a (mujoco.MjModel, uwml.Robot) pair; "
            f"got {type(description).__name__}"
        )
    if os.fspath(description).lower().endswith(".toml"):
        raise ValueError(
            f"{os.fspath(description)}: the rigid-body inverse dynamics needs a URDF or MJCF description (MuJoCo's model of the "
            "rigid bodies), not a uwml model file"
        )
    return model_and_robot(description, hydro, floating)


class RigidBodyInverse:
    """``mj_inverse`` of ``model`` (a ``mujoco.MjModel``, copied) for the :class:`uwml.Robot`
    ``robot`` of the same description: its joints are the model's hinge and slide joints in
    model order (module docstring)."""

    def __init__(self, model: Any, robot: Robot) -> None:
        import mujoco

        if not isinstance(model, mujoco.MjModel):
            raise TypeError(f"model must be a mujoco.MjModel, got {type(model).__name__}")
        self._mj = mujoco
        m = copy.deepcopy(model)
        m.opt.density, m.opt.viscosity = 0.0, 0.0
        m.opt.disableflags = int(m.opt.disableflags) | int(mujoco.mjtDisableBit.mjDSBL_CONSTRAINT)
        gravity = np.asarray(m.opt.gravity, dtype=np.float64)
        if not np.allclose(gravity, (0.0, 0.0, -robot.water.gravity), rtol=1e-12, atol=0.0):
            raise ValueError(f"the model's gravity {gravity.tolist()} must be (0, 0, -{robot.water.gravity:g}), the robot's water's")
        roots = [b for b in range(1, m.nbody) if m.body_parentid[b] == 0]
        if len(roots) != 1:
            raise ValueError(f"the model's world must hold exactly one root body (the robot's base), got {len(roots)}")
        kinds = [int(kind) for kind in m.jnt_type]
        free = [j for j, kind in enumerate(kinds) if kind == int(mujoco.mjtJoint.mjJNT_FREE)]
        moving = [j for j, kind in enumerate(kinds) if kind in (int(mujoco.mjtJoint.mjJNT_HINGE), int(mujoco.mjtJoint.mjJNT_SLIDE))]
        if len(moving) != robot.n_joints or len(moving) + len(free) != m.njnt or (free and m.jnt_bodyid[free[0]] != roots[0]):
            raise ValueError(
                f"the model's joints are not the robot's: {len(moving)} hinge and slide joints and {len(free)} free joints "
                f"(at most one, on the root body), the robot {robot.n_joints} joints"
            )
        self._model, self._data, self._robot = m, mujoco.MjData(m), robot
        self._root = roots[0]
        self._free = (int(m.jnt_qposadr[free[0]]), int(m.jnt_dofadr[free[0]])) if free else None
        self._qpos = np.array([m.jnt_qposadr[j] for j in moving], dtype=np.int64)
        self._dofs = np.array([m.jnt_dofadr[j] for j in moving], dtype=np.int64)

    @property
    def floating(self) -> bool:
        """Whether the base is on a free joint."""
        return self._free is not None

    @property
    def robot(self) -> Robot:
        return self._robot

    def __call__(self, log: Log) -> Array:
        """``(n, 6 + n_joints)``: the rigid-body generalized forces at every sample of ``log``
        (its ``qd``, ``qdd`` and, on a floating base, ``base_twist_dot`` given or estimated): the
        wrench on the base about its origin in its axes (zero on a fixed base), then the joints'
        torques [N·m, N]."""
        assert log.qd is not None and log.qdd is not None
        mj, m, d = self._mj, self._model, self._data
        n, nj = log.n_samples, self._robot.n_joints
        moving = log.base_twist is not None or log.base_orientation is not None
        if moving and self._free is None:
            raise ValueError(
                f"{log.source}: row 1 (header), column {'u' if log.base_twist is not None else 'qw'!r}: the log moves the vehicle, "
                "but the description's base is fixed (float it: the hydro file's [base] floating = true, or floating=True)"
            )
        motion = log.base_motion() if self._free is not None else None
        out = np.zeros((n, 6 + nj))
        for i in range(n):
            d.qpos[self._qpos], d.qvel[self._dofs], d.qacc[self._dofs] = log.q[i], log.qd[i], log.qdd[i]
            turn = None
            if self._free is not None and motion is not None:
                turn = self._set_base(i, motion, log.base_position)
            mj.mj_inverse(m, d)
            out[i, 6:] = d.qfrc_inverse[self._dofs]
            if turn is not None and self._free is not None:
                dof = self._free[1]
                out[i, :3] = turn.T @ d.qfrc_inverse[dof : dof + 3]
                out[i, 3:6] = d.qfrc_inverse[dof + 3 : dof + 6]
        return out

    def _set_base(self, i: int, motion: dict[str, Array], position: Array | None) -> Array:
        """The free joint's ``qpos``, ``qvel`` and ``qacc`` at sample ``i`` (module docstring);
        the base's rotation, world from body."""
        assert self._free is not None
        mj, d = self._mj, self._data
        address, dof = self._free

        def row(name: str) -> Array:
            value = motion[name]
            return value if value.ndim == 1 else value[i]

        quaternion = row("orientation")
        turn = np.zeros(9)
        mj.mju_quat2Mat(turn, quaternion)
        rotation = turn.reshape(3, 3)
        v, w, v_dot, w_dot = row("velocity"), row("angular_velocity"), row("acceleration"), row("angular_acceleration")
        d.qpos[address : address + 3] = 0.0 if position is None else position[i]
        d.qpos[address + 3 : address + 7] = quaternion
        d.qvel[dof : dof + 3], d.qvel[dof + 3 : dof + 6] = rotation @ v, w
        d.qacc[dof : dof + 3], d.qacc[dof + 3 : dof + 6] = rotation @ (v_dot + np.cross(w, v)), w_dot
        return rotation
