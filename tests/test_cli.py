"""The ``uwml`` command line's subcommands, each run in a subprocess on small generated inputs:
``paper``, ``torques``, ``fit hydro``, and hostile logs and arguments (``demo`` is
``test_cli_demo.py``'s, ``fit losses`` ``test_cli_fit_losses.py``'s)."""

from __future__ import annotations

import json
import math
import re
import subprocess
from pathlib import Path
from typing import Any

import numpy as np
import pytest
import uwml
import uwml.cli
from cli_runs import assert_bad_file, in_process, read_csv, replace_cell, run_uwml, run_uwml_all
from uwml.io.logs import Log, write_log
from uwml.paper import synthetic

LEG = uwml.paper_leg()


@pytest.fixture(scope="module")
def experiment(tmp_path_factory: pytest.TempPathFactory) -> Log:
    return synthetic.land_water_experiment(cycles=1, seed=3)


# --------------------------------------------------------------------------------------------
# --help
# --------------------------------------------------------------------------------------------


_HELP = [
    ([], ["paper", "torques", "fit"]),
    (["paper"], ["--out", "--seed", "report.md", "fig8_torques.png"]),
    (["torques"], ["LOG", "--out", "--depth", "--temperature", "--cd", "--cm", "--losses", "--joints", "drag1", "total1"]),
    (["fit"], ["hydro", "losses"]),
    (["fit", "hydro"], ["LOG", "glob", "--joints", "--per", "--robust", "--json", "--plot", "tau_land1"]),
    (["fit", "losses"], ["CSV", "--json", "--plot", "configuration", "current_a"]),
]


@pytest.mark.parametrize("command, words", _HELP, ids=[" ".join(c) or "uwml" for c, _ in _HELP])
def test_help_describes_each_subcommand(command: list[str], words: list[str], capsys: pytest.CaptureFixture[str]) -> None:
    status, out, _ = in_process([*command, "--help"], capsys)
    assert status == 0
    for word in words:
        assert word in out, (word, out)


def test_help_in_a_subprocess() -> None:
    result = run_uwml("fit", "hydro", "--help")
    assert result.returncode == 0 and "usage: uwml fit hydro" in result.stdout and not result.stderr, result.stderr


# --------------------------------------------------------------------------------------------
# uwml paper
# --------------------------------------------------------------------------------------------


def test_paper_writes_figures_report_and_summary(tmp_path: Path) -> None:
    out = tmp_path / "paper"
    result = run_uwml("paper", "--out", out)
    assert result.returncode == 0, result.stderr
    for name in ("fig8_torques.png", "fig7_fit.png", "fig13_14_loss_maps.png", "efficiency_map.png"):
        assert (out / name).read_bytes()[:8] == b"\x89PNG\r\n\x1a\n", name
    report = (out / "report.md").read_text(encoding="utf-8")
    for text in ("Cd", "Cm", "synthetic", "illustrative", "27.4 %", "](fig7_fit.png)", "](fig8_torques.png)"):
        assert text in report, text

    # The printed fit of the paper-like experiment: its unweighted statistics near the paper's
    # (2.425 N·m², 0.826), its coefficients in the report.
    number = r"([-+0-9.eE]+)"
    for name in ("Cd", "Cm"):
        match = re.search(rf"^\s*{name} = {number} ± {number}$", result.stdout, re.MULTILINE)
        assert match, result.stdout
        assert float(match.group(2)) > 0.0 and f"{float(match.group(1)):.5f}" in report
    match = re.search(
        rf"unweighted, as the paper's Origin fit: reduced chi-square = {number} N·m² \(paper: 2.425\), COD = {number}", result.stdout
    )
    assert match, result.stdout
    assert 2.0 < float(match.group(1)) < 2.9 and 0.79 < float(match.group(2)) < 0.86, match.group(0)
    # One line per part of the model error; with noise only the fit finds the truth (within 3
    # standard errors), with all of it Cd and Cm are off by more than that.
    parts = re.findall(
        rf"^    (.+?) +Cd = {number} \({number} %, {number} σ\), Cm = {number} \({number} %, {number} σ\), COD = {number}$",
        result.stdout,
        re.MULTILINE,
    )
    assert [p[0] for p in parts][::4] == ["noise only", "all of it (the experiment above)"], result.stdout
    assert len(parts) == 5
    for _, cd, cd_percent, _, cm, cm_percent, _, _ in parts:
        assert float(cd_percent) == pytest.approx(100.0 * (float(cd) - 2.2) / 2.2, abs=0.06)
        assert float(cm_percent) == pytest.approx(100.0 * (float(cm) - 0.5) / 0.5, abs=0.15)
    assert abs(float(parts[0][3])) < 3.0 and abs(float(parts[0][6])) < 3.0
    assert abs(float(parts[-1][3])) > 3.0 and abs(float(parts[-1][6])) > 3.0
    assert "| all of it (the experiment above) |" in report and "PAPER_LIKE_ERROR" in report
    # The loss budget at 10 r/min, 10 MPa.
    assert re.search(r"loss current = 2\.850 A = 27\.4 % of the 10\.4 A rated current", result.stdout), result.stdout
    # The RMS table parses: one row per component, one number per joint, drag and added mass > 0.
    rms = {}
    for line in result.stdout.splitlines():
        tokens = line.split()
        if len(tokens) >= 4 and tokens[0] in ("total", "drag", "added", "buoyancy"):
            rms[tokens[0]] = [float(t) for t in tokens[-3:]]
    assert set(rms) == {"total", "drag", "added", "buoyancy"}, result.stdout
    assert rms["drag"][0] > 0 and rms["added"][0] > 0 and rms["buoyancy"][0] == 0.0  # hip yaw: vertical axis
    # The synthetic log it writes is a valid input of `uwml fit hydro`.
    assert uwml.read_log(out / "land_water.csv").tau_water is not None


