"""``uwml replay`` of a trial with its thrusters on, read as it was recorded (docs/simulation.md,
"Replaying a pool trial"). The trial is made by simulating the BlueROV2 example (floating, eight
T200s) with its arm waving (:func:`test_replay.waving`) and known thruster commands, a few held
steps (surge, heave, a turn, idle), and recording it at 100 Hz under other column names, with a
sign flip, an offset, time in milliseconds and Euler angles in degrees: a column map reads it.
The replay holds each command from its sample until the next (as an ESC does) and reproduces the
recorded pose; without the commands it does not; a log with another number of commands than the
robot has thrusters is refused."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

pytest.importorskip("mujoco")

from scipy.spatial.transform import Rotation
from test_replay import HYDRO, URDF, waving
from uwml.cli import main
from uwml.errors import UwmlError
from uwml.sim.mujoco import Simulation
from uwml.sim.prescribed import Trajectory
from uwml.sim.replay import Replay, held_commands, replay

#: The commands held from each time [s]: surge on the horizontal four, heave on the vertical
#: four, a turn (the horizontal pairs against each other), then idle.
SCHEDULE = (
    (0.0, [0.5, 0.5, 0.5, 0.5, 0.0, 0.0, 0.0, 0.0]),
    (0.5, [0.0, 0.0, 0.0, 0.0, 0.3, 0.3, 0.3, 0.3]),
    (1.0, [0.4, -0.4, 0.4, -0.4, 0.0, 0.0, 0.0, 0.0]),
    (1.5, [0.0] * 8),
)
#: The recorder's clock at the trial's start [ms].
CLOCK_MS = 5000.0
#: The recorded file's columns as the map reads them: time in ms, the shoulder's sign flipped,
#: the elbow's encoder offset by 0.25 rad, depth for z, Euler angles in degrees.
MAP = """\
[time]
column = "stamp_ms"
unit = "ms"
[joints]
q1 = { column = "shoulder_enc", sign = -1 }
q2 = { column = "elbow_enc", offset = -0.25 }
[vehicle]
x = "px"
y = "py"
z = { column = "depth", sign = -1 }
roll = { column = "roll_deg", unit = "deg" }
pitch = { column = "pitch_deg", unit = "deg" }
yaw = { column = "yaw_deg", unit = "deg" }
"""


def _thrusters(count: int = 8, prefix: str = "esc_") -> str:
    return "".join(f'u{k + 1} = "{prefix}{k + 1}"\n' for k in range(count))


@pytest.fixture(scope="module")
def trial() -> dict[str, np.ndarray]:
    """The trial, 2 s sampled at 100 Hz (every fifth 2 ms step): time [s], joint angles, rates and
    accelerations, the vehicle's pose and the commands held from each sample on."""
    sim = Simulation.from_file(URDF, HYDRO)
    sim.prescribe(["shoulder", "elbow"], Trajectory.of(waving, joints=2))
    h = sim.model.opt.timestep
    changes = {round(t / h): np.array(u) for t, u in SCHEDULE}
    rows, steps = [], round(2.0 / h)
    for k in range(steps + 1):
        if k in changes:
            sim.command_thrusters(changes[k])
            held = changes[k]
        if k % 5 == 0:
            q, qd, qdd = waving(sim.data.time)
            rows.append([sim.data.time, *q, *qd, *qdd, *sim.data.qpos[:7], *held])
        if k < steps:
            sim.step()
    table = np.array(rows)
    names = ("time", "q", "qd", "qdd", "position", "quaternion", "commands")
    return dict(zip(names, np.split(table, [1, 3, 5, 7, 10, 14], axis=1), strict=True)) | {"time": table[:, 0]}


def _write(path: Path, columns: dict[str, np.ndarray]) -> Path:
    rows = zip(*columns.values(), strict=True)
    path.write_text(",".join(columns) + "\n" + "".join(",".join(repr(float(x)) for x in row) + "\n" for row in rows))
    return path


