"""Hostile robot descriptions (URDF, MJCF) and hydro files, read by uwml.io.descriptions
(docs/model.md section 10, "From URDF and MJCF").

What must hold: a correct load, or a :class:`uwml.DescriptionError` (a ``ValueError``) whose
message names the file, says what is wrong and is short (under ``MAX_MESSAGE`` characters); never
another exception (``RecursionError``, ``UnicodeDecodeError``, a numpy warning, which pytest turns
into an error), never a silent change of what the file says (a mass clamped, a mass invented, a
joint renamed, a coupling dropped, a table ignored), and never a hang (a named pipe where a file
should be, a description that expands into thousands of bodies).
"""

from __future__ import annotations

import os
import time
from pathlib import Path

import pytest

pytest.importorskip("mujoco")

import uwml
from hostile_descriptions import ARM, DATA, MAX_MESSAGE, MJCF, joint, link, refused, urdf, write
from watchdog import run_with_watchdog

# --- 1. descriptions accepted silently ---------------------------------------------------------


def test_a_negative_mass_is_refused_not_clamped(tmp_path: Path) -> None:
    """MuJoCo's compile clamps a negative mass of a body that does not move to 0."""
    path = write(tmp_path, "neg.urdf", urdf(link("base", -5.0), link("arm"), joint("j", "base", "arm")))
    refused(lambda: uwml.Robot.from_urdf(path), "neg.urdf", match=r"link 'base'.*mass -5 .*negative")
    path = write(tmp_path, "neg.xml", MJCF.format(mass=-5))
    refused(lambda: uwml.Robot.from_mjcf(path), "neg.xml", match=r"body 'base'.*mass -5 .*negative")


def test_a_mass_beyond_the_bound_is_uwml_s_error_before_mujoco_s_warning(tmp_path: Path) -> None:
    """A link of 1e308 kg: uwml's bound (1e9 kg, ``MAX_MASS``) names the link, for the robot and
    for its simulation (floating, MuJoCo warned of a singular inertia matrix first)."""
    from uwml.sim.mujoco import Simulation

    path = write(tmp_path, "heavy.urdf", urdf(link("base", 2.0), link("upper", 1e308), joint("shoulder", "base", "upper")))
    match = r"heavy\.urdf: link 'upper' has mass 1e\+308 kg in its <inertial>, beyond 1e\+09 kg"
    refused(lambda: uwml.Robot.from_urdf(path), "heavy.urdf", match=match)
    refused(lambda: Simulation.from_file(path, floating=True), "heavy.urdf", match=match)
    refused(lambda: Simulation.from_file(path), "heavy.urdf", match=match)
    path = write(tmp_path, "heavy.xml", MJCF.format(mass=1e308))
    refused(lambda: uwml.Robot.from_mjcf(path), "heavy.xml", match=r"body 'base' has mass 1e\+308 kg in its <inertial>, beyond 1e\+09 kg")


def test_a_urdf_link_without_inertial_is_massless(tmp_path: Path) -> None:
    """URDF: no <inertial>, no mass (MuJoCo would compute one from the collision geometry)."""
    path = write(tmp_path, "noinertial.urdf", urdf(link("base"), link("arm", None), joint("j", "base", "arm")))
    refused(lambda: uwml.Robot.from_urdf(path), "noinertial.urdf", match=r"link 'arm' .*no <inertial>")
    # A fixed link without <inertial> adds its geometry, and no mass, to the link it is fused into.
    path = write(
        tmp_path,
        "fixed.urdf",
        urdf(link("base"), link("arm"), link("sensor", None), joint("j", "base", "arm"), joint("f", "arm", "sensor", "fixed")),
    )
    robot = uwml.Robot.from_urdf(path)
    assert robot.links[0].mass == 1.0 and robot.links[0].volume == pytest.approx(2 * 0.1 * 0.2 * 0.3, rel=1e-12)
    # The root without <inertial>: a massless base (the URDF convention for a frame to hang from).
    path = write(tmp_path, "root.urdf", urdf(link("base", None), link("arm"), joint("j", "base", "arm")))
    assert uwml.Robot.from_urdf(path).base.mass == 0.0  # type: ignore[union-attr]


