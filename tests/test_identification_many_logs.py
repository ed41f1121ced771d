"""One fit over many logs, and logs read chunk by chunk (``uwml.fit.hydro_coefficients`` with
a list of logs or a glob, ``uwml.fit.log_set``; docs/identification.md, "Many logs, and logs larger than memory"): the pooled
fit equals the fit of the same rows in one log held in memory, statistics included; each log's
diagnostics find the one log that disagrees."""

import importlib.util
import json
from pathlib import Path

import numpy as np
import pytest
import uwml
from uwml import fit
from uwml.cli import main
from uwml.fit import log_set
from uwml.io.logs import Log, write_log
from uwml.paper import synthetic

STATISTICS = ("chisqr", "redchi", "rsquared", "aic", "bic", "rss", "cod", "redchi_unweighted")


def joined(logs: list[Log]) -> Log:
    """The logs as one, row after row."""
    names = ("time", "q", "qd", "qdd", "tau_land", "tau_water")
    return Log(**{name: np.concatenate([getattr(log, name) for log in logs]) for name in names}, source="joined")


def dives(cds: tuple[float, ...] = (2.2, 2.2, 2.2)) -> list[Log]:
    """Logs of consecutive runs (the second starts after the first ends), one per Cd."""
    logs, start = [], 0.0
    for k, cd in enumerate(cds):
        log = synthetic.land_water_experiment(cycles=1.5, cd=cd, seed=20 + k, start_time=start)
        logs.append(log)
        start = float(log.time[-1]) + 1.0
    return logs


def assert_same_fit(a: fit.HydroFit, b: fit.HydroFit, rtol: float) -> None:
    assert a.var_names == b.var_names and a.ndata == b.ndata
    for name in a.var_names:
        assert a.params[name] == pytest.approx(b.params[name], rel=rtol, abs=1e-13), name
        assert a.stderr[name] == pytest.approx(b.stderr[name], rel=rtol), name
    for name in STATISTICS:
        # AIC and BIC are N log(χ²/N) + …: their scale is N's, whatever their value.
        scale = a.ndata if name in ("aic", "bic") else 0.0
        assert getattr(a, name) == pytest.approx(getattr(b, name), rel=rtol, abs=rtol * scale), name
    np.testing.assert_allclose(a.residual, b.residual, rtol=rtol, atol=1e-12)
    np.testing.assert_array_equal(a.time, b.time)


@pytest.mark.parametrize("robust", [False, True])
@pytest.mark.parametrize("suffix", [".csv", ".parquet"])
def test_a_fit_over_several_files_is_the_fit_of_their_rows_in_one_log(tmp_path: Path, robust: bool, suffix: str) -> None:
    logs = dives()
    paths = []
    for k, log in enumerate(logs):
        paths.append(tmp_path / f"dive{k}{suffix}")
        write_log(log, paths[-1])
    arguments = {"joints": (0, 1, 2), "per": "link", "robust": robust}
    pooled = fit.hydro_coefficients([str(p) for p in paths], **arguments)
    whole = fit.hydro_coefficients(joined(logs), **arguments)
    assert_same_fit(pooled, whole, 1e-10)
    # A glob pattern names the same files (sorted).
    assert_same_fit(fit.hydro_coefficients(str(tmp_path / f"dive*{suffix}"), **arguments), whole, 1e-10)
    assert [log.source for log in pooled.logs] == [str(p) for p in paths]
    assert [log.rows for log in pooled.logs] == [log.n_samples for log in logs]
    assert pooled.source == f"{paths[0]} and 2 more logs"


