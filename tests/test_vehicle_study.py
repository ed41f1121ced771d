"""Studies of one's own floating vehicle and scenarios of one's own (issue 33 point 4; docs/scale.md):
the thrusters' curves inverted (``uwml.sim.thrust_inverse``), the BlueROV2 example holding
station through its thrusters while its arm moves (``kind = "vehicle"``,
``uwml.sim.station_keeping``), a function named in the study file (``kind = "custom"``,
``uwml.study.custom``) run serially and on Ray, and what is refused."""

import math
import os
import shutil
from pathlib import Path

import numpy as np
import pytest
from uwml import ThrustCurve, Thruster, study
from uwml.study import runner
from uwml.study.store import StudyError

ROOT = Path(__file__).resolve().parents[1]
BLUEROV2 = ROOT / "examples" / "bluerov2"
TESTS = Path(__file__).resolve().parent


def write(tmp_path: Path, text: str, name: str = "study.toml") -> Path:
    path = tmp_path / name
    path.write_text(text)
    return path


def rows(out: Path) -> list[dict]:
    return study.read_results(out).to_pylist()


# --- the thrust curves inverted --------------------------------------------------------------


CURVES = {
    "t200": Thruster((0, 0, 0), (1, 0, 0), ThrustCurve.t200(), max_forward=51.5, max_reverse=40.2),
    "t200 held to 30 N": Thruster((0, 0, 0), (1, 0, 0), ThrustCurve.t200(), max_forward=30.0, max_reverse=20.0),
    "table with a dead band": Thruster((0, 0, 0), (1, 0, 0), ThrustCurve.table([-1.0, -0.1, 0.1, 1.0], [-30.0, 0.0, 0.0, 45.0])),
    "table crossing zero off 0": Thruster((0, 0, 0), (1, 0, 0), ThrustCurve.table([1100.0, 1500.0, 1900.0], [-35.0, 5.0, 50.0])),
    "cubic past a dead band": Thruster(
        (0, 0, 0),
        (1, 0, 0),
        ThrustCurve.polynomial([0.0, 10.0, 0.0, 40.0], [0.0, 8.0, 0.0, 20.0], 0.05),
        max_forward=40.0,
        max_reverse=25.0,
    ),
}


@pytest.mark.parametrize("name", list(CURVES))
def test_a_thrust_curve_inverted_gives_back_the_thrust_within_its_range_and_saturates_beyond(name: str) -> None:
    from uwml.sim.thrust_inverse import ThrustInverse

    thruster = CURVES[name]
    inverse = ThrustInverse(thruster)
    limits = {"t200": (-40.2, 51.5), "t200 held to 30 N": (-20.0, 30.0), "table with a dead band": (-30.0, 45.0)}
    if name in limits:
        assert (inverse.low, inverse.high) == pytest.approx(limits[name], abs=1e-9)
    inside = np.linspace(inverse.low, inverse.high, 4001)
    commands = inverse.command(inside)
    # Linear interpolation of the samples: exact for a table, within 1e-5 N for a polynomial.
    assert np.max(np.abs(thruster.thrust(commands) - inside)) < 1e-5
    beyond = np.array([inverse.high + 1.0, inverse.high * 10.0, inverse.low - 1.0, inverse.low * 10.0])
    assert thruster.thrust(inverse.command(beyond)) == pytest.approx([inverse.high] * 2 + [inverse.low] * 2, abs=1e-5)
    # Zero thrust is the command of zero thrust nearest 0; a command never leaves the curve's span.
    assert thruster.thrust(inverse.command(0.0)) == pytest.approx(0.0, abs=1e-9)
    if name == "t200":
        assert inverse.command(0.0) == 0.0 and inverse.command(1.0) > 0.0625  # past the dead band
        assert inverse.command(51.5) == pytest.approx(1.0, abs=1e-12) and inverse.command(-40.2) == pytest.approx(-1.0, abs=1e-12)
    if name == "table crossing zero off 0":
        assert inverse.command(0.0) == pytest.approx(1450.0)  # 1100 + 400 · 35 / 40


def test_several_thrusters_inverted_at_once_agree_with_each_alone() -> None:
    from uwml.sim.thrust_inverse import ThrustInverses

    thrusters = list(CURVES.values())
    inverses = ThrustInverses(thrusters)
    rng = np.random.default_rng(0)
    for _ in range(200):
        thrust = rng.uniform(-60.0, 60.0, len(thrusters))
        together = inverses.commands(thrust)
        alone = [float(i.command(t)) for i, t in zip(inverses.inverses, thrust, strict=True)]
        assert together == pytest.approx(alone, abs=1e-9)