def test_a_joint_name_given_twice_is_refused(tmp_path: Path) -> None:
    """MuJoCo's URDF reader renames the second joint ('joint1')."""
    path = write(tmp_path, "dup.urdf", urdf(link("base"), link("a"), link("b"), joint("j", "base", "a"), joint("j", "a", "b")))
    refused(lambda: uwml.Robot.from_urdf(path), "dup.urdf", match=r"joint name 'j' .*twice")


def test_a_link_name_given_twice_names_the_link(tmp_path: Path) -> None:
    """MuJoCo says 'repeated URDF name:' and cuts the name off."""
    path = write(tmp_path, "dup.urdf", urdf(link("base"), link("forearm"), link("forearm"), joint("j", "base", "forearm")))
    refused(lambda: uwml.Robot.from_urdf(path), "dup.urdf", match=r"link name 'forearm' .*twice")


def test_a_mimic_joint_is_refused(tmp_path: Path) -> None:
    path = write(
        tmp_path,
        "mimic.urdf",
        urdf(link("base"), link("a"), link("b"), joint("j", "base", "a"), joint("k", "a", "b", extra='<mimic joint="j" multiplier="2"/>')),
    )
    refused(lambda: uwml.Robot.from_urdf(path), "mimic.urdf", match=r"joint 'k' .*mimic.*'j'")


@pytest.mark.parametrize("form", ["urdf", "mjcf", "mujoco"])
def test_a_hydro_table_for_the_world_is_refused(tmp_path: Path, form: str) -> None:
    """[links.world] named no link of the robot and was ignored."""
    hydro = write(tmp_path, "h.toml", "[links.world]\nvolume = 1.0\n")
    if form == "urdf":
        load = lambda: uwml.Robot.from_urdf(DATA / "paper_leg.urdf", hydro)
    elif form == "mjcf":
        load = lambda: uwml.Robot.from_mjcf(DATA / "paper_leg.xml", hydro)
    else:
        import mujoco

        model = mujoco.MjModel.from_xml_string(MJCF.format(mass=1.0))
        load = lambda: uwml.Robot.from_mujoco(model, hydro)
    refused(load, "h.toml", match=r"h\.toml: \[links\.world\]: .*world")


def test_a_urdf_link_named_world_with_a_mass_is_refused(tmp_path: Path) -> None:
    """MuJoCo takes a URDF link named 'world' for its world body: its mass would be lost."""
    path = write(tmp_path, "w.urdf", urdf(link("world", 5.0), link("arm"), joint("j", "world", "arm")))
    refused(lambda: uwml.Robot.from_urdf(path), "w.urdf", match=r"link 'world'.*<inertial>")
    # The ROS idiom, an empty 'world' link fixed to the base, still loads.
    path = write(
        tmp_path,
        "ros.urdf",
        urdf('<link name="world"/>', link("base", 3.0), link("arm"), joint("fix", "world", "base", "fixed"), joint("j", "base", "arm")),
    )
    robot = uwml.Robot.from_urdf(path)
    assert robot.base is not None and robot.base.name == "base" and robot.base.mass == 3.0


# --- 2. uncaught exceptions and hangs ----------------------------------------------------------


def test_a_deeply_nested_hydro_array_is_a_description_error(tmp_path: Path) -> None:
    hydro = write(tmp_path, "deep.toml", "[links.calf]\ncd = " + "[" * 5000 + "]" * 5000 + "\n")
    refused(lambda: uwml.Robot.from_urdf(DATA / "paper_leg.urdf", hydro), "deep.toml", match="nested too deeply")


