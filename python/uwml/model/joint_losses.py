"""A joint's losses as the Rust core evaluates them: :class:`JointLosses` bundles one joint's
:class:`~uwml.model.losses.Drive` with its optional :class:`~uwml.model.losses.OilDrag` and
:class:`~uwml.model.losses.Seal`, and evaluates them (:meth:`JointLosses.torques`); the robots'
evaluations (:meth:`uwml.Robot.environment`) take them read and
validated by the core once per set (:func:`pack_leg_losses`, a native ``Losses``).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field

import numpy as np
from numpy.typing import ArrayLike, NDArray

from .. import _core
from .._checks import check_overflow
from .._checks import real_array as _real_array
from ..sea.conditions import MAX_PRESSURE_MPA, check_temperatures
from .losses import Drive, OilDrag, Seal

__all__ = ["JointLosses", "LossTorques", "pack_leg_losses"]

FloatArray = NDArray[np.float64]

_MPA = 1e6


@dataclass(frozen=True)
class LossTorques:
    """One joint's losses [environment sign: they oppose motion]."""

    #: Oil drag reflected to the output, ``−N η T_oil`` [N·m].
    visc: FloatArray
    #: Seal friction, ``−T_seal`` [N·m].
    seal: FloatArray
    #: Loss current ``T_oil/K_t + T_seal/(N η K_t)`` [A], signed like the motion.
    current: FloatArray


@dataclass(frozen=True)
class JointLosses:
    """The losses of one joint: its drive, and optionally oil drag and a dynamic seal.

    ``epsilon`` [rad/s, output speed] is the smooth sign's width (a few times the velocity
    noise; 0 for the hard sign). The defaults are the illustrative ones of :mod:`uwml.model.losses`.
    """

    drive: Drive = field(default_factory=Drive)
    oil: OilDrag | None = field(default_factory=OilDrag)
    seal: Seal | None = field(default_factory=Seal)
    epsilon: float = 1e-3

    def __post_init__(self) -> None:
        if not isinstance(self.drive, Drive):
            raise TypeError(f"drive must be a uwml.Drive, got {type(self.drive).__name__}")
        if self.oil is not None and not isinstance(self.oil, OilDrag):
            raise TypeError(f"oil must be a uwml.OilDrag or None, got {type(self.oil).__name__}")
        if self.seal is not None and not isinstance(self.seal, Seal):
            raise TypeError(f"seal must be a uwml.Seal or None, got {type(self.seal).__name__}")
        epsilon = float(self.epsilon)
        if not np.isfinite(epsilon) or epsilon < 0:
            raise ValueError(f"epsilon must be finite and >= 0, got {self.epsilon!r}")
        object.__setattr__(self, "epsilon", epsilon)

    def torques(self, speed: ArrayLike, pressure_mpa: ArrayLike = 0.0, temperature_c: ArrayLike = 20.0) -> LossTorques:
        """Losses at output speed [rad/s], ambient pressure [MPa] and oil temperature [°C].

        The three arguments broadcast against each other; the results have their common shape.
        """
        arrays = [
            _real_array(value, name, "a real number or array")
            for name, value in (("speed", speed), ("pressure_mpa", pressure_mpa), ("temperature_c", temperature_c))
        ]
        try:
            speed_b, pressure_b, temperature_b = np.broadcast_arrays(*arrays)
        except ValueError:
            raise ValueError(f"speed, pressure_mpa and temperature_c must broadcast, got shapes {[a.shape for a in arrays]}") from None
        bad = np.flatnonzero(~np.isfinite(np.ravel(speed_b)))
        if bad.size:
            raise ValueError(f"speed[{bad[0]}] is {float(np.ravel(speed_b)[bad[0]])!r}: speed must be finite")
        pressures = np.ravel(pressure_b)
        bad = np.flatnonzero(~np.isfinite(pressures) | (pressures < 0.0) | (pressures > MAX_PRESSURE_MPA))
        if bad.size:
            raise ValueError(
                f"pressure_mpa[{bad[0]}] is {float(pressures[bad[0]])!r}: pressure_mpa must be finite, >= 0 (gauge pressure) "
                f"and at most {MAX_PRESSURE_MPA:g} MPa (the deepest ocean's, with margin)"
            )
        check_temperatures(temperature_b)
        shape = speed_b.shape
        flat = [np.ascontiguousarray(a.ravel()) for a in (speed_b, pressure_b * _MPA, temperature_b)]
        visc, seal, current = _core.joint_losses(_core.Losses([self]), *flat)
        check_overflow((visc, seal, current), len(flat[0]), flat[0], np.zeros_like(flat[0]))
        return LossTorques(visc=visc.reshape(shape), seal=seal.reshape(shape), current=current.reshape(shape))


def pack_leg_losses(losses: JointLosses | Sequence[JointLosses | None] | None, n_joints: int) -> _core.Losses:
    """Per-joint losses for the native evaluations (``uwml._core.Losses``: each joint's
    ``JointLosses`` read and validated by the core once): one ``JointLosses`` for every joint, a
    sequence with one entry (or None) per joint, or None for no losses."""
    if losses is None or isinstance(losses, JointLosses):
        per_joint: list[JointLosses | None] = [losses] * n_joints
    else:
        try:
            per_joint = list(losses)
        except TypeError:
            raise TypeError(
                f"losses must be a uwml.JointLosses, a sequence of them (or None), or None; got {type(losses).__name__}"
            ) from None
        if len(per_joint) != n_joints:
            raise ValueError(f"losses must have one entry per joint ({n_joints}), got {len(per_joint)}")
    for i, item in enumerate(per_joint):
        if item is not None and not isinstance(item, JointLosses):
            raise TypeError(f"losses[{i}] must be a uwml.JointLosses or None, got {type(item).__name__}")
    return _core.Losses(per_joint)
