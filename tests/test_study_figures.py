"""A study's figures and summary (``uwml.study.figures``, ``uwml.study.summary``, ``uwml study``;
docs/scale.md): every metric has its unit, declared where the scenarios' metrics are
(``uwml.study.scenarios.METRICS``, a custom study's ``metrics`` table), and every figure's y axes
carry it; the runs are coloured by the values of the categorical parameters (a controller), one
legend entry per group; the summary is per group, not averaged across them."""

import json
import math
from pathlib import Path

import numpy as np
import pytest
from uwml import examples, study
from uwml.cli import main
from uwml.study import scenarios, study_results

#: A scenario of one's own (tests/study_scenarios.py) with a categorical parameter, ``label``,
#: whose value changes the metric ``label_length``, and a numeric grid, ``stiffness``.
CUSTOM = """
[scenario]
kind = "custom"
function = "study_scenarios:oscillator"
metrics = { amplitude = "m", seen = "count", label_length = "characters" }
mass = 2.0
time = 1.5

[parameters]
stiffness = [1.0, 4.0]
label = ["ab", "abcd", "abcdef"]
damping = { distribution = "uniform", low = 0.0, high = 1.0 }

[sampling]
samples = 2
"""
#: The same with its metrics listed, without units.
LISTED = CUSTOM.replace('{ amplitude = "m", seen = "count", label_length = "characters" }', '["amplitude", "seen", "label_length"]')


@pytest.fixture(scope="module")
def done(tmp_path_factory: pytest.TempPathFactory) -> Path:
    out = tmp_path_factory.mktemp("figures") / "out"
    study.run_study(study.loads(CUSTOM), out, serial=True)
    return out


@pytest.mark.parametrize("kind", ["paper_leg", "rov", "vehicle"])
def test_every_metric_of_a_scenario_has_its_unit(kind: str) -> None:
    units = scenarios.METRICS[kind]
    assert units and all(isinstance(unit, str) and unit for unit in units.values()), units


def test_a_study_records_its_metrics_units_from_the_scenario() -> None:
    """The vehicle's metrics in m, °, N, ...; a robot's errors in rad (its joints revolute); a
    custom study's as its table declares them, or none from a list."""
    bluerov2 = examples.path("bluerov2")
    vehicle = study.loads(
        f'[scenario]\nkind = "vehicle"\nrobot = "{bluerov2 / "bluerov2_arm.urdf"}"\nhydro = "{bluerov2 / "bluerov2_arm.hydro.toml"}"\n'
    )
    assert vehicle.units["rms_drift"] == "m" and vehicle.units["max_pitch"] == "°" and vehicle.units["mean_thrust"] == "N"
    assert tuple(vehicle.units) == vehicle.metrics
    arm = examples.path("my_arm")
    robot = study.loads(f'[scenario]\nkind = "robot"\nrobot = "{arm / "my_arm.urdf"}"\nhydro = "{arm / "my_arm.hydro.toml"}"\n')
    assert robot.units == {
        "rms_error_1": "rad",
        "rms_error_2": "rad",
        "peak_error_1": "rad",
        "peak_error_2": "rad",
        "positive_work": "J",
        "energy": "J",
    }
    custom = study.loads(CUSTOM)
    assert custom.units == {"amplitude": "m", "seen": "count", "label_length": "characters"}
    assert custom.settings["metrics"] == ["amplitude", "seen", "label_length"]  # the fingerprint as for a list
    listed = study.loads(LISTED)
    assert listed.units == dict.fromkeys(listed.metrics, "") and listed.fingerprint() == custom.fingerprint()
    with pytest.raises(study.ConfigError, match="scenario.metrics.*unit as a string"):
        study.loads(CUSTOM.replace('amplitude = "m"', "amplitude = 1"))


def test_the_summary_is_per_group_of_the_categorical_parameters(done: Path) -> None:
    result = study.summary(done)
    table = study.read_results(done).to_pylist()
    assert result["units"] == {"amplitude": "m", "seen": "count", "label_length": "characters"}
    assert [group["parameters"] for group in result["groups"]] == [{"label": "ab"}, {"label": "abcd"}, {"label": "abcdef"}]
    for group in result["groups"]:
        mine = [row for row in table if row["label"] == group["parameters"]["label"]]
        assert group["runs"] == len(mine) == 4 and group["failed"] == 0
        for name in ("amplitude", "label_length"):
            values = [row[name] for row in mine]
            assert group["metrics"][name] == pytest.approx({"mean": np.mean(values), "min": min(values), "max": max(values)}, rel=1e-12)
        assert group["metrics"]["label_length"]["min"] == group["metrics"]["label_length"]["max"] == len(group["parameters"]["label"])
    # The mean over every run stays (JSON's "metrics"), and mixes the groups.
    assert result["metrics"]["label_length"] == {"mean": 4.0, "min": 2.0, "max": 6.0}


