"""Hostile robot descriptions grown by hypothesis: every number of a URDF, an MJCF and a hydro
file replaced by hostile text (NaN, infinities, huge, tiny, empty, not a number) or random bytes.
What must hold (as in ``test_adversarial_descriptions.py``): a correct load, or a short
:class:`uwml.DescriptionError` naming the file; never another exception, never a hang.
"""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path
from typing import Any

import pytest

pytest.importorskip("mujoco")

import uwml
from hostile_descriptions import DATA, MAX_MESSAGE, refused, urdf, write
from hypothesis import given, settings
from hypothesis import strategies as st

# --- 5. grown by hypothesis --------------------------------------------------------------------

HOSTILE = ["nan", "-nan", "inf", "-inf", "1e308", "-1e308", "1e400", "-1", "0", "", "abc", "1 2", "1e-320", " ", "0x10", "1,2,3"]

TEMPLATE_URDF = urdf(
    '<link name="base"><inertial><origin xyz="{0}" rpy="{1}"/><mass value="{2}"/><inertia ixx="{3}" iyy="1" izz="1" ixy="{4}" ixz="0" iyz="0"/></inertial>'
    '<collision><origin xyz="{5}" rpy="{6}"/><geometry><box size="{7}"/></geometry></collision></link>',
    '<link name="arm"><inertial><origin xyz="{8}"/><mass value="{9}"/><inertia ixx="0.1" iyy="{10}" izz="0.1" ixy="0" ixz="0" iyz="0"/></inertial>'
    '<collision><origin xyz="{11}" rpy="{12}"/><geometry><cylinder radius="{13}" length="{14}"/></geometry></collision>'
    '<collision><geometry><sphere radius="{15}"/></geometry></collision></link>',
    '<joint name="shoulder" type="revolute"><parent link="base"/><child link="arm"/><origin xyz="{16}" rpy="{17}"/>'
    '<axis xyz="{18}"/><limit lower="{19}" upper="1" effort="10" velocity="1"/></joint>',
)
GOOD_URDF = [
    "0 0 0",
    "0 0 0",
    "2",
    "1",
    "0",
    "0 0 0",
    "0 0 0",
    "0.1 0.2 0.3",
    "0.1 0 0",
    "1",
    "0.1",
    "0.2 0 0",
    "0 0 0",
    "0.05",
    "0.4",
    "0.05",
    "0.5 0 0",
    "0 0 0",
    "0 0 1",
    "-1",
]

TEMPLATE_MJCF = (
    '<mujoco><compiler angle="radian"/><worldbody><body name="base" pos="{0}" euler="{1}"><inertial pos="{2}" mass="{3}" diaginertia="{4}"/>'
    '<geom type="box" size="{5}" pos="{6}"/><body name="arm" pos="{7}" quat="{8}"><joint name="shoulder" axis="{9}" pos="{10}" ref="{11}"/>'
    '<geom type="capsule" fromto="{12}" size="{13}" density="{14}"/><geom type="cylinder" size="{15}" mass="{16}"/></body></body></worldbody></mujoco>'
)
GOOD_MJCF = [
    "0 0 0",
    "0 0 0",
    "0 0 0",
    "2",
    "1 1 1",
    "0.1 0.2 0.3",
    "0 0 0",
    "0.5 0 0",
    "1 0 0 0",
    "0 0 1",
    "0 0 0",
    "0",
    "0 0 0 0.4 0 0",
    "0.05",
    "1000",
    "0.05 0.1",
    "1",
]


def hostile_values(good: list[str]) -> st.SearchStrategy[list[str]]:
    """The good values with one to three replaced by hostile ones (a number in each slot of a
    vector too)."""

    def mutate(draw: Any) -> list[str]:
        values = list(good)
        for _ in range(draw(st.integers(1, 3))):
            slot = draw(st.integers(0, len(values) - 1))
            width = len(values[slot].split()) or 1
            bad = draw(st.sampled_from(HOSTILE))
            if width > 1 and draw(st.booleans()):
                tokens = values[slot].split()
                tokens[draw(st.integers(0, width - 1))] = bad or "0"
                values[slot] = " ".join(tokens)
            else:
                values[slot] = " ".join([bad] * width) if bad.strip() else bad
        return values

    return st.composite(lambda draw: mutate(draw))()


def assert_loads_or_refused_clearly(load: Callable[[], Any], *names: str) -> None:
    try:
        load()
    except uwml.DescriptionError as exc:
        message = str(exc)
        assert len(message) < MAX_MESSAGE and any(name in message for name in names), message[:600]


@settings(max_examples=60, deadline=None)
@given(values=hostile_values(GOOD_URDF))
def test_hostile_urdf_numbers(tmp_path_factory: pytest.TempPathFactory, values: list[str]) -> None:
    path = tmp_path_factory.mktemp("urdf") / "hostile.urdf"
    path.write_text(TEMPLATE_URDF.format(*values))
    assert_loads_or_refused_clearly(lambda: uwml.Robot.from_urdf(path), "hostile.urdf")


@settings(max_examples=60, deadline=None)
@given(values=hostile_values(GOOD_MJCF))
def test_hostile_mjcf_numbers(tmp_path_factory: pytest.TempPathFactory, values: list[str]) -> None:
    path = tmp_path_factory.mktemp("mjcf") / "hostile.xml"
    path.write_text(TEMPLATE_MJCF.format(*values))
    assert_loads_or_refused_clearly(lambda: uwml.Robot.from_mjcf(path), "hostile.xml")