FIFO_CASES = {
    "description": ("robot.urdf", {}, "uwml.Robot.from_urdf('robot.urdf')"),
    "hydro file": ("h.toml", {"robot.urdf": ARM}, "uwml.Robot.from_urdf('robot.urdf', 'h.toml')"),
    "collision mesh": (
        "m.stl",
        {
            "robot.xml": '<mujoco><asset><mesh name="m" file="m.stl"/></asset><worldbody><body name="b"><geom size="0.1"/>'
            '<body name="hand"><joint name="j"/><geom type="mesh" mesh="m"/></body></body></worldbody></mujoco>',
            "h.toml": "[links.hand]\nvolume = 0.001\n",
        },
        "uwml.Robot.from_mjcf('robot.xml', 'h.toml')",
    ),
    "collision mesh in meshdir": (
        "meshes/m.stl",
        {
            "robot.urdf": urdf(
                '<mujoco><compiler meshdir="meshes"/></mujoco>',
                link("base"),
                link("hand", None, '<mesh filename="m.stl"/>'),
                joint("j", "base", "hand"),
            ),
            "h.toml": "[links.hand]\nvolume = 0.001\n",
        },
        "uwml.Robot.from_urdf('robot.urdf', 'h.toml')",
    ),
    "include": (
        "inc.xml",
        {"robot.xml": '<mujoco><include file="inc.xml"/><worldbody><body name="b"><geom size="0.1"/></body></worldbody></mujoco>'},
        "uwml.Robot.from_mjcf('robot.xml')",
    ),
}


@pytest.mark.skipif(not hasattr(os, "mkfifo"), reason="named pipes need os.mkfifo")
@pytest.mark.parametrize("case", list(FIFO_CASES))
def test_a_named_pipe_is_refused_not_waited_on(tmp_path: Path, case: str) -> None:
    fifo, files, call = FIFO_CASES[case]
    for name, text in files.items():
        write(tmp_path, name, text)
    (tmp_path / fifo).parent.mkdir(exist_ok=True)
    os.mkfifo(tmp_path / fifo)
    code = f"""
    import uwml
    try:
        {call}
    except uwml.DescriptionError as exc:
        print(exc)
    else:
        print("loaded")
    """
    run = run_with_watchdog(code, tmp_path)
    assert run.returncode == 0, run.stderr[-2000:]
    message = run.stdout.strip()
    assert Path(fifo).name in message and "not a regular file" in message and len(message) < MAX_MESSAGE, message


def test_a_directory_or_a_missing_file_says_so(tmp_path: Path) -> None:
    (tmp_path / "robot.urdf").mkdir()
    refused(lambda: uwml.Robot.from_urdf(tmp_path / "robot.urdf"), "robot.urdf", match="is a directory")
    (tmp_path / "h.toml").mkdir()
    refused(lambda: uwml.Robot.from_urdf(DATA / "paper_leg.urdf", tmp_path / "h.toml"), "h.toml", match="is a directory")
    refused(lambda: uwml.Robot.from_urdf(tmp_path / "absent.urdf"), "absent.urdf", match="no such file")


# --- 3. huge descriptions ----------------------------------------------------------------------


def chain(n: int) -> str:
    parts = [link("l0")]
    for i in range(1, n):
        parts += [link(f"l{i}"), joint(f"j{i}", f"l{i - 1}", f"l{i}")]
    return urdf(*parts)


def test_a_10000_link_chain_is_refused_before_mujoco_reads_it(tmp_path: Path) -> None:
    path = write(tmp_path, "chain.urdf", chain(10_000))
    start = time.perf_counter()
    refused(lambda: uwml.Robot.from_urdf(path), "chain.urdf", match=r"9999 moving joints.*at most 64 \(uwml\.MAX_ROBOT_JOINTS\)")
    elapsed = time.perf_counter() - start
    print(f"10,000-link URDF refused in {elapsed:.3f} s")
    assert elapsed < 30.0