def test_a_curve_that_cannot_be_inverted_is_refused_naming_the_thruster() -> None:
    from uwml.sim.thrust_inverse import ThrustInverse, ThrustInverses

    with pytest.raises(ValueError, match="thruster 1 'aft': its polynomial curve has no finite max_forward"):
        ThrustInverses([CURVES["t200"], Thruster((0, 0, 0), (1, 0, 0), ThrustCurve.t200(), max_reverse=40.0, name="aft")])
    falling = Thruster((0, 0, 0), (1, 0, 0), ThrustCurve.table([-1.0, 0.0, 0.5, 1.0], [-10.0, 0.0, 20.0, 15.0]))
    with pytest.raises(ValueError, match="its thrust falls from 20 N at command 0.5 to 15 N at 1"):
        ThrustInverse(falling)


# --- a vehicle of one's own -------------------------------------------------------------------

VEHICLE_STUDY = f"""
[scenario]
kind = "vehicle"
robot = "{BLUEROV2 / "bluerov2_arm.urdf"}"
hydro = "{BLUEROV2 / "bluerov2_arm.hydro.toml"}"
duration = 2.0
current = 0.3
payload = 0.2
amplitude = 0.5

[parameters]
station_keeping = ["off", "pd"]
feedforward = ["none", "uwml"]
"""


def test_the_bluerov2_holds_station_better_with_uwmls_feedforward_and_drifts_without_station_keeping(tmp_path: Path) -> None:
    config = study.load(write(tmp_path, VEHICLE_STUDY))
    assert config.metrics[:6] == ("rms_drift", "max_drift", "rms_roll", "max_roll", "rms_pitch", "max_pitch")
    outcome = study.run_study(config, tmp_path / "out", serial=True)
    assert outcome.ran == 4 and outcome.errors == 0
    table = {(r["station_keeping"], r["feedforward"]): r for r in rows(tmp_path / "out")}
    adrift, pd, fed = table[("off", "none")], table[("pd", "none")], table[("pd", "uwml")]
    # Measured (2 s, 0.3 m/s of current, 0.2 kg the controller does not know): adrift 0.246 m RMS
    # (0.483 m at most), PD 0.0501 m (0.0723 m), PD with uwml's feedforward 0.00465 m (0.00616 m);
    # pitch 28.2°, 9.9° and 7.6° RMS.
    assert adrift["rms_drift"] > 3.0 * pd["rms_drift"] and adrift["max_drift"] > 4.0 * pd["max_drift"]
    assert fed["rms_drift"] < 0.25 * pd["rms_drift"] and fed["max_drift"] < 0.25 * pd["max_drift"]
    assert fed["rms_pitch"] < 0.9 * pd["rms_pitch"] < adrift["rms_pitch"]
    # Adrift, the thrusters are idle (the feedforward too); holding station, they push, unsaturated.
    assert adrift["mean_thrust"] == adrift["thrust_energy"] == 0.0 and table[("off", "uwml")]["rms_drift"] == adrift["rms_drift"]
    assert 0.0 < pd["mean_thrust"] <= pd["peak_thrust"] < 51.5 and fed["saturation"] == pd["saturation"] == 0.0


def test_the_feedforward_of_the_model_the_plant_is_holds_the_vehicle_still() -> None:
    """With nothing unknown to the controller, the feedforward is the whole wrench on the vehicle:
    it stays put to rounding, so the station keeping's frames, signs and allocation are right."""
    from uwml.study.scenarios import run_one

    settings = {"robot": str(BLUEROV2 / "bluerov2_arm.urdf"), "hydro": str(BLUEROV2 / "bluerov2_arm.hydro.toml")}
    still = run_one(
        "vehicle", settings, {"duration": 1.0, "current": 0.4, "current_heading": 60.0, "amplitude": 0.6, "station_keeping": "pd"}
    )
    assert still["max_drift"] < 1e-6 and still["max_roll"] < 1e-4 and still["max_pitch"] < 1e-4
    assert still["mean_thrust"] > 1.0


def test_a_current_beyond_the_thrusters_saturates_them_within_their_limits() -> None:
    from uwml.study.scenarios import run_one

    settings = {"robot": str(BLUEROV2 / "bluerov2_arm.urdf"), "hydro": str(BLUEROV2 / "bluerov2_arm.hydro.toml")}
    # 1 m/s of current drags the hull with 155 N; the four vectored T200s push back with 4 · 40.2 · cos 45° = 114 N.
    strong = run_one("vehicle", settings, {"duration": 0.5, "current": 1.0, "station_keeping": "pd"})
    assert strong["saturation"] > 0.9 and strong["peak_thrust"] == pytest.approx(40.2)  # the T200's reverse limit