# --------------------------------------------------------------------------------------------
# uwml torques
# --------------------------------------------------------------------------------------------


def test_torques_match_the_library(tmp_path: Path, experiment: Log) -> None:
    path = tmp_path / "trajectory.csv"
    write_log(Log(time=experiment.time, q=experiment.q, qd=experiment.qd, qdd=experiment.qdd), path)
    out = tmp_path / "torques.csv"
    result = run_uwml("torques", path, "--out", out, "--cd", "1.8", "--cm", "0.7")
    assert result.returncode == 0, result.stderr
    header, table = read_csv(out)
    assert header == ["time"] + [f"{f}{k}" for f in ("drag", "added_mass", "buoyancy", "total") for k in (1, 2, 3)]
    assert table.shape == (experiment.n_samples, 13)
    expected = LEG.hydro(experiment.q, experiment.qd, experiment.qdd, cd=1.8, cm=0.7, water=uwml.Water(density=1025.0))  # sea water
    # Numbers are written in their shortest round-trip form: what is read back is the library's
    # float64, bit for bit.
    np.testing.assert_array_equal(table[:, 0], experiment.time)
    for i, name in enumerate(("drag", "added_mass", "buoyancy", "total")):
        np.testing.assert_array_equal(table[:, 1 + 3 * i : 4 + 3 * i], getattr(expected, name), err_msg=name)


def test_torques_of_a_robot_from_its_model_file(tmp_path: Path) -> None:
    from uwml.examples import arm_on_rov

    arm = arm_on_rov()
    model = tmp_path / "arm.toml"
    arm.save(model)
    rng = np.random.default_rng(3)
    t = np.linspace(0.0, 2.0, 50)
    q = np.sin(np.outer(t, rng.uniform(0.5, 2.0, 7)))
    qd = np.cos(np.outer(t, rng.uniform(0.5, 2.0, 7)))
    qdd = np.zeros_like(q)
    path = tmp_path / "trajectory.csv"
    write_log(Log(time=t, q=q, qd=qd, qdd=qdd), path)
    out = tmp_path / "torques.csv"
    result = run_uwml("torques", path, "--robot", model, "--joints", "7", "--out", out)
    assert result.returncode == 0, result.stderr
    header, table = read_csv(out)
    assert header[-6:] == ["base_fx", "base_fy", "base_fz", "base_mx", "base_my", "base_mz"] and table.shape == (50, 1 + 28 + 6)
    assert "base_fx..base_mz: the water's wrench on the robot" in result.stderr and "not the weight" in result.stderr
    expected = arm.hydro(q, qd, qdd)  # the segments' own coefficients
    np.testing.assert_allclose(table[:, 1:8], expected.drag, rtol=1e-10, atol=1e-10)
    np.testing.assert_allclose(table[:, -6:], expected.base.total, rtol=1e-10, atol=1e-9)
    # The robot's joint count is the log's by default; a file that is not a model file is refused.
    assert run_uwml("torques", path, "--robot", model).returncode == 0
    result = run_uwml("torques", path, "--robot", tmp_path / "arm.stl")
    assert result.returncode == 2 and "--robot takes a uwml model file" in result.stderr
    result = run_uwml("torques", path, "--robot", model, "--hydro", tmp_path / "hydro.toml")
    assert result.returncode == 2 and "--hydro goes with a URDF or MJCF" in result.stderr


