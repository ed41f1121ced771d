"""Kirchhoff's added mass (``added_mass="kirchhoff"``; docs/simulation.md, "Energy-consistent
added mass") everywhere a robot evaluates added mass: its forces differ from the Morison ones
only in the velocity terms (the same ``M_A``); the regressors at the coefficients give them; the
jacobians' value is ``environment``'s total and their velocity derivative the slope. Its energy
conservation in a simulation is ``test_simulation.py``'s.
"""

import numpy as np
import pytest
import uwml
from robots import COMPONENTS, motion_arguments


def test_kirchhoff_regressors_and_jacobians_are_its_forces() -> None:
    """``added_mass="kirchhoff"`` everywhere a robot evaluates added mass: the regressors at the
    segments' coefficients give ``hydro``'s forces; the jacobians' value is ``environment``'s
    total and their velocity derivative matches central differences; ``M_A`` is the Morison one."""
    from uwml.examples import arm_on_rov

    robot = arm_on_rov()
    rng = np.random.default_rng(12)
    q, qd, qdd = rng.uniform(-1, 1, (3, 7)), rng.uniform(-1, 1, (3, 7)), rng.uniform(-1, 1, (3, 7))
    motion = uwml.BaseMotion(**motion_arguments(rng, 3))
    current = rng.normal(size=(3, 3))
    forces = robot.hydro(q, qd, qdd, base_motion=motion, current=current, added_mass="kirchhoff")
    morison = robot.hydro(q, qd, qdd, base_motion=motion, current=current)
    assert np.max(np.abs(forces.added_mass - morison.added_mass)) > 1e-3
    cd = np.array([s.cd for s in robot.segments])
    cm = np.array([s.cm for s in robot.segments])
    columns = robot.hydro_regressors(q, qd, qdd, base_motion=motion, current=current, added_mass="kirchhoff").torques(cd, cm)
    for name in COMPONENTS:
        np.testing.assert_allclose(getattr(columns, name), getattr(forces, name), rtol=1e-12, atol=1e-12)
        np.testing.assert_allclose(getattr(columns.base, name), getattr(forces.base, name), rtol=1e-12, atol=1e-12)
    one = uwml.BaseMotion(
        **{
            k: np.asarray(getattr(motion, k))[0]
            for k in ("orientation", "velocity", "angular_velocity", "acceleration", "angular_acceleration")
        }
    )
    jac = robot.jacobians(q[0], qd[0], qdd[0], base_motion=one, current=current[0], added_mass="kirchhoff")
    env = robot.environment(q[0], qd[0], qdd[0], base_motion=one, current=current[0], added_mass="kirchhoff")
    np.testing.assert_allclose(jac.value, np.concatenate([env.base.total, env.total]), rtol=1e-12, atol=1e-12)
    np.testing.assert_array_equal(
        jac.added_mass_matrix, robot.jacobians(q[0], qd[0], qdd[0], base_motion=one, current=current[0]).added_mass_matrix
    )
    h = 1e-6
    for j in range(7):
        step = np.zeros(7)
        step[j] = h
        plus = robot.environment(q[0], qd[0] + step, qdd[0], base_motion=one, current=current[0], added_mass="kirchhoff")
        minus = robot.environment(q[0], qd[0] - step, qdd[0], base_motion=one, current=current[0], added_mass="kirchhoff")
        fd = (np.concatenate([plus.base.total, plus.total]) - np.concatenate([minus.base.total, minus.total])) / (2 * h)
        np.testing.assert_allclose(jac.d_velocity[:, 6 + j], fd, rtol=1e-6, atol=1e-6 * np.max(np.abs(fd)))
    with pytest.raises(ValueError, match="added_mass must be one of morison, kirchhoff"):
        robot.hydro(q, qd, qdd, added_mass="potential")


def test_a_chain_takes_kirchhoffs_added_mass_too() -> None:
    """The paper's leg with ``added_mass="kirchhoff"`` in every evaluation: at zero velocity the
    Morison forces; ``environment`` adds the losses only; the jacobians' value is its total, their
    ``M_A`` the Morison one; the regressors at the coefficients give the forces."""
    leg = uwml.paper_leg()
    rng = np.random.default_rng(13)
    q, qd, qdd = rng.uniform(-1, 1, (4, 3)), rng.uniform(-1, 1, (4, 3)), rng.uniform(-2, 2, (4, 3))
    cd, cm = rng.uniform(0.5, 2.5, (2, 2)), rng.uniform(0.2, 1.5, (2, 2))
    kirchhoff = uwml.Conditions(cd=cd, cm=cm, added_mass="kirchhoff")
    morison = kirchhoff.replace(added_mass="morison")
    k = leg.hydro(q, qd, qdd, kirchhoff)
    at_rest = leg.hydro(q, 0 * qd, qdd, kirchhoff)
    np.testing.assert_allclose(at_rest.added_mass, leg.hydro(q, 0 * qd, qdd, morison).added_mass, rtol=1e-12, atol=1e-12)
    assert np.max(np.abs(k.added_mass - leg.hydro(q, qd, qdd, morison).added_mass)) > 1e-3
    losses = {"depth": 2000.0, "temperature_c": 4.0, "losses": uwml.JointLosses()}
    env = leg.environment(q, qd, qdd, kirchhoff, **losses)
    np.testing.assert_array_equal(env.added_mass, k.added_mass)
    np.testing.assert_array_equal(env.seal, leg.environment(q, qd, qdd, morison, **losses).seal)
    jac = leg.jacobians(q, qd, qdd, kirchhoff, **losses)
    np.testing.assert_allclose(jac.value[:, 6:], env.total, rtol=1e-12, atol=1e-10)
    np.testing.assert_allclose(jac.added_mass_matrix, leg.jacobians(q, qd, qdd, morison).added_mass_matrix, rtol=1e-12, atol=1e-12)
    regressors = leg.hydro_regressors(q, qd, qdd, added_mass="kirchhoff")
    np.testing.assert_allclose(regressors.torques(cd, cm).added_mass, k.added_mass, rtol=1e-12, atol=1e-12)
    with pytest.raises(ValueError, match="added_mass must be one of morison, kirchhoff"):
        leg.hydro(q, qd, qdd, added_mass="Kirchhoff")
