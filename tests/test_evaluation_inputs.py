"""How an evaluation reads its inputs, on serial chains (the paper's leg and random ones): one
state and a batch give the same numbers (a state alone is its batch row, bit for bit), every
memory layout, container and dtype of the same values gives the same numbers, float32 states
are converted exactly, an empty batch, concurrent calls, normals within the tolerance made an
exact frame, huge joint angles kept accurate. ``chains.py`` says how a relative error is
measured.
"""

import threading

import numpy as np
import pytest
import uwml
from chains import (
    PAPER,
    RTOL_REFERENCE,
    assert_batch_close,
    drawn,
    natural_scales,
    random_chain,
    random_states,
    random_unit,
    seeds,
    segment_coefficients,
)
from hypothesis import given, settings
from uwml import reference as ref

KEYS = ("drag", "added_mass", "buoyancy", "gravity")


@pytest.mark.parametrize("kind", ["paper", "chain"])
@settings(max_examples=max(5, settings.default.max_examples // 20))
@given(seed=seeds)
def test_single_samples_and_batches_agree(kind: str, seed: int) -> None:
    m = 12
    rng, leg, _, links, (q, qd, qdd) = drawn(kind, seed, m)
    n, segments = leg.n_joints, len(leg.segments)
    cd, cm = segment_coefficients(rng, links)
    batch = leg.hydro(q, qd, qdd, cd=cd, cm=cm)
    regressors = leg.hydro_regressors(q, qd, qdd)
    for key in KEYS:
        assert getattr(batch, key).shape == (m, n)
        assert getattr(batch, key).dtype == np.float64
    assert batch.total.shape == (m, n)
    assert regressors.drag.shape == regressors.added_mass.shape == (m, n, segments, 2)
    assert regressors.buoyancy.shape == (m, n)
    for s in range(m):
        one = leg.hydro(q[s], qd[s], qdd[s], cd=cd, cm=cm)
        one_regressors = leg.hydro_regressors(q[s], qd[s], qdd[s])
        for key in KEYS:
            assert getattr(one, key).shape == (n,)
            np.testing.assert_array_equal(getattr(one, key), getattr(batch, key)[s], err_msg=f"sample {s} {key}")
        assert one.total.shape == (n,)
        assert one_regressors.drag.shape == one_regressors.added_mass.shape == (n, segments, 2)
        assert one_regressors.buoyancy.shape == (n,)
        np.testing.assert_array_equal(one_regressors.drag, regressors.drag[s], err_msg=f"sample {s} drag regressor")
        np.testing.assert_array_equal(one_regressors.added_mass, regressors.added_mass[s], err_msg=f"sample {s} added-mass regressor")
        # torques() keeps the single-sample layout.
        assert one_regressors.torques(cd, cm).drag.shape == (n,)


def _layouts(q: np.ndarray) -> dict[str, object]:
    """The same float64 values in other memory layouts and containers."""
    m, n = q.shape
    wide = np.zeros((m, 2 * n))
    wide[:, ::2] = q
    tall = np.zeros((3 * m, n))
    tall[::3] = q
    read_only = q.copy()
    read_only.flags.writeable = False
    return {
        "fortran": np.asfortranarray(q),
        "strided columns": wide[:, ::2],
        "strided rows": tall[::3],
        "transposed view": np.ascontiguousarray(q.T).T,
        "big-endian": q.astype(">f8"),
        "read-only": read_only,
        "nested lists": q.tolist(),
    }


@pytest.mark.parametrize("kind", ["paper", "chain"])
@settings(max_examples=max(5, settings.default.max_examples // 10))
@given(seed=seeds)
def test_memory_layouts_give_the_same_numbers(kind: str, seed: int) -> None:
    _, leg, _, _, (q, qd, qdd) = drawn(kind, seed, 40)
    expected = leg.hydro(q, qd, qdd)
    expected_reg = leg.hydro_regressors(q, qd, qdd)
    layouts = [_layouts(x) for x in (q, qd, qdd)]
    for name in layouts[0]:
        args = [layout[name] for layout in layouts]
        before = [np.array(a, copy=True) for a in args]
        out = leg.hydro(*args)
        reg = leg.hydro_regressors(*args)
        for key in KEYS:
            np.testing.assert_array_equal(getattr(out, key), getattr(expected, key), err_msg=f"{name} {key}")
        np.testing.assert_array_equal(reg.drag, expected_reg.drag, err_msg=f"{name} drag regressor")
        np.testing.assert_array_equal(reg.added_mass, expected_reg.added_mass, err_msg=f"{name} added-mass regressor")
        for a, b in zip(args, before):
            np.testing.assert_array_equal(np.asarray(a), b, err_msg=f"{name}: input modified")
    # Mixed layouts in one call.
    out = leg.hydro(layouts[0]["fortran"], layouts[1]["strided rows"], layouts[2]["nested lists"])
    for key in KEYS:
        np.testing.assert_array_equal(getattr(out, key), getattr(expected, key), err_msg=f"mixed {key}")


@pytest.mark.parametrize("dtype", [np.int8, np.int32, np.int64, np.uint16, np.float16, np.float32, np.longdouble])
def test_other_dtypes_are_converted_to_float64(dtype: type) -> None:
    """Integer and other float inputs give the numbers of the same values in float64."""
    rng = np.random.default_rng(3)
    for leg in (PAPER, random_chain(rng, 5)[0]):
        n = leg.n_joints
        q, qd, qdd = (rng.uniform(-3.0, 3.0, (50, n)) for _ in range(3))
        if np.issubdtype(dtype, np.unsignedinteger):
            q, qd, qdd = np.abs(q), np.abs(qd), np.abs(qdd)
        args = [x.astype(dtype) for x in (q, qd, qdd)]
        as_float64 = [a.astype(np.float64) for a in args]
        out, expected = leg.hydro(*args), leg.hydro(*as_float64)
        reg, expected_reg = leg.hydro_regressors(*args), leg.hydro_regressors(*as_float64)
        for key in KEYS:
            assert getattr(out, key).dtype == np.float64
            np.testing.assert_array_equal(getattr(out, key), getattr(expected, key), err_msg=f"{dtype.__name__} {key}")
        np.testing.assert_array_equal(reg.drag, expected_reg.drag)
        np.testing.assert_array_equal(reg.added_mass, expected_reg.added_mass)
        # One dtype mixed with float64 contiguous arrays.
        mixed = leg.hydro(args[0], as_float64[1], as_float64[2])
        np.testing.assert_array_equal(mixed.drag, expected.drag)


def test_float32_inputs_match_float64_closely() -> None:
    """Float32 states are converted exactly: their results are the float64 results of the same
    values, and differ from the unrounded float64 states only as much as the rounding of q, q̇, q̈."""
    rng = np.random.default_rng(4)
    q, qd, qdd = random_states(rng, 500, 3)
    out32 = PAPER.hydro(q.astype(np.float32), qd.astype(np.float32), qdd.astype(np.float32))
    out64 = PAPER.hydro(q, qd, qdd)
    for key in KEYS:
        assert getattr(out32, key).dtype == np.float64
        assert_batch_close(getattr(out32, key), getattr(out64, key), 1e-5, f"float32 {key}")
    expected = ref.hydro(PAPER.joints, PAPER.links, q.astype(np.float32), qd.astype(np.float32), qdd.astype(np.float32))
    for key in KEYS:
        assert_batch_close(getattr(out32, key), expected[key], RTOL_REFERENCE, f"float32 {key} vs reference")


def test_empty_batch() -> None:
    out = PAPER.hydro(np.zeros((0, 3)), np.zeros((0, 3)), np.zeros((0, 3)))
    for key in KEYS:
        assert getattr(out, key).shape == (0, 3)
    reg = PAPER.hydro_regressors(np.zeros((0, 3)), np.zeros((0, 3)), np.zeros((0, 3)))
    assert reg.drag.shape == (0, 3, 2, 2) and reg.buoyancy.shape == (0, 3)


def test_concurrent_calls_agree() -> None:
    """The batch loop runs without the GIL: calls from several threads give the serial results."""
    rng = np.random.default_rng(8)
    leg = random_chain(rng, 6)[0]
    batches = [random_states(rng, 5000, 6) for _ in range(4)]
    expected = [leg.hydro(*b).total for b in batches]
    results: list = [None] * len(batches)

    def work(i: int) -> None:
        for _ in range(3):
            results[i] = leg.hydro(*batches[i]).total

    threads = [threading.Thread(target=work, args=(i,)) for i in range(len(batches))]
    for thread in threads:
        thread.start()
    for thread in threads:
        thread.join()
    for got, want in zip(results, expected):
        np.testing.assert_array_equal(got, want)


def test_normals_within_the_tolerance_become_an_exact_frame() -> None:
    """Normals accepted within AXIS_TOLERANCE (1e-6) of an orthonormal frame are made an exact
    one on input (Gram-Schmidt; the second normal on the side it was given), in Python and in
    the core: the strip integrals' identities assume an exact frame. A two-link chain whose
    second segment's normals are tilted by 5e-7 (the first towards the axis, the second towards
    the first) evaluates as the reference does with the exact frame the tilt came from (they differed by 3e-7 in drag and 1.2e-6 in added
    mass when the normals were only renormalized)."""
    rng = np.random.default_rng(5)
    axis = random_unit(rng)
    n1 = np.cross(axis, random_unit(rng))
    n1 /= np.linalg.norm(n1)
    n2 = np.cross(axis, n1)
    tilted1, tilted2 = n1 + 5e-7 * axis, n2 + 5e-7 * n1
    tilted1, tilted2 = tilted1 / np.linalg.norm(tilted1), tilted2 / np.linalg.norm(tilted2)

    def chain(normals: tuple) -> tuple[list, list]:
        segment = uwml.Segment(start=(0.05, 0.0, 0.0), axis=tuple(axis), length=0.6, normals=normals, widths=(0.2, 0.05), area=0.01)
        joints = [uwml.Joint(origin=(0.0, 0.0, 0.0), axis=(0.0, 0.0, 1.0)), uwml.Joint(origin=(0.4, 0.0, 0.0), axis=(0.0, 1.0, 0.0))]
        first = uwml.Segment(
            start=(0.0, 0.0, 0.0), axis=(1.0, 0.0, 0.0), length=0.4, normals=((0, 1, 0), (0, 0, 1)), widths=(0.1, 0.1), area=0.008
        )
        links = [uwml.Link(2.0, (0.2, 0, 0), 1e-3, segments=(first,)), uwml.Link(3.0, (0.3, 0, 0), 2e-3, segments=(segment,))]
        return joints, links

    joints, links = chain((tuple(tilted1), tuple(tilted2)))
    stored = links[1].segments[0].normals
    for a, b in ((stored[0], axis), (stored[1], axis), (stored[0], stored[1])):
        assert abs(float(np.dot(a, b))) < 1e-15
    assert max(abs(float(np.linalg.norm(n)) - 1.0) for n in stored) < 1e-15
    np.testing.assert_allclose(stored, [n1, n2], atol=1e-15)
    exact_joints, exact_links = chain((tuple(n1), tuple(n2)))
    q, qd, qdd = random_states(rng, 500, 2)
    expected = ref.hydro(exact_joints, exact_links, q, qd, qdd)
    natural = natural_scales(exact_joints, exact_links, qd, qdd, cd=2.2, cm=0.5)
    out = uwml.Robot(joints, links).hydro(q, qd, qdd)
    for key in ("drag", "added_mass", "buoyancy"):
        assert_batch_close(getattr(out, key), expected[key], 1e-12, key, natural[key])


@pytest.mark.filterwarnings("ignore::uwml.PlausibilityWarning")  # values beyond plausible on purpose
@pytest.mark.parametrize("size", [1e5, 1e8, 1e10, 1e15, 1e300])
def test_huge_joint_angles_keep_their_accuracy(size: float) -> None:
    """The batch path's SIMD sine and cosine reduce their argument in double precision only
    (exact to about 1e8 rad, 4e-7 relative off at 1e10 and 0.02 at 1e15); angles beyond 1e6 rad
    are reduced exactly first. So at any finite angle the batch, the one-state path, the scalar
    jacobians and the reference agree to rounding (the jacobians' docstring: 1e-13)."""
    leg = uwml.paper_leg()
    q = np.array([[size, -0.3 * size + 0.1, size / 7.0], [0.2, size, -size]])
    qd, qdd = np.full_like(q, 0.5), np.full_like(q, -0.8)
    out = leg.hydro(q, qd, qdd)
    expected = ref.hydro(leg.joints, leg.links, q, qd, qdd)
    for key in ("drag", "added_mass", "buoyancy", "gravity"):
        scale = float(np.max(np.abs(expected[key])))
        np.testing.assert_allclose(getattr(out, key), expected[key], rtol=0, atol=1e-13 * scale, err_msg=key)
    one = leg.hydro(q[0], qd[0], qdd[0])
    np.testing.assert_array_equal(one.total, out.total[0])
    environment = leg.environment(q, qd, qdd).total
    value = leg.jacobians(q, qd, qdd).value[:, 6:]
    np.testing.assert_allclose(value, environment, rtol=0, atol=1e-13 * float(np.max(np.abs(environment))))
