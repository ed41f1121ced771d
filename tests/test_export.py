"""``uwml export``: the robot's model as Rust constants and C initializers. The checked-in outputs
for the arm of ``uwml.examples.arm_on_rov`` are what the exporter writes today (so the Rust test
``crates/uwml-core/tests/exported.rs`` and the C program ``crates/uwml-ffi/tests/c/exported.c``
compile and evaluate exactly this output); every literal reads back to the model's number."""

import re
import shutil
import subprocess
from pathlib import Path

import numpy as np
import pytest
import uwml
from uwml.cli import main
from uwml.examples import arm_on_rov
from uwml.export import to_c, to_rust

ROOT = Path(__file__).resolve().parents[1]
SOURCE = "uwml.examples.arm_on_rov()"


def test_the_checked_in_exports_are_the_exporters_output() -> None:
    arm = arm_on_rov()
    rust = ROOT / "crates/uwml-core/tests/exported/arm_on_rov.rs"
    c = ROOT / "crates/uwml-ffi/tests/c/exported_arm.h"
    regenerate = "the exporter's output changed: regenerate the files from uwml.export.to_rust(arm_on_rov(), 'f64' and 'f32') / to_c(arm_on_rov(), prefix='ARM')"
    assert rust.read_text() == to_rust(arm, source=SOURCE), regenerate
    assert rust.with_name("arm_on_rov_f32.rs").read_text() == to_rust(arm, "f32", source=SOURCE), regenerate
    assert c.read_text() == to_c(arm, prefix="ARM", source=SOURCE), regenerate


def test_every_literal_reads_back_to_the_models_number() -> None:
    arm = arm_on_rov()
    numbers = [arm.base.mass, *arm.base.com, arm.base.volume] + [
        x for link in arm.links for x in (link.mass, *link.com, link.volume, *link.cob)
    ]
    numbers += [x for s in arm.segments for x in (*s.start, *s.axis, s.length, s.area)]
    for precision, suffix in (("f64", ""), ("f32", "f")):
        text = to_c(arm, precision)
        cast = float if precision == "f64" else (lambda x: float(np.float32(x)))
        literals = {cast(float(x)) for x in re.findall(r"(-?\d+\.\d*(?:e[-+]?\d+)?)" + suffix, text)}
        missing = [x for x in numbers if cast(x) not in literals]
        assert not missing, f"{precision}: {missing[:3]}"
    assert "TreeJoint<f32>" in to_rust(arm, "f32") and "Section::Circular { diameter: 0.6 }" in to_rust(arm)
    # The robot's water goes with it.
    leg = uwml.Leg.paper()
    sea = uwml.Robot(leg.joints, leg.links, water=uwml.Water(1025.5, 9.80665))
    assert "pub const WATER_DENSITY: f64 = 1025.5;\npub const GRAVITY: f64 = 9.80665;" in to_rust(sea)
    assert "#define ROBOT_WATER_DENSITY 1025.5f\n#define ROBOT_GRAVITY 9.80665f" in to_c(sea, "f32")
    # A number that float32 cannot hold exactly is written as float32's shortest text.
    assert "mass: 0.1," in to_rust(uwml.Robot([uwml.Joint((0, 0, 0), (0, 0, 1))], [uwml.Link(0.1, (0, 0, 0), 0.0)]), "f32")


