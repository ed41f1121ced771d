"""Tests of the whole-robot numpy reference ``python/uwml/reference/robot.py`` (MODEL.md section 9).

The package is loaded standalone from its directory (as in ``test_reference.py``), so these tests
need no compiled extension, except the one against ``uwml.Leg.paper()``. No expected value comes
from the code under test:

* against the serial-chain reference ``reference.hydro`` (a different algorithm) and the numbers
  typed from MODEL.md section 5;
* analytic special cases written out by hand (a spinning or translating cylinder, a sliding box,
  Froude-Krylov, buoyancy moments, a base spinning about an offset body);
* a brute force that shares nothing with the reference: body poses by quaternions, slice
  velocities and accelerations by finite differences in time along a trajectory, generalized
  forces as virtual work against complex-step Jacobians of slice positions, and dense composite
  Gauss-Legendre quadrature of the strip forces;
* the invariants of MODEL.md 9.6 on random trees with random states, base motion and current.
"""

import importlib.util
import math
import subprocess
import sys
from pathlib import Path
from types import ModuleType, SimpleNamespace
from typing import Any

import numpy as np
import pytest

NS = SimpleNamespace
RHO, G = 1000.0, 9.81
REFERENCE_DIR = Path(__file__).resolve().parents[1] / "python" / "uwml" / "reference"


def _load_reference() -> ModuleType:
    """The package ``python/uwml/reference/`` on its own, without the compiled extension."""
    name = "uwml_reference_standalone"
    if name in sys.modules:
        return sys.modules[name]
    spec = importlib.util.spec_from_file_location(name, REFERENCE_DIR / "__init__.py", submodule_search_locations=[str(REFERENCE_DIR)])
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    sys.modules[name] = module
    try:
        spec.loader.exec_module(module)
    except BaseException:
        del sys.modules[name]
        raise
    return module


ref = _load_reference()

PARTS = ("drag", "added_mass", "buoyancy", "gravity")
KEYS = PARTS + tuple(f"base_{p}" for p in PARTS)


def assert_close(got: Any, expected: Any, rtol: float, what: str = "", atol: float = 0.0) -> None:
    """``|got − expected| <= rtol · max|expected| + atol`` elementwise (one scale per array)."""
    got, expected = np.asarray(got, dtype=float), np.asarray(expected, dtype=float)
    assert got.shape == expected.shape, f"{what}: shape {got.shape} != {expected.shape}"
    scale = float(np.max(np.abs(expected))) if expected.size else 0.0
    err = float(np.max(np.abs(got - expected))) if expected.size else 0.0
    message = f"{what}: max error {err:.3e} > {rtol:.0e} × scale {scale:.3e} + {atol:.0e}\ngot {got}\nexpected {expected}"
    assert err <= rtol * scale + atol, message


# --------------------------------------------------------------------------------------------
# Descriptions (duck-typed, built here) and random robots
# --------------------------------------------------------------------------------------------


def unit(v: Any) -> np.ndarray:
    v = np.asarray(v, dtype=float)
    return v / np.linalg.norm(v)


def random_unit(rng: np.random.Generator) -> np.ndarray:
    return unit(rng.normal(size=3))


def cylinder(start: Any, axis: Any, length: float, diameter: float, cd: float = 1.2, cm: float = 1.0) -> NS:
    area = math.pi * diameter**2 / 4
    axis = tuple(unit(axis))
    return NS(start=tuple(start), axis=axis, length=length, section="circular", diameter=diameter, area=area, cd=(cd, cd), cm=(cm, cm))


def box(start: Any, axis: Any, length: float, normals: Any, widths: Any, area: float, cd: Any = (2.2, 2.2), cm: Any = (0.5, 0.5)) -> NS:
    return NS(
        start=tuple(start),
        axis=tuple(unit(axis)),
        length=length,
        section="rectangular",
        normals=tuple(map(tuple, normals)),
        widths=tuple(widths),
        area=area,
        cd=tuple(cd),
        cm=tuple(cm),
    )


def body(mass: float = 0.0, com: Any = (0, 0, 0), volume: float = 0.0, cob: Any = None, segments: tuple = ()) -> NS:
    return NS(mass=mass, com=tuple(com), volume=volume, cob=None if cob is None else tuple(cob), segments=tuple(segments))


def joint(origin: Any, axis: Any, parent: int | None = None, kind: str = "revolute") -> NS:
    return NS(origin=tuple(origin), axis=tuple(unit(axis)), parent=parent, kind=kind)


def random_segment(rng: np.random.Generator) -> NS:
    axis = random_unit(rng) if rng.random() < 0.8 else np.eye(3)[rng.integers(3)]
    start = rng.uniform(-0.3, 0.3, 3)
    length = float(rng.uniform(0.1, 0.9))
    if rng.random() < 0.5:
        d = float(rng.uniform(0.02, 0.3))
        return cylinder(start, axis, length, d, cd=float(rng.uniform(0.5, 2.0)), cm=float(rng.uniform(0.5, 1.5)))
    n1 = unit(np.cross(axis, random_unit(rng)))
    n2 = np.cross(axis, n1)
    widths = rng.uniform(0.03, 0.3, 2)
    area = float(widths.prod() * rng.uniform(0.6, 1.0))
    return box(start, axis, length, (n1, n2), widths, area, cd=rng.uniform(0.5, 3.0, 2), cm=rng.uniform(0.2, 1.5, 2))