def test_a_vehicle_study_follows_a_log_of_joint_angles(tmp_path: Path) -> None:
    time = np.arange(0.0, 2.5, 0.01)
    q = 0.5 * np.sin(2.0 * math.pi * time[:, None] / 4.0 + np.arange(2) * math.pi / 3.0)
    lines = ["time,q1,q2", *(f"{t:.2f},{a:.9f},{b:.9f}" for t, (a, b) in zip(time, q, strict=True))]
    write(tmp_path, "\n".join(lines) + "\n", "arm.csv")
    logged = VEHICLE_STUDY.replace("amplitude = 0.5", 'trajectory = "arm.csv"').replace('["off", "pd"]', '["pd"]')
    config = study.load(write(tmp_path, logged))
    assert study.run_study(config, tmp_path / "log", serial=True).errors == 0
    sines = study.load(write(tmp_path, VEHICLE_STUDY.replace('["off", "pd"]', '["pd"]'), "sines.toml"))
    study.run_study(sines, tmp_path / "sines", serial=True)
    for from_log, from_sines in zip(rows(tmp_path / "log"), rows(tmp_path / "sines"), strict=True):
        assert from_log["rms_drift"] == pytest.approx(from_sines["rms_drift"], rel=1e-4)  # measured within 7e-6
        assert from_log["rms_pitch"] == pytest.approx(from_sines["rms_pitch"], rel=1e-4)  # measured within 7e-6
    # A log shorter than the run is that run's error; sines' settings beside a log are refused.
    short = study.load(write(tmp_path, logged.replace("duration = 2.0", "duration = 3.0")))
    assert study.run_study(short, tmp_path / "short", serial=True).errors == 2
    assert "shorter than the run's duration of 3 s" in rows(tmp_path / "short")[0]["error"]
    with pytest.raises(study.ConfigError, match="key 'scenario.trajectory': the arm follows the log; period is the sines'"):
        study.loads(logged.replace("[parameters]", "[parameters]\nperiod = [2.0, 4.0]"), folder=tmp_path)


def test_a_vehicle_study_refuses_a_description_that_does_not_float_or_cannot_keep_station(tmp_path: Path) -> None:
    hydro = (BLUEROV2 / "bluerov2_arm.hydro.toml").read_text()
    shutil.copy(BLUEROV2 / "bluerov2_arm.urdf", tmp_path / "bluerov2_arm.urdf")
    write(tmp_path, hydro.replace("floating = true", "floating = false"), "fixed.toml")
    write(tmp_path, hydro[: hydro.index("[[links.hull.thrusters]]")], "no_thrusters.toml")
    base = '[scenario]\nkind = "vehicle"\nrobot = "bluerov2_arm.urdf"\nhydro = "{}"\n'
    with pytest.raises(study.ConfigError, match=r"key 'scenario.robot': .*bluerov2_arm.urdf does not float .*floating = true"):
        study.load(write(tmp_path, base.format("fixed.toml")))
    with pytest.raises(study.ConfigError, match="has no thrusters .* station_keeping = 'pid' cannot hold it"):
        study.load(write(tmp_path, base.format("no_thrusters.toml")))
    adrift = study.load(write(tmp_path, base.format("no_thrusters.toml") + 'station_keeping = "off"\nduration = 0.2\n'))
    assert study.run_study(adrift, tmp_path / "adrift", serial=True).errors == 0


# --- a scenario of one's own ------------------------------------------------------------------

CUSTOM_STUDY = """
[scenario]
kind = "custom"
function = "study_scenarios:oscillator"
metrics = ["amplitude", "seen", "label_length"]
mass = 2.0
label = "abcd"

[parameters]
stiffness = [1.0, 4.0]
time = 1.5
damping = { distribution = "uniform", low = 0.0, high = 1.0 }

[sampling]
samples = 2
"""


def expected(run: dict) -> dict:
    omega = math.sqrt(run["stiffness"] / 2.0)
    return {"amplitude": math.exp(-run["damping"] * 1.5) * abs(math.cos(omega * 1.5)), "seen": 5.0, "label_length": 4.0}


def test_a_scenario_of_ones_own_is_called_with_each_runs_parameters(tmp_path: Path) -> None:
    config = study.loads(CUSTOM_STUDY)
    assert config.kind == "custom" and config.metrics == ("amplitude", "seen", "label_length")
    assert config.parameter_names == ["stiffness", "time", "damping"] and config.inputs.keys() == {"function_file"}
    outcome = study.run_study(config, tmp_path / "out", serial=True)
    assert outcome.ran == 4 and outcome.errors == 0
    for row in rows(tmp_path / "out"):
        assert {k: row[k] for k in config.metrics} == pytest.approx(expected(row), rel=1e-15)


