"""Tests of the whole-robot numpy reference (docs/model.md section 10), continued from
``test_reference_robot.py``: a brute force that shares nothing with the reference (body poses by
quaternions, slice velocities and accelerations by finite differences in time, generalized
forces as virtual work against complex-step Jacobians, dense quadrature of the strip forces), and
the invariants of docs/model.md section 10, "Invariants" on random trees with random states, base motion and current."""

from types import ModuleType
from typing import Any

import numpy as np
import pytest
from reference_trees import (
    KEYS,
    NS,
    PARTS,
    RHO,
    G,
    assert_close,
    body,
    hydro,
    joint,
    quat_axis_angle,
    quat_matrix,
    quat_mul,
    random_motion,
    random_quaternion,
    random_tree,
    ref,
    rotation_vector_matrix,
    skew,
)

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
# 4. Invariants (docs/model.md section 10, "Invariants") on random trees
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
