"""Type stubs of the native module ``uwml._core`` (the Rust bindings). Use :mod:`uwml` instead."""

from collections.abc import Sequence
from typing import Self, TypeAlias, final

import numpy as np
from numpy.typing import NDArray

from .model.joint_losses import JointLosses
from .model.parts import Joint, Link, Segment, Water
from .robot.evaluation_conditions import Conditions as _Conditions
from .robot.results import Jacobians, Regressors, Torques

_Vec3: TypeAlias = tuple[float, float, float]
#: A robot's validated parts (`Robot.parts`): a joint (parent, kind, origin, axis), a body (mass,
#: com, volume, cob), a segment (owner, start, axis, length, area, section, normals, widths, diameter,
#: cd, cm, cd_axial, axial_area).
_JointParts: TypeAlias = tuple[int, str, _Vec3, _Vec3]
_BodyParts: TypeAlias = tuple[float, _Vec3, float, _Vec3]
_SegmentParts: TypeAlias = tuple[
    int,
    _Vec3,
    _Vec3,
    float,
    float,
    str,
    tuple[_Vec3, _Vec3] | None,
    tuple[float, float] | None,
    float | None,
    tuple[float, float],
    tuple[float, float],
    float,
    float,
]

__all__ = [
    "ABSOLUTE_ZERO_C",
    "MAX_AREA",
    "MAX_COEFFICIENT",
    "MAX_DENSITY",
    "MAX_DEPTH",
    "MAX_GRAVITY",
    "MAX_LENGTH",
    "MAX_LUMPED_BODIES",
    "MAX_MASS",
    "MAX_PRESSURE",
    "MAX_ROBOT_JOINTS",
    "MAX_SEGMENTS",
    "MAX_VOLUME",
    "OIL_TEMPERATURE_RANGE_C",
    "Conditions",
    "Losses",
    "ModelError",
    "MujocoCoupling",
    "Robot",
    "UwmlError",
    "joint_losses",
]

MAX_DEPTH: float
MAX_PRESSURE: float
MAX_LENGTH: float
MAX_MASS: float
MAX_VOLUME: float
MAX_AREA: float
MAX_COEFFICIENT: float
MAX_DENSITY: float
MAX_GRAVITY: float
ABSOLUTE_ZERO_C: float
OIL_TEMPERATURE_RANGE_C: tuple[float, float]
MAX_ROBOT_JOINTS: int
MAX_LUMPED_BODIES: int
MAX_SEGMENTS: int

class UwmlError(ValueError):
    """The base of every uwml exception: a bad value, model or file."""

class ModelError(UwmlError):
    """A non-physical or malformed model parameter."""

@final
class Losses:
    def __new__(cls, per_joint: Sequence[JointLosses | None]) -> Self: ...
    @property
    def n_joints(self) -> int: ...

@final
class Conditions:
    def __new__(cls, robot: Robot, conditions: _Conditions, water: Water, losses: Losses | None) -> Self: ...
    @property
    def n_samples(self) -> int | None: ...

@final
class Robot:
    def __new__(
        cls,
        joints: Sequence[Joint],
        links: Sequence[Link],
        base: Link,
        segments: Sequence[tuple[int, Segment]],
        bounds: Sequence[tuple[float, float, float]],
    ) -> Self: ...
    @staticmethod
    def paper_leg() -> Robot: ...
    @property
    def n_joints(self) -> int: ...
    def parts(self) -> tuple[list[_JointParts], list[_BodyParts], _BodyParts, list[_SegmentParts]]: ...
    def point_jacobian(
        self, q: NDArray[np.float64], link: int, point: NDArray[np.float64]
    ) -> tuple[NDArray[np.float64], NDArray[np.float64]]: ...
    def hydro_design(
        self,
        q: NDArray[np.float64],
        qd: NDArray[np.float64],
        qdd: NDArray[np.float64],
        delta: NDArray[np.float64],
        conditions: Conditions,
        joints: Sequence[int],
        per: str,
    ) -> NDArray[np.float64]: ...
    def hydro(
        self, q: object, qd: object, qdd: object, conditions: Conditions, threads: int = 1, base: bool = False, checked: bool = False
    ) -> Torques | None: ...
    def environment(
        self, q: object, qd: object, qdd: object, conditions: Conditions, threads: int = 1, base: bool = False, checked: bool = False
    ) -> Torques | None: ...
    def evaluate_into(
        self, q: object, qd: object, qdd: object, conditions: Conditions, base: bool, losses: bool, workspace: NDArray[np.float64]
    ) -> bool: ...
    def link_wrenches(self, q: object, qd: object, qdd: object, conditions: Conditions, *, threads: int = 1) -> NDArray[np.float64]: ...
    def regressors(self, q: object, qd: object, qdd: object, conditions: Conditions, *, threads: int = 1) -> Regressors: ...
    def jacobians(self, q: object, qd: object, qdd: object, conditions: Conditions) -> Jacobians: ...
    def added_mass_matrix(self, q: object, conditions: Conditions) -> NDArray[np.float64]: ...

@final
class MujocoCoupling:
    def __new__(
        cls,
        robot: Robot,
        qpos: NDArray[np.float64],
        qvel: NDArray[np.float64],
        qacc: NDArray[np.float64],
        xquat: NDArray[np.float64],
        xmat: NDArray[np.float64],
        mass_matrix: NDArray[np.float64],
        qfrc_applied: NDArray[np.float64],
        dof_damping: NDArray[np.float64],
        dof_frictionloss: NDArray[np.float64],
        model_gravity: NDArray[np.float64],
        root: int | None,
        joint_qpos: Sequence[int],
        joint_dofs: Sequence[int],
        free_dof: int | None,
        mass_pairs: NDArray[np.int64],
        conditions: Conditions,
        lagged: bool,
    ) -> Self: ...
    def write_joint_losses(self) -> None: ...
    def apply(self, torque: object = None) -> int: ...
    def rk4_begin(self) -> None: ...
    def rk4_stage(self, stage: int, offset: float) -> NDArray[np.float64] | None: ...
    def rk4_keep(self, stage: int) -> None: ...
    def rk4_finish(self, h: float) -> NDArray[np.float64]: ...
    def remember_acceleration(self) -> None: ...
    def prescribe(
        self,
        dofs: Sequence[int],
        qpos: Sequence[int],
        solved: NDArray[np.float64],
        knots: Sequence[float] | None = None,
        coefficients: Sequence[NDArray[np.float64]] | None = None,
        slack: float = 0.0,
    ) -> None: ...
    def impose(self, time: float, target: Sequence[float] | None = None) -> int: ...
    def put_on_motion(self, time: float, q: Sequence[float] | None = None, qd: Sequence[float] | None = None) -> int: ...
    def prescribed_torque(self) -> NDArray[np.float64]: ...

def joint_losses(
    losses: Losses | None,
    speed: NDArray[np.float64],
    pressure: NDArray[np.float64],
    temperature: NDArray[np.float64],
) -> list[NDArray[np.float64]]: ...