def test_a_small_mjcf_that_replicates_into_thousands_of_bodies_is_refused(tmp_path: Path) -> None:
    text = (
        '<mujoco><worldbody><body name="b"><geom size=".1"/><replicate count="30" offset=".1 0 0"><replicate count="30" '
        'offset="0 .1 0"><replicate count="30" offset="0 0 .1"><body name="c"><joint/><geom size=".1"/></body></replicate>'
        "</replicate></replicate></body></worldbody></mujoco>"
    )
    assert len(text) < 300
    path = write(tmp_path, "rep.xml", text)
    start = time.perf_counter()
    refused(lambda: uwml.Robot.from_mjcf(path), "rep.xml", match=r"27001 bodies.*at most \d+.*MAX_ROBOT_JOINTS.*MAX_SEGMENTS")
    elapsed = time.perf_counter() - start
    print(f"replicated MJCF refused in {elapsed:.3f} s")
    assert elapsed < 30.0


def test_a_model_over_the_limits_is_refused_before_the_mapping() -> None:
    import mujoco

    text = (
        '<mujoco><worldbody><body name="b"><geom size=".1"/><replicate count="20" offset=".1 0 0"><replicate count="20" '
        'offset="0 .1 0"><body name="c"><joint/><geom size=".1"/></body></replicate></replicate></body></worldbody></mujoco>'
    )
    model = mujoco.MjModel.from_xml_string(text)
    refused(lambda: uwml.Robot.from_mujoco(model), "mujoco.MjModel", match=r"400 joints.*MAX_ROBOT_JOINTS")


# --- 4. clear messages -------------------------------------------------------------------------


def test_a_hydro_file_that_is_not_utf8_is_named(tmp_path: Path) -> None:
    hydro = write(tmp_path, "latin1.toml", "[links.calf]\n# ±\nvolume = 0.1\n".encode("latin-1"))
    message = refused(lambda: uwml.Robot.from_urdf(DATA / "paper_leg.urdf", hydro), "latin1.toml", match="UTF-8")
    assert "0xb1" in message and "codec" not in message


def test_a_nan_joint_axis_names_the_file_and_the_joint(tmp_path: Path) -> None:
    text = ARM.replace('<axis xyz="0 0 1"/></joint></robot>', '<axis xyz="nan 0 1"/></joint></robot>')
    path = write(tmp_path, "nan.urdf", text)
    refused(lambda: uwml.Robot.from_urdf(path), "nan.urdf", match=r"joint 'elbow'.*<axis>.*xyz.*finite")


def test_a_huge_hydro_value_gives_a_short_message(tmp_path: Path) -> None:
    big = "[" + ", ".join(["1.0"] * 200_000) + "]"
    for key in ("volume", "cob", "cd"):
        hydro = write(tmp_path, "big.toml", f"[links.calf]\n{key} = {big}\n")
        refused(
            lambda hydro=hydro: uwml.Robot.from_urdf(DATA / "paper_leg.urdf", hydro), "big.toml", match=rf"\[links\.calf\], key '{key}'"
        )
    text = f'[[links.calf.segments]]\nsection = "circular"\nstart = {big}\n'
    hydro = write(tmp_path, "big.toml", text)
    refused(lambda: uwml.Robot.from_urdf(DATA / "paper_leg.urdf", hydro), "big.toml", match=r"segments\[0\], key 'start'")
    hydro = write(tmp_path, "big.toml", f"[joints.knee]\nepsilon = {big}\n")
    refused(lambda: uwml.Robot.from_urdf(DATA / "paper_leg.urdf", hydro), "big.toml", match=r"\[joints\.knee\], key 'epsilon'")


@pytest.mark.parametrize("kind", ["planar", "floating"])
def test_an_unsupported_urdf_joint_is_named(tmp_path: Path, kind: str) -> None:
    path = write(tmp_path, "p.urdf", urdf(link("base"), link("arm"), joint("j3_elbow", "base", "arm", kind)))
    message = refused(lambda: uwml.Robot.from_urdf(path), "p.urdf", match=rf"joint 'j3_elbow' is a {kind} joint.*revolute.*prismatic")
    assert "_TX" not in message