def test_a_file_read_chunk_by_chunk_fits_as_the_file_read_whole(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    given = synthetic.land_water_experiment(cycles=3, seed=4)
    estimated = synthetic.land_water_experiment(cycles=3, seed=4, derivatives=False)
    for log, rtol in ((given, 1e-10), (estimated, 1e-9)):
        path = tmp_path / "run.csv"
        write_log(log, path)
        whole = fit.hydro_coefficients(str(path), joints=(0, 1), per="direction")
        monkeypatch.setattr(log_set, "STREAM_BYTES", 0)
        monkeypatch.setattr(fit.design, "CHUNK_SAMPLES", 101)  # chunks that align with nothing
        streamed = fit.hydro_coefficients(str(path), joints=(0, 1), per="direction")
        monkeypatch.undo()
        assert_same_fit(streamed, whole, rtol)


def test_the_log_that_disagrees_with_the_pooled_fit_is_named(tmp_path: Path) -> None:
    logs = dives((2.2, 2.2, 3.0, 2.2))
    result = fit.hydro_coefficients(logs, joints=(0,))
    assert [log.disagrees for log in result.logs] == [False, False, True, False]
    odd = result.logs[2]
    assert odd.params is not None and odd.params["cd"] == pytest.approx(3.0, rel=0.05)
    assert all(log.params is not None and log.params["cd"] == pytest.approx(2.2, rel=0.05) for k, log in enumerate(result.logs) if k != 2)
    # Residuals: the odd log's are the largest.
    assert max(result.logs, key=lambda log: log.residual_rms) is odd
    report = result.fit_report()
    assert "logs               = 4," in report and "disagreeing (> 3σ) = " in report
    assert [entry["disagrees"] for entry in result.summary()["logs"]] == [False, False, True, False]
    # Logs that agree: none named.
    calm = fit.hydro_coefficients(dives(), joints=(0,))
    assert not any(log.disagrees for log in calm.logs)


def test_bad_sets_of_logs_are_refused_naming_the_file(tmp_path: Path) -> None:
    with pytest.raises(ValueError, match=r"nothing\*\.csv: no file matches the pattern"):
        fit.hydro_coefficients(str(tmp_path / "nothing*.csv"))
    with pytest.raises(ValueError, match="give at least one log"):
        fit.hydro_coefficients([])
    good = tmp_path / "good.csv"
    write_log(synthetic.land_water_experiment(cycles=1, seed=1), good)
    four = tmp_path / "four.csv"
    robot = uwml.paper_leg()
    with pytest.raises(TypeError, match="a log must be a uwml.io.logs.Log, a file or a glob pattern"):
        fit.hydro_coefficients([str(good), 3])  # type: ignore[list-item]
    four.write_text("time,q1,q2,q3,q4,tau_land1,tau_land2,tau_land3,tau_land4\n0,0,0,0,0,0,0,0,0\n")
    with pytest.raises(ValueError, match=rf"{four}: row 1 \(header\)"):
        fit.hydro_coefficients([str(good), str(four)], robot)


def test_the_command_line_takes_several_logs_and_a_pattern(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    for k, log in enumerate(dives()):
        write_log(log, tmp_path / f"dive{k}.csv")
    assert main(["fit", "hydro", str(tmp_path / "dive0.csv"), str(tmp_path / "dive1.csv"), str(tmp_path / "dive2.csv"), "--json"]) == 0
    listed = json.loads(capsys.readouterr().out)
    assert main(["fit", "hydro", str(tmp_path / "dive*.csv"), "--json"]) == 0
    pattern = json.loads(capsys.readouterr().out)
    assert listed["params"] == pattern["params"] and len(listed["logs"]) == 3
    assert main(["fit", "hydro", str(tmp_path / "dive*.csv"), "--no-points", "--json"]) == 0
    lean = json.loads(capsys.readouterr().out)
    assert lean["params"] == pytest.approx(listed["params"], rel=1e-12) and lean["points"]["time"] == []
    assert main(["fit", "hydro", str(tmp_path / "dive*.csv"), "--no-points", "--robust"]) == 2
    assert "--no-points: a robust fit and the figure need the points" in capsys.readouterr().err
    if importlib.util.find_spec("ray") is not None:
        assert main(["fit", "hydro", str(tmp_path / "dive*.csv"), "--ray", "--workers", "2", "--json"]) == 0
        spread = json.loads(capsys.readouterr().out)
        for name, value in listed["params"].items():
            assert spread["params"][name] == pytest.approx(value, rel=1e-10)
    # Two logs of one environment each are still a (land, water) pair.
    log = synthetic.land_water_experiment(cycles=1, seed=3)
    write_log(log.land(), tmp_path / "land.csv")
    write_log(log.water(), tmp_path / "water.csv")
    assert main(["fit", "hydro", str(tmp_path / "land.csv"), str(tmp_path / "water.csv"), "--json"]) == 0
    pair = json.loads(capsys.readouterr().out)
    assert pair["params"]["cd"] == pytest.approx(fit.hydro_coefficients(log).params["cd"], rel=1e-9)


@pytest.mark.parametrize("robust", [False, True])
def test_a_fit_on_ray_is_the_fit_in_one_process(tmp_path: Path, robust: bool) -> None:
    """Four logs shared out among the actors of a local Ray of 2 CPUs, each reducing its own: the
    one-process fit, statistics and each log's diagnostics included."""
    ray = pytest.importorskip("ray")
    logs = dives((2.2, 2.2, 2.6, 2.2))
    paths = []
    for k, log in enumerate(logs):
        paths.append(str(tmp_path / f"dive{k}.csv"))
        write_log(log, paths[-1])
    arguments = {"joints": (0, 1), "per": "link", "robust": robust}
    here = fit.hydro_coefficients(paths, **arguments)
    ray.init(num_cpus=2, include_dashboard=False, logging_level="ERROR", log_to_driver=False)
    try:
        spread = fit.hydro_coefficients(paths, on_ray=True, **arguments)
        lean = None if robust else fit.hydro_coefficients(paths, on_ray=True, points=False, **arguments)
    finally:
        ray.shutdown()
    if lean is not None:  # without the points, from the actors' residual sums
        assert lean.residual.size == 0 and lean.chisqr == pytest.approx(here.chisqr, rel=1e-10)
        assert lean.cod == pytest.approx(here.cod, rel=1e-10) and lean.params == pytest.approx(here.params, rel=1e-10)
    assert_same_fit(spread, here, 1e-10)
    assert [log.disagrees for log in spread.logs] == [log.disagrees for log in here.logs] == [False, False, True, False]
    for a, b in zip(spread.logs, here.logs, strict=True):
        assert a.rows == b.rows and a.residual_rms == pytest.approx(b.residual_rms, rel=1e-10)


def test_a_fit_without_its_points_has_the_same_statistics(tmp_path: Path) -> None:
    """points=False: the statistics from sums over the logs, the per-point arrays left out."""
    logs = dives((2.2, 2.2, 2.6, 2.2))
    arguments = {"joints": (0, 1), "per": "link"}
    full = fit.hydro_coefficients(logs, **arguments)
    lean = fit.hydro_coefficients(logs, points=False, **arguments)
    assert lean.residual.size == lean.best_fit.size == lean.data.size == lean.time.size == 0
    assert lean.var_names == full.var_names and lean.ndata == full.ndata and lean.nfree == full.nfree
    for name in full.var_names:
        assert lean.params[name] == full.params[name]
        assert lean.stderr[name] == pytest.approx(full.stderr[name], rel=1e-10)
    for name in STATISTICS:
        scale = full.ndata if name in ("aic", "bic") else 0.0
        assert getattr(lean, name) == pytest.approx(getattr(full, name), rel=1e-10, abs=1e-10 * scale), name
    assert [log.disagrees for log in lean.logs] == [log.disagrees for log in full.logs] == [False, False, True, False]
    for a, b in zip(lean.logs, full.logs, strict=True):
        assert a.residual_rms == pytest.approx(b.residual_rms, rel=1e-10) and a.params == b.params
    assert "R-squared" in lean.fit_report() and all(values == [] for values in lean.summary()["points"].values())
    assert lean.sigma_given == full.sigma_given
    known = fit.hydro_coefficients(logs, points=False, sigma=0.7, **arguments)
    assert known.sigma_given and known.redchi == pytest.approx(fit.hydro_coefficients(logs, sigma=0.7, **arguments).redchi, rel=1e-10)
    with pytest.raises(ValueError, match="points=False takes plain least squares"):
        fit.hydro_coefficients(logs, points=False, robust=True)
