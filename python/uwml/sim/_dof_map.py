"""Where uwml's coordinates sit among a MuJoCo model's degrees of freedom, for
:class:`uwml.sim.mujoco.Simulation`: the robot's base (the one root body, on a free joint when it
floats), its joints (the model's hinge and slide joints, in model order), and where each entry of
the joint-space inertia sits in MuJoCo's sparse storage ``data.M``."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

from ..robot.tree import Robot

__all__ = ["DofMap", "body_id", "map_degrees_of_freedom", "sparse_inertia_entries"]

IntArray = NDArray[np.int64]


@dataclass(frozen=True)
class DofMap:
    """The robot in MuJoCo's coordinates (see the module)."""

    #: The root body: the robot's base.
    root: int
    #: The free joint's first degree of freedom and ``qpos`` entry (None: a fixed base).
    free_dof: int | None
    free_qpos: int | None
    #: Each joint's degree of freedom and ``qpos`` entry.
    joint_dofs: IntArray
    joint_qpos: IntArray
    #: The base is the world frame: the root body hangs from the world by a joint.
    base_is_world: bool

    @property
    def floating(self) -> bool:
        return self.free_dof is not None


def map_degrees_of_freedom(mj: Any, m: Any, robot: Robot) -> DofMap:
    """The map of ``robot`` on the MuJoCo model ``m`` (``mj``: the ``mujoco`` module), or a
    ValueError saying why the model is not this robot's."""
    roots = [i for i in range(1, m.nbody) if m.body_parentid[i] == 0]
    if len(roots) != 1:
        raise ValueError(f"the model's world must hold exactly one root body (the robot's base), got {len(roots)}")
    root = roots[0]
    free_kind, hinge, slide = (int(k) for k in (mj.mjtJoint.mjJNT_FREE, mj.mjtJoint.mjJNT_HINGE, mj.mjtJoint.mjJNT_SLIDE))
    free = [j for j in range(m.njnt) if int(m.jnt_type[j]) == free_kind]
    if free and (len(free) > 1 or m.jnt_bodyid[free[0]] != root):
        raise ValueError("only the root body may have a free joint (the floating base)")
    ball = int(mj.mjtJoint.mjJNT_BALL)
    if any(int(kind) == ball for kind in m.jnt_type):
        raise ValueError("the model has a ball joint: uwml's joints are revolute and prismatic (hinge and slide)")
    free_dof = int(m.jnt_dofadr[free[0]]) if free else None
    moving = [j for j in range(m.njnt) if int(m.jnt_type[j]) in (hinge, slide)]
    if len(moving) != robot.n_joints:
        raise ValueError(f"the model has {len(moving)} hinge and slide joints, the robot {robot.n_joints} joints: not the same robot")
    for i, (j, joint) in enumerate(zip(moving, robot.joints, strict=True)):
        kind = "revolute" if int(m.jnt_type[j]) == hinge else "prismatic"
        name = m.joint(j).name
        if kind != joint.kind or (joint.name is not None and name and name != joint.name):
            raise ValueError(f"the model's joint {j} ('{name}', {kind}) is not the robot's joint {i} ({joint.name!r}, {joint.kind})")
    return DofMap(
        root=root,
        free_dof=free_dof,
        free_qpos=int(m.jnt_qposadr[free[0]]) if free else None,
        joint_dofs=np.array([m.jnt_dofadr[j] for j in moving], dtype=np.int64),
        joint_qpos=np.array([m.jnt_qposadr[j] for j in moving], dtype=np.int64),
        # The base is the root body's frame unless the root hangs from the world by a joint.
        base_is_world=free_dof is None and m.body_jntnum[root] > 0,
    )


def body_id(mj: Any, m: Any, name: Any, what: str) -> int:
    """The id of the MuJoCo body ``name`` of the model ``m`` (not the world), or a ValueError
    naming the argument ``what`` and listing the model's bodies."""
    body = mj.mj_name2id(m, mj.mjtObj.mjOBJ_BODY, name) if isinstance(name, str) else -1
    if body < 1:
        bodies = ", ".join(m.body(i).name for i in range(1, m.nbody))
        raise ValueError(f"{what}: no body named {name!r} (the model's bodies: {bodies})")
    return int(body)


def sparse_inertia_entries(mj: Any, m: Any, d: Any) -> IntArray:
    """``(nM, 2)``: the (row, column) degrees of freedom of each entry of ``d.M``, found by
    writing each entry's number and reading the dense matrix back (``d.M`` is restored)."""
    mj.mj_forward(m, d)
    saved = d.M.copy()
    d.M[:] = np.arange(1.0, m.nM + 1.0)
    probe = np.zeros((m.nv, m.nv))
    mj.mj_fullM(m, d, probe)
    d.M[:] = saved
    rows, columns = np.nonzero(np.tril(probe))
    order = np.argsort(probe[rows, columns])
    rows, columns = rows[order], columns[order]
    if not np.array_equal(probe[rows, columns], np.arange(1.0, m.nM + 1.0)):
        raise RuntimeError("unexpected layout of MuJoCo's sparse inertia (data.M)")
    entries: IntArray = np.stack([rows, columns], axis=1).astype(np.int64)
    return entries