@pytest.mark.parametrize(
    "text, match",
    [
        ("", r"not a readable URDF file: .*no element found"),
        ('<html><body name="b"/></html>', r"root element <html> is neither <robot> \(URDF\) nor <mujoco> \(MJCF\)"),
        ("\x00\x01binary", r"not a readable URDF file"),
        ('<robot name="r"><link name="a"></robot>', r"not a readable URDF file: .*mismatched tag.*line 1"),
    ],
)
def test_files_that_are_not_descriptions(tmp_path: Path, text: str, match: str) -> None:
    path = write(tmp_path, "x.urdf", text)
    refused(lambda: uwml.Robot.from_urdf(path), "x.urdf", match=match)


def test_an_unknown_urdf_joint_type_is_named(tmp_path: Path) -> None:
    path = write(tmp_path, "t.urdf", urdf(link("base"), link("arm"), joint("wrist", "base", "arm", "spherical")))
    refused(lambda: uwml.Robot.from_urdf(path), "t.urdf", match=r"joint 'wrist' .*type 'spherical'.*revolute")


@pytest.mark.parametrize(
    "parts, match",
    [
        ((link("base"), link("a"), joint("j", "nobody", "a")), r"joint 'j': its parent 'nobody' is not a link"),
        ((link("base"), link("a"), joint("j", "base", "nobody")), r"joint 'j': its child 'nobody' is not a link"),
        (
            (link("base"), link("a"), link("b"), joint("j", "base", "a"), joint("k", "b", "a")),
            r"link 'a' is the child of joints 'j' and 'k'",
        ),
        ((link("a"), link("b"), joint("j", "a", "b"), joint("k", "b", "a")), r"links 'a', 'b' form a loop"),
        ((link("base"), link("a"), '<joint name="j" type="continuous"><child link="a"/></joint>'), r"joint 'j' has no <parent"),
        ((link("base"), link("a"), '<joint name="j"><parent link="base"/><child link="a"/></joint>'), r"joint 'j' has no type"),
    ],
)
def test_a_urdf_that_is_not_a_tree_names_the_joint_or_link(tmp_path: Path, parts: tuple[str, ...], match: str) -> None:
    """MuJoCo said 'URDF joint parent or child missing', 'URDF body has multiple parents', 'URDF
    body not found', naming no joint or link."""
    path = write(tmp_path, "t.urdf", urdf(*parts))
    refused(lambda: uwml.Robot.from_urdf(path), "t.urdf", match=match)


def test_huge_coordinates_give_a_description_error_not_a_numpy_warning(tmp_path: Path) -> None:
    text = ARM.replace('<origin xyz="0.2 0 0"/>', '<origin xyz="1e308 0 0"/>')
    path = write(tmp_path, "far.urdf", text)
    refused(lambda: uwml.Robot.from_urdf(path), "far.urdf", match=r"joint '(shoulder|elbow)'")


def test_a_mujoco_compile_error_names_the_link(tmp_path: Path) -> None:
    """MuJoCo names the geom by its index ('Element name '', id 1'); uwml names its link."""
    path = write(
        tmp_path, "g.urdf", urdf(link("base"), link("arm", 1.0, '<cylinder radius="-1" length="0.2"/>'), joint("j", "base", "arm"))
    )
    refused(lambda: uwml.Robot.from_urdf(path), "g.urdf", match=r"link 'arm'.*size")


BODY = '<worldbody><body name="b"><geom size="0.1"/><body name="c"><joint name="j"/><geom size="0.1"/></body></body></worldbody>'
LAUGHS = "".join(f'<!ENTITY l{i + 1} "{f"&l{i};" * 10}">' for i in range(8))
MESH_LINK = '<mujoco><asset><mesh name="m" file="{file}"/></asset><worldbody><body name="b"><geom size="0.1"/><body name="hand"><joint name="j"/><geom type="mesh" mesh="m"/></body></body></worldbody></mujoco>'