def random_body(rng: np.random.Generator, segments: int | None = None) -> NS:
    count = int(rng.integers(0, 3)) if segments is None else segments
    mass = float(rng.uniform(0.2, 20.0))
    com = rng.uniform(-0.4, 0.4, 3)
    segments = tuple(random_segment(rng) for _ in range(count))
    return body(mass, com, mass / float(rng.uniform(1000.0, 8000.0)), com + rng.uniform(-0.1, 0.1, 3), segments)


def random_tree(
    rng: np.random.Generator, n: int | None = None, *, base: bool | None = None, prismatic: float = 0.35
) -> tuple[list, list, NS | None]:
    """Random parents (default, the base, or any earlier link), kinds, axes, origins; links with
    0-2 random rectangular or circular segments; a random base body or none."""
    n = int(rng.integers(1, 6)) if n is None else n
    joints, links = [], []
    for i in range(n):
        r = rng.random()
        parent = None if r < 0.4 else (-1 if r < 0.55 else int(rng.integers(-1, i)))
        kind = "prismatic" if rng.random() < prismatic else "revolute"
        axis = random_unit(rng) if rng.random() < 0.8 else np.eye(3)[rng.integers(3)] * rng.choice([-1.0, 1.0])
        origin = np.zeros(3) if rng.random() < 0.15 else rng.uniform(-0.5, 0.5, 3)
        joints.append(joint(origin, axis, parent, kind))
        links.append(random_body(rng, segments=1 if i == n - 1 else None))
    has_base = rng.random() < 0.7 if base is None else base
    return joints, links, (random_body(rng) if has_base else None)


def random_quaternion(rng: np.random.Generator, m: int | None = None) -> np.ndarray:
    shape = (4,) if m is None else (m, 4)
    q = rng.normal(size=shape)
    return q / np.linalg.norm(q, axis=-1, keepdims=True)


def random_motion(rng: np.random.Generator, m: int, n: int) -> dict[str, np.ndarray]:
    """States and base motion and current, one per sample (some exact zeros)."""
    qd = rng.uniform(-2.0, 2.0, (m, n))
    qd[rng.random((m, n)) < 0.15] = 0.0
    return {
        "q": rng.uniform(-math.pi, math.pi, (m, n)),
        "qd": qd,
        "qdd": rng.uniform(-5.0, 5.0, (m, n)),
        "orientation": random_quaternion(rng, m),
        "velocity": rng.uniform(-1.0, 1.0, (m, 3)),
        "angular_velocity": rng.uniform(-1.0, 1.0, (m, 3)),
        "acceleration": rng.uniform(-2.0, 2.0, (m, 3)),
        "angular_acceleration": rng.uniform(-2.0, 2.0, (m, 3)),
        "current": rng.uniform(-0.8, 0.8, (m, 3)),
        "current_acceleration": rng.uniform(-1.0, 1.0, (m, 3)),
    }


def hydro(joints: Any, links: Any, base: Any, motion: dict, **kwargs: Any) -> dict[str, np.ndarray]:
    m = dict(motion)
    return ref.robot_hydro(joints, links, base, m.pop("q"), m.pop("qd"), m.pop("qdd"), **m, **kwargs)


# --------------------------------------------------------------------------------------------
# Rotations written here (quaternions), independent of the reference
# --------------------------------------------------------------------------------------------


