"""``uwml simulate`` (uwml.paper.control_study): the paper's leg walking in sea water under four controllers."""

from __future__ import annotations

import json
import math
import re
from pathlib import Path

import numpy as np
import pytest
import uwml

mujoco = pytest.importorskip("mujoco")
from uwml import study
from uwml.cli import main
from uwml.paper import control_study as simulate
from uwml.sim.control import rov_drift


def test_the_plant_is_table_ii_with_box_inertias() -> None:
    model = mujoco.MjModel.from_xml_string(simulate.leg_model())
    np.testing.assert_allclose(model.body_mass[2:5], [10.758, 19.261, 10.375], rtol=1e-15)
    # The thigh: a uniform box 0.66 m along x, 0.238 m along y (n0), 0.131 m along z (n1).
    a, b, c = 0.66, 0.238, 0.131
    expected = 19.261 / 12 * np.array([b * b + c * c, a * a + c * c, a * a + b * b])
    np.testing.assert_allclose(model.body_inertia[3], expected, rtol=1e-12)
    # The hip housing: a cube of its displaced volume.
    side = (uwml.paper_leg().links[0].volume) ** (1 / 3)
    np.testing.assert_allclose(model.body_inertia[2], 10.758 * side**2 / 6 * np.ones(3), rtol=1e-12)
    np.testing.assert_allclose(model.body_ipos[3], (0.506, 0.0, 0.0), atol=1e-15)
    np.testing.assert_allclose(model.jnt_axis[1], (0.0, -1.0, 0.0), atol=1e-15)


def test_exact_feedforward_tracks_and_a_land_controller_does_not() -> None:
    """The plant is the model the feedforward comes from, so the full feedforward leaves only
    the step's discretization (and the seal's smooth sign); PD tuned on land lags by degrees."""
    land = simulate.run("land", 0.0, cycles=1.0)
    full = simulate.run("hydro_losses", 0.0, cycles=1.0)
    assert np.all(np.degrees(full.rms_error()) < 0.05), np.degrees(full.rms_error())
    assert np.all(land.rms_error() > 10.0 * full.rms_error())
    assert np.degrees(np.max(land.peak_error())) > 1.0
    # Deeper, the seal's friction grows with pressure: the land controller lags more.
    deep = simulate.run("land", 6000.0, cycles=1.0)
    assert np.max(deep.rms_error()) > 2.0 * np.max(land.rms_error())
    assert full.positive_work() > 0.0 and math.isfinite(full.positive_work())


def test_bad_inputs() -> None:
    with pytest.raises(ValueError, match="controller must be one of land, hydro, hydro_losses, hydro_wrong, hydro_losses_wrong"):
        simulate.run("pid", 0.0)
    with pytest.raises(ValueError, match="depth must be between 0 and 11000 m"):
        simulate.run("land", -1.0)
    with pytest.raises(ValueError, match="cycles must be finite and > 0"):
        simulate.run("land", 0.0, cycles=0.0)


def test_uwml_simulate_writes_its_report(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    out = tmp_path / "sim"
    assert main(["simulate", "--out", str(out), "--depths", "0,6000", "--cycles", "1", "--json"]) == 0
    captured = capsys.readouterr()
    summary = json.loads(captured.out)
    runs = summary["runs"]
    assert set(summary["fluid_models_relative_rms_difference"]) == {"box", "ellipsoid"}
    assert [row["station_keeping"] for row in summary["rov"]] == ["PD", "PD + uwml base wrench"]
    assert [(r["depth_m"], r["controller"]) for r in runs] == [(d, c) for d in (0.0, 6000.0) for c in simulate.CONTROLLERS]
    assert all(len(r["rms_error_rad"]) == 3 and r["positive_work_per_cycle_j"] > 0.0 for r in runs)
    assert "10/10 runs" in captured.err
    report = (out / "report.md").read_text()
    assert report.count("| 6000 |") == 5 and "tracking.png" in report and "depth_sweep.png" in report and "fluid_models.png" in report
    # Without the plant's joint losses the right coefficients track better than the wrong ones.
    why = report.split("## Why the wrong coefficients track better", 1)[1].split("##", 1)[0]
    right, wrong = (float(x) for x in re.findall(r"`hydro` ([0-9.]+)° against `hydro_wrong`'s ([0-9.]+)°", why)[0])
    assert right < wrong / 3
    assert (out / "tracking.png").stat().st_size > 10_000 and (out / "depth_sweep.png").stat().st_size > 10_000
    # A study preset: its runs in Parquet, the table's numbers; the same command again reuses them.
    (results,) = out.glob("study-*")
    table = study.read_results(results).to_pylist()
    assert [(r["depth"], r["controller"]) for r in table] == [(r["depth_m"], r["controller"]) for r in runs]
    assert [r["rms_error_1"] for r in table] == [r["rms_error_rad"][0] for r in runs]
    assert main(["simulate", "--out", str(out), "--depths", "0,6000", "--cycles", "1", "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["runs"] == runs
    assert main(["simulate", "--out", str(out), "--depths", "0", "--cycles", "0.5"]) == 0
    table = capsys.readouterr().out
    assert re.search(r"^\s+0\s+hydro_losses\s", table, re.MULTILINE) and "report:" in table
    with pytest.raises(SystemExit) as exit_info:
        main(["simulate", "--depths", "12000"])
    assert exit_info.value.code == 2
    assert "must be depths from 0 to 11000 m" in capsys.readouterr().err


def test_mujocos_fluid_models_beside_uwml() -> None:
    """On one gait cycle, MuJoCo's lumped fluid models (no buoyancy, no added-mass acceleration
    term) differ from uwml's drag + added mass by tens of percent or more on every joint."""
    comparison = simulate.fluid_models(samples=100)
    rms = comparison.rms()
    assert np.all(rms["uwml"] > 1.0) and np.all(rms["box"] > 0.0) and np.all(rms["ellipsoid"] > 0.0)
    for name in ("box", "ellipsoid"):
        assert np.all(comparison.relative_difference(name) > 0.3), (name, comparison.relative_difference(name))
    # uwml's buoyancy is kept apart: Table II's links are denser than water, the thigh's is large.
    assert np.sqrt(np.mean(comparison.buoyancy[:, 1] ** 2)) > 10.0


def test_uwmls_base_wrench_helps_an_rov_hold_station() -> None:
    """The arm moving on its free-floating hull in a 0.5 m/s current: with uwml's predicted
    wrench fed to the station keeping, the vehicle drifts and tilts less than with PD alone."""
    alone, helped = rov_drift(False, duration=4.0), rov_drift(True, duration=4.0)
    a, b = alone.summary(), helped.summary()
    assert a["max_drift_m"] > 0.01 and a["rms_attitude_deg"] > 1.0
    assert b["rms_drift_m"] < 0.8 * a["rms_drift_m"] and b["rms_attitude_deg"] < 0.8 * a["rms_attitude_deg"], (a, b)
    # The current pushes downstream (+x) without the feedforward.
    assert np.mean(alone.position[:, 0] - alone.position[0, 0]) > 0.0
