"""Tests of the whole-robot numpy reference ``python/uwml/reference/robot_hydro.py`` (docs/model.md section 10).

The package is loaded standalone from its directory (as in ``test_reference.py``), so these tests
need no compiled extension, except the one against ``uwml.paper_leg()``. No expected value comes
from the code under test:

* against the serial-chain reference ``reference.hydro`` (a different algorithm) and the numbers
  typed from docs/model.md section 5;
* analytic special cases written out by hand (a spinning or translating cylinder, a sliding box,
  Froude-Krylov, buoyancy moments, a base spinning about an offset body);
* a brute force that shares nothing with the reference: body poses by quaternions, slice
  velocities and accelerations by finite differences in time along a trajectory, generalized
  forces as virtual work against complex-step Jacobians of slice positions, and dense composite
  Gauss-Legendre quadrature of the strip forces;
* the invariants of docs/model.md section 10, "Invariants" on random trees with random states, base motion and current.

The brute force and the invariants (sections 3 and 4) are in
``test_reference_robot_invariants.py``; the descriptions and random robots they share are in
``reference_trees.py``.
"""

import math
import subprocess
import sys

import numpy as np
import pytest
from pure import REFERENCE_DIR
from reference_trees import (
    KEYS,
    NS,
    PARTS,
    RHO,
    G,
    assert_close,
    body,
    box,
    cylinder,
    hydro,
    joint,
    quat_axis_angle,
    quat_matrix,
    random_motion,
    random_quaternion,
    random_tree,
    random_unit,
    ref,
    unit,
)

# --------------------------------------------------------------------------------------------
# 0. The package stands alone
# --------------------------------------------------------------------------------------------


def test_reference_package_imports_only_numpy_and_the_standard_library():
    code = """
import importlib.abc, importlib.util, sys
class Block(importlib.abc.MetaPathFinder):
    def find_spec(self, name, path=None, target=None):
        if name.split('.')[0] in ('uwml', 'scipy', 'uwml_pure'):
            raise ImportError('blocked: ' + name)
sys.meta_path.insert(0, Block())
before = set(sys.modules)  # whatever the interpreter's start-up (site, .pth files) loaded
d = @DIRECTORY@
spec = importlib.util.spec_from_file_location('ref_alone', d + '/__init__.py', submodule_search_locations=[d])
m = importlib.util.module_from_spec(spec); sys.modules['ref_alone'] = m; spec.loader.exec_module(m)
names = ('robot_hydro', 'robot_added_mass_matrix', 'robot_link_wrenches', 'hydro', 'paper_equations', 'smooth_sign')
print(sorted(n for n in names if hasattr(m, n)))
tops = {n.split('.')[0] for n in set(sys.modules) - before if not n.startswith('_')}
print(sorted(tops - set(sys.stdlib_module_names) - {'ref_alone', 'numpy'}))
""".replace("@DIRECTORY@", repr(str(REFERENCE_DIR)))
    result = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=60, check=False)
    assert result.returncode == 0, result.stderr
    names, others = result.stdout.strip().splitlines()
    expected = ["robot_hydro", "robot_added_mass_matrix", "robot_link_wrenches", "hydro", "paper_equations", "smooth_sign"]
    assert names == str(sorted(expected)), names
    assert others == "[]", f"modules other than numpy and the standard library: {others}"


# --------------------------------------------------------------------------------------------
# 1. A serial chain on a fixed, upright base in still water is section 3
# --------------------------------------------------------------------------------------------