def quat_mul(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    w1, x1, y1, z1 = a
    w2, x2, y2, z2 = b
    return np.array(
        [
            w1 * w2 - x1 * x2 - y1 * y2 - z1 * z2,
            w1 * x2 + x1 * w2 + y1 * z2 - z1 * y2,
            w1 * y2 - x1 * z2 + y1 * w2 + z1 * x2,
            w1 * z2 + x1 * y2 - y1 * x2 + z1 * w2,
        ]
    )


def quat_axis_angle(axis: Any, angle: Any) -> np.ndarray:
    """The quaternion ``(cos θ/2, sin θ/2 · axis)``; a complex angle is allowed."""
    axis = np.asarray(axis, dtype=float)
    return np.concatenate([[np.cos(angle / 2)], np.sin(angle / 2) * axis])


def quat_matrix(q: np.ndarray) -> np.ndarray:
    """Rotation matrix of a unit quaternion (w, x, y, z) (complex entries allowed)."""
    w, x, y, z = q
    return np.array(
        [
            [1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
            [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
            [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)],
        ]
    )


def rotation_vector_matrix(phi: np.ndarray) -> np.ndarray:
    """``exp([φ]×)`` for a real rotation vector, via its quaternion."""
    angle = float(np.linalg.norm(phi))
    if angle == 0.0:
        return np.eye(3)
    return quat_matrix(quat_axis_angle(phi / angle, angle))


def skew(v: Any) -> np.ndarray:
    return np.array([[0, -v[2], v[1]], [v[2], 0, -v[0]], [-v[1], v[0], 0]])


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

    leg = uwml.Leg.paper()
    joints, links = leg.joints, leg.links
    q, qd, qdd = _chain_states(np.random.default_rng(5), 64, 3)
    got = ref.robot_hydro(joints, links, None, q, qd, qdd, cd=2.2, cm=0.5)
    expected = ref.hydro(joints, links, q, qd, qdd, cd=2.2, cm=0.5)
    for key in PARTS:
        assert_close(got[key], expected[key], 1e-12, key)
    # MODEL.md section 5, typed from the table.
    one = ref.robot_hydro(joints, links, None, (0.3, -0.4, 0.6), (0.8, 0.5, -0.7), (1.0, -2.0, 0.5), cd=2.2, cm=0.5)
    table = {
        "drag": (-24.24084, -5.060505, -0.7383118),
        "added_mass": (-8.525438, 21.77596, 9.484545),
        "buoyancy": (0.0, 59.72457, 4.193843),
    }
    for key, values in table.items():
        assert one[key].shape == (3,)
        np.testing.assert_allclose(one[key], values, rtol=1e-6, atol=1e-9, err_msg=key)
    # The same leg as the reference's own description (no parent/kind/segments/section attributes).
    ref_joints, ref_links = ref.paper_leg()
    again = ref.robot_hydro(ref_joints, ref_links, None, q, qd, qdd, cd=2.2, cm=0.5)
    for key in KEYS:
        assert_close(again[key], got[key], 1e-14, key)


def _random_chain(rng: np.random.Generator) -> tuple[list, list, np.ndarray]:
    """A serial chain of revolute joints (parents default) with one rectangular segment or none
    per link, as RefJoint/RefLink-like objects (``segment``), and per-link coefficients."""
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
        links.append(NS(mass=mass, com=tuple(com), volume=mass / 3000.0, cob=tuple(com + rng.uniform(-0.1, 0.1, 3)), segment=segment))
    return joints, links, np.array([link.segment is not None for link in links])


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
    # ν̇ convention (MODEL.md 9.2): base origin moving at v = (V, 0, 0) while spinning at Ω
    # with v̇ = 0 accelerates classically at ω × v = (0, Ω V, 0); a cylinder at the origin sees it.
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
# 3. Brute force: quaternion poses, finite differences in time, complex-step Jacobians, dense
#    quadrature
# --------------------------------------------------------------------------------------------


def _poses(joints: list, q: np.ndarray, base_rot: np.ndarray, base_pos: np.ndarray) -> list[tuple[np.ndarray, np.ndarray]]:
    """World (rotation, origin) of every body (base first), by quaternions; complex q allowed."""
    poses = [(base_rot, base_pos)]
    for i, jt in enumerate(joints):
        parent = (i - 1 if jt.parent is None else jt.parent) + 1
        rot, pos = poses[parent]
        point = pos + rot @ np.asarray(jt.origin)
        if jt.kind == "revolute":
            poses.append((rot @ quat_matrix(quat_axis_angle(jt.axis, q[i])), point))
        else:
            poses.append((rot, point + q[i] * (rot @ np.asarray(jt.axis))))
    return poses


def _local_points(bodies: list) -> list[tuple[int, np.ndarray]]:
    """(body, local point) of every segment's two ends, then every body's COB and COM."""
    points = []
    for b, bd in enumerate(bodies):
        for seg in bd.segments:
            start = np.asarray(seg.start, dtype=float)
            points.append((b, start))
            points.append((b, start + seg.length * np.asarray(seg.axis)))
    for b, bd in enumerate(bodies):
        points.append((b, np.asarray(bd.com if bd.cob is None else bd.cob, dtype=float)))
        points.append((b, np.asarray(bd.com, dtype=float)))
    return points


def _world(joints: list, local: list, q: np.ndarray, base_rot: np.ndarray, base_pos: np.ndarray) -> np.ndarray:
    poses = _poses(joints, q, base_rot, base_pos)
    return np.array([poses[b][1] + poses[b][0] @ r for b, r in local])


def brute_force(joints: list, links: list, base: Any, sample: dict, *, with_matrix: bool = False) -> dict[str, np.ndarray]:
    """Everything ``robot_hydro``, ``robot_link_wrenches`` and ``robot_added_mass_matrix`` return,
    for one sample, without screws, cross-product kinematics or closed-form integrals."""
    bodies = [base if base is not None else body()] + list(links)
    local = _local_points(bodies)
    n = len(joints)
    q, qd, qdd = (np.asarray(sample[k], dtype=float) for k in ("q", "qd", "qdd"))
    v, w = np.asarray(sample["velocity"], dtype=float), np.asarray(sample["angular_velocity"], dtype=float)
    vdot, wdot = np.asarray(sample["acceleration"], dtype=float), np.asarray(sample["angular_acceleration"], dtype=float)
    c, cdot = np.asarray(sample["current"], dtype=float), np.asarray(sample["current_acceleration"], dtype=float)
    quaternion = np.asarray(sample["orientation"], dtype=float)
    rot0 = quat_matrix(quaternion / np.linalg.norm(quaternion))

    def at_time(t: float) -> np.ndarray:
        base_rot = rot0 @ rotation_vector_matrix(w * t + 0.5 * wdot * t * t)
        base_pos = rot0 @ (v * t + 0.5 * (vdot + np.cross(w, v)) * t * t)
        return _world(joints, local, q + qd * t + 0.5 * qdd * t * t, base_rot, base_pos)

    h = 2e-3
    p = {k: at_time(k * h) for k in (-2, -1, 0, 1, 2)}
    pos = p[0]
    vel = (-p[2] + 8 * p[1] - 8 * p[-1] + p[-2]) / (12 * h)
    acc = (-p[2] + 16 * p[1] - 30 * p[0] + 16 * p[-1] - p[-2]) / (12 * h * h)

    # Jacobians of the points w.r.t. (base body-frame displacement δx, δθ; q) by complex step.
    step = 1e-30
    jac = np.empty((len(local), 3, 6 + n))
    for k in range(3):
        e = np.eye(3)[k]
        jac[:, :, k] = _world(joints, local, q.astype(complex), rot0.astype(complex), rot0 @ (1j * step * e)).imag / step
        turned = rot0 @ (np.eye(3) + skew(1j * step * e) + skew(1j * step * e) @ skew(1j * step * e) / 2)
        jac[:, :, 3 + k] = _world(joints, local, q.astype(complex), turned, np.zeros(3, dtype=complex)).imag / step
    for j in range(n):
        dq = q.astype(complex)
        dq[j] += 1j * step
        jac[:, :, 6 + j] = _world(joints, local, dq, rot0.astype(complex), np.zeros(3, dtype=complex)).imag / step

    # Dense composite Gauss-Legendre in t = s/L: 1500 panels of 4 nodes.
    x, wx = np.polynomial.legendre.leggauss(4)
    panels = 1500
    edges = np.linspace(0.0, 1.0, panels + 1)
    t = (edges[:-1, None] + (edges[1:] - edges[:-1])[:, None] * (x + 1) / 2).ravel()
    wt = np.tile(wx / 2, panels) / panels

    g_vec = np.array([0.0, 0.0, -G])
    size = 6 + n
    out = {part: np.zeros(size) for part in PARTS}
    wrenches = np.zeros((len(bodies), 6))
    matrix = np.zeros((size, size))
    coms = {}
    index = 0
    poses = _poses(joints, q, rot0, np.zeros(3))
    for b, bd in enumerate(bodies):
        coms[b] = pos[2 * sum(len(x.segments) for x in bodies) + 2 * b + 1]
    for b, bd in enumerate(bodies):
        brot = poses[b][0]
        for seg in bd.segments:
            ia, ib = index, index + 1
            index += 2

            def lerp(a: np.ndarray, ia: int = ia, ib: int = ib) -> np.ndarray:
                return (1 - t)[:, None] * a[ia] + t[:, None] * a[ib]

            ps, vr, ar = lerp(pos), lerp(vel) - c, lerp(acc) - cdot
            js = (1 - t)[:, None, None] * jac[ia] + t[:, None, None] * jac[ib]  # (T, 3, size)
            coef = seg.length * wt
            if seg.section == "circular":
                u = brot @ np.asarray(seg.axis)
                proj = np.eye(3) - np.outer(u, u)
                vp, ap = vr @ proj, ar @ proj
                fd = -0.5 * RHO * seg.cd[0] * seg.diameter * np.linalg.norm(vp, axis=1)[:, None] * vp
                fa = -RHO * seg.cm[0] * seg.area * ap
                inertia = RHO * seg.cm[0] * seg.area * proj
            else:
                normals = [brot @ np.asarray(nk) for nk in seg.normals]
                fd = sum(
                    -0.5 * RHO * seg.cd[k] * seg.widths[k] * ((vr @ nk) * np.abs(vr @ nk))[:, None] * nk for k, nk in enumerate(normals)
                )
                fa = sum(-RHO * seg.cm[k] * seg.area * (ar @ nk)[:, None] * nk for k, nk in enumerate(normals))
                inertia = sum(RHO * seg.cm[k] * seg.area * np.outer(nk, nk) for k, nk in enumerate(normals))
            for part, f in (("drag", fd), ("added_mass", fa)):
                out[part] += np.einsum("t,tcs,tc->s", coef, js, f)
                wrenches[b, :3] += coef @ f
                wrenches[b, 3:] += coef @ np.cross(ps - coms[b], f)
            # Jᵀ C J is quadratic in t: 3-point Gauss-Legendre is exact.
            x3, w3 = np.polynomial.legendre.leggauss(3)
            for node, weight in zip((x3 + 1) / 2, w3 / 2, strict=True):
                jn = (1 - node) * jac[ia] + node * jac[ib]
                matrix += seg.length * weight * jn.T @ inertia @ jn
    for b, bd in enumerate(bodies):
        icob, icom = index + 2 * b, index + 2 * b + 1
        for part, point, force in (("buoyancy", icob, RHO * bd.volume * (cdot - g_vec)), ("gravity", icom, bd.mass * g_vec)):
            out[part] += jac[point].T @ force
            wrenches[b, :3] += force
            wrenches[b, 3:] += np.cross(pos[point] - coms[b], force)
    result = {part: out[part][6:] for part in PARTS} | {f"base_{part}": out[part][:6] for part in PARTS}
    result["wrenches"] = wrenches
    if with_matrix:
        result["matrix"] = matrix
    return result


@pytest.mark.parametrize("seed", range(8))
def test_random_trees_against_the_brute_force(seed):
    rng = np.random.default_rng(200 + seed)
    joints, links, base = random_tree(rng)
    m = 3
    motion = random_motion(rng, m, len(joints))
    got = hydro(joints, links, base, motion)
    wrenches = ref.robot_link_wrenches(joints, links, base, **motion)
    matrix = ref.robot_added_mass_matrix(joints, links, base, motion["q"], orientation=motion["orientation"])
    assert wrenches.shape == (m, len(joints) + 1, 6) and matrix.shape == (m, 6 + len(joints), 6 + len(joints))
    for s in range(m):
        sample = {k: v[s] for k, v in motion.items()}
        expected = brute_force(joints, links, base, sample, with_matrix=True)
        # Finite differences in time (~1e-10) and the kinks inside quadrature panels (~1e-9)
        # limit the drag and added mass; buoyancy, gravity and M_A only see rounding.
        for key in KEYS:
            rtol = 1e-12 if "buoyancy" in key or "gravity" in key else 2e-8
            assert_close(got[key][s], expected[key], rtol, f"sample {s} {key}", atol=1e-12)
        assert_close(wrenches[s], expected["wrenches"], 2e-8, f"sample {s} link wrenches", atol=1e-12)
        assert_close(matrix[s], expected["matrix"], 1e-11, f"sample {s} added-mass matrix", atol=1e-14)


# --------------------------------------------------------------------------------------------
# 4. Invariants (MODEL.md 9.6) on random trees
# --------------------------------------------------------------------------------------------

TREE_SEEDS = range(10)


@pytest.mark.parametrize("seed", TREE_SEEDS)
def test_galilean(seed):
    rng = np.random.default_rng(300 + seed)
    joints, links, base = random_tree(rng)
    m = 8
    motion = random_motion(rng, m, len(joints))
    rot = np.array([quat_matrix(qq) for qq in motion["orientation"]])
    # The base moving with the current (base components of c), joints at rest: no drag.
    riding = motion | {
        "qd": np.zeros_like(motion["qd"]),
        "angular_velocity": np.zeros((m, 3)),
        "velocity": np.einsum("nba,nb->na", rot, motion["current"]),
    }
    out = hydro(joints, links, base, riding)
    assert np.all(np.abs(out["drag"]) < 1e-13) and np.all(np.abs(out["base_drag"]) < 1e-13)
    # A uniform velocity u added to the base and to the current changes nothing (with v̇
    # corrected so that the base's classical acceleration stays the same: d/dt(Rᵀu) = −ω × Rᵀu).
    u = rng.uniform(-1.0, 1.0, (m, 3))
    u_base = np.einsum("nba,nb->na", rot, u)
    shifted = motion | {
        "velocity": motion["velocity"] + u_base,
        "acceleration": motion["acceleration"] - np.cross(motion["angular_velocity"], u_base),
        "current": motion["current"] + u,
    }
    before, after = hydro(joints, links, base, motion), hydro(joints, links, base, shifted)
    for key in KEYS:
        assert_close(after[key], before[key], 1e-12, key, atol=1e-12)


@pytest.mark.parametrize("seed", TREE_SEEDS)
def test_frame_invariance(seed):
    rng = np.random.default_rng(400 + seed)
    joints, links, base = random_tree(rng)
    m = 8
    motion = random_motion(rng, m, len(joints))

    def turned(quaternion: np.ndarray) -> dict:
        rot = quat_matrix(quaternion)
        return motion | {
            "orientation": np.array([quat_mul(quaternion, qq) for qq in motion["orientation"]]),
            "current": motion["current"] @ rot.T,
            "current_acceleration": motion["current_acceleration"] @ rot.T,
        }

    # Any rotation: drag, added mass and Froude-Krylov (gravity off) are unchanged.
    general = turned(random_quaternion(rng))
    before, after = hydro(joints, links, base, motion, gravity=0.0), hydro(joints, links, base, general, gravity=0.0)
    for key in KEYS:
        assert_close(after[key], before[key], 1e-12, key, atol=1e-12)
    # With gravity, the statement holds for rotations about the vertical only.
    vertical = turned(quat_axis_angle((0, 0, 1), rng.uniform(-3, 3)))
    before, after = hydro(joints, links, base, motion), hydro(joints, links, base, vertical)
    for key in KEYS:
        assert_close(after[key], before[key], 1e-12, key, atol=1e-12)
    # ... and not for a tilt, when there is any buoyancy or weight off the base origin.
    tilted = turned(quat_axis_angle((1, 0, 0), 0.5))
    after = hydro(joints, links, base, tilted)
    assert not np.allclose(after["base_gravity"], before["base_gravity"])


def _six_virtual_joints(joints: list, links: list, base: Any) -> tuple[list, list]:
    """The robot with its base replaced by 3 prismatic (base x, y, z) and 3 revolute (about x, y,
    z) joints on a fixed base; the last virtual link carries the base body."""
    virtual = [joint((0, 0, 0), np.eye(3)[k], None, "prismatic") for k in range(3)] + [joint((0, 0, 0), np.eye(3)[k]) for k in range(3)]
    moved = []
    for i, jt in enumerate(joints):
        parent = i - 1 if jt.parent is None else jt.parent
        moved.append(joint(jt.origin, jt.axis, 5 if parent == -1 else parent + 6, jt.kind))
    carriers = [body() for _ in range(5)] + [base if base is not None else body()]
    return virtual + moved, carriers + list(links)


@pytest.mark.parametrize("seed", TREE_SEEDS)
def test_six_virtual_joints_reproduce_the_base_wrench(seed):
    rng = np.random.default_rng(500 + seed)
    joints, links, base = random_tree(rng)
    m = 6
    motion = random_motion(rng, m, len(joints))
    v, w = motion["velocity"], motion["angular_velocity"]
    vdot, wdot = motion["acceleration"], motion["angular_acceleration"]
    big_joints, big_links = _six_virtual_joints(joints, links, base)
    # Velocities: q̇ = (v, ω). Accelerations: the prismatic ones give the base origin's classical
    # acceleration v̇ + ω × v; three revolute joints about x, y, z at zero angle give the angular
    # acceleration q̈ + (q̇y q̇z, −q̇x q̇z, q̇x q̇y).
    coupling = np.stack([w[:, 1] * w[:, 2], -w[:, 0] * w[:, 2], w[:, 0] * w[:, 1]], axis=1)
    big = motion | {
        "q": np.concatenate([np.zeros((m, 6)), motion["q"]], axis=1),
        "qd": np.concatenate([v, w, motion["qd"]], axis=1),
        "qdd": np.concatenate([vdot + np.cross(w, v), wdot - coupling, motion["qdd"]], axis=1),
        "velocity": np.zeros((m, 3)),
        "angular_velocity": np.zeros((m, 3)),
        "acceleration": np.zeros((m, 3)),
        "angular_acceleration": np.zeros((m, 3)),
    }
    original, virtual = hydro(joints, links, base, motion), hydro(big_joints, big_links, None, big)
    for part in PARTS:
        assert_close(virtual[part][:, :6], original[f"base_{part}"], 1e-12, part, atol=1e-12)
        assert_close(virtual[part][:, 6:], original[part], 1e-12, part, atol=1e-12)
        assert np.all(np.abs(virtual[f"base_{part}"] - original[f"base_{part}"]) <= 1e-12 * (1 + np.abs(original[f"base_{part}"]).max()))
    # The added-mass matrix is the virtual robot's joint block (rows and columns alike).
    ma = ref.robot_added_mass_matrix(joints, links, base, motion["q"], orientation=motion["orientation"])
    mb = ref.robot_added_mass_matrix(big_joints, big_links, None, big["q"], orientation=motion["orientation"])
    assert_close(mb[:, 6:, 6:], ma, 1e-12, "M_A")


@pytest.mark.parametrize("seed", TREE_SEEDS)
def test_a_joint_frozen_into_the_base_motion(seed):
    """Joint 0 (the base's only child) moves link 0; the same motion given as the motion of a base
    that is link 0 leaves the other joints' generalized forces unchanged."""
    rng = np.random.default_rng(600 + seed)
    joints, links, _ = random_tree(rng, n=int(rng.integers(2, 6)), base=False)
    # The base's only child is joint 0: the others hang from links.
    for i in range(1, len(joints)):
        if joints[i].parent == -1:
            joints[i] = joint(joints[i].origin, joints[i].axis, int(rng.integers(0, i)), joints[i].kind)
    m = 6
    motion = random_motion(rng, m, len(joints))
    v, w = motion["velocity"], motion["angular_velocity"]
    vdot, wdot = motion["acceleration"], motion["angular_acceleration"]
    a0, r0 = np.asarray(joints[0].axis), np.asarray(joints[0].origin)
    q0, qd0, qdd0 = motion["q"][:, 0, None], motion["qd"][:, 0, None], motion["qdd"][:, 0, None]
    # Link 0's origin and rotation relative to the base, its twist and classical accelerations
    # (base components), written out by hand.
    if joints[0].kind == "revolute":
        r = np.broadcast_to(r0, (m, 3))
        omega = w + qd0 * a0
        vel = v + np.cross(w, r)
        acc = vdot + np.cross(w, v) + np.cross(wdot, r) + np.cross(w, np.cross(w, r))
        alpha = wdot + qdd0 * a0 + np.cross(w, qd0 * a0)
        relative = [quat_axis_angle(a0, angle) for angle in q0[:, 0]]
    else:
        r = r0 + q0 * a0
        omega = w.copy()
        vel = v + np.cross(w, r) + qd0 * a0
        acc = vdot + np.cross(w, v) + np.cross(wdot, r) + np.cross(w, np.cross(w, r)) + 2 * np.cross(w, qd0 * a0) + qdd0 * a0
        alpha = wdot.copy()
        relative = [np.array([1.0, 0, 0, 0])] * m
    rel_rot = np.array([quat_matrix(qq) for qq in relative])
    v_b = np.einsum("nab,na->nb", rel_rot, vel)
    w_b = np.einsum("nab,na->nb", rel_rot, omega)
    frozen = motion | {
        "q": motion["q"][:, 1:],
        "qd": motion["qd"][:, 1:],
        "qdd": motion["qdd"][:, 1:],
        "orientation": np.array([quat_mul(a, b) for a, b in zip(motion["orientation"], relative, strict=True)]),
        "velocity": v_b,
        "angular_velocity": w_b,
        "acceleration": np.einsum("nab,na->nb", rel_rot, acc) - np.cross(w_b, v_b),
        "angular_acceleration": np.einsum("nab,na->nb", rel_rot, alpha),
    }
    rest = []
    for i, jt in enumerate(joints[1:], start=1):
        parent = i - 1 if jt.parent is None else jt.parent
        rest.append(joint(jt.origin, jt.axis, parent - 1, jt.kind))
    whole = hydro(joints, links, None, motion)
    part = hydro(rest, links[1:], links[0], frozen)
    for key in PARTS:
        assert_close(part[key], whole[key][:, 1:], 1e-12, key, atol=1e-12)
    # The whole robot's wrench is the same too, once moved from link 0's origin and frame to
    # the original base's: F_a = R_rel F_b, M_a = R_rel M_b + r × F_a.
    for key in PARTS:
        force = np.einsum("nab,nb->na", rel_rot, part[f"base_{key}"][:, :3])
        moment = np.einsum("nab,nb->na", rel_rot, part[f"base_{key}"][:, 3:]) + np.cross(r, force)
        assert_close(np.concatenate([force, moment], axis=1), whole[f"base_{key}"], 1e-12, f"base_{key}", atol=1e-12)


@pytest.mark.parametrize("seed", TREE_SEEDS)
def test_drag_is_dissipative_and_quadratic_in_still_water(seed):
    rng = np.random.default_rng(700 + seed)
    joints, links, base = random_tree(rng)
    m = 32
    motion = random_motion(rng, m, len(joints)) | {"current": np.zeros((m, 3))}
    out = hydro(joints, links, base, motion)
    twist = np.concatenate([motion["velocity"], motion["angular_velocity"]], axis=1)
    power = np.einsum("nj,nj->n", motion["qd"], out["drag"]) + np.einsum("nk,nk->n", twist, out["base_drag"])
    scale = np.abs(out["drag"]).sum(axis=1) + np.abs(out["base_drag"]).sum(axis=1)
    assert np.all(power <= 1e-13 * (1 + scale)), power.max()
    assert np.any(power < -1e-3)  # not vacuous
    # Homogeneous of degree 2 in all velocities together (the current included).
    lam = -1.7
    scaled = motion | {k: lam * motion[k] for k in ("qd", "velocity", "angular_velocity", "current")}
    again = hydro(joints, links, base, scaled)
    for key in ("drag", "base_drag"):
        assert_close(again[key], lam * abs(lam) * out[key], 1e-12, key)


@pytest.mark.parametrize("seed", TREE_SEEDS)
def test_added_mass_matrix_is_symmetric_psd_and_gives_the_acceleration_part(seed):
    rng = np.random.default_rng(800 + seed)
    joints, links, base = random_tree(rng)
    m, n = 8, len(joints)
    motion = random_motion(rng, m, n)
    ma = ref.robot_added_mass_matrix(joints, links, base, motion["q"], orientation=motion["orientation"])
    assert ma.shape == (m, 6 + n, 6 + n)
    scale = np.abs(ma).max()
    assert np.all(np.abs(ma - np.swapaxes(ma, 1, 2)) <= 1e-13 * scale)
    assert np.all(np.linalg.eigvalsh(0.5 * (ma + np.swapaxes(ma, 1, 2))) >= -1e-12 * scale)
    # Added mass is affine in the accelerations with slope −M_A, at any velocity and current.
    still = motion | {k: np.zeros_like(motion[k]) for k in ("qdd", "acceleration", "angular_acceleration", "current_acceleration")}
    full, rest = hydro(joints, links, base, motion), hydro(joints, links, base, still)
    accel = np.concatenate([motion["acceleration"], motion["angular_acceleration"], motion["qdd"]], axis=1)
    # The current's acceleration enters as −ċ on every slice, as a uniform base acceleration
    # −Rᵀċ would: through the base-linear columns of M_A.
    cdot_only = still | {"current_acceleration": motion["current_acceleration"]}
    cdot_part = hydro(joints, links, base, cdot_only)
    rot = np.array([quat_matrix(qq) for qq in motion["orientation"]])
    cdot_base = np.einsum("nba,nb->na", rot, motion["current_acceleration"])
    expected_cdot = -np.einsum("nrc,nc->nr", ma[:, :, :3], -cdot_base)
    got_cdot = np.concatenate(
        [cdot_part["base_added_mass"] - rest["base_added_mass"], cdot_part["added_mass"] - rest["added_mass"]], axis=1
    )
    assert_close(got_cdot, expected_cdot, 1e-12, "ċ part", atol=1e-12)
    expected = -np.einsum("nrc,nc->nr", ma, accel) + expected_cdot
    got = np.concatenate([full["base_added_mass"] - rest["base_added_mass"], full["added_mass"] - rest["added_mass"]], axis=1)
    assert_close(got, expected, 1e-12, "M_A ν̈", atol=1e-12)
    # One sample without a sample axis gives one matrix.
    assert ref.robot_added_mass_matrix(joints, links, base, motion["q"][0]).shape == (6 + n, 6 + n)


def _segments(links: list, base: Any) -> list:
    return ([] if base is None else list(base.segments)) + [seg for link in links for seg in link.segments]


@pytest.mark.parametrize("seed", TREE_SEEDS)
def test_linear_in_each_coefficient_and_own_coefficients(seed):
    rng = np.random.default_rng(900 + seed)
    joints, links, base = random_tree(rng)
    segments = _segments(links, base)
    count = len(segments)
    m = 4
    motion = random_motion(rng, m, len(joints))
    circular = np.array([seg.section == "circular" for seg in segments])
    own_cd = np.array([seg.cd for seg in segments])
    own_cm = np.array([seg.cm for seg in segments])
    # cd=None is each segment's own pair, in the order base, link 0, link 1, ...
    default, explicit = hydro(joints, links, base, motion), hydro(joints, links, base, motion, cd=own_cd, cm=own_cm)
    for key in KEYS:
        np.testing.assert_array_equal(default[key], explicit[key], err_msg=key)
    # Sum of single-coefficient contributions (circular segments: both directions together).
    for name, part in (("cd", "drag"), ("cm", "added_mass")):
        coefficients = rng.uniform(0.2, 2.0, (count, 2))
        coefficients[circular, 1] = coefficients[circular, 0]
        total = hydro(joints, links, base, motion, **{name: coefficients})
        acc = {key: 0.0 for key in (part, f"base_{part}")}
        for s in range(count):
            for k in range(1 if circular[s] else 2):
                single = np.zeros((count, 2))
                single[s, k] = 1.0
                if circular[s]:
                    single[s, 1] = 1.0
                out = hydro(joints, links, base, motion, **{name: single})
                for key, value in acc.items():
                    acc[key] = value + coefficients[s, k] * out[key]
        for key, value in acc.items():
            assert_close(total[key], value if count else np.zeros_like(total[key]), 1e-12, f"{name} {key}", atol=1e-12)
        # A scalar is every segment and direction; (S,) is per segment.
        scalar = hydro(joints, links, base, motion, **{name: 1.3})
        per_segment = hydro(joints, links, base, motion, **{name: np.full(count, 1.3)})
        for key in acc:
            np.testing.assert_array_equal(scalar[key], per_segment[key])


def _as_model(model: ModuleType, joints: list, links: list, base: Any) -> tuple[list, list, Any]:
    """The same robot as :mod:`uwml.model` objects (circular segments get their own normals)."""

    def segment(sg: NS) -> Any:
        if sg.section == "circular":
            return model.Segment(
                start=sg.start, axis=sg.axis, length=sg.length, section="circular", diameter=sg.diameter, cd=sg.cd[0], cm=sg.cm[0]
            )
        return model.Segment(
            start=sg.start, axis=sg.axis, length=sg.length, normals=sg.normals, widths=sg.widths, area=sg.area, cd=sg.cd, cm=sg.cm
        )

    def link(bd: NS) -> Any:
        return model.Link(mass=bd.mass, com=bd.com, volume=bd.volume, cob=bd.cob, segments=tuple(segment(sg) for sg in bd.segments))

    model_joints = [model.Joint(origin=jt.origin, axis=jt.axis, parent=jt.parent, kind=jt.kind) for jt in joints]
    return model_joints, [link(bd) for bd in links], None if base is None else link(base)


@pytest.mark.parametrize("seed", range(3))
def test_uwml_model_descriptions_fit(seed):
    from pure import load

    model = load("model")
    rng = np.random.default_rng(1000 + seed)
    joints, links, base = random_tree(rng, base=True)
    motion = random_motion(rng, 4, len(joints))
    expected = hydro(joints, links, base, motion)
    got = hydro(*_as_model(model, joints, links, base), motion)
    for key in KEYS:
        assert_close(got[key], expected[key], 1e-13, key, atol=1e-13)


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
