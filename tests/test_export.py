"""``uwml export``: the robot's model as Rust constants and C initializers. The checked-in outputs
for the arm of ``uwml.examples.arm_on_rov`` are what the exporter writes today (so the Rust test
``crates/uwml-core/tests/exported.rs`` and the C program ``crates/uwml-ffi/tests/c/exported.c``
compile and evaluate exactly this output); every literal reads back to the model's number."""

import dataclasses
import math
import re
import shutil
import subprocess
from pathlib import Path

import numpy as np
import pytest
import uwml
from hypothesis import given, settings
from hypothesis import strategies as st
from uwml.cli import main
from uwml.examples import arm_on_rov
from uwml.io.export import to_c, to_rust

ROOT = Path(__file__).resolve().parents[1]
SOURCE = "uwml.examples.arm_on_rov()"


def test_the_checked_in_exports_are_the_exporters_output() -> None:
    arm = arm_on_rov()
    rust = ROOT / "crates/uwml-core/tests/exported/arm_on_rov.rs"
    c = ROOT / "crates/uwml-ffi/tests/c/exported_arm.h"
    regenerate = "the exporter's output changed: regenerate the files from uwml.io.export.to_rust(arm_on_rov(), 'f64' and 'f32') / to_c(arm_on_rov(), prefix='ARM')"
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
    leg = uwml.paper_leg()
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


# Issue 31: what the exporters write is what the firmware's constructor takes (the C API's caps,
# every number in its precision's range, names clear of the header's), refused before writing.
HEADER = ROOT / "crates/uwml-ffi/include/uwml.h"


def small_robot(*, length: float = 0.3, mass: float = 1.0, n: int = 1, segments: int = 1) -> uwml.Robot:
    """``n`` joints in a row, each link with ``segments`` circular segments of ``length``."""
    segment = uwml.Segment((0.0, 0.0, 0.0), (1.0, 0.0, 0.0), length, section="circular", diameter=0.05)
    links = [uwml.Link(mass, (0.1, 0.0, 0.0), 0.001, segments=(segment,) * segments) for _ in range(n)]
    return uwml.Robot([uwml.Joint((0.2, 0.0, 0.0), (0.0, 0.0, 1.0)) for _ in range(n)], links)


def test_the_c_caps_are_the_headers() -> None:
    from uwml.io import export

    defined = dict(re.findall(r"^#define (UWML_ROBOT_MAX_\w+) (\d+)$", HEADER.read_text(), re.MULTILINE))
    assert {name: int(value) for name, value in defined.items()} == {
        "UWML_ROBOT_MAX_JOINTS": export.C_MAX_JOINTS,
        "UWML_ROBOT_MAX_SEGMENTS": export.C_MAX_SEGMENTS,
        "UWML_ROBOT_MAX_LUMPED": export.C_MAX_LUMPED,
    }


def test_more_than_the_c_apis_caps_is_refused() -> None:
    with pytest.raises(ValueError, match=r"the C API's robot carries at most 16 joints \(UWML_ROBOT_MAX_JOINTS\), this one 17"):
        to_c(small_robot(n=17, segments=0))
    with pytest.raises(ValueError, match=r"the C API's robot carries at most 32 segments \(UWML_ROBOT_MAX_SEGMENTS\), this one 33"):
        to_c(small_robot(n=11, segments=3))
    assert "#define ROBOT_N_JOINTS 16u\n#define ROBOT_N_SEGMENTS 32u" in to_c(small_robot(n=16, segments=2))
    # Rust sizes its robot from the export: no caps.
    assert "pub const N_JOINTS: usize = 17;" in to_rust(small_robot(n=17, segments=2))


@pytest.mark.parametrize(
    "robot, precision, message",
    [
        # Issue 31: a 1e-300 m segment was written as 0.0f, which the constructor refuses.
        (
            small_robot(length=1e-300),
            "f32",
            r"segment 0 \(link 0\): length = 1e-300 cannot be written in f32: .*between 1\.17549e-38 and 3\.40282e\+38",
        ),
        (small_robot(length=1e-40), "f32", r"segment 0 \(link 0\): length = 1e-40 cannot be written in f32"),
        (small_robot(mass=1e-39), "f32", r"link 0: mass = 1e-39 cannot be written in f32"),
        (small_robot(length=5e-324), "f64", r"segment 0 \(link 0\): length = 5e-324 cannot be written in f64: .*between 2\.22507e-308"),
    ],
)
def test_a_number_its_precision_cannot_hold_is_refused_naming_it(robot: uwml.Robot, precision: str, message: str) -> None:
    with pytest.raises(ValueError, match=message):
        to_c(robot, precision)
    with pytest.raises(ValueError, match=message):
        to_rust(robot, precision)