def test_uwml_export_prints_them(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    path = tmp_path / "arm.toml"
    arm_on_rov().save(path)
    assert main(["export", "--robot", str(path), "--c", "--name", "ARM"]) == 0
    out = capsys.readouterr().out
    assert out == to_c(uwml.Robot.load(path), prefix="ARM", source=str(path))
    assert main(["export", "--rust", "--f32"]) == 0
    out = capsys.readouterr().out
    assert "pub const N_JOINTS: usize = 3;" in out and "RigidBody<f32>" in out
    assert main(["export", "--c", "--name", "not valid"]) == 2
    assert "prefix must be an upper-case C identifier" in capsys.readouterr().err


# Hostile names: a URDF's or MJCF's names are untrusted text. Each must land in the generated
# source as inert comment text, never as code (docs/firmware.md, "The model as source").
INJECTION = "x */ int pwned(void) { return 42; } /* y"
HOSTILE_NAMES = [
    INJECTION,
    "a\npub fn pwned() -> i32 { 42 }\n//",  # a newline would end a Rust line comment
    "a\r\npub fn pwned() -> i32 { 42 } //",
    "b\rc",
    "end */",
    "/* open",
    "// slashes",
    'quote " and \\ backslash\\',
    "tab\there",
    "trailing backslash\\",
    "??/",  # a C trigraph for a backslash
    "é ü 水 \u202e\u2066",  # non-ASCII, with the text-direction marks Rust refuses in comments
    "nul\x00byte",
    "del\x7f and \x1b[31m escape",
    "<b>html</b> & `code` [link](javascript:pwned())",
]
PWNED_PROBE_C = "int pwned(void);\nint probe(void) { return pwned(); }\n"
# A stand-in for uwml_core's plain types, enough for the exported constants to type-check
# (the real crate compiles the checked-in export in crates/uwml-core/tests/exported.rs).
UWML_CORE_STUB = """
#![allow(dead_code)]
pub mod uwml_core {
    pub mod nalgebra {
        pub struct Vector3<T>([T; 3]);
        impl<T> Vector3<T> { pub const fn new(x: T, y: T, z: T) -> Self { Vector3([x, y, z]) } }
        pub struct Matrix3<T>([T; 9]);
        impl<T> Matrix3<T> {
            #[allow(clippy::too_many_arguments)]
            pub const fn new(a: T, b: T, c: T, d: T, e: T, f: T, g: T, h: T, i: T) -> Self { Matrix3([a, b, c, d, e, f, g, h, i]) }
        }
        pub struct Matrix6<T>([[T; 6]; 6]);
        impl<T> Matrix6<T> {
            #[allow(clippy::too_many_arguments)]
            pub const fn new(
                a0: T, a1: T, a2: T, a3: T, a4: T, a5: T, b0: T, b1: T, b2: T, b3: T, b4: T, b5: T,
                c0: T, c1: T, c2: T, c3: T, c4: T, c5: T, d0: T, d1: T, d2: T, d3: T, d4: T, d5: T,
                e0: T, e1: T, e2: T, e3: T, e4: T, e5: T, f0: T, f1: T, f2: T, f3: T, f4: T, f5: T,
            ) -> Self {
                Matrix6([[a0, a1, a2, a3, a4, a5], [b0, b1, b2, b3, b4, b5], [c0, c1, c2, c3, c4, c5],
                         [d0, d1, d2, d3, d4, d5], [e0, e1, e2, e3, e4, e5], [f0, f1, f2, f3, f4, f5]])
            }
        }
    }
    use self::nalgebra::Vector3;
    pub enum JointKind { Revolute, Prismatic }
    pub enum Owner { Base, Link(usize) }
    pub struct TreeJoint<T> { pub parent: Option<usize>, pub kind: JointKind, pub origin: Vector3<T>, pub axis: Vector3<T> }
    pub struct RigidBody<T> { pub mass: T, pub com: Vector3<T>, pub volume: T, pub cob: Vector3<T> }
    pub enum Section<T> { Circular { diameter: T }, Rectangular { normals: [Vector3<T>; 2], widths: [T; 2] } }
    pub struct LumpedBody<T> {
        pub owner: Owner, pub point: Vector3<T>, pub axes: nalgebra::Matrix3<T>, pub added_mass: nalgebra::Matrix6<T>,
        pub linear_damping: nalgebra::Matrix6<T>, pub quadratic_damping: [T; 6],
    }
    pub struct RobotSegment<T> {
        pub owner: Owner, pub start: Vector3<T>, pub axis: Vector3<T>, pub length: T, pub area: T,
        pub section: Section<T>, pub cd: [T; 2], pub cm: [T; 2], pub cd_axial: T, pub axial_area: T,
    }
}
"""


def hostile_robot(names: list[str]) -> uwml.Robot:
    """The arm on an ROV with ``names`` for its joints and, reversed, its links (cycled)."""
    arm = arm_on_rov()
    n = arm.n_joints
    joint_names = [f"{names[i % len(names)]}#{i}" if i >= len(names) else names[i] for i in range(n)]
    link_names = [f"{names[-1 - i % len(names)]}@{i}" for i in range(n)]
    joints = [uwml.Joint(j.origin, j.axis, parent=j.parent, kind=j.kind, name=name) for j, name in zip(arm.joints, joint_names)]
    links = [
        uwml.Link(link.mass, link.com, link.volume, cob=link.cob, segments=link.segments, name=name)
        for link, name in zip(arm.links, link_names)
    ]
    return uwml.Robot(joints, links, base=arm.base)


def hostile_robots() -> list[uwml.Robot]:
    return [hostile_robot(HOSTILE_NAMES[i : i + 7]) for i in range(0, len(HOSTILE_NAMES), 7)]


def _run(command: list[str], cwd: Path) -> subprocess.CompletedProcess[str]:
    return subprocess.run(command, cwd=cwd, capture_output=True, text=True, timeout=120, check=False)


@pytest.mark.skipif(shutil.which("gcc") is None or shutil.which("nm") is None, reason="needs gcc and nm (binutils) to compile the C export")
def test_hostile_names_stay_comments_in_c(tmp_path: Path) -> None:
    include = ROOT / "crates/uwml-ffi/include"
    for k, robot in enumerate(hostile_robots()):
        header = tmp_path / f"robot{k}.h"
        source = "evil.toml */ int pwned(void) { return 1; } /*\n#error"
        header.write_bytes(to_c(robot, prefix="ROBOT", source=source).encode("ascii"))  # ASCII only: nothing for a charset to mangle
        # One translation unit that uses every constant: with -Wall -Werror it must compile cleanly.
        unit = tmp_path / f"unit{k}.c"
        unit.write_text(
            f'#include "{header.name}"\n'
            "unsigned long used(void) { return sizeof ROBOT_JOINTS + sizeof ROBOT_LINKS + sizeof ROBOT_SEGMENTS + ROBOT_N_JOINTS"
            " + ROBOT_N_SEGMENTS + (unsigned long)(ROBOT_BASE->mass + ROBOT_WATER_DENSITY + ROBOT_GRAVITY); }\n"
        )
        built = _run(
            ["gcc", "-std=c11", "-Wall", "-Wextra", "-Werror", "-pedantic", "-I", str(include), "-c", unit.name, "-o", "unit.o"], tmp_path
        )
        assert built.returncode == 0, built.stderr
        symbols = _run(["nm", "unit.o"], tmp_path)
        assert symbols.returncode == 0 and "used" in symbols.stdout and "pwned" not in symbols.stdout, symbols.stdout
        # A program that calls pwned() must not link: no such function came with the header.
        (tmp_path / "main.c").write_text(PWNED_PROBE_C + "int main(void) { return probe(); }\n")
        linked = _run(["gcc", "main.c", "unit.o", "-o", "main"], tmp_path)
        assert linked.returncode != 0 and "pwned" in linked.stderr, linked.stderr


@pytest.mark.skipif(shutil.which("rustc") is None, reason="needs rustc to compile the Rust export")
def test_hostile_names_stay_comments_in_rust(tmp_path: Path) -> None:
    for k, robot in enumerate(hostile_robots()):
        exported = to_rust(robot, source="evil.toml\npub fn pwned() -> i32 { 1 }\n//")
        assert {ch for ch in exported if not ch.isascii()} <= {"³", "²"}  # the units in the water's doc comment
        lib = tmp_path / f"lib{k}.rs"
        lib.write_text(UWML_CORE_STUB + exported)
        command = ["rustc", "--edition", "2021", "--crate-type", "lib", "--emit", "metadata", "-D", "warnings", "--out-dir", str(tmp_path)]
        built = _run([*command, lib.name], tmp_path)
        assert built.returncode == 0, built.stderr
        # The same crate with a function that calls pwned(): it must not resolve.
        probe = tmp_path / f"probe{k}.rs"
        probe.write_text(UWML_CORE_STUB + exported + "pub fn probe() -> i32 { pwned() }\n")
        probed = _run([*command, probe.name], tmp_path)
        assert probed.returncode != 0 and "cannot find function `pwned`" in probed.stderr, probed.stderr


def test_names_are_escaped_in_comments() -> None:
    robot = hostile_robot(["a*/b", "c\nd", "e\\f", "ü", "plain_name-1.x/y"])
    c, rust = to_c(robot), to_rust(robot)
    assert c.isascii() and {ch for ch in rust if not ch.isascii()} <= {"³", "²"}  # the units in the water's doc comment
    for text in (c, rust):
        assert "a\\u{2a}/b" in text and "c\\u{a}d" in text and "e\\u{5c}f" in text and "\\u{fc}" in text and "plain_name-1.x/y" in text
    # Every comment line of the C header stays one comment: no */ but the one closing it.
    for line in c.splitlines():
        if line.startswith(("/* joints", "/* links")):
            assert line.count("*/") == 1 and line.endswith(" */") and line.count("/*") == 1, line


@pytest.mark.parametrize("prefix", ["ÄRM", "ＡＲＭ", "ARM\n", "ARM */", "ARM;", "arm", "", "1ARM", "AR M"])
def test_the_c_prefix_is_an_ascii_identifier(prefix: str) -> None:
    with pytest.raises(ValueError, match="prefix must be an upper-case C identifier"):
        to_c(arm_on_rov(), prefix=prefix)
    assert "#define _ARM_2_N_JOINTS 7u" in to_c(arm_on_rov(), prefix="_ARM_2")


def with_hull() -> uwml.Robot:
    """The arm on its ROV with a lumped model on the hull (turned axes, a coupled added mass)."""
    import dataclasses

    arm = arm_on_rov()
    added = np.diag([190.0, 360.0, 420.0, 12.0, 30.0, 25.0])
    added[0, 4] = added[4, 0] = 8.0
    turn = np.array([[0.0, -1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]])
    lumped = uwml.LumpedModel(
        point=(0.0, 0.0, 0.05), added_mass=added, linear_damping=np.diag([120.0, 150, 160, 20, 30, 25]),
        quadratic_damping=[420.0, 600, 700, 30, 60, 50], axes=turn,
    )  # fmt: skip
    assert arm.base is not None
    return uwml.Robot(arm.joints, arm.links, base=dataclasses.replace(arm.base, lumped=lumped), water=arm.water)


def test_a_lumped_model_is_exported_for_the_firmware(tmp_path: Path) -> None:
    robot = with_hull()
    c, rust = to_c(robot, prefix="ARM"), to_rust(robot)
    assert "#define ARM_N_LUMPED 1u" in c and "static const UwmlLumpedF64 ARM_LUMPED[1]" in c and ".owner = UWML_BASE" in c
    assert "pub const N_LUMPED: usize = 1;" in rust and "LumpedBody { owner: Owner::Base" in rust and "Matrix6::new(190.0," in rust
    for number in (8.0, 420.0, 0.05, -1.0, 700.0):
        assert repr(number) in c and repr(number) in rust
    # Without lumped models, nothing about them (the arm's checked-in exports stay as they were).
    assert "LUMPED" not in to_c(arm_on_rov()) and "LumpedBody" not in to_rust(arm_on_rov())
    # More than the C API's robot holds: refused, not cut.
    import dataclasses

    many = uwml.Robot(
        robot.joints, [dataclasses.replace(link, lumped=uwml.LumpedModel()) for link in robot.links], base=robot.base, water=robot.water
    )
    with pytest.raises(ValueError, match="at most 4 lumped models"):
        to_c(many)
    if shutil.which("gcc") is not None:
        header = tmp_path / "arm.h"
        header.write_text(c)
        unit = tmp_path / "unit.c"
        unit.write_text(
            '#include "arm.h"\nunsigned long used(void) { return sizeof ARM_LUMPED + ARM_N_LUMPED + sizeof ARM_SEGMENTS + sizeof ARM_JOINTS + sizeof ARM_LINKS; }\n'
        )
        include = ROOT / "crates/uwml-ffi/include"
        built = _run(
            ["gcc", "-std=c11", "-Wall", "-Wextra", "-Werror", "-pedantic", "-I", str(include), "-c", unit.name, "-o", "unit.o"], tmp_path
        )
        assert built.returncode == 0, built.stderr
    if shutil.which("rustc") is not None:
        lib = tmp_path / "lumped.rs"
        lib.write_text(UWML_CORE_STUB + rust)
        command = ["rustc", "--edition", "2021", "--crate-type", "lib", "--emit", "metadata", "-D", "warnings", "--out-dir", str(tmp_path)]
        built = _run([*command, lib.name], tmp_path)
        assert built.returncode == 0, built.stderr
