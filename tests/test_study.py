"""Studies (``uwml.study``, ``uwml study``; docs/scale.md): the runs a configuration names, run on
a local Ray of 2 CPUs or serially; results written batch by batch to Parquet, resumed, failures
kept as rows; a worker killed mid-study loses no run and counts none twice."""

import json
import os
import signal
import threading
import time
from pathlib import Path

import numpy as np
import pyarrow.parquet
import pytest
from uwml import study
from uwml.cli import main
from uwml.study import runner

ray = pytest.importorskip("ray")

CONFIG = """
[scenario]
kind = "paper_leg"
cycles = 0.1

[parameters]
depth = [0.0, 6000.0]
controller = ["land", "hydro_losses"]
payload = { distribution = "uniform", low = 0.0, high = 2.0 }

[sampling]
samples = 3
seed = 7
"""


@pytest.fixture(scope="module")
def local_ray():
    """A local Ray of 2 CPUs for the module's tests (a study uses the running one)."""
    ray.init(num_cpus=2, include_dashboard=False, logging_level="ERROR", log_to_driver=False)
    yield
    ray.shutdown()


def write(tmp_path: Path, text: str = CONFIG) -> Path:
    path = tmp_path / "study.toml"
    path.write_text(text)
    return path


def rows(out: Path) -> list[dict]:
    return study.read_results(out).to_pylist()


def test_the_runs_are_the_grid_times_the_draws_the_same_for_the_same_seed(tmp_path: Path) -> None:
    config = study.load(write(tmp_path))
    runs = config.runs()
    assert config.n_runs == len(runs) == 12 and [r["run"] for r in runs] == list(range(12))
    assert [(r["depth"], r["controller"]) for r in runs[::3]] == [
        (0.0, "land"),
        (0.0, "hydro_losses"),
        (6000.0, "land"),
        (6000.0, "hydro_losses"),
    ]
    payloads = [r["payload"] for r in runs]
    assert len(set(payloads)) == 12 and all(0.0 <= p <= 2.0 for p in payloads)
    assert study.load(write(tmp_path)).runs() == runs
    assert study.loads(CONFIG.replace("seed = 7", "seed = 8")).runs() != runs


def test_study_rows_on_ray_are_the_serial_runs(tmp_path: Path, local_ray: None) -> None:
    config = study.load(write(tmp_path))
    on_ray = study.run_study(config, tmp_path / "ray")
    serial = study.run_study(config, tmp_path / "serial", serial=True)
    assert on_ray.ran == serial.ran == 12 and on_ray.errors == serial.errors == 0
    assert rows(tmp_path / "ray") == rows(tmp_path / "serial")
    # Against one run made here, directly.
    first = rows(tmp_path / "serial")[0]
    from uwml.sim.studies import run

    direct = run("land", 0.0, 0.1, payload=first["payload"])
    assert first["rms_error_1"] == direct.rms_error()[0] and first["energy"] == direct.energy()
    # The deeper, the larger the tracking error of the land controller (the seals' friction).
    land = [r for r in rows(tmp_path / "serial") if r["controller"] == "land"]
    shallow = np.mean([r["rms_error_1"] for r in land if r["depth"] == 0.0])
    deep = np.mean([r["rms_error_1"] for r in land if r["depth"] == 6000.0])
    assert deep > 2 * shallow


def test_resume_runs_only_the_runs_missing(tmp_path: Path) -> None:
    config = study.load(write(tmp_path))
    out = tmp_path / "out"
    study.run_study(config, out, serial=True)
    before = rows(out)
    parts = sorted((out / "runs").glob("part-*.parquet"))
    assert len(parts) >= 2
    lost = parts[-1]
    lost_runs = set(pyarrow.parquet.read_table(lost).column("run").to_pylist())
    lost.unlink()  # a study stopped before its last batch
    outcome = study.run_study(config, out, serial=True, resume=True)
    assert outcome.ran == len(lost_runs) and outcome.skipped == 12 - len(lost_runs)
    assert rows(out) == before
    again = study.run_study(config, out, serial=True, resume=True)
    assert again.ran == 0 and again.skipped == 12
    with pytest.raises(ValueError, match="holds a study already; resume it"):
        study.run_study(config, out, serial=True)
    other = study.loads(CONFIG.replace("seed = 7", "seed = 9"), "other.toml")
    with pytest.raises(ValueError, match=r"holds another study \(.*study.toml\)"):
        study.run_study(other, out, serial=True, resume=True)


