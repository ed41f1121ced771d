"""The examples that ship with the package (``uwml.examples``): found where the package is
installed (from any folder), their robots, and ``uwml examples DIR`` copying them for the
documentation's command lines."""

from __future__ import annotations

from pathlib import Path

import pytest
import uwml.examples
from uwml.cli import main


def test_every_example_is_found_in_the_installed_package() -> None:
    assert {"bluerov2", "hydro.toml", "my_arm", "study.toml", "vehicle_study.toml"} <= set(uwml.examples.names())
    package = Path(uwml.examples.__file__).parent
    for name in uwml.examples.names():
        assert uwml.examples.path(name).resolve().is_relative_to(package.resolve())
    assert uwml.examples.path("bluerov2", "bluerov2_arm.urdf").is_file()
    with pytest.raises(ValueError, match="no example 'nautilus'; the examples are bluerov2, hydro.toml"):
        uwml.examples.path("nautilus")
    with pytest.raises(ValueError, match="example 'my_arm' has no 'arm.urdf'"):
        uwml.examples.path("my_arm", "arm.urdf")


def test_the_example_robots() -> None:
    pytest.importorskip("mujoco")
    rov = uwml.examples.bluerov2()
    assert rov.n_joints == 2 and len(rov.thrusters) == 8 and rov.base is not None and rov.base.lumped is not None
    assert uwml.examples.my_arm().n_joints == 2
    assert uwml.examples.arm_on_rov().n_joints == 7


def test_uwml_examples_copies_them_and_keeps_what_is_there(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["examples", str(tmp_path)]) == 0
    copied = tmp_path / "examples"
    assert sorted(p.name for p in copied.iterdir()) == list(uwml.examples.names())
    urdf = copied / "my_arm" / "my_arm.urdf"
    assert urdf.read_bytes() == uwml.examples.path("my_arm", "my_arm.urdf").read_bytes()
    urdf.write_text("mine")
    assert main(["examples", str(tmp_path)]) == 2
    assert "already holds bluerov2" in capsys.readouterr().err and urdf.read_text() == "mine"
    assert main(["examples", str(tmp_path), "--force"]) == 0
    assert urdf.read_bytes() == uwml.examples.path("my_arm", "my_arm.urdf").read_bytes()
