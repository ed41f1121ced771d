"""Hostile replay logs (``uwml replay``, :func:`uwml.sim.replay.replay`): a log whose motion would
make the floating vehicle's simulation diverge (a joint jumping or offset beyond its range, a pose
at 1e300 m, accelerations that blow the state up) ends in one line ``uwml: error:`` naming the
file and the cause, with exit status 2, never a ``FloatingPointError`` traceback; a quaternion's
sign does not matter; short, semicolon-separated and Parquet logs of the wrong types are named."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

pytest.importorskip("mujoco")

from test_replay import HYDRO, URDF, pool_trial
from uwml.cli import main
from uwml.sim.replay import replay
from uwml.sim.replay_inputs import read_vehicle_pose

#: 30 samples at 100 Hz: 0.29 s of replay.
TIME = np.arange(30) * 0.01
POSE = "x,y,z,qw,qx,qy,qz"


def _log(path: Path, q1: np.ndarray, pose: tuple[float, ...] | None = None, extra: dict[str, np.ndarray] | None = None) -> Path:
    """A joint log of the BlueROV2 arm (``q2`` still), with a fixed pose if given and extra columns."""
    columns = {"time": TIME, "q1": q1, "q2": np.zeros_like(TIME), **(extra or {})}
    if pose is not None:
        columns |= {name: np.full_like(TIME, value) for name, value in zip(POSE.split(","), pose, strict=True)}
    lines = [",".join(columns)] + [",".join(repr(float(c[k])) for c in columns.values()) for k in range(TIME.size)]
    path.write_text("\n".join(lines) + "\n")
    return path


def _replay_error(log: Path, capsys: pytest.CaptureFixture[str], *words: str) -> str:
    """``uwml replay LOG`` in this process: exit status 2 and one line ``uwml: error:`` with ``words``."""
    out = log.parent / "out"
    status = main(["replay", str(log), "--robot", str(URDF), "--hydro", str(HYDRO), "--out", str(out), "--json"])
    err = capsys.readouterr().err
    assert status == 2, err[-2000:]
    assert err.count("\n") == 1 and err.startswith("uwml: error: ") and "Traceback" not in err, err[-2000:]
    for word in (str(log), *words):
        assert word in err, (word, err)
    return err


def test_a_jump_beyond_the_joint_s_range_names_its_row(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    """The arm's shoulder (range ±1.5 rad) jumps to 100 rad at row 17: the simulation diverged."""
    log = _log(tmp_path / "jump.csv", np.where(TIME < 0.15, 0.0, 100.0))
    _replay_error(log, capsys, "row 17, column 'q1'", "'shoulder'", "jumps by 100 rad", "t = 0.14 to 0.15 s")
    # Within half a turn, but beyond the range: the joint's limit would fight the log.
    log = _log(tmp_path / "step.csv", np.where(TIME < 0.15, 0.0, 3.0))
    _replay_error(log, capsys, "row 17, column 'q1'", "3 rad is outside the range of joint 1 ('shoulder'), -1.5 to 1.5 rad")


