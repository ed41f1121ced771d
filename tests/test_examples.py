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


@pytest.mark.parametrize(
    ("example", "script", "log"), [("my_arm", "make_water_log.py", "water.csv"), ("bluerov2", "make_dive_log.py", "dive.csv")]
)
def test_the_shipped_logs_are_their_scripts_and_give_their_coefficients_back(example: str, script: str, log: str, tmp_path: Path) -> None:
    """The logs are what their scripts write (to rounding: another machine's MuJoCo may differ in
    the last bits), and a fit of each gives back what it was made with."""
    pytest.importorskip("mujoco")
    import subprocess
    import sys

    import numpy as np
    from uwml import fit
    from uwml.io.logs import read_log

    subprocess.run([sys.executable, str(uwml.examples.path(example, script))], cwd=tmp_path, check=True, capture_output=True)
    shipped, made = read_log(uwml.examples.path(example, log)), read_log(tmp_path / log)
    for name in ("time", "q", "qd", "qdd", "tau", "base_twist", "base_twist_dot", "thruster_commands"):
        a, b = getattr(shipped, name), getattr(made, name)
        assert (a is None) == (b is None), name
        if a is not None:
            np.testing.assert_allclose(a, b, rtol=1e-9, atol=1e-12, err_msg=name)
    folder = uwml.examples.path(example)
    if example == "my_arm":
        result = fit.hydro_from_water_logs(folder / log, folder / "my_arm.urdf", folder / "my_arm.hydro.toml", per="leg")
        assert abs(result.params["cd"] - 1.1) < 3 * result.stderr["cd"] and abs(result.params["cm"] - 0.9) < 3 * result.stderr["cm"]
    else:
        zero = ["base.linear_damping[1][1]", "base.linear_damping[3][3]", "base.linear_damping[5][5]"]
        result = fit.hull_from_free_running(folder / log, folder / "bluerov2_arm.urdf", folder / "bluerov2_arm.hydro.toml", hold=zero)
        published = {"base.added_mass[2][2]": 18.68, "base.linear_damping[0][0]": 13.7, "base.quadratic_damping[1]": 217.0}
        for name, value in published.items():
            assert result.params[name] == pytest.approx(value, rel=1e-6), name
