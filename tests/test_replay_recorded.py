"""``uwml replay`` on logs as recorders write them (docs/simulation.md, "Replaying a pool trial"):
joint values written 2–3 times in a row, gaps in a motion-capture stream after the joints end,
a jittery pose at rest, a joint starting beyond its limit, time stamps printed to the
microsecond that are not on the simulation's step grid. Each file is made to look like a
recorded one (times from a logger's clock, six decimals) from the BlueROV2 example's arm waving
(:func:`test_replay.waving`), whose exact motion the tests hold the replay against."""

from __future__ import annotations

import json
import warnings
from pathlib import Path

import numpy as np
import pytest
import uwml

pytest.importorskip("mujoco")

from scipy.spatial.transform import Rotation
from test_replay import HYDRO, URDF, waving
from uwml.cli import main
from uwml.errors import UwmlError
from uwml.sim.prescribed import Trajectory
from uwml.sim.replay import MAX_TIMESTEP_S, replay, step_times
from uwml.sim.replay_inputs import PLAUSIBLE_ANGULAR_ACCELERATION, collapse_repeats, joint_motion, read_streams

#: A logger's clock at the start of the recordings [s].
CLOCK = 12.134635


def _write(path: Path, columns: dict[str, np.ndarray]) -> Path:
    """A CSV file as a recorder writes it: times and values to six decimals."""
    rows = zip(*columns.values(), strict=True)
    path.write_text(",".join(columns) + "\n" + "".join(",".join(f"{float(x):.6f}" for x in row) + "\n" for row in rows))
    return path


def _stalled_joints(seconds: float = 2.0, seed: int = 5) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """A 500 Hz joint log whose encoder is new every 2nd or 3rd sample (the logger writes each
    value 2–3 times): the times, the angles written, and the samples where they were new."""
    rng = np.random.default_rng(seed)
    count = round(seconds / 0.002) + 1
    fresh = np.cumsum(np.concatenate([[0], rng.integers(2, 4, count)]))
    fresh = fresh[fresh < count]
    time = CLOCK + 0.002 * np.arange(count)
    newest = np.searchsorted(fresh, np.arange(count), side="right") - 1
    q = np.array([waving(t - CLOCK)[0] for t in time[fresh]])[newest]
    return time, q, fresh


def test_repeated_samples_are_collapsed_and_the_accelerations_stay_the_motion_s(tmp_path: Path) -> None:
    """The cubic spline through the staircase (what the replay differentiated before) has
    accelerations of 9,000 rad/s²; collapsed to the samples where the values were new and
    smoothed over 0.1 s, the accelerations are the arm's (at most 3.2 and 5.4 rad/s²) to 0.03
    rad/s² (measured 0.021), and no warning is raised."""
    time, q, fresh = _stalled_joints()
    spline = Trajectory(time, q)
    assert max(np.abs(spline(t)[2]).max() for t in time) > 5000.0  # the defect, as it was replayed
    log = _write(tmp_path / "joints.csv", {"time": time, "q1": q[:, 0], "q2": q[:, 1]})
    for j in range(2):
        kept = collapse_repeats(time, np.round(q[:, j], 6), 0.1)
        np.testing.assert_array_equal(kept, np.union1d(fresh, [time.size - 1]))
    result = replay(log, URDF, HYDRO)
    motion = result.motion
    assert motion is not None and motion.smoothing_s == 0.1 and motion.window == 51 and motion.samples == time.size
    assert motion.kept == (len(np.union1d(fresh, [time.size - 1])),) * 2 and motion.kept[0] < time.size / 2
    truth = np.array([waving(t - CLOCK)[2] for t in motion.time])
    assert np.abs(motion.qdd - truth).max() < 0.03
    assert np.abs(motion.qdd).max() < 5.5


def test_an_implausible_acceleration_after_smoothing_names_the_joint(tmp_path: Path) -> None:
    """A glitch of 1 rad in one sample of the elbow: smoothed over 0.02 s its acceleration is
    still 8,700 rad/s², beyond the plausible 500 rad/s²: a PlausibilityWarning names the joint,
    the value and the bound; over 0.1 s it is 107 rad/s², and nothing is said."""
    time = CLOCK + 0.002 * np.arange(1001)
    q = np.array([waving(t - CLOCK)[0] for t in time])
    q[500, 1] += 1.0
    log = _write(tmp_path / "glitch.csv", {"time": time, "q1": q[:, 0], "q2": q[:, 1]})
    streams = read_streams(log, 2)
    joints = uwml.Robot.from_urdf(URDF, HYDRO).joints
    with pytest.warns(uwml.PlausibilityWarning, match=r"column 'q2': joint 2 \('elbow'\)'s acceleration, smoothed over 0\.02 s") as caught:
        joint_motion(streams.joints, joints, smoothing=0.02)
    message = str(caught[0].message)
    assert f"beyond a plausible {PLAUSIBLE_ANGULAR_ACCELERATION:g} rad/s²" in message and "glitch.csv" in message, message
    assert "q1" not in message
    motion = joint_motion(streams.joints, joints, smoothing=0.1)  # filterwarnings = error: no warning
    assert 50.0 < np.abs(motion.qdd[:, 1]).max() < PLAUSIBLE_ANGULAR_ACCELERATION


