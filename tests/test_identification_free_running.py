"""A hull from free-running logs (``fit.hull_from_free_running``, ``uwml fit hull``; docs/model.md
section 13, "13.3 Identifying a vehicle"): the BlueROV2 of examples/bluerov2 floating in a
``uwml.sim.mujoco.Simulation``, its eight thrusters driven by sums of sines, the arm held still,
the pose, twist and commands logged; the fit gives the published hull back."""

from __future__ import annotations

import json
import re
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest
import uwml
from uwml import fit
from uwml.cli import main
from uwml.io.logs import Log, write_log
from uwml.sim import synthetic_logs
from uwml.sim.mujoco import Simulation

ROOT = Path(__file__).resolve().parents[1]
URDF, HYDRO = ROOT / "examples/bluerov2/bluerov2_arm.urdf", ROOT / "examples/bluerov2/bluerov2_arm.hydro.toml"
#: The published hull (magnitudes), (x, y, z, roll, pitch, yaw), and its buoyancy ρV [kg], ρV r_B [kg·m].
PUBLISHED = {
    "added_mass": [6.36, 7.12, 18.68, 0.189, 0.135, 0.222],
    "linear_damping": [13.7, 0.0, 33.0, 0.0, 0.8, 0.0],
    "quadratic_damping": [141.0, 217.0, 190.0, 1.19, 0.47, 1.5],
}
BUOYANCY = {"base.rho_volume": 13.4, "base.rho_volume_cob[0]": 0.0, "base.rho_volume_cob[1]": 0.0, "base.rho_volume_cob[2]": 0.134}
#: The linear dampings the published model leaves at zero: held where noise would make them ±.
ZERO = ["base.linear_damping[1][1]", "base.linear_damping[3][3]", "base.linear_damping[5][5]"]


def truth(name: str) -> float:
    if name in BUOYANCY:
        return BUOYANCY[name]
    family, index = re.fullmatch(r"base\.(\w+)\[(\d)\].*", name).groups()  # type: ignore[union-attr]
    return PUBLISHED[family][int(index)]


def free_running(seconds: float = 20.0, timestep: float = 0.002, every: int = 5, logged_noise: float = 0.0) -> Log:
    """The vehicle on its thrusters (:func:`uwml.sim.synthetic_logs.free_running`), its hull the
    published one; ``logged_noise`` on the logged commands only (the fit's data error alone)."""
    return synthetic_logs.free_running(URDF, HYDRO, seconds=seconds, timestep=timestep, every=every, logged_noise=logged_noise)


@pytest.fixture(scope="module")
def exact() -> Log:
    return free_running()


def test_noise_free_logs_give_the_published_hull_and_its_buoyancy_back(exact: Log) -> None:
    """Exactly what the simulation did (its rates its own accelerations): to 1e-8, the zeros to
    1e-9 N·s/m, and no warning for a zero fitted as ±1e-13."""
    result = fit.hull_from_free_running(exact, URDF, HYDRO, hydrostatics=True)
    assert len(result.var_names) == 22 and not result.fixed and not result.negative
    for name in result.var_names:
        assert result.params[name] == pytest.approx(truth(name), rel=1e-8, abs=1e-9), name
    model = result.lumped_model()
    assert np.allclose(np.diag(np.asarray(model.added_mass)), PUBLISHED["added_mass"], rtol=1e-8)
    assert model.point == (0.0, 0.0, 0.01)
    report = result.fit_report()
    assert "thrusters          = 8 (commands u1 … u8)" in report and "(fixed)" not in report
    assert result.summary()["model"] == "hull"


def test_held_terms_keep_the_description_s_values(exact: Log) -> None:
    result = fit.hull_from_free_running(exact, URDF, HYDRO, terms=["added_mass"], hold=["base.added_mass[5][5]"])
    assert result.var_names == tuple(f"base.added_mass[{i}][{i}]" for i in range(5))
    assert result.fixed == {"base.added_mass[5][5]": 0.222} and result.params["base.added_mass[5][5]"] == 0.222
    assert "base.added_mass[5][5]: 0.222 (fixed)" in result.fit_report()
    for name in result.var_names:
        assert result.params[name] == pytest.approx(truth(name), rel=1e-8), name


