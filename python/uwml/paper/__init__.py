"""The paper's material (Liao et al.; docs/model.md sections 2 and 6), in one place: its leg's
inverse kinematics and a walking gait (:mod:`uwml.paper.gait`), synthetic data of its
experiments with a known truth for the fits (:mod:`uwml.paper.synthetic`), its analysis end to
end (:mod:`uwml.paper.analysis`, ``uwml paper`` and ``uwml demo``) and its control question
simulated, with the study preset of ``uwml simulate`` (:mod:`uwml.paper.control_study`).

The package imports only :mod:`~uwml.paper.gait` (numpy alone), whose names ``import uwml``
gives; name the others.
"""

from .gait import WalkingGait, paper_leg_foot, paper_leg_ik

__all__ = ["WalkingGait", "paper_leg_foot", "paper_leg_ik"]
