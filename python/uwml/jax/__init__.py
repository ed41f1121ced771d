"""Any robot's evaluation on JAX arrays, under ``jit``, ``vmap`` and ``grad`` (docs/batched.md).

:func:`compile_robot` turns a :class:`uwml.Robot` (the same model object, read as the core reads
it) into a :class:`RobotModel`: a pytree of arrays with the tree's shape as static structure.
Pure functions of one state then give what :class:`uwml.Robot` gives for it, by the same
physics (docs/model.md sections 3, 10 and 12; the joint losses of docs/losses.md): :func:`hydro`
and :func:`environment` (a :class:`uwml.Torques` with its :class:`uwml.BaseWrench`),
:func:`regressors` (a :class:`uwml.Regressors`), :func:`added_mass_matrix` and :func:`jacobians`
(a :class:`uwml.Jacobians`). The base's motion and the current of a sample are a :class:`Motion`
(:func:`motion` reads them from a :class:`uwml.Conditions`). Batches are ``jax.vmap``'s.

Needs JAX (``pip install "uwml[jax]"``); ``import uwml`` does not import it.
"""

import importlib.util

if importlib.util.find_spec("jax") is None:
    raise ModuleNotFoundError('uwml.jax needs JAX: pip install "uwml[jax]"', name="jax")

from .compiled_robot import Bodies, JointLossParameters, Joints, LumpedModels, RobotModel, Segments, Structure, compile_robot
from .evaluations import added_mass_matrix, environment, hydro, jacobians, regressors
from .tree_motion import Motion, motion

__all__ = [
    "Bodies",
    "JointLossParameters",
    "Joints",
    "LumpedModels",
    "Motion",
    "RobotModel",
    "Segments",
    "Structure",
    "added_mass_matrix",
    "compile_robot",
    "environment",
    "hydro",
    "jacobians",
    "motion",
    "regressors",
]