@pytest.mark.parametrize(
    ("function", "error"),
    [
        ("not_metrics", "TypeError: study_scenarios:not_metrics returned str, not a dict of its metrics"),
        ("not_finite", "ValueError: study_scenarios:not_finite returned metric amplitude = nan: a metric must be a finite real"),
        ("a_flag", "ValueError: study_scenarios:a_flag returned metric amplitude = True"),
        ("one_too_many", "do not match the study's (amplitude, seen, label_length): it has extra undeclared"),
        ("where_am_i", "it lacks amplitude, seen, label_length; has pid undeclared"),
        ("exits", "RuntimeError: study_scenarios:exits called exit(3)"),
    ],
)
def test_a_function_that_does_not_return_its_metrics_fails_its_runs_alone(tmp_path: Path, function: str, error: str) -> None:
    config = study.loads(CUSTOM_STUDY.replace("oscillator", function))
    outcome = study.run_study(config, tmp_path / "out", serial=True)
    assert outcome.ran == 4 and outcome.errors == 4
    for row in rows(tmp_path / "out"):
        assert error in row["error"] and row["error_kind"] == "run" and math.isnan(row["amplitude"])


@pytest.mark.parametrize(
    ("change", "message"),
    [
        (("study_scenarios:oscillator", "a b:c"), 'must be "package.module:function", each part a Python identifier'),
        (("study_scenarios:oscillator", "os:system"), r"names a module of Python's standard library \(os\)"),
        (("study_scenarios:oscillator", "subprocess:run"), "standard library"),
        (("study_scenarios:oscillator", "study_scenarios:_private"), "a leading underscore"),
        (("study_scenarios:oscillator", "study_scenarios:oscillator:x"), 'must be "package.module:function"'),
        (("study_scenarios:oscillator", "study_scenarios.oscillator"), 'must be "package.module:function"'),
        (("study_scenarios:oscillator", "no_such_module_of_uwml:f"), "cannot import no_such_module_of_uwml"),
        (("study_scenarios:oscillator", "study_scenarios:absent"), "module study_scenarios has no 'absent'"),
        (("study_scenarios:oscillator", "study_scenarios:NotAFunction"), "is a type, not a Python function"),
        (("study_scenarios:oscillator", "study_scenarios:math"), "is a module, not a Python function"),
        (("study_scenarios:oscillator", "study_scenarios:two_arguments"), "does not take one argument"),
        (('metrics = ["amplitude", "seen", "label_length"]\n', ""), "key 'scenario.metrics': missing"),
        (('"label_length"]', '"label_length", "mass"]'), "key 'scenario.metrics': 'mass' is a parameter already"),
        (('"label_length"]', '"label_length", "run"]'), "'run' is a result column already"),
        (("stiffness = [1.0, 4.0]", "run = [1.0]"), "key 'parameters.run': a parameter's name must be an identifier other than"),
        (("stiffness = [1.0, 4.0]", 'stiffness = [1.0, "soft"]'), "key 'parameters.stiffness': mixes numbers and strings"),
        (("stiffness = [1.0, 4.0]", "stiffness = [true]"), "must be a finite number or a string, got True"),
        (("time = 1.5", "time = inf"), "key 'parameters.time': must be a finite number or a string, got inf"),
    ],
)
def test_a_bad_function_or_name_is_refused_before_anything_runs(change: tuple[str, str], message: str) -> None:
    text = CUSTOM_STUDY.replace(*change)
    assert text != CUSTOM_STUDY
    with pytest.raises(study.ConfigError, match=message):
        study.loads(text)