@pytest.mark.parametrize(
    "files, match",
    [
        ({"robot.xml": f'<mujoco><include file="robot.xml"/>{BODY}</mujoco>'}, r"robot\.xml: included in itself"),
        (
            {"robot.xml": f'<mujoco><include file="b.xml"/>{BODY}</mujoco>', "b.xml": '<mujoco><include file="robot.xml"/></mujoco>'},
            r"included in itself",
        ),
        (
            {"robot.xml": f'<mujoco><include file="sub"/>{BODY}</mujoco>', "sub/x": ""},
            r"sub: the included file cannot be read: it is a directory",
        ),
        (
            {"robot.xml": MESH_LINK.format(file="/dev/zero"), "h.toml": "[links.hand]\nvolume = 0.001\n"},
            r"'/dev/zero'.*not a regular file \(a device\)",
        ),
        (
            {"robot.xml": f'<?xml version="1.0"?><!DOCTYPE m [<!ENTITY l0 "lol">{LAUGHS}]><mujoco model="&l8;">{BODY}</mujoco>'},
            r"not well-formed XML \(limit on input amplification",
        ),
        (
            {
                "robot.xml": f'<?xml version="1.0"?><!DOCTYPE m [<!ENTITY x SYSTEM "file:///etc/hostname">]><mujoco model="&x;">{BODY}</mujoco>'
            },
            r"external entity",
        ),
        (
            {
                "robot.xml": '<mujoco><asset><model name="arm" file="arm.xml"/></asset><worldbody><body name="b"><geom size="0.1"/>'
                '<replicate count="100"><attach model="arm" body="c" prefix="p"/></replicate></body></worldbody></mujoco>',
                "arm.xml": f"<mujoco>{BODY}</mujoco>",
            },
            r"too large for uwml: 100 joints",
        ),
        (
            {
                "robot.xml": '<mujoco><worldbody><body name="b"><geom size="0.1"/><composite type="cable" count="1000 1 1"><geom type="capsule" size=".01"/></composite></body></worldbody></mujoco>'
            },
            r"<composite> generates bodies",
        ),
        (
            {
                "robot.xml": '<mujoco><worldbody><flexcomp name="f" type="grid" count="1000 1000 1" spacing=".1 .1 .1" dim="2"/></worldbody></mujoco>'
            },
            r"<flexcomp> generates bodies",
        ),
    ],
)
def test_hostile_includes_assets_and_entities(tmp_path: Path, files: dict[str, str], match: str) -> None:
    for name, text in files.items():
        (tmp_path / name).parent.mkdir(parents=True, exist_ok=True)
        write(tmp_path, name, text)
    hydro = tmp_path / "h.toml" if "h.toml" in files else None
    refused(lambda: uwml.Robot.from_mjcf(tmp_path / "robot.xml", hydro), "robot.xml", "sub", match=match)


def test_a_hydro_file_may_start_with_a_byte_order_mark(tmp_path: Path) -> None:
    hydro = write(tmp_path, "bom.toml", b"\xef\xbb\xbf[links.calf]\nvolume = 0.1\n")
    assert uwml.Robot.from_urdf(DATA / "paper_leg.urdf", hydro).links[2].volume == 0.1


def test_too_many_hydro_segments_are_refused_before_they_are_read(tmp_path: Path) -> None:
    segment = '[[links.calf.segments]]\nsection = "circular"\nstart = [0.0, 0.0, 0.0]\naxis = [1.0, 0.0, 0.0]\nlength = 0.1\n'
    hydro = write(tmp_path, "h.toml", "[links.calf]\nvolume = 0.1\n" + segment * 300)
    refused(
        lambda: uwml.Robot.from_urdf(DATA / "paper_leg.urdf", hydro),
        "h.toml",
        match=r"key 'segments': has 300 entries; .*256 .*MAX_SEGMENTS",
    )


def test_a_nul_in_a_path_is_a_description_error(tmp_path: Path) -> None:
    refused(lambda: uwml.Robot.from_urdf("robot\x00.urdf"), "robot", match="null")
    refused(lambda: uwml.Robot.from_urdf(DATA / "paper_leg.urdf", "h\x00.toml"), "h", match="null")
