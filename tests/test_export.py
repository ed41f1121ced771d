"""``uwml export``: the robot's model as Rust constants and C initializers. The checked-in outputs
for the arm of ``uwml.examples.arm_on_rov`` are what the exporter writes today (so the Rust test
``crates/uwml-core/tests/exported.rs`` and the C program ``crates/uwml-ffi/tests/c/exported.c``
compile and evaluate exactly this output); every literal reads back to the model's number."""

import re
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