def _pose_columns(time: np.ndarray, position: np.ndarray, quaternion: np.ndarray) -> dict[str, np.ndarray]:
    return {"time": time, **{name: position[:, k] for k, name in enumerate("xyz")}} | {
        name: quaternion[:, k] for k, name in enumerate(("qw", "qx", "qy", "qz"))
    }


def test_pose_gaps_are_bridged_and_joint_gaps_refused_naming_rows(tmp_path: Path) -> None:
    """Motion capture at 100 Hz for 2 s, dropping out for 0.11 s three times (once while the
    joints are logged, twice after they end); the joints for the first second. The pose's gaps
    are bridged (one of them in the replayed span); a gap of 0.11 s in the joints is refused
    naming its rows, and replayed with ``max_gap=0.2``."""
    joint_time = CLOCK + 0.01 * np.arange(101)
    q = np.array([waving(t - CLOCK)[0] for t in joint_time])
    joints = _write(tmp_path / "joints.csv", {"time": joint_time, "q1": q[:, 0], "q2": q[:, 1]})
    pose_time = CLOCK + 0.01 * np.arange(201)
    dropped = np.zeros(pose_time.size, dtype=bool)
    for start in (50, 130, 170):
        dropped[start + 1 : start + 11] = True  # 10 samples missing: 0.11 s between two left
    pose_time = pose_time[~dropped]
    level = np.tile([1.0, 0.0, 0.0, 0.0], (pose_time.size, 1))
    mocap = _write(tmp_path / "mocap.csv", _pose_columns(pose_time, np.zeros((pose_time.size, 3)), level))
    result = replay([joints, mocap], URDF, HYDRO, start_at_rest=True)
    assert result.bridged == 1 and result.errors is not None
    assert result.time[0] == joint_time[0] and result.time[-1] == joint_time[-1]
    # A gap in the joints: refused, naming the rows of the joint file.
    kept = np.delete(np.arange(101), np.arange(41, 51))
    gappy = _write(tmp_path / "gappy.csv", {"time": joint_time[kept], "q1": q[kept, 0], "q2": q[kept, 1]})
    pattern = r"gappy\.csv: a gap of 0\.11 s between t = 12\.5346 and 12\.6446 s \(rows 42 and 43\), longer than 0\.1 s: split"
    with pytest.raises(UwmlError, match=pattern):
        replay([gappy, mocap], URDF, HYDRO)
    assert replay([gappy, mocap], URDF, HYDRO, max_gap=0.2, start_at_rest=True).time[-1] == joint_time[-1]
    with pytest.raises(ValueError, match=r"max_gap must be a finite number of seconds > 0, got -1"):
        replay([gappy, mocap], URDF, HYDRO, max_gap=-1)


def test_the_start_twist_of_a_jittery_pose_at_rest_is_near_zero(tmp_path: Path) -> None:
    """The vehicle at rest, its pose recorded at 100 Hz with noise of 0.5 mm and 0.1° (motion
    capture in a pool): the slopes of the first three samples said 0.1 m/s and 0.4 rad/s; the
    cubic fit over 0.5 s says 5e-3 m/s and 0.016 rad/s (one standard deviation): bounded here at
    0.02 m/s and 0.07 rad/s."""
    rng = np.random.default_rng(11)
    time = CLOCK + 0.01 * np.arange(101)
    position = np.array([0.3, -0.2, -1.5]) + rng.normal(0.0, 5e-4, (time.size, 3))
    quaternion = Rotation.from_rotvec(rng.normal(0.0, np.radians(0.1), (time.size, 3))).as_quat()[:, [3, 0, 1, 2]]
    columns = _pose_columns(time, position, quaternion) | {"q1": np.zeros(time.size), "q2": np.zeros(time.size)}
    log = _write(tmp_path / "still.csv", columns)
    result = replay(log, URDF, HYDRO)
    start = result.twist[0]
    assert np.abs(start[:3]).max() < 0.02 and np.abs(start[3:]).max() < 0.07, start
    assert result.start is not None and result.start.how == "fit" and result.start.samples == 51
    np.testing.assert_array_equal(result.start.twist, start)
    # The window is an option; zero twist on request.
    assert replay(log, URDF, HYDRO, start_window=0.2).start.samples == 21  # type: ignore[union-attr]
    np.testing.assert_array_equal(replay(log, URDF, HYDRO, start_at_rest=True).twist[0], np.zeros(6))
    with pytest.raises(UwmlError, match=r"still\.csv: 1 pose sample within the start window.*--start-window.*--start-at-rest"):
        replay(log, URDF, HYDRO, start_window=0.005)


