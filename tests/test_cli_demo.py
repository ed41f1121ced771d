"""``uwml demo`` (the paper's leg along a gait-like motion, from the console script and from
``python -m uwml``): its table's torques are the numpy reference's to the decimals printed; bad
arguments name the option, without a traceback."""

import os
import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
import uwml
import uwml.cli
from uwml import reference as ref
from uwml.paper.analysis import gait_like_motion, torque_figure

RHO, G = 1000.0, 9.81
PAPER = uwml.paper_leg()


def _run(command: list[str]) -> subprocess.CompletedProcess:
    env = {**os.environ, "PYTHONIOENCODING": "utf-8", "PYTHONWARNINGS": "error"}
    return subprocess.run(command, capture_output=True, text=True, encoding="utf-8", env=env, timeout=120, check=False)


def _console_script() -> str:
    script = shutil.which("uwml", path=str(Path(sys.executable).parent)) or shutil.which("uwml")
    assert script is not None, "the `uwml` console script is not installed"
    return script


def _check_demo_output(stdout: str, samples: int, period: float, cd: float, cm: float, density: float) -> None:
    """Every table row parses as 8 numbers, and the torques are the reference's, to the 3
    decimals printed; the RMS lines too."""
    rows = []
    rms = {}
    for line in stdout.splitlines():
        tokens = line.split()
        try:
            numbers = [float(t) for t in tokens]
        except ValueError:
            numbers = None
        if numbers is not None and len(numbers) == 8:
            rows.append(numbers)
        elif tokens and tokens[0] in ("drag", "added_mass", "buoyancy"):
            rms[tokens[0]] = [float(t) for t in tokens[1:]]
    rows = np.array(rows)
    assert rows.shape == (samples * 3, 8), stdout
    t, q, qd, qdd = gait_like_motion(samples, period)
    expected = ref.hydro(PAPER.joints, PAPER.links, q, qd, qdd, cd=cd, cm=cm, density=density, gravity=G)
    half_digit = 0.5e-3 + 1e-9
    np.testing.assert_allclose(rows[:, 0], np.repeat(t, 3), atol=0.5e-2 + 1e-9)
    np.testing.assert_array_equal(rows[:, 1], np.tile([1, 2, 3], samples))
    for column, key in ((4, "drag"), (5, "added_mass"), (6, "buoyancy"), (7, "total")):
        np.testing.assert_allclose(rows[:, column], expected[key].ravel(), rtol=0, atol=half_digit, err_msg=key)
    assert set(rms) == {"drag", "added_mass", "buoyancy"}, stdout
    for key, values in rms.items():
        np.testing.assert_allclose(values, np.sqrt(np.mean(expected[key] ** 2, axis=0)), rtol=0, atol=half_digit, err_msg=key)


def test_cli_module_demo() -> None:
    result = _run([sys.executable, "-m", "uwml", "demo"])
    assert result.returncode == 0, result.stderr
    _check_demo_output(result.stdout, samples=9, period=2.0, cd=2.2, cm=0.5, density=RHO)


def test_cli_console_script_with_options() -> None:
    result = _run([_console_script(), "demo", "--samples", "5", "--period", "3", "--cd", "1.5", "--cm", "0.8", "--density", "1025"])
    assert result.returncode == 0, result.stderr
    _check_demo_output(result.stdout, samples=5, period=3.0, cd=1.5, cm=0.8, density=1025.0)


@pytest.mark.parametrize(
    "args, option",
    [(["--samples", "1"], "--samples"), (["--cd", "-1"], "--cd")],
    ids=["samples 1", "cd -1"],
)
def test_cli_rejects_bad_arguments_in_a_subprocess(args: list[str], option: str) -> None:
    result = _run([sys.executable, "-m", "uwml", "demo", *args])
    assert result.returncode != 0
    assert option in result.stderr, result.stderr
    assert "Traceback" not in result.stderr, result.stderr


@pytest.mark.parametrize(
    "args, option",
    [
        (["demo", "--samples", "0"], "--samples"),
        (["demo", "--samples", "2.5"], "--samples"),
        (["demo", "--samples", "many"], "--samples"),
        (["demo", "--period", "0"], "--period"),
        (["demo", "--period", "nan"], "--period"),
        (["demo", "--cm", "-0.5"], "--cm"),
        (["demo", "--cd", "inf"], "--cd"),
        (["demo", "--density", "-1000"], "--density"),
        (["demo", "--density", "water"], "--density"),
        (["demo", "--unknown"], "--unknown"),
        (["fly"], "fly"),
        ([], "command"),
    ],
)
def test_cli_rejects_bad_arguments(args: list[str], option: str, capsys: pytest.CaptureFixture[str]) -> None:
    with pytest.raises(SystemExit) as exit_info:
        uwml.cli.main(args)
    assert exit_info.value.code not in (0, None)
    assert option in capsys.readouterr().err


def test_fig8_puts_buoyancy_on_its_own_scale() -> None:
    """Joint 2's buoyancy (tens of N·m) and the drag and added mass (a few) on separate axes: one
    row per joint, drag and added mass on the left, buoyancy and the total on the right."""
    t = np.linspace(0.0, 1.0, 50)
    q = np.stack([0.3 * np.sin(2 * np.pi * t), 0.5 + 0.4 * np.sin(2 * np.pi * t), -1.0 + 0.3 * np.cos(2 * np.pi * t)], axis=1)
    qd = np.gradient(q, t, axis=0)
    tau = PAPER.hydro(q, qd, np.gradient(qd, t, axis=0))
    figure = torque_figure(t, tau)
    axes = np.asarray(figure.axes).reshape(3, 2)
    for j in range(3):
        left = {line.get_label() for line in axes[j, 0].get_lines()}
        right = {line.get_label() for line in axes[j, 1].get_lines()}
        assert left == {"drag", "added mass"} and right == {"buoyancy", "total"}
        # The left axis is scaled to the drag and the added mass, not to the buoyancy.
        low, high = axes[j, 0].get_ylim()
        reach = max(np.abs(tau.drag[:, j]).max(), np.abs(tau.added_mass[:, j]).max())
        assert high - low < 3.0 * reach or reach == 0.0
