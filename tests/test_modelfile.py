"""The uwml model file (``uwml.io.modelfile``): a saved robot loads equal to itself and gives the same
forces bit for bit; every bad file is an error naming the file, the table and the key."""

import os
from pathlib import Path

import numpy as np
import pytest
import uwml
from hypothesis import given, settings
from hypothesis import strategies as st
from test_robot import motion_arguments, random_robot
from uwml.examples import arm_on_rov
from uwml.io.modelfile import dumps
from uwml.robot.files import loads


def same_forces(a: uwml.Robot, b: uwml.Robot, rng: np.random.Generator) -> None:
    n = a.n_joints
    q, qd, qdd = rng.uniform(-2, 2, (3, 8, n))
    motion = uwml.BaseMotion(**motion_arguments(rng, 8))
    ra = a.hydro(q, qd, qdd, base_motion=motion, current=(0.2, 0.1, 0.0))
    rb = b.hydro(q, qd, qdd, base_motion=motion, current=(0.2, 0.1, 0.0))
    np.testing.assert_array_equal(ra.total, rb.total)
    np.testing.assert_array_equal(ra.base.total, rb.base.total)
    np.testing.assert_array_equal(ra.gravity, rb.gravity)


def test_the_paper_leg_saved_and_loaded_is_itself(tmp_path: Path) -> None:
    leg = uwml.paper_leg()
    path = tmp_path / "paper.toml"
    leg.save(path)
    robot = uwml.Robot.load(path)
    assert robot == leg
    np.testing.assert_array_equal(
        robot.hydro([0.3, -0.4, 0.6], [0.8, 0.5, -0.7], [1.0, -2.0, 0.5]).total,
        leg.hydro([0.3, -0.4, 0.6], [0.8, 0.5, -0.7], [1.0, -2.0, 0.5]).total,
    )
    text = path.read_text()
    assert text.startswith("# uwml model file") and 'format = "uwml-robot"' in text and "mass = 19.261" in text


def test_the_arm_on_an_rov_round_trips_with_names(tmp_path: Path) -> None:
    arm = arm_on_rov()
    named = uwml.Robot(
        [uwml.Joint(j.origin, j.axis, parent=j.parent, kind=j.kind, name=f'j{i} "quoted"') for i, j in enumerate(arm.joints)],
        [
            uwml.Link(link.mass, link.com, link.volume, cob=link.cob, segments=link.segments, name=f"link-{i}")
            for i, link in enumerate(arm.links)
        ],
        base=arm.base,
    )
    path = tmp_path / "arm.toml"
    named.save(path)
    loaded = uwml.Robot.load(path)
    assert loaded == named and loaded != arm
    assert loaded.joint_names[3] == 'j3 "quoted"' and loaded.link_names[6] == "link-6" and arm.joint_names[0] == "joint0"
    same_forces(loaded, named, np.random.default_rng(1))


@settings(max_examples=max(5, int(settings.default.max_examples / 4)))
@given(seed=st.integers(0, 2**32 - 1), n=st.integers(1, 8))
def test_random_robots_round_trip_exactly(seed: int, n: int) -> None:
    rng = np.random.default_rng(seed)
    robot = random_robot(rng, n, base_body=bool(rng.random() < 0.7))
    robot = uwml.Robot(robot.joints, robot.links, base=robot.base, water=uwml.Water(rng.uniform(990.0, 1050.0), rng.uniform(9.7, 9.9)))
    again = loads(dumps(robot))
    assert again == robot
    assert dumps(again) == dumps(robot)
    same_forces(again, robot, rng)