def test_a_joint_starting_beyond_its_limit_is_refused_naming_joint_value_range_file_and_row(tmp_path: Path) -> None:
    """The shoulder (range ±1.5 rad) logged from 1.52 rad, coming back within its range: its
    limit would fight the replayed motion from the first step."""
    time = CLOCK + 0.01 * np.arange(50)
    q1 = 1.52 - 0.2 * (time - CLOCK)
    log = _write(tmp_path / "beyond.csv", {"time": time, "q1": q1, "q2": np.zeros(time.size)})
    expected = (
        r"beyond\.csv: row 2, column 'q1' \(at the start\): 1\.52 rad is outside the range of joint 1 \('shoulder'\), "
        r"-1\.5 to 1\.5 rad, allowed by .*bluerov2_arm\.urdf \(10 samples outside"
    )
    with pytest.raises(UwmlError, match=expected):
        replay(log, URDF, HYDRO)


def test_the_last_sample_replays_when_the_span_is_off_the_step_grid(tmp_path: Path) -> None:
    """Times from a logger's clock, the last one not on the 2 ms step grid of the first: the
    replay runs to the last sample (its last step shortened; before, it stopped a step short or,
    its clock summed past the end, failed with "the prescribed motion is given from t = 0.134635
    to 16.9946 s, not at t = 16.9946 s")."""
    time = CLOCK + 0.01 * np.arange(30)
    time[-1] = CLOCK + 0.2873
    q = np.array([waving(t - CLOCK)[0] for t in time])
    log = _write(tmp_path / "span.csv", {"time": time, "q1": q[:, 0], "q2": q[:, 1]})
    result = replay(log, URDF, HYDRO)
    assert result.time[0] == time[0] and result.time[-1] == time[-1]
    steps = np.diff(result.time)
    assert np.allclose(steps[:-1], 0.002, rtol=0.0, atol=1e-12) and 0.0 < steps[-1] < 0.002
    # The end a millionth of a step beside the grid (the report's 0.134635 to 16.9946 s): the
    # last step lands on it, no step beyond.
    np.testing.assert_array_equal(step_times(0.134635, 0.134635 + 8430 * 0.002 - 1.5e-12, 0.002)[-1], 0.134635 + 8430 * 0.002 - 1.5e-12)
    assert step_times(0.134635, 16.9946, 0.002).size == 8430


def test_the_command_line_options(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    """--smoothing, --max-gap, --start-window, --start-at-rest, --timestep and --integrator reach
    the replay; the JSON has the start twist and how the log was read; the figure is written;
    bad values are refused in one line."""
    time, q, _ = _stalled_joints(seconds=0.6)
    log = _write(tmp_path / "joints.csv", {"time": time, "q1": q[:, 0], "q2": q[:, 1]})
    out = tmp_path / "out"
    base = ["replay", str(log), "--robot", str(URDF), "--hydro", str(HYDRO), "--out", str(out)]
    options = ["--smoothing", "0.05", "--max-gap", "0.2", "--timestep", "0.001", "--integrator", "RK4", "--json"]
    assert main([*base, *options]) == 0
    summary = json.loads(capsys.readouterr().out)
    assert summary["errors"] is None and summary["joints"]["smoothing_s"] == 0.05 and summary["joints"]["samples"] == time.size
    assert summary["start"] == {
        "twist": dict.fromkeys(("vx", "vy", "vz", "wx", "wy", "wz"), 0.0),
        "how": "no pose",
        "window_s": None,
        "samples": 0,
    }
    written = np.loadtxt(out / "replay.csv", delimiter=",", skiprows=1)
    assert written[1, 0] - written[0, 0] == pytest.approx(0.001, abs=1e-12) and written[-1, 0] == round(time[-1], 6)
    assert (out / "replay.png").stat().st_size > 1000
    # The table: the start twist, the samples kept.
    assert main([*base, "--start-at-rest", "--start-window", "0.3"]) == 0
    printed = capsys.readouterr().out
    assert "start twist v = (0, 0, 0) m/s" in printed and "after collapsing repeats" in printed, printed
    for bad, words in (
        (["--integrator", "implicit"], "--integrator: invalid choice: 'implicit'"),
        (["--timestep", "0"], "--timestep: must be a positive number"),
        (["--smoothing", "nan"], "--smoothing: must be a positive number"),
    ):
        with pytest.raises(SystemExit) as exit_status:
            main([*base, *bad])
        assert exit_status.value.code == 2 and words in capsys.readouterr().err
    assert main([*base, "--timestep", "0.5"]) == 2
    assert f"timestep must be at most {MAX_TIMESTEP_S:g} s" in capsys.readouterr().err
    with pytest.raises(
        ValueError, match=r"integrator must be one of euler, rk4 \(.*MuJoCo's implicit integrators are not used\), got 'implicitfast'"
    ):
        replay(log, URDF, HYDRO, integrator="implicitfast")
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        with pytest.raises(ValueError, match=r"smoothing window of 1 s \(501 samples .*\) is longer than the replayed span"):
            replay(log, URDF, HYDRO, smoothing=1.0)
