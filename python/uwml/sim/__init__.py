"""Motions, simulations and synthetic experiments: the walking gait (:mod:`uwml.sim.gait`), MuJoCo
stepped with uwml's forces (:mod:`uwml.sim.mujoco`), the simulation studies of ``uwml simulate``
(:mod:`uwml.sim.studies`), synthetic experiments with a known truth for the fits
(:mod:`uwml.sim.synthetic`) and the paper's analysis of ``uwml paper``
(:mod:`uwml.sim.paper_analysis`).

The package imports only :mod:`~uwml.sim.gait` (numpy alone); name the others (MuJoCo is imported
when a simulation is made).
"""

from .gait import WalkingGait, paper_leg_foot, paper_leg_ik

__all__ = ["WalkingGait", "paper_leg_foot", "paper_leg_ik"]
