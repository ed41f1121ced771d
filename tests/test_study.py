"""Studies (``uwml.study``, ``uwml study``; docs/scale.md): the runs a configuration names, run on
a local Ray of 2 CPUs or serially; results written batch by batch to Parquet, resumed, failures
kept as rows; a worker killed mid-study loses no run and counts none twice; nor does a run that
kills its worker every time, a driver killed mid-study (its Ray ends with it) or two studies
started on one folder at once; a resume refuses a robot file that changed."""

import json
import os
import re
import shutil
import signal
import subprocess
import sys
import threading
import time
import tracemalloc
from pathlib import Path

import numpy as np
import pyarrow.parquet
import pytest
from uwml import study
from uwml.cli import main
from uwml.errors import UwmlError
from uwml.study import runner
from uwml.study.config import Distribution

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
    from uwml.paper.control_study import run

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


# Studies never lose, mix or duplicate a run (issue 31).


def test_resume_after_the_robot_or_hydro_file_changed_is_refused_naming_the_file(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, capsys
) -> None:
    for name in ("bluerov2_arm.urdf", "bluerov2_arm.hydro.toml"):
        shutil.copy(ROOT / "examples/bluerov2" / name, tmp_path / name)
    path = write(
        tmp_path,
        '[scenario]\nkind = "robot"\nrobot = "bluerov2_arm.urdf"\nhydro = "bluerov2_arm.hydro.toml"\nduration = 0.05\n'
        '[parameters]\ncontroller = ["land", "hydro"]\namplitude = [0.0, 0.4]\n',
    )
    out = tmp_path / "out"
    study.run_study(study.load(path), out, serial=True)
    before = rows(out)
    max(out.glob("runs/part-*.parquet")).unlink()  # a study stopped before its last batch
    urdf, hydro = tmp_path / "bluerov2_arm.urdf", tmp_path / "bluerov2_arm.hydro.toml"
    original_urdf, original_hydro = urdf.read_text(), hydro.read_text()
    urdf.write_text(original_urdf.replace('<mass value="0.2"/>', '<mass value="0.3"/>'))  # the same joints, another arm
    with pytest.raises(UwmlError, match=r"bluerov2_arm\.urdf changed since the study began; start a new --out or restore it"):
        study.run_study(study.load(path), out, serial=True, resume=True)
    assert main(["study", str(path), "--out", str(out), "--serial", "--resume", "--no-figures"]) == 2
    assert "bluerov2_arm.urdf changed since the study began" in capsys.readouterr().err
    urdf.write_text(original_urdf)
    hydro.write_text(original_hydro.replace("density = 1000.0", "density = 1025.0"))
    with pytest.raises(UwmlError, match=r"bluerov2_arm\.hydro\.toml changed since the study began") as refused:
        study.run_study(study.load(path), out, serial=True, resume=True)
    assert "bluerov2_arm.urdf" not in str(refused.value)
    hydro.write_text(original_hydro)
    assert len(rows(out)) == 3, "nothing written by the refused resumes"
    assert study.run_study(study.load(path), out, serial=True, resume=True).ran == 1
    assert rows(out) == before
    # Changed during a study: it stops before writing a run that may have read the new file.
    real = runner.run_one

    def changing(kind: str, settings: dict, parameters: dict) -> dict:
        result = real(kind, settings, parameters)
        urdf.write_text(original_urdf.replace('<mass value="0.2"/>', '<mass value="0.3"/>'))
        return result

    monkeypatch.setattr(runner, "run_one", changing)
    with pytest.raises(UwmlError, match=r"bluerov2_arm\.urdf changed during the study"):
        study.run_study(study.load(path), tmp_path / "during", serial=True)
    assert study.read_results(tmp_path / "during") is None