def test_noisy_commands_give_the_hull_within_its_error_bars() -> None:
    """0.02 of noise on the logged commands (about 1 N of thrust per thruster): every term within 4
    standard errors."""
    result = fit.hull_from_free_running(free_running(logged_noise=0.02), URDF, HYDRO, hold=ZERO)
    for name in result.var_names:
        error = result.stderr[name]
        assert error is not None and abs(result.params[name] - truth(name)) < 4.0 * error, (name, result.params[name], error)


def test_rates_estimated_by_the_smoothing_fit_give_the_hull_within_one_percent(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    """A log of pose, twist and commands alone (200 Hz, from a simulation at 0.5 ms so that
    Euler's lag of half a step stays far below 1 %), through ``uwml fit hull``: ν̇ and the arm's
    rates estimated by the Savitzky-Golay fit."""
    log = free_running(seconds=12.0, timestep=0.0005, every=10)
    path = tmp_path / "free.csv"
    write_log(replace(log, base_twist_dot=None, qd=None, qdd=None, base_position=None), path)
    held = ",".join(ZERO)
    assert main(["fit", "hull", str(path), "--robot", str(URDF), "--hydro", str(HYDRO), "--hold", held, "--json"]) == 0
    summary = json.loads(capsys.readouterr().out)
    assert summary["model"] == "hull" and summary["fixed"] == dict.fromkeys(ZERO, 0.0)
    for name in summary["var_names"]:
        assert summary["params"][name] == pytest.approx(truth(name), rel=0.01), name


def test_a_negative_damping_is_named(exact: Log, tmp_path: Path) -> None:
    """The sway's quadratic damping held at twice its value: the linear one goes negative to
    make up for it, and the warning and the result say which."""
    hydro = tmp_path / "doubled.hydro.toml"
    hydro.write_text(HYDRO.read_text(encoding="utf-8").replace("[141.0, 217.0,", "[141.0, 434.0,"), encoding="utf-8")
    with pytest.warns(
        uwml.PlausibilityWarning, match=r"hull terms came out negative, which is not physical: base\.linear_damping\[1\]\[1\] = -"
    ):
        result = fit.hull_from_free_running(exact, URDF, hydro, hold=["base.quadratic_damping[1]", *ZERO[1:]])
    assert result.negative == ("base.linear_damping[1][1]",)
    assert "##  Warning: negative, not physical: base.linear_damping[1][1]" in result.fit_report()


def surge_only(speed: np.ndarray) -> Log:
    """A log of the vehicle upright, moving in surge alone at ``speed`` (its rate estimated)."""
    n = len(speed)
    twist = np.zeros((n, 6))
    twist[:, 0] = speed
    return Log(
        time=np.arange(n) / 100.0, q=np.zeros((n, 2)), base_orientation=np.tile([1.0, 0.0, 0.0, 0.0], (n, 1)),
        base_twist=twist, thruster_commands=np.zeros((n, 8)), source="surge",
    )  # fmt: skip


def test_terms_the_data_do_not_determine_are_refused_by_name() -> None:
    t = np.arange(1000) / 100.0
    with pytest.raises(
        ValueError,
        match=r"surge: the data do not determine base\.added_mass\[1\]\[1\], .*base\.quadratic_damping\[5\]: their regressors are zero",
    ):
        fit.hull_from_free_running(surge_only(0.3 * np.sin(t)), URDF, HYDRO)
    # At one speed both ways, |u| u = 0.5 u: linear and quadratic surge damping are collinear.
    others = [
        f"base.{family}[{i}]" + ("" if family == "quadratic_damping" else f"[{i}]")
        for family in ("linear_damping", "quadratic_damping")
        for i in range(1, 6)
    ]
    with pytest.raises(
        ValueError, match=r"surge: the data do not determine base\.(linear|quadratic)_damping.*\[0\].*\[0\].* apart: .*nearly collinear"
    ):
        fit.hull_from_free_running(
            surge_only(np.full(1000, 0.5) * np.sign(np.sin(t) + 1e-9)),
            URDF,
            HYDRO,
            terms=["linear_damping", "quadratic_damping"],
            hold=others,
        )


def test_refusals(exact: Log) -> None:
    cases = [
        (replace(exact, thruster_commands=None), r"column 'u1': missing column \(the thruster commands u1 … u8, one per thruster of the description: front_right"),
        (replace(exact, thruster_commands=exact.thruster_commands[:, :7]), r"column 'u8': the log has 7 thruster commands \(u1 … u7\), the description 8 thrusters"),
        (replace(exact, base_twist=None, base_twist_dot=None), r"column 'u': missing column \(a free-running fit needs the vehicle's twist"),
        (replace(exact, base_orientation=None), r"column 'qw': missing column \(a free-running fit needs its orientation"),
    ]  # fmt: skip
    for log, message in cases:
        with pytest.raises(ValueError, match=r"free-running: row 1 \(header\), " + message):
            fit.hull_from_free_running(log, URDF, HYDRO)
    with pytest.raises(ValueError, match=r"hold: 'base\.added_mass\[0\]\[1\]' not among the terms fitted"):
        fit.hull_from_free_running(exact, URDF, HYDRO, hold=["base.added_mass[0][1]"])
    with pytest.raises(ValueError, match="terms must be some of added_mass, linear_damping, quadratic_damping"):
        fit.hull_from_free_running(exact, URDF, HYDRO, terms=["drag"])
    with pytest.raises(ValueError, match="the hydrostatic terms are held all together or fitted all together"):
        fit.hull_from_free_running(exact, URDF, HYDRO, hydrostatics=True, hold=["base.rho_volume"])
    arm = replace(exact, q=np.zeros((exact.n_samples, 3)), qd=None, qdd=None)
    with pytest.raises(ValueError, match="the description's base has no lumped model"):
        fit.hull_from_free_running(arm, ROOT / "tests/data/arm.urdf", ROOT / "tests/data/arm.hydro.toml")


def test_the_thrust_of_lagging_thrusters_is_the_simulation_s(tmp_path: Path) -> None:
    """With a time constant, the fit's thrust from the logged commands (each held until the next
    sample, the lag advanced exactly) is the simulation's, step by step, to 1e-12."""
    from uwml.fit.thrust_wrench import thrust, thrust_wrench

    hydro = tmp_path / "lagging.hydro.toml"
    hydro.write_text(
        HYDRO.read_text(encoding="utf-8").replace("max_reverse = 40.2\n", "max_reverse = 40.2\ntime_constant = 0.05\n"), encoding="utf-8"
    )
    sim = Simulation.from_file(URDF, hydro)
    steps, h = 300, sim.model.opt.timestep
    commands = np.zeros((steps, 8))
    commands[1:] = 0.8 * np.sin(np.arange(1, steps)[:, None] * h * np.linspace(2.0, 9.0, 8))
    simulated = np.zeros_like(commands)
    for k in range(steps):
        sim.command_thrusters(commands[k])
        simulated[k] = sim.thrust
        sim.step()
    log = Log(time=np.arange(steps) * h, q=np.zeros((steps, 2)), thruster_commands=commands)
    assert all(t.time_constant == 0.05 for _, t in sim.robot.thrusters)
    np.testing.assert_allclose(thrust(log, sim.robot), simulated, rtol=0.0, atol=1e-12)
    np.testing.assert_allclose(thrust_wrench(log, sim.robot), simulated @ sim.robot.thruster_allocation().T, atol=1e-12)