def test_numbers_in_range_are_written_as_they_are() -> None:
    assert ".length = 1e-300," in to_c(small_robot(length=1e-300))
    assert ".length = 1.2e-38f," in to_c(small_robot(length=1.2e-38), "f32")
    assert "mass: 0.0," in to_rust(small_robot(mass=0.0), "f32")


@pytest.mark.parametrize("prefix", ["UWML", "UWML_", "UWML_ROBOT", "UWML_ERR"])
def test_a_c_prefix_in_the_headers_names_is_refused(prefix: str) -> None:
    with pytest.raises(ValueError, match=r"prefix must not be UWML or start with UWML_: uwml.h's own names are UWML_"):
        to_c(arm_on_rov(), prefix=prefix)


def test_uwml_export_reports_each_refusal_in_one_line(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    for robot, arguments, message in [
        (arm_on_rov(), ["--c", "--name", "UWML"], "prefix must not be UWML"),
        (small_robot(length=1e-300), ["--c", "--f32"], "segment 0 (link 0): length = 1e-300 cannot be written in f32"),
        (small_robot(length=1e-300), ["--rust", "--f32"], "segment 0 (link 0): length = 1e-300 cannot be written in f32"),
        (small_robot(n=17, segments=0), ["--c"], "at most 16 joints"),
    ]:
        path = tmp_path / "robot.toml"
        robot.save(path)
        assert main(["export", "--robot", str(path), *arguments]) == 2
        captured = capsys.readouterr()
        assert captured.out == "" and captured.err.startswith("uwml: error: ") and captured.err.count("\n") == 1, captured.err
        assert message in captured.err
    for name in ("UWMLX", "MY_UWML"):
        assert main(["export", "--c", "--name", name]) == 0
        assert f"#define {name}_BASE" in capsys.readouterr().out


def test_a_lumped_model_that_f32_cannot_hold_is_refused_in_f32() -> None:
    """A singular semi-definite added mass that is not diagonal rounds, in f32, to a slightly
    indefinite one, which the core refuses; axes a rotation only within the core's 1e-6 may not
    stay one in f32 arithmetic. Both are written in f64, refused in f32, naming the model."""
    rng = np.random.default_rng(7)
    a = rng.normal(size=(6, 3))
    singular = a @ a.T * 1e5
    robot = with_hull()
    assert robot.base is not None
    for model, message in [
        (
            uwml.LumpedModel(added_mass=0.5 * (singular + singular.T)),
            r"lumped model 0 \(base\) cannot be written in f32: rounded to f32, lumped.added_mass must be positive semi-definite",
        ),
        (
            uwml.LumpedModel(axes=[[1.0, 0.9e-6, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]),
            r"lumped model 0 \(base\) cannot be written in f32: its axes, rounded to f32, are a rotation only within 9e-07",
        ),
    ]:
        turned = uwml.Robot(robot.joints, robot.links, base=dataclasses.replace(robot.base, lumped=model), water=robot.water)
        to_c(turned)
        to_rust(turned)
        with pytest.raises(ValueError, match=message):
            to_c(turned, "f32")
        with pytest.raises(ValueError, match=message):
            to_rust(turned, "f32")
    # The usual hull (diagonal-dominant) is written in f32.
    assert "UwmlLumpedF32" in to_c(robot, "f32")


# The property of issue 31: whenever `uwml export --c` writes a header, the C API's constructor
# takes it. Robots drawn with edge values (tiny and huge lengths, masses and entries, numbers f32
# rounds to zero or a subnormal, joints and segments about the caps, lumped models that f32 may
# not hold, odd names and prefixes); every header written is compiled into one program (one
# translation unit per header, one compiler run) that builds each robot with
# uwml_robot_new_f64/_f32 and sets its lumped models, linked with the C ABI's static library.
#: Per robot, the tiny numbers its values may take (besides zero and the bounds): none, numbers
#: f32 holds only as zero or a subnormal, a float64 subnormal, f32's smallest normal numbers.
TINY = [(), (), (), (1e-300,), (1e-40, 1.1754942e-38), (5e-324,), (1.2e-38, 1e-30)]


def _edge(low: float, high: float, tiny: tuple[float, ...], *, zero: bool = True) -> st.SearchStrategy[float]:
    """Floats in [low, high], drawn often from the edges: the bounds, zero, ``tiny`` numbers."""
    edges = [x for x in (low, high, 1.0, 0.5) if low <= x <= high] + [0.0] * zero
    edges += [x for x in tiny if low <= x <= high] + [-x for x in tiny if low <= -x <= high]
    # Drawn floats stay off the tiny ones, which ``tiny`` alone gives (else nearly every robot
    # would hold one somewhere, and f32 refuse it).
    drawn = st.floats(low, high, allow_nan=False, allow_infinity=False, allow_subnormal=False).filter(lambda x: x == 0.0 or abs(x) >= 1e-30)
    return st.one_of(st.sampled_from(edges), drawn)


def _positive(high: float, tiny: tuple[float, ...]) -> st.SearchStrategy[float]:
    return _edge(0.0, high, tiny, zero=False).filter(lambda x: x > 0.0)


def _unit_vectors(tiny: tuple[float, ...]) -> st.SearchStrategy[tuple[float, float, float]]:
    def normalized(v: tuple[float, float, float]) -> tuple[float, float, float]:
        norm = float(np.linalg.norm(v))
        return (v[0] / norm, v[1] / norm, v[2] / norm)

    drawn = st.tuples(*[st.floats(-1, 1).filter(lambda x: x == 0.0 or abs(x) >= 1e-30)] * 3)
    drawn = drawn.filter(lambda v: float(np.linalg.norm(v)) > 0.1).map(normalized)
    fixed = [(1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0), (0.6, 0.0, 0.8)] + [(1.0, x, 0.0) for x in tiny]
    return st.one_of(st.sampled_from(fixed), drawn)


@st.composite
def _segment(draw: st.DrawFn, tiny: tuple[float, ...]) -> uwml.Segment:
    axis = draw(_unit_vectors(tiny))
    start = tuple(draw(_edge(-1e4, 1e4, tiny)) for _ in range(3))
    length = draw(_positive(1e4, tiny))
    cd, cm = draw(_edge(0.0, 1e3, tiny)), draw(_edge(0.0, 1e3, tiny))
    axial = {"cd_axial": draw(_edge(0.0, 1e3, tiny)), "axial_area": draw(st.none() | _edge(0.0, 1e8, tiny))}
    if draw(st.booleans()):
        # (A diameter whose area π d²/4 underflows to zero is refused by uwml.Robot itself.)
        diameter = draw(_positive(1e4, tiny).filter(lambda x: math.pi * x * x / 4.0 > 0.0))
        return uwml.Segment(start, axis, length, section="circular", diameter=diameter, cd=cd, cm=cm, **axial)
    a = np.asarray(axis)
    helper = np.eye(3)[int(np.argmin(np.abs(a)))]
    n0 = helper - a * float(a @ helper)
    n0 /= np.linalg.norm(n0)
    n1 = np.cross(a, n0)
    widths = (draw(_positive(1e4, tiny)), draw(_positive(1e4, tiny)))
    area = draw(_positive(1e8, tiny))
    return uwml.Segment(start, axis, length, normals=(n0, n1), widths=widths, area=area, cd=(cd, cd), cm=(cm, cm), **axial)


@st.composite
def _lumped(draw: st.DrawFn, tiny: tuple[float, ...]) -> uwml.LumpedModel:
    """Diagonal, positive definite or singular (rank 3, not diagonal) at scales up to the cap."""
    from scipy.spatial.transform import Rotation

    rng = np.random.default_rng(draw(st.integers(0, 2**32 - 1)))
    scale = draw(st.sampled_from([1e-3, 1.0, 50.0, 1e6, 1e12]))
    kind = draw(st.sampled_from(["diagonal", "definite", "singular"]))
    if kind == "diagonal":
        added = np.diag([draw(_edge(0.0, 1e12, tiny)) for _ in range(6)])
    else:
        a = rng.normal(size=(6, 6 if kind == "definite" else 3))
        added = a @ a.T + (np.eye(6) if kind == "definite" else 0.0)
        added = 0.5 * (added + added.T) * (scale / float(np.max(np.diag(added))) * 0.999)
    skew = rng.normal(size=(6, 6)) * min(scale, 1e9) * 1e-3
    return uwml.LumpedModel(
        point=draw(st.none() | st.tuples(*[_edge(-1e4, 1e4, tiny)] * 3)),
        added_mass=added,
        linear_damping=np.diag([draw(_edge(0.0, 1e12, tiny)) for _ in range(6)]) + (skew - skew.T),
        quadratic_damping=[draw(_edge(0.0, 1e12, tiny)) for _ in range(6)],
        axes=Rotation.random(random_state=rng).as_matrix() if draw(st.booleans()) else np.eye(3),
    )


@st.composite
def _body(draw: st.DrawFn, segments: int, lumped: bool, tiny: tuple[float, ...]) -> uwml.Link:
    return uwml.Link(
        draw(_edge(0.0, 1e9, tiny)),
        tuple(draw(_edge(-1e4, 1e4, tiny)) for _ in range(3)),
        draw(_edge(0.0, 1e6, tiny)),
        cob=draw(st.none() | st.tuples(*[_edge(-1e4, 1e4, tiny)] * 3)),
        segments=tuple(draw(_segment(tiny)) for _ in range(segments)),
        lumped=draw(_lumped(tiny)) if lumped and draw(st.integers(0, 3)) == 0 else None,
        name=draw(st.none() | st.text(min_size=1, max_size=6)),
    )


@st.composite
def firmware_robots(draw: st.DrawFn) -> uwml.Robot:
    """Robots about the C API's caps, with edge values (module comment above)."""
    tiny = draw(st.sampled_from(TINY))
    n = draw(st.integers(1, 18))
    per_link = draw(st.sampled_from([0, 1, 2, 3]))
    joints = [
        uwml.Joint(
            tuple(draw(_edge(-1e4, 1e4, tiny)) for _ in range(3)),
            draw(_unit_vectors(tiny)),
            parent=draw(st.integers(-1, i - 1)),
            kind=draw(st.sampled_from(["revolute", "prismatic"])),
            name=draw(st.none() | st.text(min_size=1, max_size=6).map(lambda text, i=i: f"{text}#{i}")),
        )
        for i in range(n)
    ]
    # Lumped models on up to 12 links and the base: more than the C API's 4 at times.
    links = [draw(_body(draw(st.integers(0, per_link)), i < 12, tiny)) for i in range(n)]
    links = [dataclasses.replace(link, name=None if link.name is None else f"{link.name}@{i}") for i, link in enumerate(links)]
    base = draw(st.none() | _body(draw(st.integers(0, 3)), True, tiny))
    water = uwml.Water(draw(_positive(1e5, tiny)), draw(_edge(0.0, 1e3, tiny)))
    return uwml.Robot(joints, links, base=base, water=water)


_PREFIXES = st.one_of(
    st.from_regex(r"[A-Z_][A-Z0-9_]{0,10}", fullmatch=True),
    st.from_regex(r"[A-Z][A-Z0-9_]{0,10}", fullmatch=True),
    st.sampled_from(["UWML", "UWML_ROBOT", "UWMLX", "_ARM", "ROBOT", "R", "UWML_EXPORT", "NULL", "EXPORT_ROBOT"]),
)


#: Half the profile's examples (the fast profile's 200: about 100 robots, half of them written).
EXAMPLES = max(50, settings.default.max_examples // 2)


def _c_abi_library() -> Path:
    """The C ABI's static library, built by cargo for this checkout (the C API's own tests link
    the same)."""
    import json

    metadata = _run(["cargo", "metadata", "--format-version", "1", "--no-deps"], ROOT)
    assert metadata.returncode == 0, metadata.stderr
    built = subprocess.run(["cargo", "build", "-q", "-p", "uwml-ffi"], cwd=ROOT, capture_output=True, text=True, timeout=1800, check=False)
    assert built.returncode == 0, built.stderr
    return Path(json.loads(metadata.stdout)["target_directory"]) / "debug" / "libuwml_ffi.a"


def _c_check(k: int, prefix: str, precision: str, lumped: bool) -> str:
    """A translation unit of header ``k`` alone (it must stand on its own: NULL, the C API's
    types): builds the robot, sets its lumped models; 0, or 1 (new) or 2 (set_lumped) with
    ``*error``."""
    t = precision.upper()
    set_lumped = (
        f"    if (uwml_robot_set_lumped_{precision}(&robot, {prefix}_LUMPED, {prefix}_N_LUMPED, error) != UWML_OK) return 2;\n"
        if lumped
        else ""
    )
    return (
        f'#include "h{k}.h"\nint check{k}(UwmlError *error);\nint check{k}(UwmlError *error) {{\n'
        f"    static UwmlRobot{t} robot;\n"
        f"    if (uwml_robot_new_{precision}(&robot, {prefix}_JOINTS, {prefix}_N_JOINTS, {prefix}_LINKS, {prefix}_BASE,\n"
        f"            {prefix}_SEGMENTS, {prefix}_N_SEGMENTS, {prefix}_WATER_DENSITY, {prefix}_GRAVITY, error) != UWML_OK) return 1;\n"
        f"{set_lumped}    return 0;\n}}\n"
    )


@pytest.mark.skipif(shutil.which("cc") is None or shutil.which("cargo") is None, reason="needs cc and cargo to build against the C ABI")
@pytest.mark.filterwarnings("ignore::uwml.PlausibilityWarning")  # edge values on purpose
def test_every_header_export_writes_is_one_the_c_abi_takes(tmp_path: Path) -> None:
    from uwml.io import export

    written: list[tuple[str, str, bool, uwml.Robot]] = []
    refused: dict[str, int] = {}

    @settings(max_examples=EXAMPLES)
    @given(robot=firmware_robots(), prefix=_PREFIXES, precision=st.sampled_from(["f32", "f64"]))
    def draw(robot: uwml.Robot, prefix: str, precision: str) -> None:
        try:
            header = to_c(robot, precision, prefix=prefix)
        except ValueError as exc:
            reason = "a number" if "cannot be written" in str(exc) else re.sub(r"\d+|\(.*", "N", str(exc).split(":")[0])
            refused[reason] = refused.get(reason, 0) + 1
            # The Rust export refuses the same robots but for the C API's caps and names.
            if "C API" not in str(exc) and "prefix" not in str(exc):
                with pytest.raises(ValueError):
                    to_rust(robot, precision)
            return
        # Written in C: written in Rust too (it has no caps and no prefix), every literal a
        # normal number of the precision or zero.
        rust = to_rust(robot, precision)
        smallest, largest = export._RANGE[precision]
        for text in re.findall(r"(?<![\w.])-?\d+\.\d*(?:e[-+]?\d+)?", rust):
            assert float(text) == 0.0 or smallest <= abs(float(text)) <= largest, text
        k = len(written)
        (tmp_path / f"h{k}.h").write_text(header)
        (tmp_path / f"u{k}.c").write_text(_c_check(k, prefix, precision, "_N_LUMPED" in header))
        written.append((prefix, precision, "_N_LUMPED" in header, robot))

    draw()
    kinds = {(p, lumped): sum(1 for _, q, has, _ in written if (q, has) == (p, lumped)) for p in ("f64", "f32") for lumped in (False, True)}
    assert len(written) >= 20 and kinds["f64", False] + kinds["f64", True] >= 5 and kinds["f32", False] + kinds["f32", True] >= 5, (
        f"too few headers written to test the property: {kinds}; refused: {refused}"
    )
    n = len(written)
    declarations = "".join(f"int check{k}(UwmlError *error);\n" for k in range(n))
    calls = "".join(f"    report({k}, check{k}(&error), &error, &failed);\n" for k in range(n))
    (tmp_path / "main.c").write_text(
        f'#include <stdio.h>\n#include "uwml.h"\n{declarations}'
        "static void report(int k, int stage, const UwmlError *error, int *failed) {\n"
        '    if (stage != 0) { printf("%d %s %d %s %lld\\n", k, stage == 1 ? "new" : "set_lumped", (int)error->code, error->field, (long long)error->index); ++*failed; }\n'
        "}\n"
        f'int main(void) {{\n    UwmlError error;\n    int failed = 0;\n{calls}    printf("%d failed\\n", failed);\n    return failed != 0;\n}}\n'
    )
    library = _c_abi_library()
    compiler = ["cc", "-std=c11", "-Wall", "-Wextra", "-Werror", "-pedantic", "-I", str(ROOT / "crates/uwml-ffi/include"), "-I", "."]
    built = _run([*compiler, "main.c", *(f"u{k}.c" for k in range(n)), str(library), "-lm", "-o", "check"], tmp_path)
    assert built.returncode == 0, built.stderr[:4000]
    ran = _run(["./check"], tmp_path)
    failures = [line for line in ran.stdout.splitlines() if not line.endswith("failed")]
    details = [f"{line}: prefix {written[int(line.split()[0])][0]}, {written[int(line.split()[0])][1]}" for line in failures[:5]]
    assert ran.returncode == 0 and not failures, "\n".join(details)
    print(f"{n} headers written and taken by the C API ((precision, with lumped models): count {kinds}); refused: {refused}")
