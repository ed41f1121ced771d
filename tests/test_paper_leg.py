"""The paper's leg as a preset of the robot (``uwml.paper_leg``, from the core's
``presets::paper_leg``): Table II as docs/model.md section 2 types it, the same numbers when
rebuilt from its parts, the walking gait's and the numpy reference's lengths its own. Its
forces against the reference and the paper's equations are ``test_chain_reference.py``'s.
"""

import numpy as np
import pytest
import uwml

RHO_M = 2700.0
PAPER = uwml.paper_leg()


def test_paper_leg_is_table_ii() -> None:
    """Typed from docs/model.md section 2."""
    leg = uwml.paper_leg()
    assert leg.n_joints == 3 and len(leg.joints) == len(leg.links) == 3
    assert repr(leg) == "Robot(n_joints=3, n_segments=2, base=None)" and isinstance(leg, uwml.Robot)
    assert all(isinstance(j, uwml.Joint) for j in leg.joints) and all(isinstance(link, uwml.Link) for link in leg.links)
    hip_yaw, hip_roll, knee = leg.joints
    assert hip_yaw.axis == (0.0, 0.0, 1.0) and hip_yaw.origin == (0.0, 0.0, 0.0)
    assert hip_roll.axis == (0.0, -1.0, 0.0) and hip_roll.origin == (0.0, 0.0, 0.0)  # L1 = 0, about −e_t
    assert knee.axis == (0.0, -1.0, 0.0) and knee.origin == pytest.approx((0.660, 0.0, 0.0), abs=1e-15)
    base, thigh, calf = leg.links
    assert [link.mass for link in leg.links] == pytest.approx([10.758, 19.261, 10.375], rel=1e-15)
    assert [link.volume for link in leg.links] == pytest.approx([10.758 / RHO_M, 19.261 / RHO_M, 10.375 / RHO_M], rel=1e-14)
    assert base.segments == () and base.com == (0.0, 0.0, 0.0) and leg.base is None
    assert thigh.com == pytest.approx((0.506, 0.0, 0.0), abs=1e-15) and thigh.cob == thigh.com
    assert calf.com == pytest.approx((0.0, 0.0, -0.560), abs=1e-15) and calf.cob == calf.com
    for link, length, axis, widths, in_plane in (
        (thigh, 0.660, (1.0, 0.0, 0.0), (0.131, 0.238), (0.0, 0.0, 1.0)),
        (calf, 0.714, (0.0, 0.0, -1.0), (0.131, 0.279), (1.0, 0.0, 0.0)),
    ):
        (s,) = link.segments
        assert s.cd == (2.2, 2.2) and s.cm == (0.5, 0.5)  # the paper's fit, rounded
        assert s.start == (0.0, 0.0, 0.0) and s.axis == axis
        assert s.length == pytest.approx(length, rel=1e-15)
        assert s.widths == pytest.approx(widths, rel=1e-15)
        assert s.area == pytest.approx(widths[0] * widths[1], rel=1e-14)
        # Column 0 is out of the leg plane (±y, width D_i1), column 1 in the plane (width D_i2).
        assert np.abs(s.normals[0]) == pytest.approx((0.0, 1.0, 0.0), abs=1e-15)
        assert np.abs(s.normals[1]) == pytest.approx(in_plane, abs=1e-15)


def test_paper_leg_round_trip_gives_identical_torques() -> None:
    rebuilt = uwml.Robot(PAPER.joints, PAPER.links)
    assert rebuilt.joints == PAPER.joints and rebuilt.links == PAPER.links and rebuilt == PAPER
    rng = np.random.default_rng(1)
    q, qd, qdd = rng.uniform(-3.0, 3.0, (3, 500, 3))
    for cd, cm in ((2.2, 0.5), (rng.uniform(1, 3, 2), rng.uniform(0, 1, 2)), (rng.uniform(1, 3, (2, 2)), rng.uniform(0, 1, (2, 2)))):
        a, b = PAPER.hydro(q, qd, qdd, cd=cd, cm=cm), rebuilt.hydro(q, qd, qdd, cd=cd, cm=cm)
        for key in ("drag", "added_mass", "buoyancy", "gravity", "total"):
            np.testing.assert_array_equal(getattr(a, key), getattr(b, key), err_msg=key)
    a, b = PAPER.hydro_regressors(q, qd, qdd), rebuilt.hydro_regressors(q, qd, qdd)
    np.testing.assert_array_equal(a.drag, b.drag)
    np.testing.assert_array_equal(a.added_mass, b.added_mass)


def test_the_gaits_leg_lengths_are_the_papers() -> None:
    """The walking gait's own copy of Table II's lengths equals the core's paper leg and the numpy
    reference's."""
    from uwml import reference
    from uwml.paper import gait

    leg = uwml.paper_leg()
    assert (gait.PAPER_L2, gait.PAPER_L3) == (reference.PAPER_L2, reference.PAPER_L3)
    assert leg.joints[2].origin == (gait.PAPER_L2, 0.0, 0.0)
    assert leg.links[2].segments[0].length == gait.PAPER_L3