def recorded(trial: dict[str, np.ndarray], path: Path, rates: bool = False, commands: int = 8) -> Path:
    """The trial as its recorder wrote it (the module), with ``commands`` thruster columns."""
    euler = Rotation.from_quat(trial["quaternion"][:, [1, 2, 3, 0]]).as_euler("ZYX")[:, ::-1]
    q, position = trial["q"], trial["position"]
    columns = {"stamp_ms": CLOCK_MS + 1e3 * trial["time"], "shoulder_enc": -q[:, 0], "elbow_enc": q[:, 1] + 0.25}
    if rates:
        columns |= {"w1": trial["qd"][:, 0], "w2": trial["qd"][:, 1], "a1": trial["qdd"][:, 0], "a2": trial["qdd"][:, 1]}
    columns |= {"px": position[:, 0], "py": position[:, 1], "depth": -position[:, 2]}
    columns |= {f"{name}_deg": np.degrees(euler[:, k]) for k, name in enumerate(("roll", "pitch", "yaw"))}
    columns |= {f"esc_{k + 1}": trial["commands"][:, k] for k in range(commands)}
    return _write(path, columns)


def pose_error(result: Replay, trial: dict[str, np.ndarray]) -> tuple[float, float]:
    """The largest distance [m] and turn [rad] between the replayed pose and the trial's, at the
    trial's samples inside the replayed span."""
    time = CLOCK_MS / 1e3 + trial["time"]
    inside = (time >= result.time[0]) & (time <= result.time[-1])
    time = time[inside]
    position = np.column_stack([np.interp(time, result.time, result.position[:, k]) for k in range(3)])
    quaternion = np.column_stack([np.interp(time, result.time, result.quaternion[:, k]) for k in range(4)])
    turn = Rotation.from_quat(quaternion[:, [1, 2, 3, 0]]).inv() * Rotation.from_quat(trial["quaternion"][inside][:, [1, 2, 3, 0]])
    return float(np.abs(position - trial["position"][inside]).max()), float(turn.magnitude().max())


def test_the_replay_holds_the_recorded_commands_and_reproduces_the_trial(trial: dict[str, np.ndarray], tmp_path: Path) -> None:
    """Through the map, started at rest as the trial was: within 2e-5 m and 3e-4 rad of the trial's
    pose (measured 4.0e-6 m, 6.2e-5 rad; the joints' rates and accelerations come from the
    smoothing fit over 0.1 s, not the trial's). With the trial's rates and accelerations in the
    log too, to rounding (measured 3.8e-12 m, 4.6e-11 rad): each command acts from its sample's
    step, exactly as in the trial. Without the commands, the vehicle neither surges, heaves nor
    turns: 0.27 m and 0.97 rad off (the commands matter)."""
    log, columns = recorded(trial, tmp_path / "trial.csv"), tmp_path / "map.toml"
    columns.write_text(MAP + _thrusters())
    result = replay(log, URDF, HYDRO, columns=columns, start_at_rest=True)
    assert result.time[0] == CLOCK_MS / 1e3 and result.time[-1] == pytest.approx(CLOCK_MS / 1e3 + 2.0, abs=1e-12)
    assert np.ptp(trial["position"][:, 0]) > 0.2 and np.ptp(trial["position"][:, 2]) > 0.05  # it moved
    distance, turn = pose_error(result, trial)
    assert distance < 2e-5 and turn < 3e-4, (distance, turn)
    drive = result.thrusters
    assert drive is not None and drive.driven and drive.count == 8 and drive.samples == 200, drive
    assert drive.longest_hold_s == pytest.approx(0.01, abs=1e-9) and "(through" in str(drive.source)
    assert result.summary()["thrusters"] == {
        "count": 8,
        "driven": True,
        "samples": 200,
        "source": drive.source,
        "longest_hold_s": drive.longest_hold_s,
    }
    rates = recorded(trial, tmp_path / "rates.csv", rates=True)
    given = tmp_path / "rates.toml"
    given.write_text(MAP.replace("[vehicle]", 'qd1 = "w1"\nqd2 = "w2"\nqdd1 = "a1"\nqdd2 = "a2"\n[vehicle]') + _thrusters())
    distance, turn = pose_error(replay(rates, URDF, HYDRO, columns=given, start_at_rest=True), trial)
    assert distance < 1e-9 and turn < 1e-9, (distance, turn)
    idle_map = tmp_path / "idle.toml"
    idle_map.write_text(MAP)
    idle = replay(log, URDF, HYDRO, columns=idle_map, start_at_rest=True)
    assert idle.thrusters is not None and not idle.thrusters.driven and idle.thrusters.count == 8
    distance, turn = pose_error(idle, trial)
    assert distance > 0.1 and turn > 0.5, (distance, turn)