def test_a_study_without_categorical_parameters_is_one_group(tmp_path: Path) -> None:
    out = tmp_path / "out"
    study.run_study(study.loads(CUSTOM.replace('label = ["ab", "abcd", "abcdef"]', "")), out, serial=True)
    (group,) = study.summary(out)["groups"]
    assert group["parameters"] == {} and group["runs"] == 4


def test_every_figure_labels_its_y_axes_with_the_unit_and_colours_each_group(done: Path) -> None:
    units = {"amplitude": "m", "seen": "count", "label_length": "characters"}
    for metric, unit in units.items():
        figure = study_results.metric_figure(done, metric)
        axes = figure.axes
        assert [ax.get_xlabel() for ax in axes] == ["stiffness", "label", "damping"]
        for ax in axes:
            assert ax.get_ylabel() == f"{metric} [{unit}]"
        (legend,) = figure.legends
        assert legend.get_title().get_text() == "label"
        assert [text.get_text() for text in legend.get_texts()] == ["ab", "abcd", "abcdef"]
        # Each panel's points: one colour per group, the legend's.
        legend_colours = [tuple(handle.get_color()) for handle in legend.legend_handles]
        for ax in axes:
            points = [line for line in ax.get_lines() if line.get_marker() == "o"]
            assert [tuple(line.get_color()) for line in points] == legend_colours
            assert sum(len(line.get_xdata()) for line in points) == 12
        # The grid's numeric parameter: each group's mean joined by a line.
        means = [line for line in axes[0].get_lines() if line.get_linestyle() == "-" and line.get_marker() in ("None", "")]
        assert len(means) == 3
        assert metric in figure.get_suptitle() and f"[{unit}]" in figure.get_suptitle()
    written = study.figures(done)
    assert sorted(path.name for path in written) == sorted(f"{metric}.png" for metric in units)


def test_a_metric_of_many_decades_is_drawn_on_a_log_axis_and_a_custom_metric_without_unit_says_so(tmp_path: Path) -> None:
    out = tmp_path / "out"
    long = LISTED.replace("time = 1.5\n", "").replace("stiffness = [1.0, 4.0]", "stiffness = [1.0, 4.0]\ntime = [0.5, 40.0]")
    study.run_study(study.loads(long), out, serial=True)
    figure = study_results.metric_figure(out, "amplitude")
    assert figure.axes[0].get_ylabel() == "amplitude [no unit declared]"
    amplitudes = np.array([row["amplitude"] for row in study.read_results(out).to_pylist()])
    assert amplitudes.max() / amplitudes.min() > 1e3 and all(ax.get_yscale() == "log" for ax in figure.axes)
    assert study_results.metric_figure(out, "label_length").axes[0].get_yscale() == "linear"


def test_a_study_begun_without_units_in_its_record_takes_its_scenario_s(done: Path) -> None:
    record = {"kind": "vehicle", "metrics": ["rms_drift", "rms_pitch"], "parameters": []}
    assert study_results.units(record) == {"rms_drift": "m", "rms_pitch": "°"}
    assert study_results.units({"kind": "robot", "metrics": ["rms_error_1", "energy"]}) == {"rms_error_1": "rad", "energy": "J"}
    assert study_results.units({"kind": "custom", "metrics": ["x"]}) == {"x": ""}
    assert json.loads((done / "study.json").read_text())["units"]["amplitude"] == "m"


def test_the_command_line_prints_the_summary_per_group_with_units(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    path = tmp_path / "study.toml"
    path.write_text(CUSTOM)
    out = tmp_path / "out"
    assert main(["study", str(path), "--out", str(out), "--serial", "--no-figures"]) == 0
    printed = capsys.readouterr().out
    blocks = printed.split("\nlabel = ")[1:]
    assert [block.split(" ")[0] for block in blocks] == ["ab", "abcd", "abcdef"]
    for block, length in zip(blocks, (2, 4, 6), strict=True):
        assert "(4 runs)" in block.splitlines()[0]
        (line,) = [line for line in block.splitlines() if "label_length [characters]" in line]
        assert [float(cell) for cell in line.split()[-3:]] == [length] * 3
    assert main(["study", str(path), "--out", str(out), "--serial", "--resume", "--json"]) == 0
    result = json.loads(capsys.readouterr().out)
    assert len(result["groups"]) == 3 and result["units"]["amplitude"] == "m"
    assert math.isfinite(result["groups"][0]["metrics"]["amplitude"]["mean"])