def test_two_studies_on_one_folder_at_once_the_second_is_refused(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    path = write(tmp_path)
    config = study.load(path)
    out = tmp_path / "out"
    real = runner.run_one
    started, release = threading.Event(), threading.Event()

    def held(kind: str, settings: dict, parameters: dict) -> dict:
        if threading.current_thread().name == "first":
            started.set()
            release.wait(120)
        return real(kind, settings, parameters)

    monkeypatch.setattr(runner, "run_one", held)
    result: dict = {}
    first = threading.Thread(target=lambda: result.setdefault("outcome", study.run_study(config, out, serial=True)), name="first")
    first.start()
    try:
        assert started.wait(120)
        where = re.escape(str(out))
        with pytest.raises(UwmlError, match=rf"{where}: a study is running in this folder already \(pid {os.getpid()} "):
            study.run_study(config, out, serial=True, resume=True)
        # Another process, on Ray: refused at once (exit 2, one line), before starting Ray.
        env = {k: v for k, v in os.environ.items() if k != "RAY_ADDRESS"}
        second = subprocess.run(
            [sys.executable, "-m", "uwml.cli", "study", str(path), "--out", str(out), "--resume", "--workers", "3", "--no-figures"],
            check=False, capture_output=True, text=True, timeout=300, env=env,
        )  # fmt: skip
        assert second.returncode == 2, second.stderr
        assert f"a study is running in this folder already (pid {os.getpid()} " in second.stderr
    finally:
        release.set()
        first.join(300)
    assert result["outcome"].ran == 12
    assert sorted(row["run"] for row in rows(out)) == list(range(12)), "every run once"
    assert study.run_study(config, out, serial=True, resume=True).ran == 0  # the lock ends with its study


def test_a_run_that_kills_its_worker_every_time_fails_alone(tmp_path: Path, local_ray: None, monkeypatch: pytest.MonkeyPatch) -> None:
    config = study.loads(CONFIG.replace("samples = 3", "samples = 16"), str(tmp_path / "deadly.toml"))  # batches of 4
    real = runner.run_batch

    def deadly(kind: str, settings: dict, metrics: tuple, batch: list) -> list:
        if any(run["run"] == 13 for run in batch):
            os.kill(os.getpid(), signal.SIGKILL)
        return real(kind, settings, metrics, batch)

    monkeypatch.setattr(runner, "run_batch", deadly)
    out = tmp_path / "out"
    outcome = study.run_study(config, out)
    got = rows(out)
    assert sorted(row["run"] for row in got) == list(range(64)), "every run once"
    failed = [row for row in got if row["error"] is not None]
    assert [row["run"] for row in failed] == [13] and outcome.errors == 1, "the culprit alone"
    assert failed[0]["error"].startswith("WorkerCrashedError: this run killed its worker on each of its 4 tries")
    assert failed[0]["error_kind"] == "run"
    monkeypatch.undo()
    assert study.run_study(config, out, resume=True).ran == 0, "its own failure: not run again"


def test_resume_retries_the_runs_that_failed_by_infrastructure_only(
    tmp_path: Path, local_ray: None, monkeypatch: pytest.MonkeyPatch
) -> None:
    config = study.load(write(tmp_path))  # batches of 1 on 2 CPUs
    real = runner.run_batch

    def lost(kind: str, settings: dict, metrics: tuple, batch: list) -> list:
        if any(run["run"] == 4 for run in batch):
            raise RuntimeError("the node went away")  # not a run's exception: run_batch keeps those as rows
        return real(kind, settings, metrics, batch)

    monkeypatch.setattr(runner, "run_batch", lost)
    out = tmp_path / "out"
    assert study.run_study(config, out).errors == 1
    monkeypatch.undo()
    (row,) = [row for row in rows(out) if row["error"] is not None]
    assert row["run"] == 4 and row["error_kind"] == "infrastructure" and "the node went away" in row["error"]
    # A batch that an earlier uwml recorded as crashed (no error_kind column): its rows are Ray's too.
    part = next(p for p in out.glob("runs/part-*.parquet") if 9 in pyarrow.parquet.read_table(p).column("run").to_pylist())
    table = pyarrow.parquet.read_table(part).drop_columns(["error_kind"]).to_pylist()
    table = [{**r, "energy": float("nan"), "error": "WorkerCrashedError: The worker died unexpectedly"} for r in table]
    pyarrow.parquet.write_table(pyarrow.Table.from_pylist(table), part)
    parts = sorted(out.glob("runs/*"))
    resumed = study.run_study(config, out, resume=True)
    assert resumed.ran == 2 and resumed.skipped == 10 and resumed.errors == 0
    assert sorted(out.glob("runs/*")) == parts, "the retried rows replaced the failed ones, part by part"
    serial = study.run_study(config, tmp_path / "serial", serial=True)
    assert serial.errors == 0 and rows(out) == rows(tmp_path / "serial"), "every run once, with its own result"
    assert study.run_study(config, out, resume=True).ran == 0


def test_a_normal_distribution_whose_low_is_above_its_high_is_refused(tmp_path: Path, capsys) -> None:
    explicit = '[parameters]\ndepth = { distribution = "normal", mean = 50, std = 10, low = 100, high = 20 }\n'
    with pytest.raises(study.ConfigError, match=r"key 'parameters.depth.high': must be above low \(100\), got 20"):
        study.load(write(tmp_path, explicit))
    assert main(["study", str(write(tmp_path, explicit)), "--out", str(tmp_path / "never"), "--serial"]) == 2
    assert "key 'parameters.depth.high': must be above low" in capsys.readouterr().err
    # low at the parameter's upper bound, high left to it: no room either.
    bound = '[parameters]\npayload = { distribution = "normal", mean = 99, std = 1, low = 100 }\n'
    with pytest.raises(study.ConfigError, match=r"key 'parameters.payload.low': must be below high \(100, the parameter's bound\)"):
        study.load(write(tmp_path, bound))
    draws = study.loads(
        '[parameters]\npayload = { distribution = "normal", mean = 1, std = 0.2, low = 0.5, high = 1.5 }\n[sampling]\nsamples = 50\n'
    ).runs()
    payloads = [run["payload"] for run in draws]
    assert all(0.5 <= p <= 1.5 for p in payloads) and len(set(payloads)) > 40


BIG = """
[scenario]
kind = "paper_leg"
cycles = 0.1
[parameters]
depth = [0.0, 1000.0, 2000.0, 3000.0, 4000.0, 5000.0, 6000.0, 7000.0, 8000.0, 9000.0]
controller = ["land", "hydro", "hydro_losses"]
coefficient_scale = { distribution = "uniform", low = 0.7, high = 1.3 }
payload = { distribution = "normal", mean = 1.0, std = 0.2, low = 0.0 }
[sampling]
samples = 333333
"""


def test_a_ten_million_run_study_starts_without_listing_its_runs(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    config = study.loads(BIG, str(tmp_path / "big.toml"))
    assert config.n_runs == 9_999_990
    drawn = [0]
    real_draw = Distribution.draw

    def draw(self: Distribution, rng: np.random.Generator) -> object:
        drawn[0] += 1
        if drawn[0] > 100_000:
            raise AssertionError("the runs were listed before the first batch")
        return real_draw(self, rng)

    class First(Exception):
        pass

    batches: list[list[dict]] = []

    def first(kind: str, settings: dict, metrics: tuple, batch: list) -> list:
        batches.append(batch)
        if len(batches) > 1:
            raise First
        return [{**run, **dict.fromkeys(metrics, 0.0), "error": None} for run in batch]

    monkeypatch.setattr(Distribution, "draw", draw)
    monkeypatch.setattr(runner, "run_batch", first)
    out = tmp_path / "out"
    tracemalloc.start()
    try:
        with pytest.raises(First):
            study.run_study(config, out, serial=True)
        assert [run["run"] for run in batches[0]] == list(range(64)) and batches[1][0]["run"] == 64
        assert drawn[0] <= 2 * 2 * 2 * 64, "only the runs of the batches taken"
        # Resumed: the done runs are skipped (their draws made, nothing kept), not listed either.
        batches.clear()
        with pytest.raises(First):
            study.run_study(config, out, serial=True, resume=True)
        _, peak = tracemalloc.get_traced_memory()
    finally:
        tracemalloc.stop()
    assert batches[0][0]["run"] == 64 and study.read_results(out).num_rows == 128
    assert peak < 64 * 2**20, f"{peak / 2**20:.0f} MiB"
    small = study.load(write(tmp_path))
    assert list(small.iter_runs()) == small.runs(), "the same runs, drawn in the same order"


def _processes() -> dict[int, tuple[int, str, str]]:
    """The live processes: pid -> (parent, start time, name), from /proc (zombies left out)."""
    found = {}
    for entry in Path("/proc").iterdir():
        if entry.name.isdigit():
            try:
                stat = (entry / "stat").read_text()
            except OSError:
                continue
            fields = stat[stat.rindex(")") + 2 :].split()
            if fields[0] != "Z":
                found[int(entry.name)] = (int(fields[1]), fields[19], stat[stat.index("(") + 1 : stat.rindex(")")])
    return found


def _descendants(pid: int) -> dict[int, tuple[int, str, str]]:
    table = _processes()
    found: dict[int, tuple[int, str, str]] = {}
    parents = [pid]
    while parents:
        parent = parents.pop()
        for child, info in table.items():
            if info[0] == parent and child not in found:
                found[child] = info
                parents.append(child)
    return found


@pytest.mark.skipif(not Path("/proc/self/stat").exists(), reason="finds the driver's processes in /proc")
def test_a_driver_killed_mid_study_takes_its_ray_along_and_the_study_resumes(tmp_path: Path, local_ray: None) -> None:
    path = write(tmp_path, CONFIG.replace("cycles = 0.1", "cycles = 2.0").replace("samples = 3", "samples = 30"))
    out = tmp_path / "out"
    env = {k: v for k, v in os.environ.items() if k != "RAY_ADDRESS"}  # a local Ray of its own
    with open(tmp_path / "driver.err", "wb") as err:
        driver = subprocess.Popen(
            [sys.executable, "-m", "uwml.cli", "study", str(path), "--out", str(out), "--workers", "2", "--no-figures", "--json"],
            stdout=subprocess.DEVNULL, stderr=err, env=env,
        )  # fmt: skip
    ray_processes: dict[int, tuple[int, str, str]] = {}
    try:
        deadline = time.monotonic() + 180
        while driver.poll() is None and time.monotonic() < deadline and not list(out.glob("runs/part-*.parquet")):
            time.sleep(0.05)
        assert driver.poll() is None, (tmp_path / "driver.err").read_text()
        ray_processes = _descendants(driver.pid)
        assert "raylet" in {name for _, _, name in ray_processes.values()}, ray_processes
        os.kill(driver.pid, signal.SIGKILL)
        driver.wait(60)
        left = ray_processes
        deadline = time.monotonic() + 60
        while left and time.monotonic() < deadline:
            time.sleep(0.2)
            now = _processes()
            left = {pid: info for pid, info in ray_processes.items() if pid in now and now[pid][1] == info[1]}
        assert not left, f"still alive 60 s after the driver: {sorted(name for _, _, name in left.values())}"
    finally:
        if driver.poll() is None:
            driver.kill()
        now = _processes()
        for pid, info in ray_processes.items():
            if pid in now and now[pid][1] == info[1]:
                os.kill(pid, signal.SIGKILL)
    config = study.load(path)
    done_before = len(rows(out))
    resumed = study.run_study(config, out, resume=True)  # no stale lock
    assert resumed.skipped == done_before and resumed.ran == 120 - done_before and resumed.errors == 0
    assert sorted(row["run"] for row in rows(out)) == list(range(120)), "every run once"