def _chain_states(rng: np.random.Generator, m: int, n: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    q = rng.uniform(-math.pi, math.pi, (m, n))
    qd = rng.uniform(-3.0, 3.0, (m, n))
    qd[rng.random((m, n)) < 0.15] = 0.0
    return q, qd, rng.uniform(-10.0, 10.0, (m, n))


def test_paper_leg_equals_the_chain_reference_and_model_md_section_5():
    import uwml

    leg = uwml.paper_leg()
    joints, links = leg.joints, leg.links
    q, qd, qdd = _chain_states(np.random.default_rng(5), 64, 3)
    got = ref.robot_hydro(joints, links, None, q, qd, qdd, cd=2.2, cm=0.5)
    expected = ref.hydro(joints, links, q, qd, qdd, cd=2.2, cm=0.5)
    for key in PARTS:
        assert_close(got[key], expected[key], 1e-12, key)
    # docs/model.md section 5, typed from the table.
    one = ref.robot_hydro(joints, links, None, (0.3, -0.4, 0.6), (0.8, 0.5, -0.7), (1.0, -2.0, 0.5), cd=2.2, cm=0.5)
    table = {
        "drag": (-24.24084, -5.060505, -0.7383118),
        "added_mass": (-8.525438, 21.77596, 9.484545),
        "buoyancy": (0.0, 59.72457, 4.193843),
    }
    for key, values in table.items():
        assert one[key].shape == (3,)
        np.testing.assert_allclose(one[key], values, rtol=1e-6, atol=1e-9, err_msg=key)
    # The same leg as the reference's own description (no parent, kind or section attributes).
    ref_joints, ref_links = ref.paper_leg()
    again = ref.robot_hydro(ref_joints, ref_links, None, q, qd, qdd, cd=2.2, cm=0.5)
    for key in KEYS:
        assert_close(again[key], got[key], 1e-14, key)


def _random_chain(rng: np.random.Generator) -> tuple[list, list, np.ndarray]:
    """A serial chain of revolute joints (parents default) with one rectangular segment or none
    per link, as RefJoint/RefLink-like objects (``segments``), and per-link coefficients."""
    n = int(rng.integers(1, 7))
    joints, links = [], []
    for i in range(n):
        axis = random_unit(rng) if rng.random() < 0.8 else np.eye(3)[rng.integers(3)]
        joints.append(NS(origin=tuple(rng.uniform(-0.5, 0.5, 3)), axis=tuple(axis)))
        segment = None
        if i == n - 1 or rng.random() < 0.7:
            seg_axis = random_unit(rng)
            n1 = unit(np.cross(seg_axis, random_unit(rng)))
            w = rng.uniform(0.03, 0.3, 2)
            segment = NS(
                start=tuple(rng.uniform(-0.2, 0.2, 3)),
                axis=tuple(seg_axis),
                length=float(rng.uniform(0.1, 1.0)),
                normals=(tuple(n1), tuple(np.cross(seg_axis, n1))),
                widths=tuple(w),
                area=float(w.prod()),
            )
        mass = float(rng.uniform(0.2, 20.0))
        com = rng.uniform(-0.4, 0.4, 3)
        links.append(
            NS(
                mass=mass,
                com=tuple(com),
                volume=mass / 3000.0,
                cob=tuple(com + rng.uniform(-0.1, 0.1, 3)),
                segments=() if segment is None else (segment,),
            )
        )
    return joints, links, np.array([bool(link.segments) for link in links])


@pytest.mark.parametrize("seed", range(6))
def test_random_serial_chains_equal_the_chain_reference(seed):
    rng = np.random.default_rng(100 + seed)
    joints, links, has_segment = _random_chain(rng)
    n = len(joints)
    q, qd, qdd = _chain_states(rng, 40, n)
    cd = rng.uniform(0.5, 3.0, (n, 2))
    cm = rng.uniform(0.2, 1.5, (n, 2))
    expected = ref.hydro(joints, links, q, qd, qdd, cd=cd, cm=cm, density=1025.0, gravity=9.8)
    got = ref.robot_hydro(joints, links, None, q, qd, qdd, cd=cd[has_segment], cm=cm[has_segment], density=1025.0, gravity=9.8)
    for key in PARTS:
        assert_close(got[key], expected[key], 1e-12, key)


# --------------------------------------------------------------------------------------------
# 2. Analytic special cases, written out by hand
# --------------------------------------------------------------------------------------------

L_CYL, D_CYL, CD, CM = 0.8, 0.12, 1.1, 0.9
A_CYL = math.pi * D_CYL**2 / 4


@pytest.mark.parametrize("w", [1.7, -2.3])
def test_cylinder_spinning_about_a_vertical_axis_at_its_end(w):
    # One horizontal cylinder from the joint along +x; the joint turns it about z at rate w.
    joints = [joint((0.3, -0.2, 0.1), (0, 0, 1))]
    links = [body(segments=(cylinder((0, 0, 0), (1, 0, 0), L_CYL, D_CYL, CD, CM),))]
    out = ref.robot_hydro(joints, links, None, [0.4], [w], [0.0])
    assert out["drag"][0] == pytest.approx(-0.5 * RHO * CD * D_CYL * w * abs(w) * L_CYL**4 / 4, rel=1e-13)
    # The added mass of the tangential acceleration q̈ s per slice: −ρ Cm A q̈ L³/3; the
    # centripetal acceleration is along the cylinder, so it adds nothing.
    out = ref.robot_hydro(joints, links, None, [0.4], [w], [2.5])
    assert out["added_mass"][0] == pytest.approx(-RHO * CM * A_CYL * 2.5 * L_CYL**3 / 3, rel=1e-13)
    # The base wrench: the force is ∫ −½ρCdD (ws)|ws| ds along the tangent, the moment's z
    # component about the base origin is the joint torque plus (o × F)_z.
    force = -0.5 * RHO * CD * D_CYL * w * abs(w) * L_CYL**3 / 3 * np.array([-math.sin(0.4), math.cos(0.4), 0.0])
    out = ref.robot_hydro(joints, links, None, [0.4], [w], [0.0])
    np.testing.assert_allclose(out["base_drag"][:3], force, rtol=1e-13, atol=1e-14)
    torque_z = -0.5 * RHO * CD * D_CYL * w * abs(w) * L_CYL**4 / 4 + np.cross((0.3, -0.2, 0.1), force)[2]
    assert out["base_drag"][5] == pytest.approx(torque_z, rel=1e-13)


@pytest.mark.parametrize("u", [0.7, -1.3])
def test_cylinder_translating_broadside_and_at_rest_in_a_current(u):
    # The base carries the cylinder (centred on the base origin, along base y); no joints.
    base = body(segments=(cylinder((0, -L_CYL / 2, 0), (0, 1, 0), L_CYL, D_CYL, CD, CM),))
    drag = 0.5 * RHO * CD * D_CYL * L_CYL * u * abs(u)
    moving = ref.robot_hydro([], [], base, [], [], [], velocity=(u, 0, 0), gravity=0.0)
    np.testing.assert_allclose(moving["base_drag"], [-drag, 0, 0, 0, 0, 0], rtol=1e-14, atol=1e-12)
    assert moving["drag"].shape == (0,)
    # At rest in a current (world components) with the base turned: the same force, reversed,
    # in base components.
    quaternion = quat_axis_angle(unit((1, 2, 3)), 0.9)
    rot = quat_matrix(quaternion)
    current = rot @ np.array([u, 0.0, 0.0])
    still = ref.robot_hydro([], [], base, [], [], [], orientation=quaternion, current=current, gravity=0.0)
    np.testing.assert_allclose(still["base_drag"], [drag, 0, 0, 0, 0, 0], rtol=1e-13, atol=1e-12)
    # Moving along its own axis: no drag, and no added mass when accelerating along it.
    axial = ref.robot_hydro([], [], base, [], [], [], velocity=(0, u, 0), acceleration=(0, 2.0, 0), gravity=0.0)
    np.testing.assert_allclose(axial["base_drag"], np.zeros(6), atol=1e-20)
    np.testing.assert_allclose(axial["base_added_mass"], np.zeros(6), atol=1e-15)
    # Accelerating broadside: −ρ Cm A L v̇.
    accelerating = ref.robot_hydro([], [], base, [], [], [], acceleration=(0, 0, u), gravity=0.0)
    np.testing.assert_allclose(accelerating["base_added_mass"], [0, 0, -RHO * CM * A_CYL * L_CYL * u, 0, 0, 0], rtol=1e-14, atol=1e-12)


def test_cylinder_off_the_base_origin_when_the_base_spins():
    # A vertical cylinder at x = d on the base; the base spins about z at Ω, with ω̇ = β.
    d, omega, beta = 0.6, 1.4, -0.8
    base = body(segments=(cylinder((d, 0, -L_CYL / 2), (0, 0, 1), L_CYL, D_CYL, CD, CM),))
    out = ref.robot_hydro([], [], base, [], [], [], angular_velocity=(0, 0, omega), angular_acceleration=(0, 0, beta), gravity=0.0)
    speed = omega * d  # every slice moves along +y at Ω d
    drag_y = -0.5 * RHO * CD * D_CYL * L_CYL * speed * abs(speed)
    np.testing.assert_allclose(out["base_drag"], [0, drag_y, 0, 0, 0, d * drag_y], rtol=1e-14, atol=1e-12)
    # Added mass on the slice's acceleration (−Ω² d, β d, 0): a centripetal part outwards.
    am = -RHO * CM * A_CYL * L_CYL * np.array([-(omega**2) * d, beta * d, 0.0])
    np.testing.assert_allclose(out["base_added_mass"], [am[0], am[1], 0, 0, 0, d * am[1]], rtol=1e-14, atol=1e-12)
    # ν̇ convention (docs/model.md section 10, "Base motion and current"): base origin moving at
    # v = (V, 0, 0) while spinning at Ω with v̇ = 0 accelerates classically at ω × v = (0, Ω V, 0);
    # a cylinder at the origin sees it.
    centred = body(segments=(cylinder((0, 0, -L_CYL / 2), (0, 0, 1), L_CYL, D_CYL, CD, CM),))
    out = ref.robot_hydro([], [], centred, [], [], [], velocity=(0.5, 0, 0), angular_velocity=(0, 0, omega), gravity=0.0)
    np.testing.assert_allclose(out["base_added_mass"], [0, -RHO * CM * A_CYL * L_CYL * omega * 0.5, 0, 0, 0, 0], rtol=1e-14, atol=1e-12)


@pytest.mark.parametrize("speed", [0.9, -0.4])
def test_prismatic_joint_slides_a_box_broadside(speed):
    # A box along x, normals y (width 0.2) and z (width 0.05), slid along y by a prismatic joint
    # on a base turned about z (the joint axis turns with it; the force along it is unchanged).
    seg = box((-0.1, 0, 0), (1, 0, 0), 0.5, ((0, 1, 0), (0, 0, 1)), (0.2, 0.05), 0.01, cd=(2.0, 1.0), cm=(0.7, 0.3))
    joints = [joint((0.2, 0.1, 0), (0, 1, 0), kind="prismatic")]
    links = [body(mass=3.0, volume=0.002, com=(0.1, 0, 0), segments=(seg,))]
    out = ref.robot_hydro(joints, links, None, [0.3], [speed], [1.5], orientation=quat_axis_angle((0, 0, 1), 0.7))
    assert out["drag"][0] == pytest.approx(-0.5 * RHO * 2.0 * 0.2 * 0.5 * speed * abs(speed), rel=1e-14)
    assert out["added_mass"][0] == pytest.approx(-RHO * 0.7 * 0.01 * 0.5 * 1.5, rel=1e-14)
    assert abs(out["buoyancy"][0]) < 1e-14 and abs(out["gravity"][0]) < 1e-14  # horizontal slide
    # Slid vertically instead: buoyancy ρVg and weight −mg along the joint.
    up = [joint((0.2, 0.1, 0), (0, 0, 1), kind="prismatic")]
    seg_up = box((-0.1, 0, 0), (1, 0, 0), 0.5, ((0, 0, 1), (0, 1, 0)), (0.2, 0.05), 0.01, cd=(2.0, 1.0), cm=(0.7, 0.3))
    out = ref.robot_hydro(up, [body(mass=3.0, volume=0.002, com=(0.1, 0, 0), segments=(seg_up,))], None, [0.3], [speed], [0.0])
    assert out["buoyancy"][0] == pytest.approx(RHO * 0.002 * G, rel=1e-14)
    assert out["gravity"][0] == pytest.approx(-3.0 * G, rel=1e-14)
    assert out["drag"][0] == pytest.approx(-0.5 * RHO * 2.0 * 0.2 * 0.5 * speed * abs(speed), rel=1e-14)


def test_froude_krylov_and_buoyancy_moments():
    rng = np.random.default_rng(3)
    volume, mass = 0.004, 7.0
    cob, com = np.array([0.2, -0.1, 0.3]), np.array([0.1, 0.05, 0.25])
    base = body(mass=mass, com=com, volume=volume, cob=cob)
    quaternion = random_quaternion(rng)
    rot = quat_matrix(quaternion)
    cdot = np.array([0.3, -0.5, 0.8])
    out = ref.robot_hydro([], [], base, [], [], [], orientation=quaternion, current_acceleration=cdot)
    force = rot.T @ (RHO * volume * (cdot + np.array([0, 0, G])))
    np.testing.assert_allclose(out["base_buoyancy"], np.concatenate([force, np.cross(cob, force)]), rtol=1e-14, atol=1e-13)
    weight = rot.T @ np.array([0, 0, -mass * G])
    np.testing.assert_allclose(out["base_gravity"], np.concatenate([weight, np.cross(com, weight)]), rtol=1e-14, atol=1e-13)
    # On a link turned by a revolute joint: the torque of ρVċ about the joint axis.
    joints = [joint((0, 0, 0), (0, 0, 1))]
    links = [body(volume=volume, com=(0.5, 0, 0))]
    out = ref.robot_hydro(joints, links, None, [0.0], [0.0], [0.0], current_acceleration=(0.0, 2.0, 0.0))
    assert out["buoyancy"][0] == pytest.approx(0.5 * RHO * volume * 2.0, rel=1e-14)
    # Link wrenches: the whole environment force on the body, moment about its COM.
    wrench = ref.robot_link_wrenches([], [], base, [], [], [], orientation=quaternion, current_acceleration=cdot)
    total = rot @ force + rot @ weight
    np.testing.assert_allclose(wrench[0], np.concatenate([total, np.cross(rot @ (cob - com), rot @ force)]), rtol=1e-13, atol=1e-13)


def test_circular_drag_against_dense_simpson_with_v_perp_through_zero():
    """A cylinder on a spinning, translating base in a current: v⊥ vanishes inside it (exactly,
    or nearly: a small velocity along the third direction), or not at all."""
    rng = np.random.default_rng(11)
    start, axis, length, diameter = np.array([-0.3, 0.1, 0.05]), unit((1, 0.2, -0.1)), 1.0, 0.1
    base = body(segments=(cylinder(start, axis, length, diameter, CD, CM),))
    quaternion = random_quaternion(rng)
    rot = quat_matrix(quaternion)
    omega = np.cross(axis, unit((0.3, 1, 0.2))) * 2.0  # ⊥ axis: spins the cylinder about a point on it
    s_zero = 0.37
    zero_point = start + s_zero * axis
    current = rot @ np.array([0.1, -0.2, 0.3])
    for near in (0.0, 1e-3, 0.3):
        # Base velocity (base components) so that the slice at s_zero moves with the current,
        # plus `near` along ω × axis's normal (so v⊥ misses zero by `near`), plus an axial part.
        miss = unit(omega) * near  # ⊥ the axis and ⊥ ω × (p − p0): a true near miss
        velocity = rot.T @ current - np.cross(omega, zero_point) + miss + 0.4 * axis
        out = ref.robot_hydro(
            [], [], base, [], [], [], orientation=quaternion, velocity=velocity, angular_velocity=omega, current=current, gravity=0.0
        )
        # Brute force in base components: the field is rigid, v(p) = velocity + ω × p.
        s = np.linspace(0.0, length, 20001)
        p = start + s[:, None] * axis
        v_rel = velocity + np.cross(omega, p) - rot.T @ current
        v_perp = v_rel - (v_rel @ axis)[:, None] * axis
        f = -0.5 * RHO * CD * diameter * np.linalg.norm(v_perp, axis=1)[:, None] * v_perp
        weights = np.full(len(s), 2.0)
        weights[1::2] = 4.0
        weights[[0, -1]] = 1.0
        weights *= (s[1] - s[0]) / 3.0
        expected = np.concatenate([weights @ f, weights @ np.cross(p, f)])
        assert_close(out["base_drag"], expected, 1e-9 if near < 0.1 else 1e-13, f"near={near}")
        if near == 0.0:
            # Split at the zero: |v⊥| is affine on each side, the integrands are cubics, and
            # Simpson's rule is exact on each side.
            pieces = []
            for lo, hi in ((0.0, s_zero), (s_zero, length)):
                sp = np.linspace(lo, hi, 3)
                pp = start + sp[:, None] * axis
                vr = velocity + np.cross(omega, pp) - rot.T @ current
                vp = vr - (vr @ axis)[:, None] * axis
                fp = -0.5 * RHO * CD * diameter * np.linalg.norm(vp, axis=1)[:, None] * vp
                wts = np.array([1.0, 4.0, 1.0]) * (hi - lo) / 6.0
                pieces.append(np.concatenate([wts @ fp, wts @ np.cross(pp, fp)]))
            assert_close(out["base_drag"], pieces[0] + pieces[1], 1e-13, "split at the zero of v⊥")


# --------------------------------------------------------------------------------------------
# 5. Shapes, broadcasting and bad inputs
# --------------------------------------------------------------------------------------------


def test_shapes_and_broadcasting_over_samples():
    rng = np.random.default_rng(17)
    joints, links, base = random_tree(rng, n=3, base=True)
    motion = random_motion(rng, 5, 3)
    batch = hydro(joints, links, base, motion)
    for key in PARTS:
        assert batch[key].shape == (5, 3) and batch[f"base_{key}"].shape == (5, 6)
    single = hydro(joints, links, base, {k: v[2] for k, v in motion.items()})
    for key in KEYS:
        assert single[key].shape == batch[key].shape[1:]
        np.testing.assert_allclose(single[key], batch[key][2], rtol=1e-15, atol=1e-15)
    # One per-sample argument is enough to give a sample axis; the others broadcast.
    mixed = hydro(joints, links, base, {k: v[2] for k, v in motion.items()} | {"current": motion["current"]})
    assert mixed["drag"].shape == (5, 3)
    wrench = ref.robot_link_wrenches(joints, links, base, **{k: v[2] for k, v in motion.items()})
    assert wrench.shape == (4, 6)


def test_bad_inputs():
    joints = [joint((0, 0, 0), (0, 0, 1))]
    links = [body(segments=(cylinder((0, 0, 0), (1, 0, 0), 1.0, 0.1),))]
    args = (joints, links, None, [0.0], [1.0], [0.0])
    for bad in ((0, 0, 0, 0), (1.0, 0.1, 0.0, 0.0), (2.0, 0.0, 0.0, 0.0)):
        with pytest.raises(ValueError, match="orientation"):
            ref.robot_hydro(*args, orientation=bad)
    assert ref.robot_hydro(*args, orientation=(1.0 + 1e-9, 0, 0, 0))["drag"].shape == (1,)
    with pytest.raises(ValueError, match="circular"):
        ref.robot_hydro(*args, cd=[[1.0, 2.0]])
    with pytest.raises(ValueError, match="samples"):
        ref.robot_hydro(joints, links, None, [[0.0], [0.1]], [1.0], [0.0], current=np.zeros((3, 3)))
    with pytest.raises(ValueError, match="parent"):
        ref.robot_hydro([joint((0, 0, 0), (0, 0, 1), parent=0)], links, None, [0.0], [1.0], [0.0])
    with pytest.raises(ValueError, match="kind"):
        ref.robot_hydro([joint((0, 0, 0), (0, 0, 1), kind="ball")], links, None, [0.0], [1.0], [0.0])
    with pytest.raises(ValueError, match="cd"):
        ref.robot_hydro(*args, cd=[1.0, 2.0, 3.0])
    with pytest.raises(ValueError, match="density"):
        ref.robot_hydro(*args, density=0.0)
    with pytest.raises(ValueError, match="velocity"):
        ref.robot_hydro(*args, velocity=(1.0, 2.0))