def test_an_angle_offset_of_1e6_names_the_joint_s_range(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    log = _log(tmp_path / "offset.csv", 1e6 + 0.1 * np.sin(TIME))
    _replay_error(log, capsys, "row 2, column 'q1'", "1e+06 rad is outside the range", "-1.5 to 1.5 rad")


def test_a_pose_at_1e300_names_the_column_and_the_bound(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    log = _log(tmp_path / "far.csv", np.zeros_like(TIME), pose=(0.0, 1e300, 0.0, 1.0, 0.0, 0.0, 0.0))
    _replay_error(log, capsys, "row 2, column 'y'", "1e+300 m", "10000 m")
    with pytest.raises(ValueError, match=r"far\.csv: row 2, column 'y': the vehicle's position 1e\+300 m is beyond ±10000 m"):
        read_vehicle_pose(log)


def test_a_simulation_that_diverges_names_the_time_and_the_rows(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    """Angles within the range, but an acceleration of 1e12 rad/s² logged at row 12: the state
    blows up, and the error says when (the rows around it), not a FloatingPointError."""
    qdd = np.where(np.arange(TIME.size) == 10, 1e12, 0.0)
    zero = np.zeros_like(TIME)
    log = _log(tmp_path / "blows.csv", zero, extra={"qd1": zero, "qd2": zero, "qdd1": qdd, "qdd2": zero})
    err = _replay_error(log, capsys, "the replay diverged at t = ", "state is no longer finite")
    assert "rows " in err, err


def test_a_diverging_replay_is_one_line_from_the_real_command(tmp_path: Path) -> None:
    log = _log(tmp_path / "offset.csv", np.full_like(TIME, 1e6))
    command = [sys.executable, "-m", "uwml", "replay", str(log), "--robot", str(URDF), "--hydro", str(HYDRO)]
    result = subprocess.run([*command, "--out", str(tmp_path / "out"), "--json"], check=False, capture_output=True, text=True, timeout=300)
    assert result.returncode == 2, result.stderr[-2000:]
    lines = [line for line in result.stderr.splitlines() if line.strip()]
    assert len(lines) == 1 and lines[0].startswith(f"uwml: error: {log}: row 2, column 'q1'"), result.stderr[-2000:]


def test_a_sign_flip_of_the_quaternion_in_one_file_changes_nothing(tmp_path: Path) -> None:
    """q and −q are the same turn: a log whose third pose is written with the other sign starts
    with the same angular velocity and replays the same (as a separate pose stream does)."""
    log = tmp_path / "trial.csv"
    pool_trial(log, seconds=0.3)
    lines = log.read_text().splitlines()
    cells = lines[3].split(",")
    cells[10:14] = [repr(-float(c)) for c in cells[10:14]]
    flipped = tmp_path / "flipped.csv"
    flipped.write_text("\n".join([*lines[:3], ",".join(cells), *lines[4:]]) + "\n")
    plain, other = replay(log, URDF, HYDRO), replay(flipped, URDF, HYDRO)
    np.testing.assert_array_equal(other.twist[0], plain.twist[0])
    np.testing.assert_array_equal(other.position, plain.position)
    np.testing.assert_array_equal(other.quaternion, plain.quaternion)


def test_short_and_semicolon_separated_logs_name_the_file_and_the_cause(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    short = tmp_path / "short.csv"
    short.write_text("time,q1,q2\n0,0,0\n0.01,0,0\n0.02,0,0\n")
    _replay_error(short, capsys, "3 samples", "at least 4")
    semicolons = tmp_path / "semicolons.csv"
    semicolons.write_text("time;q1;q2\n" + "".join(f"{t!r};0;0\n" for t in TIME))
    _replay_error(semicolons, capsys, "row 1 (header)", "separated by commas")
    # A pose stream of semicolons beside a good joint stream: named, not ignored.
    joints, pose = _log(tmp_path / "joints.csv", np.zeros_like(TIME)), tmp_path / "pose.csv"
    pose.write_text("time;x;y;z;qw;qx;qy;qz\n" + "".join(f"{t!r};0;0;0;1;0;0;0\n" for t in TIME))
    with pytest.raises(ValueError, match=r"pose\.csv: row 1 \(header\): neither joint angles .* nor a pose .*separated by commas"):
        replay([joints, pose], URDF, HYDRO)


def test_parquet_columns_that_are_not_numbers_are_refused(tmp_path: Path) -> None:
    import pyarrow
    import pyarrow.parquet

    columns = {"time": TIME, "q1": np.zeros_like(TIME), "q2": np.zeros_like(TIME)}
    pose = {"x": np.zeros_like(TIME), "y": np.zeros_like(TIME), "z": np.zeros_like(TIME)}
    pose |= {"roll": pyarrow.array([True] * TIME.size), "pitch": np.zeros_like(TIME), "yaw": np.zeros_like(TIME)}
    path = tmp_path / "bools.parquet"
    pyarrow.parquet.write_table(pyarrow.table({**columns, **pose}), path)
    with pytest.raises(ValueError, match=r"bools\.parquet: column 'roll': .*bool.*integers or floating point"):
        read_vehicle_pose(path)
    with pytest.raises(ValueError, match=r"bools\.parquet: column 'roll': .*bool"):
        replay(path, URDF, HYDRO)