@pytest.mark.parametrize(
    ("edit", "message"),
    [
        (lambda t: t.replace('format = "uwml-robot"', 'format = "urdf"'), r"top level, key 'format': must be \"uwml-robot\""),
        (lambda t: t.replace("version = 1", "version = 2"), r"key 'version': must be 1"),
        (lambda t: t.replace("mass = 19.261", "mass = -19.261"), r"links\[1\]: link.mass must be non-negative"),
        (lambda t: t.replace("mass = 19.261", 'mass = "heavy"'), r"links\[1\], key 'mass': must be a mass \[kg\], got 'heavy'"),
        (lambda t: t.replace("mass = 19.261\n", ""), r"links\[1\], key 'mass': is missing"),
        (lambda t: t.replace("mass = 19.261", "mass = 19.261\nmas = 1.0"), r"links\[1\], key 'mas': is not a key of this table"),
        (lambda t: t.replace('kind = "revolute"', 'kind = "ball"', 1), r"joints\[0\]: joint.kind must be one of"),
        (lambda t: t.replace("parent = 1", "parent = 2"), r"top level: joints\[2\].parent must be -1 \(the base\) or an earlier link"),
        (lambda t: t.replace("length = 0.66", "length = [0.66]"), r"links\[1\], segments\[0\], key 'length': must be a length"),
        (lambda t: t.replace("widths = [0.131, 0.238]", "widths = [0.131]"), r"segments\[0\], key 'widths'"),
        (lambda t: t + "[[oops", "not valid TOML"),
        (
            lambda t: t.replace("density = 1000.0", "density = -1000.0"),
            r"water, key 'density': must be a density \[kg/m³\], 900 to 1300, got -1000.0",
        ),
        (
            lambda t: t.replace("density = 1000.0", "density = 1000.0\nsalinity = 35.0"),
            r"water, key 'salinity': is not a key of this table",
        ),
    ],
)
def test_bad_files_name_the_file_table_and_key(tmp_path: Path, edit, message: str) -> None:
    path = tmp_path / "leg.toml"
    text = dumps(uwml.paper_leg())
    path.write_text(edit(text))
    assert edit(text) != text
    with pytest.raises(uwml.ModelFileError, match=f"{path.name}.*{message}"):
        uwml.Robot.load(path)


def test_a_file_without_water_is_in_fresh_water() -> None:
    text = dumps(uwml.paper_leg())
    assert "[water]\ndensity = 1000.0\ngravity = 9.81\n" in text
    assert loads(text.replace("[water]\ndensity = 1000.0\ngravity = 9.81\n", "")).water == uwml.Water(1000.0, 9.81)


def test_a_missing_file(tmp_path: Path) -> None:
    with pytest.raises(uwml.ModelFileError, match="nowhere.toml: the model file cannot be read: no such file"):
        uwml.Robot.load(tmp_path / "nowhere.toml")


def test_joint_losses_are_part_of_the_model(tmp_path: Path) -> None:
    leg = uwml.paper_leg()
    losses = [None, uwml.JointLosses(epsilon=0.02), uwml.JointLosses(seal=None, drive=uwml.Drive(ratio=120.0))]
    robot = uwml.Robot(leg.joints, leg.links, losses=losses)
    path = tmp_path / "leg.toml"
    robot.save(path)
    text = path.read_text()
    assert "[joints.losses.seal]" in text and "ratio = 120.0" in text
    loaded = uwml.Robot.load(path)
    assert loaded == robot and loaded.losses == tuple(losses) and loaded != uwml.Robot(leg.joints, leg.links)
    # The joints' own losses are what environment uses, unless it is given others.
    q, qd = [0.3, -0.4, 0.6], [0.5, -0.8, 1.1]
    own = loaded.environment(q, qd, [0.0] * 3, depth=2000.0, temperature_c=4.0)
    given = uwml.Robot(leg.joints, leg.links).environment(q, qd, [0.0] * 3, depth=2000.0, temperature_c=4.0, losses=losses)
    np.testing.assert_array_equal(own.total, given.total)
    assert own.seal[0] == 0.0 and own.seal[1] != 0.0 and own.seal[2] == 0.0
    none = loaded.environment(q, qd, [0.0] * 3, depth=2000.0, temperature_c=4.0, losses=[None] * 3)
    assert np.all(none.visc == 0.0) and np.all(none.seal == 0.0)
    text = text.replace("ratio = 120.0", "ratio = -1.0", 1)
    path.write_text(text)
    with pytest.raises(uwml.ModelFileError, match=r"joints\[2\], losses, drive: drive.ratio must be > 0"):
        uwml.Robot.load(path)