def test_torques_with_losses_and_estimated_derivatives(tmp_path: Path, experiment: Log) -> None:
    path = tmp_path / "positions.csv"
    write_log(Log(time=experiment.time, q=experiment.q), path)  # no qd, qdd: estimated
    out = tmp_path / "torques.csv"
    result = run_uwml("torques", path, "--out", out, "--losses", "--depth", "500", "--temperature", "4", "--joints", "3")
    assert result.returncode == 0, result.stderr
    header, table = read_csv(out)
    families = ("drag", "added_mass", "buoyancy", "visc", "seal", "current", "total")
    assert header == ["time"] + [f"{f}{k}" for f in families for k in (1, 2, 3)]
    assert table.shape == (experiment.n_samples, 22) and np.all(np.isfinite(table))
    column = {name: table[:, i] for i, name in enumerate(header)}
    for k in (1, 2, 3):
        parts = sum(column[f"{f}{k}"] for f in ("drag", "added_mass", "buoyancy", "visc", "seal"))
        np.testing.assert_allclose(column[f"total{k}"], parts, rtol=1e-9, atol=1e-9)
    # Losses oppose motion and need current; the seal at 500 m is not negligible.
    moving = np.abs(experiment.qd[:, 0]) > 0.05
    assert np.all(column["seal1"][moving] * experiment.qd[moving, 0] < 0)
    assert np.all(np.abs(column["current1"][moving]) > 0)


def test_torques_to_standard_output_and_progress_on_long_inputs(tmp_path: Path) -> None:
    n = 100_001
    time = np.arange(n) * 0.005
    angle = 2.0 * np.pi * time / 2.0
    q = np.column_stack([0.2 * np.sin(angle), -0.3 + 0.1 * np.cos(angle), 0.5 + 0.1 * np.sin(angle)])
    qd = np.column_stack([0.2 * np.pi * np.cos(angle), -0.1 * np.pi * np.sin(angle), 0.1 * np.pi * np.cos(angle)])
    path = tmp_path / "long.csv"
    write_log(Log(time=time, q=q, qd=qd, qdd=np.zeros_like(q)), path)
    result = run_uwml("torques", path)
    assert result.returncode == 0, result.stderr
    lines = result.stdout.splitlines()
    assert lines[0].startswith("time,drag1,") and len(lines) == n + 1
    assert float(lines[-1].split(",")[0]) == pytest.approx(time[-1])
    assert "100000/100001 rows" in result.stderr and "100001/100001 rows (100 %)" in result.stderr, result.stderr


def test_torques_parquet(tmp_path: Path, experiment: Log) -> None:
    path = tmp_path / "trajectory.csv"
    write_log(Log(time=experiment.time, q=experiment.q, qd=experiment.qd, qdd=experiment.qdd), path)
    out = tmp_path / "torques.parquet"
    result = run_uwml("torques", path, "--out", out)
    try:
        import pyarrow.parquet
    except ImportError:
        assert result.returncode == 2 and "pyarrow" in result.stderr and str(out) in result.stderr, result.stderr
        assert not out.exists()
        return
    assert result.returncode == 0, result.stderr
    table = pyarrow.parquet.read_table(out)
    assert table.num_rows == experiment.n_samples and table.column_names[:2] == ["time", "drag1"]