TOML_VALUES = st.one_of(
    st.sampled_from(["1.0", "-1.0", "nan", "inf", "-inf", "0", "1e308", "1e4", "1e9", "true", '"x"', "[]", "[1.0]", "[1.0, 2.0]"]),
    st.sampled_from(["[[1.0, 2.0], [3.0]]", '["a", "b"]', "{ a = 1 }", "[1.0, 2.0, 3.0, 4.0]", "1979-05-27", "[[]]", "[nan, nan]"]),
    st.sampled_from(["[1.0, 2.0, 3.0]", "[1e308, 0.0, 0.0]", "[[1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]", '"rectangular"', '"circular"']),
)
HYDRO_KEYS = ["cd", "cm", "segment_cd", "segment_cm", "volume", "cob", "dry", "segments", "bogus"]
SEGMENT_KEYS = ["section", "start", "axis", "length", "diameter", "area", "normals", "widths"]
A_SEGMENT = (
    '[links.calf]\nvolume = 0.1\n[[links.calf.segments]]\nsection = "circular"\nstart = [0.0, 0.0, 0.0]\naxis = [1.0, 0.0, 0.0]\n'
    "length = 0.1\ndiameter = 0.1\narea = 0.01\ncd = [1.0, 1.0]\ncm = [1.0, 1.0]\n"
)


@settings(max_examples=80, deadline=None)
@given(
    table=st.sampled_from(
        ["links.calf", "links.thigh", "links.hip", "links.body", "joints.knee", "joints.knee.seal", "water", "links", "links.calf.segments"]
    ),
    entries=st.lists(
        st.tuples(st.sampled_from([*HYDRO_KEYS, *SEGMENT_KEYS, "epsilon", "c0", "density", "gravity"]), TOML_VALUES), min_size=1, max_size=5
    ),
    with_segment=st.booleans(),
)
def test_hostile_hydro_values(
    tmp_path_factory: pytest.TempPathFactory, table: str, entries: list[tuple[str, str]], with_segment: bool
) -> None:
    head = "[[links.calf.segments]]" if table == "links.calf.segments" else f"[{table}]"
    before = [A_SEGMENT] if with_segment and table != "links.calf" else []
    lines = [*before, head] + [f"{key} = {value}" for key, value in dict(entries).items()]
    hydro = tmp_path_factory.mktemp("hydro") / "hostile.toml"
    hydro.write_text("\n".join(lines) + "\n")
    assert_loads_or_refused_clearly(lambda: uwml.Robot.from_urdf(DATA / "paper_leg.urdf", hydro), "hostile.toml")


@pytest.mark.parametrize(
    "text, match",
    [
        ("[links.calf]\ncd = 1e308\n", r"h\.toml: \[links\.calf\], key 'cd': .*between 0 and 1000"),
        ("[links.calf]\nvolume = 1e308\n", r"h\.toml: \[links\.calf\], key 'volume': .*0 to 1e\+06"),
        ("[links.calf]\nvolume = 0.1\ncob = [1e308, 0.0, 0.0]\n", r"h\.toml: \[links\.calf\], key 'cob': .*at most 10000 m"),
        (A_SEGMENT.replace("cd = [1.0, 1.0]", "cd = [1e308, 1e308]"), r"link 'calf' \(with .*h\.toml \[links\.calf\]\), segment \d+: .*cd"),
        ("[links.calf.lumped]\npoint = [1e5, 0.0, 0.0]\n", r"h\.toml: \[links\.calf\], lumped, key 'point': .*at most 10000 m"),
    ],
)
def test_hydro_values_beyond_the_model_s_bounds_name_the_hydro_file(tmp_path: Path, text: str, match: str) -> None:
    """The model's checks refuse them after the mapping; the message must still name the hydro
    file (they were 'paper_leg.urdf: segment 1: segment.cd must be at most 1e3')."""
    hydro = write(tmp_path, "h.toml", text)
    refused(lambda: uwml.Robot.from_urdf(DATA / "paper_leg.urdf", hydro), "h.toml", match=match)


@settings(max_examples=40, deadline=None)
@given(data=st.binary(max_size=200))
def test_random_bytes_as_a_hydro_file_or_a_description(tmp_path_factory: pytest.TempPathFactory, data: bytes) -> None:
    folder = tmp_path_factory.mktemp("bytes")
    (folder / "junk.toml").write_bytes(data)
    (folder / "junk.urdf").write_bytes(data)
    assert_loads_or_refused_clearly(lambda: uwml.Robot.from_urdf(DATA / "paper_leg.urdf", folder / "junk.toml"), "junk.toml")
    with pytest.raises(uwml.DescriptionError) as info:
        uwml.Robot.from_urdf(folder / "junk.urdf")
    assert "junk.urdf" in str(info.value) and len(str(info.value)) < MAX_MESSAGE


def test_the_documented_limits_are_the_code_s() -> None:
    """docs/model.md section 10 states the description limits as numbers: they must be the code's."""
    from uwml.io.descriptions import MAX_DESCRIPTION_BODIES, MAX_DESCRIPTION_GEOMS

    docs = " ".join((Path(__file__).resolve().parents[1] / "docs" / "model.md").read_text(encoding="utf-8").split())
    assert MAX_DESCRIPTION_BODIES == 1 + uwml.MAX_ROBOT_JOINTS + uwml.MAX_SEGMENTS
    assert f"`uwml.io.descriptions.MAX_DESCRIPTION_BODIES` bodies ({MAX_DESCRIPTION_BODIES}:" in docs
    assert f"`uwml.io.descriptions.MAX_DESCRIPTION_GEOMS` geoms ({MAX_DESCRIPTION_GEOMS})" in docs
