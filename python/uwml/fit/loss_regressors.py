"""The joint losses as linear terms of a water-only fit (docs/model.md section 13, "13.3
Identifying a vehicle"; the models of docs/losses.md): at one depth and temperature, with the
oil's exponent and sensitivities and the seal's Stribeck speed and pressure slopes held, each
joint's loss torque is linear in

* ``k_oil``: the oil drag's level (:class:`uwml.OilDrag`), whose column is the reflected oil
  drag ``−N η T_oil`` at ``k_oil = 1``;
* ``c0``, ``s0``: the seal's running and breakaway levels at zero pressure, whose columns are
  ``−sgn_ε(ω)(1 − e)`` and ``−sgn_ε(ω) e`` with ``e = exp(−(ω/ω_s)²)``;
* ``d0``: the seal's viscous slope, column ``−ω``

(environment sign, as :meth:`uwml.Robot.environment` reports them), each column the core's own
evaluation (:meth:`uwml.JointLosses.torques`) of a model with that level 1 and the others 0, so
that the smooth sign and the pressure are the ones a simulation uses. The terms held (the
pressure slopes ``c1``, ``s1``, ``d1``, and any level not fitted) are the losses' known part,
``τ_loss(model) − Σ fitted level × column``. With an oil exponent of 1 the oil drag and ``d0``
are both proportional to ω away from rest: a fit of both is refused as undetermined, so the
default terms hold ``d0`` (``DEFAULT_LOSS_TERMS``).

A joint whose model has no oil or no seal takes :class:`uwml.OilDrag`'s and :class:`uwml.Seal`'s
default shape with its levels at zero; a joint without losses, the default drive too.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Sequence

import numpy as np

from ..model.joint_losses import JointLosses
from ..model.losses import Drive, OilDrag, Seal
from ._types import Array

__all__ = ["DEFAULT_LOSS_TERMS", "LOSS_TERMS", "LossColumns"]

#: The loss terms a water-only fit can take, per joint.
LOSS_TERMS = ("k_oil", "c0", "s0", "d0")
#: Those it takes by default (``losses=True``): ``d0`` held (module docstring).
DEFAULT_LOSS_TERMS = ("k_oil", "c0", "s0")
_SEAL_LEVELS = ("c0", "c1_per_mpa", "s0", "s1_per_mpa", "d0", "d1_per_mpa")


def _shape(model: JointLosses | None) -> JointLosses:
    """``model`` with an oil and a seal (module docstring): absent ones at their default shape and
    zero levels."""
    if model is None:
        model = JointLosses(drive=Drive(), oil=None, seal=None)
    oil = model.oil if model.oil is not None else OilDrag(k_oil=0.0)
    seal = model.seal if model.seal is not None else Seal(**dict.fromkeys(_SEAL_LEVELS, 0.0))
    return dataclasses.replace(model, oil=oil, seal=seal)


class LossColumns:
    """The loss columns of the joints ``joints`` (0-based) with the models ``models`` (one per
    joint of the robot, None: none), the terms ``terms`` fitted at ``pressure_mpa`` and
    ``temperature_c``; ``labels``: each joint's name in the terms' names (``<label>.k_oil``)."""

    def __init__(
        self,
        models: Sequence[JointLosses | None],
        joints: Sequence[int],
        terms: Sequence[str],
        labels: Sequence[str],
        pressure_mpa: float,
        temperature_c: float,
    ) -> None:
        unknown = [term for term in terms if term not in LOSS_TERMS]
        if unknown or len(set(terms)) != len(terms):
            raise ValueError(f"losses must be distinct terms among {', '.join(LOSS_TERMS)}, got {list(terms)!r}")
        self._models = list(models)
        self._fitted = {j: _shape(models[j]) for j in joints} if terms else {}
        self._terms = tuple(terms)
        self._pressure, self._temperature = pressure_mpa, temperature_c
        #: The terms' names, joint by joint.
        self.names = [f"{labels[j]}.{term}" for j in self._fitted for term in self._terms]
        #: Their values in the models (the held part's reference).
        self.described = np.array([self._level(self._fitted[j], term) for j in self._fitted for term in self._terms])

    @staticmethod
    def _level(model: JointLosses, term: str) -> float:
        assert model.oil is not None and model.seal is not None
        return float(model.oil.k_oil if term == "k_oil" else getattr(model.seal, term))

    def _torques(self, model: JointLosses, speed: Array) -> Array:
        """The model's loss torque (environment sign) at the output speeds ``speed``."""
        torques = model.torques(speed, self._pressure, self._temperature)
        total: Array = torques.visc + torques.seal
        return total

    def _unit(self, model: JointLosses, term: str) -> JointLosses:
        """``model`` with ``term`` 1 and every other level 0 (for ``c0``: ``c0 = s0 = 1``)."""
        assert model.oil is not None and model.seal is not None
        if term == "k_oil":
            return dataclasses.replace(model, oil=dataclasses.replace(model.oil, k_oil=1.0), seal=None)
        levels = dict.fromkeys(_SEAL_LEVELS, 0.0) | ({"c0": 1.0, "s0": 1.0} if term == "c0" else {term: 1.0})
        return dataclasses.replace(model, oil=None, seal=dataclasses.replace(model.seal, **levels))

    def __call__(self, qd: Array) -> tuple[Array, Array]:
        """``(columns (n, n_joints, L), known (n, n_joints))`` at the joint speeds ``qd``: each
        fitted term's column on its joint's row, and every joint's held loss torque."""
        n, n_joints = qd.shape
        columns = np.zeros((n, n_joints, len(self.names)))
        known = np.zeros((n, n_joints))
        for j, model in enumerate(self._models):
            if model is not None and j not in self._fitted:
                known[:, j] = self._torques(model, qd[:, j])
        k = 0
        for j, model in self._fitted.items():
            speed = qd[:, j]
            known[:, j] = self._torques(model, speed)
            units = {term: self._torques(self._unit(model, term), speed) for term in self._terms}
            if "c0" in units:
                breakaway = units["s0"] if "s0" in units else self._torques(self._unit(model, "s0"), speed)
                units["c0"] = units["c0"] - breakaway
            for term in self._terms:
                columns[:, j, k] = units[term]
                known[:, j] -= self.described[k] * units[term]
                k += 1
        return columns, known
