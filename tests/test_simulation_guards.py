"""What a Simulation refuses rather than getting wrong (issue 31, section 4): a gravity changed
after it was made (uwml's buoyancy would stay at the old one), several threads stepping it at
once (they serialize on its lock), and constraint memory too small for the joints' seal
friction (MuJoCo drops the constraints with only a warning on standard error)."""

from __future__ import annotations

import threading
from pathlib import Path

import numpy as np
import pytest
import uwml

mujoco = pytest.importorskip("mujoco")
from uwml.sim.mjcf import mjcf_of
from uwml.sim.mujoco import Simulation

SEAL = "c0 = 16.0\nc1_per_mpa = 3.7\ns0 = 21.0\ns1_per_mpa = 6.7\nd0 = 2.2\nd1_per_mpa = 0.34\nstribeck_speed = 0.05\n"


def swinging_arm() -> Simulation:
    """Three links on a fixed base, heavier than the water, released from a bent pose."""
    joints = [uwml.Joint(origin=(0.2 * (i > 0), 0.0, 0.0), axis=(0.0, 1.0, 0.0)) for i in range(3)]
    segment = uwml.Segment(start=(0.0, 0.0, 0.0), axis=(1.0, 0.0, 0.0), length=0.2, diameter=0.05, section="circular")
    links = [uwml.Link(mass=2.0, com=(0.1, 0.0, 0.0), volume=4e-4, segments=[segment]) for _ in range(3)]
    robot = uwml.Robot(joints, links)
    sim = Simulation(mujoco.MjModel.from_xml_string(mjcf_of(robot)), robot)
    sim.data.qpos[:] = (0.3, -0.4, 0.5)
    return sim


def test_a_gravity_changed_after_the_simulation_was_made_is_refused_at_the_next_step() -> None:
    """Weight would follow MuJoCo's new gravity while uwml's buoyancy stays at the water's: the
    step refuses, naming both."""
    sim = swinging_arm()
    sim.step()
    sim.model.opt.gravity[2] = -3.71
    with pytest.raises(ValueError, match=r"model\.opt\.gravity changed to \[0\.0, 0\.0, -3\.71\].*9\.81"):
        sim.step()
    sim.model.opt.gravity[2] = -9.81  # put back: the simulation steps again
    sim.step()
    sim.model.opt.gravity[0] = 0.5
    with pytest.raises(ValueError, match="model.opt.gravity changed"):
        sim.forward()


def test_one_simulation_stepped_from_several_threads_is_the_same_as_the_steps_in_turn() -> None:
    """Four threads share 400 steps of one simulation: its steps serialize on the simulation's
    lock, so the state is that of 400 steps taken one after the other (bit for bit)."""
    alone = swinging_arm()
    for _ in range(400):
        alone.step()
    shared = swinging_arm()
    errors: list[BaseException] = []
    start = threading.Barrier(4)

    def worker() -> None:
        try:
            start.wait()
            for _ in range(100):
                shared.step()
        except BaseException as exc:  # noqa: BLE001 (reported by the test below)
            errors.append(exc)

    threads = [threading.Thread(target=worker) for _ in range(4)]
    for thread in threads:
        thread.start()
    for thread in threads:
        thread.join()
    assert not errors, errors
    assert shared.data.time == pytest.approx(alone.data.time, abs=1e-12)
    np.testing.assert_array_equal(shared.data.qpos, alone.data.qpos)
    np.testing.assert_array_equal(shared.data.qvel, alone.data.qvel)


def tree_with_seals(tmp_path: Path, links: int) -> tuple[Path, Path]:
    """A floating base with a tree of ``links`` links (four on the base, then two on each), every
    link a colliding box, every joint sealed: its overlapping boxes make over a thousand contacts."""
    inertia = 'ixx="0.001" iyy="0.001" izz="0.001" ixy="0" ixz="0" iyz="0"'
    base = '<inertial><mass value="5"/><inertia ixx="0.1" iyy="0.1" izz="0.1" ixy="0" ixz="0" iyz="0"/></inertial>'
    parts = [f'<link name="base">{base}<collision><geometry><box size="0.3 0.3 0.3"/></geometry></collision></link>']
    hydro = []
    for i in range(links):
        parent = "base" if i < 4 else f"l{(i - 4) // 2}"
        parts.append(
            f'<link name="l{i}"><inertial><origin xyz="0.05 0 0"/><mass value="0.3"/><inertia {inertia}/></inertial>'
            '<collision><origin xyz="0.05 0 0"/><geometry><box size="0.1 0.04 0.04"/></geometry></collision></link>'
            f'<joint name="j{i}" type="revolute"><parent link="{parent}"/><child link="l{i}"/>'
            f'<origin xyz="0.1 0 0" rpy="0 0 {0.3 * i!r}"/><axis xyz="0 0 1"/>'
            '<limit lower="-3" upper="3" effort="100" velocity="5"/></joint>'
        )
        hydro.append(f"[joints.j{i}]\nepsilon = 0.001\n[joints.j{i}.seal]\n{SEAL}")
    urdf, toml = tmp_path / "tree.urdf", tmp_path / "tree.hydro.toml"
    urdf.write_text(f'<robot name="tree">{"".join(parts)}</robot>')
    toml.write_text("\n".join(hydro))
    return urdf, toml


def test_seal_friction_that_mujocos_constraint_memory_cannot_hold_is_an_error_not_a_warning(tmp_path: Path) -> None:
    """A 64-link tree with sealed joints and 1,167 contacts fills MuJoCo's constraint memory:
    MuJoCo drops every constraint, the seals' friction with them, and only prints a warning.
    The simulation refuses instead, saying what to enlarge."""
    urdf, toml = tree_with_seals(tmp_path, 64)
    sim = Simulation.from_file(urdf, toml, floating=True, depth=3000.0)
    with pytest.raises(uwml.UwmlError, match=r"constraint memory.*seal friction.*<size memory="):
        sim.step()


def test_a_tree_whose_constraints_fit_keeps_its_seal_friction(tmp_path: Path) -> None:
    """The same tree with 8 links: its constraints fit, the step goes on and each sealed joint has
    its friction constraint (the check does not refuse what MuJoCo holds)."""
    urdf, toml = tree_with_seals(tmp_path, 8)
    sim = Simulation.from_file(urdf, toml, floating=True, depth=3000.0)
    sim.step()
    friction = int(mujoco.mjtConstraint.mjCNSTR_FRICTION_DOF)
    assert int(np.sum(sim.data.efc_type[: sim.data.nefc] == friction)) == 8