def test_a_run_that_raises_is_a_row_with_its_error(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    real = runner.run_one

    def flaky(kind: str, settings: dict, parameters: dict) -> dict:
        if parameters["controller"] == "land" and parameters["depth"] > 0:
            raise RuntimeError("the plant went unstable")
        return real(kind, settings, parameters)

    monkeypatch.setattr(runner, "run_one", flaky)
    outcome = study.run_study(study.load(write(tmp_path)), tmp_path / "out", serial=True)
    assert outcome.ran == 12 and outcome.errors == 3
    failed = [row for row in rows(tmp_path / "out") if row["error"] is not None]
    assert {row["error"] for row in failed} == {"RuntimeError: the plant went unstable"}
    assert all(np.isnan(row["energy"]) for row in failed)
    assert study.summary(tmp_path / "out")["failed"] == 3


BAD = [
    ("[scenery]\n", "key 'scenery': unknown table"),
    ('[scenario]\nkind = "auv"\n', "key 'scenario.kind': must be one of paper_leg"),
    ("[scenario]\nspeed = 1\n", "key 'scenario.speed': unknown setting"),
    ("[parameters]\ndepth = [0, -5]\n", r"key 'parameters.depth\[1\]': must be a number from 0 to 11000"),
    ('[parameters]\ncontroller = ["pid"]\n', r"key 'parameters.controller\[0\]': must be one of land"),
    ("[parameters]\ndepth = []\n", "key 'parameters.depth': an empty grid"),
    ('[parameters]\ndepth = { distribution = "beta" }\n', "key 'parameters.depth.distribution': must be uniform, normal or choice"),
    ('[parameters]\ndepth = { distribution = "uniform", low = 5 }\n', "key 'parameters.depth.high': missing"),
    ('[parameters]\ndepth = { distribution = "uniform", low = 5, high = 1 }\n', "key 'parameters.depth.high': must be above low"),
    ('[parameters]\ndepth = { distribution = "normal", mean = 5, std = 0 }\n', "key 'parameters.depth.std': must be positive"),
    ("[parameters]\ndepth = [0]\n[sampling]\nsamples = 3\n", "key 'sampling.samples': 3 draws of no random parameter"),
    ("[sampling]\nseed = -1\n", "key 'sampling.seed': must be a non-negative integer"),
    ("[scenario]\ncycles = 1\n[parameters]\ncycles = [1, 2]\n", "key 'parameters.cycles': also set in"),
    ("depth = [", "not TOML"),
]


@pytest.mark.parametrize(("text", "message"), BAD, ids=[m[:30] for _, m in BAD])
def test_a_bad_config_is_refused_before_anything_runs_naming_the_key(tmp_path: Path, text: str, message: str, capsys) -> None:
    path = write(tmp_path, text)
    with pytest.raises(study.ConfigError, match=message):
        study.load(path)
    out = tmp_path / "never"
    assert main(["study", str(path), "--out", str(out), "--serial"]) == 2
    assert message.split(":")[0].replace("\\", "") in capsys.readouterr().err.replace("\\", "")
    assert not out.exists()


def test_the_command_line_writes_results_figures_and_a_summary(tmp_path: Path, capsys) -> None:
    path = write(tmp_path)
    out = tmp_path / "out"
    assert main(["study", str(path), "--out", str(out), "--serial", "--json"]) == 0
    result = json.loads(capsys.readouterr().out)
    assert result["runs"] == result["done"] == result["ran"] == 12 and result["failed"] == 0
    assert set(result["metrics"]) == {*(f"{m}_{j}" for m in ("rms_error", "peak_error") for j in (1, 2, 3)), "positive_work", "energy"}
    assert (out / "figures" / "energy.png").stat().st_size > 5000
    assert main(["study", str(path), "--out", str(out), "--serial", "--resume"]) == 0
    assert "0 run now, 12 done before" in capsys.readouterr().out


def _ray_workers_running() -> list[int]:
    """The processes running a batch now: Ray names a worker ``ray::<task>`` while it runs one."""
    found = []
    for entry in Path("/proc").iterdir():
        if entry.name.isdigit():
            try:
                cmdline = (entry / "cmdline").read_bytes()
            except OSError:
                continue
            if cmdline.startswith(b"ray::run_batch"):
                found.append(int(entry.name))
    return found


@pytest.mark.skipif(not Path("/proc/self/cmdline").exists(), reason="finds Ray's workers in /proc")
def test_a_worker_killed_mid_study_loses_no_run_and_counts_none_twice(tmp_path: Path, local_ray: None) -> None:
    config = study.loads(CONFIG.replace("cycles = 0.1", "cycles = 0.6").replace("samples = 3", "samples = 10"), str(tmp_path / "kill.toml"))
    out = tmp_path / "out"
    result: dict = {}
    thread = threading.Thread(target=lambda: result.setdefault("outcome", study.run_study(config, out)))
    thread.start()
    killed = None
    deadline = time.monotonic() + 60
    while killed is None and time.monotonic() < deadline and thread.is_alive():
        running = _ray_workers_running()
        if running:
            killed = running[0]
            os.kill(killed, signal.SIGKILL)
        time.sleep(0.01)
    thread.join(timeout=300)
    assert killed is not None, "no worker was caught running a batch"
    outcome = result["outcome"]
    assert outcome.ran == config.n_runs == 40
    got = [row["run"] for row in rows(out)]
    assert sorted(got) == list(range(40)), "every run once"
    assert all(row["error"] is None for row in rows(out)), "the killed batch was run again"


ROOT = Path(__file__).resolve().parents[1]
ROBOT_STUDY = f"""
[scenario]
kind = "robot"
robot = "{ROOT / "examples/bluerov2/bluerov2_arm.urdf"}"
hydro = "{ROOT / "examples/bluerov2/bluerov2_arm.hydro.toml"}"
duration = 1.0
[parameters]
controller = ["land", "hydro"]
amplitude = [0.0, 0.4]
"""


def test_a_robot_from_its_description_tracks_better_with_uwmls_feedforward(tmp_path: Path) -> None:
    config = study.load(write(tmp_path, ROBOT_STUDY))
    assert config.metrics == ("rms_error_1", "rms_error_2", "peak_error_1", "peak_error_2", "positive_work", "energy")
    outcome = study.run_study(config, tmp_path / "out", serial=True)
    assert outcome.ran == 4 and outcome.errors == 0
    table = {(r["controller"], r["amplitude"]): r for r in rows(tmp_path / "out")}
    # Held still in still water, the feedforward's buoyancy and the inverse dynamics' weight are
    # the plant's: the arm does not move; without the buoyancy's feedforward it sags.
    still = table[("hydro", 0.0)]
    assert max(still["rms_error_1"], still["rms_error_2"]) < 1e-6
    assert table[("land", 0.0)]["rms_error_2"] > 1e-3
    # Moving, the feedforward of drag and added mass tracks better.
    assert table[("hydro", 0.4)]["rms_error_2"] < 0.2 * table[("land", 0.4)]["rms_error_2"]


def test_a_robot_study_names_a_missing_or_bad_description(tmp_path: Path) -> None:
    with pytest.raises(study.ConfigError, match="key 'scenario.robot': .*absent.urdf: no such file"):
        study.load(write(tmp_path, ROBOT_STUDY.replace("bluerov2_arm.urdf", "absent.urdf")))
    with pytest.raises(study.ConfigError, match="key 'scenario.robot': missing"):
        study.loads('[scenario]\nkind = "robot"\n')
    with pytest.raises(study.ConfigError, match="key 'parameters.hydro': a file is a setting of"):
        study.loads(
            f'[scenario]\nkind = "robot"\nrobot = "{ROOT / "examples/bluerov2/bluerov2_arm.urdf"}"\n[parameters]\nhydro = ["a.toml"]\n'
        )


def test_a_floating_vehicles_drift_is_a_study_too(tmp_path: Path) -> None:
    config = study.loads(
        '[scenario]\nkind = "rov"\nduration = 2.0\n[parameters]\nstation_keeping = ["pd", "pd_uwml"]\ncurrent = [0.0, 0.8]\n'
    )
    assert config.metrics == ("rms_drift", "max_drift", "rms_attitude")
    study.run_study(config, tmp_path / "out", serial=True)
    table = {(r["station_keeping"], r["current"]): r for r in rows(tmp_path / "out")}
    # uwml's predicted wrench holds the vehicle's attitude closer; the current pushes it away.
    assert table[("pd_uwml", 0.8)]["rms_attitude"] < 0.8 * table[("pd", 0.8)]["rms_attitude"]
    assert table[("pd", 0.8)]["max_drift"] > 2 * table[("pd", 0.0)]["max_drift"]
