"""A robot from its URDF floating freely in one call (``Simulation.from_file(..., floating=True)``
or the hydro file's ``[base] floating``), with the description's own masses and inertias, and
wrenches on bodies by name for a step (thrusters, a tether)."""

from pathlib import Path

import numpy as np
import pytest
import uwml

mujoco = pytest.importorskip("mujoco")

from uwml.sim.mujoco import Simulation

DATA = Path(__file__).parent / "data"


def test_a_urdf_floats_in_one_call_with_its_own_masses_and_inertias(tmp_path: Path) -> None:
    fixed = Simulation.from_file(DATA / "rov_arm6.urdf", DATA / "rov_arm6.hydro.toml")
    floating = Simulation.from_file(DATA / "rov_arm6.urdf", DATA / "rov_arm6.hydro.toml", floating=True)
    free = int(mujoco.mjtJoint.mjJNT_FREE)
    assert free not in fixed.model.jnt_type and list(floating.model.jnt_type).count(free) == 1
    assert floating.model.nv == fixed.model.nv + 6
    # The description's own masses and inertias (the hull's 250 kg, its URDF inertia), not a
    # solid's of uniform density.
    hull = mujoco.mj_name2id(floating.model, mujoco.mjtObj.mjOBJ_BODY, "hull")
    assert floating.model.body_mass[hull] == 250.0
    np.testing.assert_allclose(sorted(floating.model.body_inertia[hull]), [18.0, 35.0, 40.0])
    np.testing.assert_array_equal(floating.model.body_mass, fixed.model.body_mass)
    # The hydro file can say so instead.
    hydro = tmp_path / "h.toml"
    hydro.write_text((DATA / "rov_arm6.hydro.toml").read_text() + "\n[base]\nfloating = true\n")
    assert Simulation.from_file(DATA / "rov_arm6.urdf", hydro).model.nv == floating.model.nv
    assert Simulation.from_file(DATA / "rov_arm6.urdf", hydro, floating=False).model.nv == fixed.model.nv
    # It moves: sinking or rising from rest as its buoyancy and weight say, the arm's joints too.
    for _ in range(200):
        floating.step()
    assert np.all(np.isfinite(floating.data.qvel)) and np.abs(floating.data.qvel[:6]).max() > 0.0


def test_a_wrench_on_a_body_is_a_world_force_at_its_centre_of_mass_for_that_step() -> None:
    """A force at the hull's centre of mass, given as a wrench on the hull, moves the vehicle as
    the same force given as generalized forces: on the free joint's linear rows, with the moment
    of the force about the free joint's origin on its angular rows (body components)."""
    first = Simulation.from_file(DATA / "rov_arm6.urdf", DATA / "rov_arm6.hydro.toml", floating=True)
    second = Simulation.from_file(DATA / "rov_arm6.urdf", DATA / "rov_arm6.hydro.toml", floating=True)
    m, d = first.model, first.data
    hull = mujoco.mj_name2id(m, mujoco.mjtObj.mjOBJ_BODY, "hull")
    force = np.array([40.0, -10.0, 5.0])
    for _ in range(100):
        mujoco.mj_kinematics(m, d)
        mujoco.mj_comPos(m, d)
        arm = d.xipos[hull] - d.xpos[hull]  # the centre of mass from the body's origin (world)
        moment_body = d.xmat[hull].reshape(3, 3).T @ np.cross(arm, force)
        qfrc = np.zeros(m.nv)
        qfrc[0:3], qfrc[3:6] = force, moment_body
        first.step(qfrc=qfrc)
        second.step(wrenches={"hull": np.concatenate([force, np.zeros(3)])})
    np.testing.assert_allclose(second.data.qvel, first.data.qvel, rtol=1e-9, atol=1e-12)
    assert first.data.qvel[0] > 0.0  # pushed forward
    # Held for the step only.
    np.testing.assert_array_equal(second.data.xfrc_applied, np.zeros_like(second.data.xfrc_applied))


@pytest.mark.parametrize(
    "wrenches, error, message",
    [
        ({"keel": np.zeros(6)}, ValueError, r"no body named 'keel' \(the model's bodies: hull"),
        ({"hull": np.zeros(5)}, ValueError, r"wrenches\['hull'\] must be 6 finite numbers"),
        ({"hull": [0, 0, np.nan, 0, 0, 0]}, ValueError, r"wrenches\['hull'\] must be 6 finite numbers"),
        ([("hull", np.zeros(6))], TypeError, "wrenches must map body names to 6 numbers"),
    ],
)
def test_bad_wrenches_are_refused_naming_them(wrenches: object, error: type, message: str) -> None:
    sim = Simulation.from_file(DATA / "rov_arm6.urdf", DATA / "rov_arm6.hydro.toml", floating=True)
    before = sim.data.qvel.copy()
    with pytest.raises(error, match=message):
        sim.step(wrenches=wrenches)  # type: ignore[arg-type]
    np.testing.assert_array_equal(sim.data.qvel, before)


def test_floating_is_refused_where_it_cannot_be(tmp_path: Path) -> None:
    with pytest.raises(TypeError, match="floating must be true, false or None"):
        Simulation.from_file(DATA / "rov_arm6.urdf", DATA / "rov_arm6.hydro.toml", floating="yes")  # type: ignore[arg-type]
    hydro = tmp_path / "h.toml"
    hydro.write_text("[base]\nfloat = true\n")
    with pytest.raises(uwml.DescriptionError, match=r"\[base\], key 'float': is not a key of this table \(allowed: floating\)"):
        Simulation.from_file(DATA / "rov_arm6.urdf", hydro)