def test_the_command_line_reads_the_map_and_says_the_thrusters_were_driven(
    trial: dict[str, np.ndarray], tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    log, columns = recorded(trial, tmp_path / "trial.csv"), tmp_path / "map.toml"
    columns.write_text(MAP + _thrusters())
    out = tmp_path / "out"
    base = ["replay", str(log), "--columns", str(columns), "--robot", str(URDF), "--hydro", str(HYDRO), "--out", str(out)]
    assert main([*base, "--start-at-rest", "--json"]) == 0
    summary = json.loads(capsys.readouterr().out)
    assert summary["thrusters"]["driven"] is True and summary["thrusters"]["samples"] == 200, summary
    assert summary["errors"]["pitch"] < 1e-4 and summary["errors"]["heave"] < 1e-5, summary["errors"]
    written = np.loadtxt(out / "replay.csv", delimiter=",", skiprows=1)
    saved = Replay(written[:, 0], written[:, 1:4], written[:, 4:8], written[:, 8:], None)
    distance, turn = pose_error(saved, trial)
    assert distance < 2e-5 and turn < 3e-4, (distance, turn)
    assert main([*base, "--start-at-rest"]) == 0
    assert "thrusters driven by the log's commands u1 … u8 (200 samples" in capsys.readouterr().out
    columns.write_text(MAP)
    assert main([*base, "--start-at-rest"]) == 0
    assert "thrusters idle: the log has no thruster commands (u1 … u8 for the robot's 8 thrusters)" in capsys.readouterr().out


def test_commands_logged_apart_on_their_own_clock_are_held_from_their_samples(trial: dict[str, np.ndarray], tmp_path: Path) -> None:
    """The ESC's commands at 20 Hz in a file of their own, on a clock 95 s ahead (the map's time
    offset puts it back): joined on time and held sample to sample, they reproduce the trial as
    the commands in the same file do (within the same bounds; the span every stream covers)."""
    log = recorded(trial, tmp_path / "trial.csv", commands=0)
    esc = {"t": trial["time"][::5] + 100.0} | {f"pwm{k + 1}": trial["commands"][::5, k] for k in range(8)}
    _write(tmp_path / "esc.csv", esc)
    streams = tmp_path / "streams.toml"
    streams.write_text(
        '[[streams]]\ntime = { column = "stamp_ms", unit = "ms" }\n[streams.joints]\n'
        + MAP.split("[joints]\n")[1].replace("[vehicle]", "[streams.vehicle]")
        + '[[streams]]\nfile = "esc.csv"\ntime = { column = "t", offset = -95.0 }\n[streams.vehicle]\n'
        + _thrusters(prefix="pwm")
    )
    result = replay(log, URDF, HYDRO, columns=streams, start_at_rest=True)
    drive = result.thrusters
    assert drive is not None and drive.samples == 40 and drive.longest_hold_s == pytest.approx(0.05, abs=1e-9), drive
    assert drive.source is not None and "esc.csv" in drive.source
    assert result.time[-1] > CLOCK_MS / 1e3 + 1.9
    distance, turn = pose_error(result, trial)
    assert distance < 2e-5 and turn < 3e-4, (distance, turn)


def test_a_log_with_another_number_of_thruster_commands_is_refused(
    trial: dict[str, np.ndarray], tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    log, columns = recorded(trial, tmp_path / "seven.csv", commands=7), tmp_path / "map.toml"
    columns.write_text(MAP + _thrusters(7))
    expected = r"seven\.csv \(through .*map\.toml\): row 1 \(header\), column 'u8': the log has 7 thruster commands \(u1 … u7\), the robot"
    with pytest.raises(UwmlError, match=expected + r" of .*bluerov2_arm\.urdf has 8 thrusters"):
        replay(log, URDF, HYDRO, columns=columns)
    out = str(tmp_path / "out")
    assert main(["replay", str(log), "--columns", str(columns), "--robot", str(URDF), "--hydro", str(HYDRO), "--out", out]) == 2
    err = capsys.readouterr().err
    assert err.startswith("uwml: error: ") and "7 thruster commands" in err and "has 8 thrusters" in err, err


def test_the_hold_starts_each_command_at_its_sample() -> None:
    """Samples on the step grid (to rounding) start their command at that step; one between two
    steps gets a step of its own, so that it too starts at its time; each step holds the last
    sample at or before its start."""
    start, h = 1.0, 0.002
    targets = start + h * np.arange(1, 6)  # 1.002 … 1.01
    times = np.array([0.99, 1.004 + 1e-15, 1.0071, 1.02])
    steps, held = held_commands(times, start, targets, h)
    np.testing.assert_array_equal(steps, np.insert(targets, 3, 1.0071))
    np.testing.assert_array_equal(held, [0, 0, 1, 1, 2, 2])