def test_resume_after_the_scenarios_module_changed_is_refused_naming_it(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    module = tmp_path / "my_scenario_of_uwml.py"
    module.write_text("def run(parameters):\n    return {'twice': 2.0 * parameters['x']}\n")
    monkeypatch.syspath_prepend(str(tmp_path))
    text = '[scenario]\nkind = "custom"\nfunction = "my_scenario_of_uwml:run"\nmetrics = ["twice"]\n[parameters]\nx = [1.0, 2.0]\n'
    config = study.loads(text)
    study.run_study(config, tmp_path / "out", serial=True)
    assert [r["twice"] for r in rows(tmp_path / "out")] == [2.0, 4.0]
    module.write_text(module.read_text() + "# changed\n")
    with pytest.raises(StudyError, match=r"my_scenario_of_uwml.py changed since the study began"):
        study.run_study(study.loads(text), tmp_path / "out", resume=True)


def test_a_scenario_of_ones_own_runs_on_ray_as_serially(tmp_path: Path) -> None:
    ray = pytest.importorskip("ray")
    previous = os.environ.get("PYTHONPATH")
    os.environ["PYTHONPATH"] = os.pathsep.join(filter(None, [str(TESTS), previous]))  # the workers import it by name
    try:
        ray.init(num_cpus=2, include_dashboard=False, logging_level="ERROR", log_to_driver=False)
        try:
            config = study.loads(CUSTOM_STUDY)
            on_ray = study.run_study(config, tmp_path / "ray")
            where = study.loads(
                CUSTOM_STUDY.replace("oscillator", "where_am_i").replace('["amplitude", "seen", "label_length"]', '["pid"]')
            )
            study.run_study(where, tmp_path / "where")
            failing = study.run_study(study.loads(CUSTOM_STUDY.replace("oscillator", "exits")), tmp_path / "exits")
        finally:
            ray.shutdown()
    finally:
        if previous is None:
            del os.environ["PYTHONPATH"]
        else:
            os.environ["PYTHONPATH"] = previous
    study.run_study(config, tmp_path / "serial", serial=True)
    assert on_ray.ran == 4 and on_ray.errors == 0 and rows(tmp_path / "ray") == rows(tmp_path / "serial")
    assert all(row["pid"] != os.getpid() for row in rows(tmp_path / "where"))  # run by Ray's workers
    assert failing.errors == 4 and all("called exit(3)" in row["error"] for row in rows(tmp_path / "exits"))


def test_run_batch_of_a_custom_scenario_is_a_row_per_run() -> None:
    config = study.loads(CUSTOM_STUDY)
    batch = runner.run_batch(config.kind, config.settings, config.metrics, config.runs())
    assert [row["run"] for row in batch] == [0, 1, 2, 3] and all(row["error"] is None for row in batch)


def test_a_vehicle_study_drives_the_thrusters_with_a_log_of_commands(tmp_path: Path) -> None:
    """``station_keeping = "log"``: the thrusters open loop on recorded commands, each held from
    its sample (issue: studies take thruster commands from a log). Idle commands are the run
    adrift; the horizontal four at half command give each T200's 11.2 N, the vehicle pushed away."""
    time = np.arange(0.0, 3.0, 0.05)

    def commands(name: str, row: list[float]) -> None:
        lines = ["time," + ",".join(f"u{k}" for k in range(1, 9)), *(f"{t:.2f}," + ",".join(f"{u:g}" for u in row) for t in time)]
        write(tmp_path, "\n".join(lines) + "\n", name)

    commands("idle.csv", [0.0] * 8)
    commands("surge.csv", [0.5] * 4 + [0.0] * 4)
    base = VEHICLE_STUDY.replace('[parameters]\nstation_keeping = ["off", "pd"]\nfeedforward = ["none", "uwml"]\n', "")
    results = {}
    for name, extra in (("off", 'station_keeping = "off"\n'), ("idle", 'station_keeping = "log"\ncommands = "idle.csv"\n'),
                        ("surge", 'station_keeping = "log"\ncommands = "surge.csv"\n')):  # fmt: skip
        config = study.load(write(tmp_path, base.replace("amplitude = 0.5\n", "amplitude = 0.5\n" + extra), f"{name}.toml"))
        assert study.run_study(config, tmp_path / name, serial=True).errors == 0
        results[name] = rows(tmp_path / name)[0]
    assert results["idle"]["rms_drift"] == results["off"]["rms_drift"] and results["idle"]["mean_thrust"] == 0.0
    t200 = 51.5 * (0.5 - 0.0625) ** 2 / (1.0 - 0.0625) ** 2
    assert results["surge"]["mean_thrust"] == pytest.approx(4 * t200 / 8, rel=1e-9)
    assert results["surge"]["rms_drift"] > 2.0 * results["off"]["rms_drift"]
    # The commands must be there, one per thruster, and span the run.
    with pytest.raises(study.ConfigError, match='station_keeping = "log" needs commands'):
        study.loads(base.replace("amplitude = 0.5\n", 'amplitude = 0.5\nstation_keeping = "log"\n'), folder=tmp_path)
    write(tmp_path, "time,u1,u2\n0,0,0\n5,0,0\n", "two.csv")
    with pytest.raises(study.ConfigError, match="the log has 2 thruster commands .* the description 8 thrusters"):
        study.loads(base.replace("amplitude = 0.5\n", 'amplitude = 0.5\nstation_keeping = "log"\ncommands = "two.csv"\n'), folder=tmp_path)