@pytest.mark.parametrize(
    ("derivatives", "rows", "suffix"),
    [(True, 50, ".csv"), (False, 7, ".csv"), (False, 50, ".csv"), (False, 60, ".parquet")],
    ids=["given", "estimated-7", "estimated-50", "estimated-parquet"],
)
def test_torques_in_chunks_equal_one_chunk(
    tmp_path: Path,
    experiment: Log,
    monkeypatch: pytest.MonkeyPatch,
    capsys: pytest.CaptureFixture[str],
    derivatives: bool,
    rows: int,
    suffix: str,
) -> None:
    """The log read, evaluated and written in chunks (and pyarrow blocks of 4 kB) gives the
    output of one chunk, byte for byte; derivatives estimated across chunk boundaries too (7 rows
    is less than the Savitzky-Golay window of 21)."""
    from uwml.io import _arrow_csv

    path = tmp_path / "trajectory.csv"
    extra = {"qd": experiment.qd, "qdd": experiment.qdd} if derivatives else {}
    write_log(Log(time=experiment.time, q=experiment.q, **extra), path)
    one, chunked = tmp_path / f"one{suffix}", tmp_path / f"chunked{suffix}"
    status, _, err = in_process(["torques", str(path), "--out", str(one), "--losses", "--depth", "300"], capsys)
    assert status == 0 and "rows (" not in err, err  # one chunk: no progress
    monkeypatch.setattr(uwml.cli.robot_commands, "CHUNK_ROWS", rows)
    monkeypatch.setattr(_arrow_csv, "STREAM_BLOCK_BYTES", 4096)
    status, _, err = in_process(["torques", str(path), "--out", str(chunked), "--losses", "--depth", "300"], capsys)
    n = experiment.n_samples
    assert status == 0 and err.count(" rows (") == -(-n // rows) > 2 and f"{n}/{n} rows (100 %)" in err, err
    if suffix == ".csv":
        assert chunked.read_bytes() == one.read_bytes()
    else:
        import pyarrow.parquet

        assert pyarrow.parquet.read_table(chunked).equals(pyarrow.parquet.read_table(one))


def test_torques_bad_cell_half_way_writes_no_file(
    tmp_path: Path, experiment: Log, monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    good = tmp_path / "good.csv"
    write_log(Log(time=experiment.time, q=experiment.q, qd=experiment.qd, qdd=experiment.qdd), good)
    bad = tmp_path / "bad.csv"
    replace_cell(good, bad, 350, "qdd2", "")
    from uwml.io import _arrow_csv

    monkeypatch.setattr(uwml.cli.robot_commands, "CHUNK_ROWS", 50)
    monkeypatch.setattr(_arrow_csv, "STREAM_BLOCK_BYTES", 4096)
    out = tmp_path / "torques.csv"
    status, _, err = in_process(["torques", str(bad), "--out", str(out)], capsys)
    assert status == 2 and f"{bad}: row 350, column 'qdd2': expected a number, got ''" in err, err
    assert "300/400 rows" in err  # chunks before the bad cell were evaluated
    assert sorted(tmp_path.iterdir()) == sorted([good, bad])  # no output, no partial file


def test_torques_bad_files(tmp_path: Path, experiment: Log, capsys: pytest.CaptureFixture[str]) -> None:
    good = tmp_path / "good.csv"
    write_log(Log(time=experiment.time, q=experiment.q), good)
    cell = tmp_path / "cell.csv"
    replace_cell(good, cell, 7, "q2", "1.2.3")
    missing = tmp_path / "missing.csv"
    missing.write_text(good.read_text(encoding="utf-8").replace("q2", "x2", 1), encoding="utf-8")
    two = tmp_path / "two.csv"
    write_log(Log(time=experiment.time, q=experiment.q[:, :2]), two)  # the leg has 3 joints
    results = run_uwml_all(("torques", cell), ("torques", missing), ("torques", two), ("torques", two, "--joints", "2"))
    assert_bad_file(results[0], cell, 7, "q2")
    assert_bad_file(results[1], missing, 1, "q2")
    assert_bad_file(results[2], two, 1, "q3")
    assert_bad_file(results[3], two, 1, "q3")
    status, _, err = in_process(["torques", str(tmp_path / "absent.csv")], capsys)
    assert status == 2 and err.startswith("uwml: error: ") and "absent.csv" in err, err


# --------------------------------------------------------------------------------------------
# uwml fit hydro
# --------------------------------------------------------------------------------------------


def test_fit_hydro_report_json_and_plot(tmp_path: Path) -> None:
    log = synthetic.land_water_experiment(seed=5)
    path = tmp_path / "both.csv"
    write_log(log, path)
    figure = tmp_path / "fig7.png"
    result, json_result = run_uwml_all(("fit", "hydro", path, "--plot", figure), ("fit", "hydro", path, "--json", "--robust"))
    assert result.returncode == 0, result.stderr
    assert "[[Fit Statistics]]" in result.stdout and "R-squared (COD)" in result.stdout
    values = {
        m.group(1): (float(m.group(2)), float(m.group(3)))
        for m in re.finditer(r"^\s+(cd|cm):\s+(\S+) \+/- (\S+)", result.stdout, re.MULTILINE)
    }
    assert set(values) == {"cd", "cm"}, result.stdout
    for name, truth in (("cd", 2.2), ("cm", 0.5)):
        assert abs(values[name][0] - truth) <= 3.0 * values[name][1], (name, values[name])
    assert figure.read_bytes()[:4] == b"\x89PNG"

    result = json_result
    assert result.returncode == 0, result.stderr
    summary = json.loads(result.stdout)  # JSON only
    assert {"params", "stderr", "covar", "redchi", "rsquared", "ndata", "points", "joints", "per"} <= set(summary)
    assert summary["joints"] == [0] and summary["ndata"] == log.n_samples
    assert summary["params"]["cd"] == pytest.approx(2.2, rel=0.02) and summary["params"]["cm"] == pytest.approx(0.5, rel=0.02)


def test_fit_hydro_two_logs_per_link(tmp_path: Path) -> None:
    log = synthetic.land_water_experiment(seed=6)
    land, water = tmp_path / "land.csv", tmp_path / "water.csv"
    write_log(log.land(), land)
    write_log(log.water(), water)
    result = run_uwml("fit", "hydro", land, water, "--joints", "1,2,3", "--per", "link", "--json")
    assert result.returncode == 0, result.stderr
    summary = json.loads(result.stdout)
    assert summary["joints"] == [0, 1, 2] and summary["per"] == "link"
    assert set(summary["params"]) == {"cd_link1", "cd_link2", "cm_link1", "cm_link2"}
    assert str(land) in summary["source"] and str(water) in summary["source"]


def test_fit_hydro_bad_files(tmp_path: Path, experiment: Log, capsys: pytest.CaptureFixture[str]) -> None:
    good = tmp_path / "good.csv"
    write_log(experiment, good)
    cell = tmp_path / "cell.csv"
    replace_cell(good, cell, 12, "tau_water1", "n/a")
    trajectory = tmp_path / "trajectory.csv"
    write_log(Log(time=experiment.time, q=experiment.q), trajectory)  # no torques
    results = run_uwml_all(("fit", "hydro", cell), ("fit", "hydro", trajectory))
    assert_bad_file(results[0], cell, 12, "tau_water1")
    assert_bad_file(results[1], trajectory, 1, "tau_land1")
    status, _, err = in_process(["fit", "hydro", str(good), "--joints", "4"], capsys)
    assert status == 2 and "--joints" in err, err
    status, _, err = in_process(["fit", "hydro", str(good), "--per", "joint"], capsys)
    assert status == 2 and "--per" in err, err


# --------------------------------------------------------------------------------------------
# Hostile logs and arguments: a one-line error, never a traceback
# --------------------------------------------------------------------------------------------


def _assert_one_line_error(result: subprocess.CompletedProcess, *words: str) -> None:
    assert result.returncode == 2, (result.returncode, result.stderr[-2000:])
    message = result.stderr.strip()
    assert "Traceback" not in message and "\n" not in message and message.startswith("uwml: error: "), message[-2000:]
    for word in words:
        assert word in message, (word, message)


def test_hostile_logs_in_a_subprocess(tmp_path: Path, experiment: Log) -> None:
    good = tmp_path / "good.csv"
    write_log(Log(time=experiment.time, q=experiment.q), good)
    text = good.read_bytes()
    latin = tmp_path / "latin.csv"
    latin.write_bytes(text.replace(b"\n", "\n\u00b1".encode("latin-1"), 1))  # a Latin-1 byte before row 2's time
    fake = tmp_path / "fake.parquet"
    fake.write_bytes(text)
    huge = tmp_path / "huge.csv"
    write_log(Log(time=5e297 * np.arange(experiment.n_samples), q=experiment.q), huge)
    both = tmp_path / "both.csv"
    write_log(Log(time=5e297 * np.arange(experiment.n_samples), q=experiment.q, tau_land=experiment.q, tau_water=experiment.q), both)
    results = run_uwml_all(("torques", latin), ("fit", "hydro", fake), ("torques", huge), ("fit", "hydro", both), ("torques", tmp_path))
    _assert_one_line_error(results[0], f"{latin}: row 2, column 'time': not UTF-8 text (byte 0xb1)")
    _assert_one_line_error(results[1], f"{fake}: not a Parquet file")
    _assert_one_line_error(results[2], f"{huge}: row 3, column 'time'")
    _assert_one_line_error(results[3], f"{both}: row 3, column 'time'")
    _assert_one_line_error(results[4], f"{tmp_path}: is a directory")


def test_hostile_logs_in_process(tmp_path: Path, experiment: Log, capsys: pytest.CaptureFixture[str]) -> None:
    good = tmp_path / "good.csv"
    write_log(experiment, good)
    bom = tmp_path / "bom.csv"
    bom.write_bytes(b"\xef\xbb\xbf" + good.read_bytes())
    out = tmp_path / "out.csv"
    status, _, err = in_process(["torques", str(bom), "--out", str(out)], capsys)
    assert status == 0 and out.exists(), err
    status, out_text, err = in_process(["fit", "hydro", str(bom), "--json"], capsys)
    assert status == 0 and json.loads(out_text)["params"]["cd"] > 0.0, err
    for args, words in [
        (["torques", str(tmp_path / "absent.csv")], [f"{tmp_path / 'absent.csv'}: no such file"]),
        (["fit", "hydro", str(good), str(tmp_path / "absent.csv")], [f"{tmp_path / 'absent.csv'}: no such file"]),
        (["fit", "hydro", str(tmp_path)], [f"{tmp_path}: is a directory"]),
        (["torques", str(good), "--out", str(tmp_path)], [f"{tmp_path}: is a directory; --out takes a file"]),
        (["torques", str(good), "--out", str(tmp_path / "no" / "x.csv")], [f"{tmp_path / 'no' / 'x.csv'}: no such directory"]),
        (["fit", "hydro", str(good), "--plot", str(tmp_path / "no" / "x.png")], [f"{tmp_path / 'no' / 'x.png'}: no such directory"]),
    ]:
        status, _, err = in_process(args, capsys)
        assert status == 2 and err.count("\n") == 1 and err.startswith("uwml: error: "), err
        for word in words:
            assert word in err, (word, err)


@pytest.mark.parametrize(
    ("args", "words"),
    [
        (["simulate", "--cycles", "1e12"], ["--cycles", "between 0 and 100", "1e12"]),
        (["simulate", "--cycles", "nan"], ["--cycles", "between 0 and 100"]),
        (["simulate", "--cycles", "inf"], ["--cycles", "between 0 and 100"]),
        (["simulate", "--cycles", "-1"], ["--cycles", "between 0 and 100"]),
        (["simulate", "--cycles", "0"], ["--cycles", "between 0 and 100"]),
        (["simulate", "--cycles", "two"], ["--cycles", "between 0 and 100", "'two'"]),
        (["simulate", "--depths", ",".join(["0"] * 21)], ["--depths", "at most 20"]),
        (["demo", "--samples", "1000000000000"], ["--samples", "2 to 10000"]),
        (["demo", "--samples", "1e3"], ["--samples", "2 to 10000", "'1e3'"]),
        (["demo", "--period", "abc"], ["--period", "positive number", "'abc'"]),
        (["torques", "log.csv", "--joints", "1000000"], ["--joints", "1 to 64"]),
        (["torques", "log.csv", "--depth", "1e6"], ["--depth", "0 to 11000"]),
        (["fit", "hydro", "log.csv", "--joints", "1," + "9" * 5000], ["--joints", "joint numbers"]),
        (["fit", "hydro", "log.csv", "--joints", "1,65"], ["--joints", "1 to 64"]),
        (["paper", "--seed", "-1"], ["--seed", "non-negative"]),
    ],
    ids=lambda v: " ".join(v)[:40] if isinstance(v, list) and v and v[0] in ("simulate", "demo", "torques", "fit", "paper") else None,
)
def test_size_like_arguments_are_bounded(args: list[str], words: list[str], capsys: pytest.CaptureFixture[str]) -> None:
    status, _, err = in_process(args, capsys)
    assert status == 2, err
    message = err.strip().splitlines()[-1]
    assert "invalid _" not in message and len(message) < 300, message
    for word in words:
        assert word in message, (word, message)


def test_simulate_run_bounds_cycles_before_allocating() -> None:
    from uwml.paper import control_study as simulate

    for cycles in (1e12, 101.0, math.nan, math.inf, -1.0, 0.0):
        with pytest.raises(ValueError, match=r"^cycles must be finite and > 0, at most 100 \(gait cycles\), got "):
            simulate.run("land", 0.0, cycles=cycles)


def test_out_of_memory_is_a_one_line_error(monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]) -> None:
    def exhausted(args: Any) -> int:
        raise MemoryError

    monkeypatch.setattr(uwml.cli.paper_commands, "_demo", exhausted)
    status, _, err = in_process(["demo"], capsys)
    assert status == 1 and err.startswith("uwml: error: out of memory") and err.count("\n") == 1, err