def _named(names: list[str]) -> uwml.Robot:
    """The paper's leg with ``names`` for its joints, then its links."""
    leg = uwml.paper_leg()
    joints = [uwml.Joint(j.origin, j.axis, parent=j.parent, kind=j.kind, name=n) for j, n in zip(leg.joints, names[:3])]
    links = [
        uwml.Link(link.mass, link.com, link.volume, cob=link.cob, segments=link.segments, name=n) for link, n in zip(leg.links, names[3:])
    ]
    return uwml.Robot(joints, links, water=uwml.Water(1025.0, 9.81))


# Any text a str can hold in UTF-8 (every code point but the lone surrogates), control
# characters, quotes and backslashes made likely.
NAME_CHARACTERS = st.one_of(
    st.characters(codec="utf-8"),
    st.sampled_from(['"', "\\", "\n", "\r", "\t", "\x00", "\x1f", "\x7f", "\x08", "\x0c", "'", "#", "=", "[", "]", "\u2028", "\ufeff"]),
)


@settings(max_examples=max(10, int(settings.default.max_examples / 2)))
@given(names=st.lists(st.text(NAME_CHARACTERS, min_size=1, max_size=12), min_size=6, max_size=6, unique=True))
def test_any_names_round_trip_exactly(names: list[str]) -> None:
    robot = _named(names)
    again = loads(dumps(robot))
    assert again.joint_names == tuple(names[:3]) and again.link_names == tuple(names[3:])
    assert again == robot


def test_control_characters_in_names_are_escaped(tmp_path: Path) -> None:
    names = ["nul\x00", 'q"uote', "back\\slash", "new\nline", "cr\r", "del\x7f esc\x1b"]
    path = tmp_path / "named.toml"
    _named(names).save(path)
    text = path.read_text(encoding="utf-8")
    assert all(c in "\n" or " " <= c != "\x7f" for c in text), "a raw control character in the file"
    assert 'name = "nul\\u0000"' in text and 'name = "new\\nline"' in text and 'name = "q\\"uote"' in text
    assert uwml.Robot.load(path).joint_names == tuple(names[:3])


