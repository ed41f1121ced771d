"""Shared by the tests of whole robots (``test_robot.py`` and the tests of one idea that use
random trees): random trees on a base body, random base motions, and the comparison of a
batch against expected values, one scale per sample."""

import numpy as np
import uwml

#: Tolerance of the core against the reference, relative to the largest entry of a sample.
RTOL_REFERENCE = 1e-10
COMPONENTS = ("drag", "added_mass", "buoyancy", "gravity")


def random_robot(rng: np.random.Generator, n: int, *, base_body: bool = True, axes: str = "any", axial: bool = False) -> uwml.Robot:
    """A random tree of ``n`` joints: random parents, kinds, axes; every body with one or two
    segments, rectangular or circular, with their own coefficients. ``axes="mixed"``: each joint
    axis along a coordinate axis (either sign) half of the time, so that parents and children
    share axes or meet at right angles, as in most real robots. ``axial``: about half the segments
    with an axial drag (docs/model.md section 12.2), half of those with their own area."""

    def unit() -> np.ndarray:
        v = rng.normal(size=3)
        return v / np.linalg.norm(v)

    def joint_axis() -> np.ndarray:
        if axes == "mixed" and rng.random() < 0.5:
            return np.eye(3)[rng.integers(0, 3)] * rng.choice([-1.0, 1.0])
        return unit()

    def segments() -> list[uwml.Segment]:
        out = []
        for _ in range(rng.integers(0, 3)):
            axis = unit()
            n0 = np.cross(axis, unit())
            n0 /= np.linalg.norm(n0)
            start, length = rng.uniform(-0.2, 0.2, 3), rng.uniform(0.1, 1.0)
            if rng.random() < 0.5:
                out.append(
                    uwml.Segment(
                        start,
                        axis,
                        length,
                        section="circular",
                        diameter=rng.uniform(0.03, 0.2),
                        cd=rng.uniform(0.5, 2),
                        cm=rng.uniform(0.2, 1.5),
                        cd_axial=rng.uniform(0.1, 1.0) if axial and rng.random() < 0.5 else 0.0,
                    )
                )
            else:
                out.append(
                    uwml.Segment(
                        start,
                        axis,
                        length,
                        normals=(n0, np.cross(axis, n0)),
                        widths=rng.uniform(0.03, 0.3, 2),
                        area=rng.uniform(0.005, 0.05),
                        cd=tuple(rng.uniform(0.5, 2.5, 2)),
                        cm=tuple(rng.uniform(0.1, 1.5, 2)),
                        cd_axial=rng.uniform(0.1, 1.0) if axial and rng.random() < 0.5 else 0.0,
                        axial_area=rng.uniform(0.001, 0.05) if rng.random() < 0.5 else None,
                    )
                )
        return out

    def body() -> uwml.Link:
        return uwml.Link(
            rng.uniform(1, 20), rng.uniform(-0.4, 0.4, 3), rng.uniform(0.0005, 0.02), cob=rng.uniform(-0.4, 0.4, 3), segments=segments()
        )

    joints = [
        uwml.Joint(
            rng.uniform(-0.5, 0.5, 3),
            joint_axis(),
            parent=int(rng.integers(-1, i)) if i else -1,
            kind="prismatic" if rng.random() < 0.3 else "revolute",
        )
        for i in range(n)
    ]
    links = [body() for _ in range(n)]
    return uwml.Robot(joints, links, base=body() if base_body else None)


def random_quaternions(rng: np.random.Generator, n: int) -> np.ndarray:
    q = rng.normal(size=(n, 4))
    return q / np.linalg.norm(q, axis=1, keepdims=True)


def motion_arguments(rng: np.random.Generator, n: int) -> dict[str, np.ndarray]:
    return {
        "orientation": random_quaternions(rng, n),
        "velocity": rng.normal(size=(n, 3)),
        "angular_velocity": rng.normal(size=(n, 3)),
        "acceleration": rng.normal(size=(n, 3)),
        "angular_acceleration": rng.normal(size=(n, 3)),
    }


def assert_close(actual: np.ndarray, expected: np.ndarray, scale: np.ndarray, rtol: float, what: str) -> None:
    error = np.max(np.abs(actual - expected).reshape(len(scale), -1), axis=1) / scale
    worst = int(np.argmax(error))
    assert error[worst] <= rtol, f"{what}: sample {worst} off by {error[worst]:.3g} relative\n{actual[worst]}\n{expected[worst]}"