def test_a_failed_save_keeps_the_old_file(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    path = tmp_path / "arm.toml"
    arm_on_rov().save(path)
    before = path.read_bytes()
    # A name that UTF-8 cannot hold (a lone surrogate): refused, and the old file is untouched.
    with pytest.raises(ValueError, match=r"joints\[1\]\.name.*cannot be written"):
        _named(["a", "b\ud800c", "d", "e", "f", "g"]).save(path)
    assert path.read_bytes() == before and sorted(p.name for p in tmp_path.iterdir()) == ["arm.toml"]

    # A failure while writing (here: the disk refuses to sync) leaves the old file and no temporary one.
    def refuse(fd: int) -> None:
        raise OSError(28, "No space left on device")

    monkeypatch.setattr("os.fsync", refuse)
    with pytest.raises(OSError, match="No space left"):
        uwml.paper_leg().save(path)
    assert path.read_bytes() == before and sorted(p.name for p in tmp_path.iterdir()) == ["arm.toml"]
    monkeypatch.undo()
    # A save that succeeds replaces the file whole.
    uwml.paper_leg().save(path)
    assert uwml.Robot.load(path) == uwml.paper_leg()
    assert sorted(p.name for p in tmp_path.iterdir()) == ["arm.toml"]


@pytest.mark.parametrize(
    ("key", "value", "message"),
    [
        ("density", "1.025", r"water, key 'density': .*900 to 1300 kg/m³.*1000 times too small"),
        ("density", "1e300", r"water, key 'density': .*900 to 1300 kg/m³"),
        ("density", "nan", r"water, key 'density': .*900 to 1300 kg/m³"),
        ("gravity", "0.0", r"water, key 'gravity': .*9.7 to 9.9 m/s²"),
        ("gravity", "32.2", r"water, key 'gravity': .*9.7 to 9.9 m/s².*ft/s²"),
    ],
)
def test_the_water_of_a_model_file_is_range_checked(tmp_path: Path, key: str, value: str, message: str) -> None:
    text = dumps(uwml.paper_leg())
    old = "density = 1000.0" if key == "density" else "gravity = 9.81"
    path = tmp_path / "leg.toml"
    path.write_text(text.replace(old, f"{key} = {value}"))
    with pytest.raises(uwml.ModelFileError, match=rf"leg.toml: {message}"):
        uwml.Robot.load(path)


@pytest.mark.filterwarnings("ignore::uwml.PlausibilityWarning")  # values beyond plausible on purpose
def test_a_robot_whose_water_a_model_file_cannot_hold_is_not_saved(tmp_path: Path) -> None:
    leg = uwml.paper_leg()
    path = tmp_path / "leg.toml"
    with pytest.raises(ValueError, match=r"water.density .*900 to 1300"):
        uwml.Robot(leg.joints, leg.links, water=uwml.Water(1.025)).save(path)
    assert not path.exists()


def test_deeply_nested_arrays_are_a_model_file_error(tmp_path: Path) -> None:
    path = tmp_path / "deep.toml"
    text = dumps(uwml.paper_leg())
    path.write_text(text.replace("com = [", "com = " + "[" * 100_000 + "]" * 100_000 + "\nxcom = [", 1))
    with pytest.raises(uwml.ModelFileError, match=r"deep.toml: .*nested too deeply") as info:
        uwml.Robot.load(path)
    assert len(str(info.value)) < 500


def test_a_file_that_is_not_utf8_names_the_file_and_the_byte(tmp_path: Path) -> None:
    path = tmp_path / "latin1.toml"
    data = dumps(_named(["a", "b", "c", "links_0", "links_1", "links_2"])).replace('name = "b"', 'name = "b±"').encode("latin-1")
    path.write_bytes(data)
    offset = data.index(b"\xb1")
    line = data[:offset].count(b"\n") + 1
    with pytest.raises(uwml.ModelFileError, match=rf"latin1.toml: not UTF-8 text: byte 0xb1 at offset {offset} \(line {line}\)"):
        uwml.Robot.load(path)


@pytest.mark.parametrize(
    ("old", "new", "where"),
    [
        ("com = [", "com = [" + "0.5, " * 1_000_000, r"key 'com'"),
        ('format = "uwml-robot"', 'format = "' + "u" * 1_000_000 + '"', r"key 'format'"),
        ("mass = 19.261", 'mass = "' + "heavy" * 200_000 + '"', r"key 'mass'"),
        ("mass = 19.261", "mass = 19.261\n" + "m" * 1_000_000 + " = 1.0", r"links\[1\], key 'mmmm"),
        ("[[joints]]\nparent", '[[joints]]\nname = "' + "j" * 1_000_000 + '"\nparent', r"names must be unique; 'jjj"),
    ],
)
def test_huge_values_give_short_messages(tmp_path: Path, old: str, new: str, where: str) -> None:
    text = dumps(uwml.paper_leg())
    if "name = " in new:  # the same huge name on two joints
        text = text.replace(old, new, 2)
    else:
        text = text.replace(old, new, 1)
    path = tmp_path / "huge.toml"
    path.write_text(text)
    with pytest.raises(uwml.ModelFileError, match=rf"huge.toml: .*{where}") as info:
        uwml.Robot.load(path)
    assert len(str(info.value)) < 500, str(info.value)[:1000]


@pytest.mark.skipif(not hasattr(os, "symlink") or os.name != "posix", reason="POSIX file modes and symbolic links")
def test_save_keeps_the_files_mode_and_its_links(tmp_path: Path) -> None:
    path = tmp_path / "arm.toml"
    arm_on_rov().save(path)
    path.chmod(0o640)
    link = tmp_path / "current.toml"
    link.symlink_to(path.name)
    uwml.paper_leg().save(link)
    assert link.is_symlink() and (path.stat().st_mode & 0o777) == 0o640
    assert uwml.Robot.load(path) == uwml.paper_leg()
    assert sorted(p.name for p in tmp_path.iterdir()) == ["arm.toml", "current.toml"]
