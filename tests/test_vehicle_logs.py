"""The vehicle in a log (docs/logs.md): one schema (``x y z``, ``qw qx qy qz`` or ``roll pitch yaw``,
``u v w p q r``, ``u_dot`` …, ``fx`` … ``mz``, thruster commands ``u1`` …) that ``read_log``,
``uwml torques`` and the fit read alike, and a column map that reads a recorded file as it is
(other names, signs, offsets, units, several streams)."""

from __future__ import annotations

import math
import re
from pathlib import Path

import numpy as np
import pytest
import uwml
from cli_runs import in_process, read_csv
from uwml import fit
from uwml.io.column_map import load_column_map
from uwml.io.logs import Log, read_log, write_log
from uwml.io.vehicle_columns import quaternion_from_euler

ROOT = Path(__file__).resolve().parents[1]
ROV, ROV_HYDRO = ROOT / "examples/bluerov2/bluerov2_arm.urdf", ROOT / "examples/bluerov2/bluerov2_arm.hydro.toml"
ARM, ARM_HYDRO = ROOT / "examples/my_arm/my_arm.urdf", ROOT / "examples/my_arm/my_arm.hydro.toml"


def position_at(t: np.ndarray) -> np.ndarray:
    """The vehicle's position [m] at times ``t``: linear in time (so interpolated exactly)."""
    return np.column_stack([0.5 * t, 0.1 * t, -2.0 + 0.05 * t])


def euler_at(t: np.ndarray) -> np.ndarray:
    """The vehicle's roll, pitch and yaw [rad] at times ``t``."""
    return np.column_stack([0.2 * np.sin(0.9 * t), 0.1 * np.cos(0.5 * t), 0.3 * t])


def vehicle_log(n: int = 200, rate: float = 100.0, n_joints: int = 2) -> Log:
    """A canonical log: the arm's joints and the vehicle's pose, twist and its rate."""
    t = np.arange(n) / rate
    w = 0.7 + 0.2 * np.arange(n_joints)
    q = 0.4 * np.sin(np.outer(t, w))
    qd, qdd = 0.4 * w * np.cos(np.outer(t, w)), -0.4 * w**2 * np.sin(np.outer(t, w))
    amplitude, frequency = np.array([0.3, 0.2, 0.1, 0.4, 0.3, 0.5]), np.array([0.31, 0.43, 0.57, 0.37, 0.49, 0.61])
    nu = amplitude * np.sin(2 * np.pi * frequency * t[:, None])
    nu_dot = amplitude * 2 * np.pi * frequency * np.cos(2 * np.pi * frequency * t[:, None])
    return Log(
        time=t, q=q, qd=qd, qdd=qdd, base_position=position_at(t), base_orientation=quaternion_from_euler(euler_at(t)),
        base_twist=nu, base_twist_dot=nu_dot, source="canonical",
    )  # fmt: skip


def test_the_schema_names_the_vehicle_once_and_round_trips(tmp_path: Path) -> None:
    log = vehicle_log(50)
    log = Log(**{**{name: getattr(log, name) for name in log.__dataclass_fields__}, "thruster_commands": np.ones((50, 4))})
    path = tmp_path / "log.csv"
    write_log(log, path)
    header = path.read_text().splitlines()[0].split(",")
    assert header == [
        "time", "q1", "q2", "qd1", "qd2", "qdd1", "qdd2", "x", "y", "z", "qw", "qx", "qy", "qz", "u", "v", "w", "p", "q", "r",
        "u_dot", "v_dot", "w_dot", "p_dot", "q_dot", "r_dot", "u1", "u2", "u3", "u4",
    ]  # fmt: skip
    back = read_log(path)
    for name in ("time", "q", "base_position", "base_orientation", "base_twist", "base_twist_dot", "thruster_commands"):
        assert np.array_equal(getattr(back, name), getattr(log, name)), name
    # u1 … un are the thrusters' commands, u the surge: a log with commands and no twist has no twist.
    path.write_text("time,q1,u1,u2\n0,0,1,2\n0.01,0,1,2\n")
    only = read_log(path)
    assert only.base_twist is None and only.thruster_commands is not None and only.thruster_commands.shape == (2, 2)
    # Euler angles [rad, z-y-x] are read as the same quaternion.
    euler = np.array([[0.2, -0.1, 2.5]])
    path.write_text("time,q1,roll,pitch,yaw\n0,0," + ",".join(repr(float(x)) for x in euler[0]) + "\n")
    from scipy.spatial.transform import Rotation

    xyzw = Rotation.from_euler("ZYX", euler[0, ::-1]).as_quat()
    expected = np.array([xyzw[3], *xyzw[:3]])
    np.testing.assert_allclose(read_log(path).base_orientation[0], expected * np.sign(expected[0]), atol=1e-15)
    # The base motion of a log: the quaternion normalized, upright and at rest where absent.
    motion = Log(time=[0.0], q=[[0.0]], base_orientation=[[1.0005, 0.0, 0.0, 0.0]]).base_motion()
    assert np.array_equal(motion["orientation"], [[1.0, 0.0, 0.0, 0.0]]) and not np.any(motion["velocity"])


@pytest.mark.parametrize("suffix", [".csv", ".parquet"])
def test_a_recorded_file_through_a_column_map_is_the_canonical_log(tmp_path: Path, suffix: str) -> None:
    """Other names, q1 = e − 3.07, q2 = −f, time in ms, the roll in degrees, x in mm: through the
    map (a TOML file, or the same dict) the canonical log, to rounding."""
    log = vehicle_log()
    assert log.qd is not None and log.base_position is not None and log.base_twist is not None
    euler = euler_at(log.time)
    recorded = {
        "stamp": np.round(log.time * 1000.0), "e": log.q[:, 0] + 3.07, "f": -log.q[:, 1], "ed": log.qd[:, 0], "fd": -log.qd[:, 1],
        "pos_n": log.base_position[:, 0] * 1000.0, "pos_e": log.base_position[:, 1], "up": log.base_position[:, 2],
        "roll_deg": np.degrees(euler[:, 0]), "pitch": euler[:, 1], "heading": euler[:, 2], "extra": np.zeros(log.n_samples),
    } | {f"nu{k}": log.base_twist[:, k] for k in range(6)}  # fmt: skip
    path = tmp_path / f"recorded{suffix}"
    if suffix == ".csv":
        lines = [",".join(recorded)] + [",".join(repr(float(c[i])) for c in recorded.values()) for i in range(log.n_samples)]
        path.write_text("\n".join(lines) + "\n")
    else:
        import pyarrow
        import pyarrow.parquet

        pyarrow.parquet.write_table(pyarrow.table(recorded), path)
    twist = "".join(f'{name} = "nu{k}"\n' for k, name in enumerate("uvwpqr"))
    text = f"""[time]
column = "stamp"
unit = "ms"
[joints]
q1 = {{ column = "e", offset = -3.07 }}
q2 = {{ column = "f", sign = -1 }}
qd1 = "ed"
qd2 = {{ column = "fd", sign = -1.0 }}
[vehicle]
x = {{ column = "pos_n", unit = "mm" }}
y = "pos_e"
z = "up"
roll = {{ column = "roll_deg", unit = "deg" }}
pitch = "pitch"
yaw = {{ column = "heading", unit = "rad" }}
{twist}"""
    column_map = tmp_path / "map.toml"
    column_map.write_text(text)
    import tomllib

    for columns in (column_map, str(column_map), tomllib.loads(text)):
        read = read_log(path, columns=columns)
        assert read.source == f"{path} (through {columns if isinstance(columns, str | Path) else '<columns>'})"
        np.testing.assert_allclose(read.time, log.time, rtol=0.0, atol=1e-15)
        for name in ("q", "qd", "base_position", "base_orientation", "base_twist"):
            np.testing.assert_allclose(getattr(read, name), getattr(log, name), rtol=0.0, atol=1e-12, err_msg=name)
        assert read.qdd is None and read.base_twist_dot is None and read.tau is None


def test_streams_recorded_apart_are_joined_on_the_first_streams_time(tmp_path: Path) -> None:
    """Joints at 100 Hz (time in ns), motion capture at 40 Hz over a shorter span (time in s,
    offset): the mocap's pose interpolated linearly onto the joints' rows inside both spans."""
    log = vehicle_log(300)
    assert log.base_position is not None and log.base_orientation is not None
    joints = tmp_path / "joints.csv"
    joints.write_text(
        "t_ns,a,b\n" + "".join(f"{round(t * 1e9)},{float(a)!r},{float(b)!r}\n" for t, (a, b) in zip(log.time, log.q, strict=True))
    )
    t_mocap = np.arange(0.5, 2.5, 0.025)
    position = position_at(t_mocap)
    quaternion = -quaternion_from_euler(np.column_stack([0.0 * t_mocap, 0.0 * t_mocap, 0.3 * t_mocap]))  # the other sign
    mocap = tmp_path / "mocap.csv"
    rows = np.column_stack([t_mocap + 100.0, position, quaternion])
    mocap.write_text("clock,px,py,pz,w,i,j,k\n" + "".join(",".join(repr(float(x)) for x in row) + "\n" for row in rows))
    column_map = tmp_path / "map.toml"
    column_map.write_text("""[[streams]]
file = "joints.csv"
time = { column = "t_ns", unit = "ns" }
joints = { q1 = "a", q2 = "b" }
[[streams]]
file = "mocap.csv"
time = { column = "clock", offset = -100.0 }
vehicle = { x = "px", y = "py", z = "pz", qw = "w", qx = "i", qy = "j", qz = "k" }
""")
    read = read_log(joints, columns=column_map)
    inside = (log.time >= 0.5 - 1e-9) & (log.time <= t_mocap[-1] + 1e-9)
    assert read.n_samples == np.count_nonzero(inside) and read.source == f"{joints} + {mocap} (through {column_map})"
    np.testing.assert_allclose(read.time, log.time[inside], atol=1e-12)
    np.testing.assert_allclose(read.q, log.q[inside], atol=0.0)
    np.testing.assert_allclose(read.base_position, position_at(read.time), atol=1e-12)
    assert read.base_orientation is not None
    truth = quaternion_from_euler(np.column_stack([0 * read.time, 0 * read.time, 0.3 * read.time]))
    np.testing.assert_allclose(np.abs(np.einsum("ij,ij->i", read.base_orientation, truth)), 1.0, atol=1e-9)
    np.testing.assert_allclose(np.linalg.norm(read.base_orientation, axis=1), 1.0, atol=1e-15)


def test_torques_of_a_floating_robot_use_the_vehicles_motion(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    """The BlueROV2 floats (its hydro file's [base] floating): ``uwml torques`` moves its base as
    the log says, the same numbers as Robot.hydro given that base motion, and names the columns."""
    log = vehicle_log()
    path = tmp_path / "dive.csv"
    write_log(log, path)
    out = tmp_path / "torques.csv"
    status, _, err = in_process(["torques", str(path), "--robot", str(ROV), "--hydro", str(ROV_HYDRO), "--out", str(out)], capsys)
    assert status == 0, err
    line = "uwml torques: the vehicle's motion from the log's columns qw, qx, qy, qz (orientation); u, v, w, p, q, r (twist); "
    line += "u_dot, v_dot, w_dot, p_dot, q_dot, r_dot (its rate) [x, y, z not used]\n"
    assert err.splitlines(keepends=True)[0] == line, err
    robot = uwml.Robot.from_urdf(ROV, ROV_HYDRO)
    motion = uwml.BaseMotion(**log.base_motion())
    expected = robot.hydro(log.q, log.qd, log.qdd, base_motion=motion)
    still = robot.hydro(log.q, log.qd, log.qdd)
    header, table = read_csv(out)
    columns = {name: table[:, k] for k, name in enumerate(header)}
    for family in ("drag", "added_mass", "buoyancy"):
        got = np.column_stack([columns[f"{family}{j}"] for j in (1, 2)])
        np.testing.assert_allclose(got, getattr(expected, family), rtol=0.0, atol=1e-12, err_msg=family)
    got = np.column_stack([columns[f"base_{name}"] for name in ("fx", "fy", "fz", "mx", "my", "mz")])
    assert expected.base is not None and still.base is not None
    np.testing.assert_allclose(got, expected.base.total, rtol=0.0, atol=1e-12)
    assert np.max(np.abs(expected.base.total - still.base.total)) > 1.0, "the motion matters"
    # The twist's rate estimated where the log has none, and said so.
    no_rate = tmp_path / "no_rate.csv"
    write_log(Log(time=log.time, q=log.q, qd=log.qd, qdd=log.qdd, base_twist=log.base_twist), no_rate)
    status, _, err = in_process(["torques", str(no_rate), "--robot", str(ROV), "--hydro", str(ROV_HYDRO), "--out", str(out)], capsys)
    assert status == 0 and "u, v, w, p, q, r (twist); its rate estimated (Savitzky-Golay) [upright]" in err, err


def test_torques_through_a_column_map_equal_the_canonical_logs(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    log = vehicle_log()
    assert log.base_twist is not None and log.base_twist_dot is not None and log.base_orientation is not None
    canonical, recorded = tmp_path / "canonical.csv", tmp_path / "recorded.csv"
    write_log(Log(time=log.time, q=log.q, base_orientation=log.base_orientation, base_twist=log.base_twist), canonical)
    cells = np.column_stack([log.time * 1e3, -log.q[:, 0], log.q[:, 1] + 1.0, log.base_orientation, log.base_twist])
    names = ["ms", "j1", "j2", "a", "b", "c", "d"] + [f"nu{k}" for k in range(6)]
    recorded.write_text(",".join(names) + "\n" + "".join(",".join(repr(float(x)) for x in row) + "\n" for row in cells))
    column_map = tmp_path / "map.toml"
    vehicle = "\n".join(f'{n} = "{c}"' for n, c in zip(["qw", "qx", "qy", "qz", *"uvwpqr"], names[3:], strict=True))
    column_map.write_text(
        f'[time]\ncolumn = "ms"\nunit = "ms"\n[joints]\nq1 = {{ column = "j1", sign = -1 }}\nq2 = {{ column = "j2", offset = -1.0 }}\n'
        f"[vehicle]\n{vehicle}\n"
    )
    outs = [tmp_path / "a.csv", tmp_path / "b.csv"]
    robot = ["--robot", str(ROV), "--hydro", str(ROV_HYDRO)]
    assert in_process(["torques", str(canonical), *robot, "--out", str(outs[0])], capsys)[0] == 0
    status, _, err = in_process(["torques", str(recorded), "--columns", str(column_map), *robot, "--out", str(outs[1])], capsys)
    assert status == 0 and "u, v, w, p, q, r (twist); its rate estimated" in err, err
    (header, a), (other, b) = read_csv(outs[0]), read_csv(outs[1])
    assert header == other
    np.testing.assert_allclose(b, a, rtol=1e-9, atol=1e-9)


def test_torques_of_a_fixed_robot_name_the_vehicle_columns_they_ignore(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    log = vehicle_log()
    path, plain = tmp_path / "dive.csv", tmp_path / "plain.csv"
    write_log(log, path)
    write_log(Log(time=log.time, q=log.q, qd=log.qd, qdd=log.qdd), plain)
    outs = [tmp_path / "a.csv", tmp_path / "b.csv"]
    robot = ["--robot", str(ARM), "--hydro", str(ARM_HYDRO)]
    status, _, err = in_process(["torques", str(path), *robot, "--out", str(outs[0])], capsys)
    assert status == 0 and err.startswith(
        f"uwml torques: warning: the robot ({ARM}) has a fixed base (its description does not float it): the log's vehicle "
        "columns x, y, z; qw, qx, qy, qz; u, v, w, p, q, r; u_dot, v_dot, w_dot, p_dot, q_dot, r_dot are ignored\n"
    ), err
    status, _, err = in_process(["torques", str(plain), *robot, "--out", str(outs[1])], capsys)
    assert status == 0 and "vehicle" not in err
    assert np.array_equal(read_csv(outs[0])[1], read_csv(outs[1])[1])
    # The paper's leg stands on a fixed base too.
    write_log(vehicle_log(n_joints=3), path)
    status, _, err = in_process(["torques", str(path), "--out", str(outs[0])], capsys)
    assert status == 0 and err.startswith("uwml torques: warning: the leg (the paper's) has a fixed base"), err


def test_the_hull_fit_reads_the_vehicle_schema_and_a_map(tmp_path: Path) -> None:
    """A captive test's log of the BlueROV2 with the schema's names (u … r, fx_land …, fx_water …)
    and the same through a column map of other names: one fit."""
    from test_identification_hull import captive_test

    robot = uwml.Robot.from_urdf(ROV, ROV_HYDRO)
    log = captive_test(robot, n=400, tilt=True)
    path = tmp_path / "captive.csv"
    write_log(log, path)
    header = path.read_text().splitlines()[0].split(",")
    assert {"qw", "u", "r_dot", "fx_land", "mz_water"} <= set(header) and not any(name.startswith("base_") for name in header)
    direct = fit.hydro_coefficients(path, robot, joints=(), base=range(6))
    assert direct.params["base.added_mass[2][2]"] == pytest.approx(18.68, rel=1e-8)
    renamed = tmp_path / "renamed.csv"
    renamed.write_text(path.read_text().replace("fx_land,", "FX_L,", 1))
    vehicle = {name: name for name in header if name not in ("time", "fx_land") and not name.startswith(("q1", "q2", "qd", "qdd", "tau"))}
    joints = {name: name for name in header if name.startswith(("q1", "q2", "qd", "qdd", "tau"))}
    mapped = fit.hydro_coefficients(
        renamed, robot, joints=(), base=range(6), columns={"joints": joints, "vehicle": vehicle | {"fx_land": "FX_L"}}
    )
    for name in direct.var_names:
        assert mapped.params[name] == pytest.approx(direct.params[name], rel=1e-12), name


@pytest.mark.parametrize(
    ("text", "message"),
    [
        (
            '[joints]\nq1 = { column = "e", scale = 2 }',
            r"map\.toml: \[joints\] q1, key 'scale': is not a key of this table \(allowed: column, sign, offset, unit\)",
        ),
        ('[joints]\nq1 = { column = "e", offset = inf }', r"\[joints\] q1, key 'offset': must be a finite number, in uwml's unit, got inf"),
        ('[joints]\nq1 = { column = "e", offset = nan }', r"\[joints\] q1, key 'offset': must be a finite number"),
        ('[joints]\nq1 = { column = "e", sign = 2 }', r"key 'sign': must be 1 or -1, got 2"),
        ('[joints]\nq1 = { column = "e", unit = "rpm" }', r"'rpm' is not a unit of q1 \(allowed: rad, deg, m, cm, mm\)"),
        ('[joints]\nq01 = "e"', r"\[joints\]: 'q01' is not a uwml column of \[joints\] \(allowed: q1 … q64"),
        ('[vehicle]\nsurge = "e"', r"\[vehicle\]: 'surge' is not a uwml column of \[vehicle\] \(allowed: x, y, z, qw"),
        ('[vehicle]\nu65 = "e"', r"'u65' is not a uwml column of \[vehicle\]"),
        ('[time]\nunit = "h"', r"\[time\], key 'unit': 'h' is not a unit of time \(allowed: s, ms, us, ns\)"),
        ('[time]\ncolumn = "stamp"\nsign = -1', r"\[time\], key 'sign': is not a key of this table \(allowed: column, unit, offset\)"),
        (
            '[joints]\nq1 = "e"\n[extras]\na = 1',
            r"top level, key 'extras': is not a key of this table \(allowed: time, joints, vehicle, streams\)",
        ),
        ('[joints]\nq1 = "e"\n[[streams]]\nfile = "a.csv"', r"top level, key 'joints': is not a key of this table \(allowed: streams\)"),
        ('[[streams]]\njoints = { q1 = "e" }\n[[streams]]\nvehicle = { x = "e" }', r"several streams without a file"),
        ('[[streams]]\njoints = { q1 = "e" }\n[[streams]]\nfile = "b.csv"\njoints = { q1 = "f" }', r"'q1' is given by two streams"),
        ("[joints\nq1 = 1", r"map\.toml: not valid TOML"),
    ],
)
def test_bad_column_maps_are_refused(tmp_path: Path, text: str, message: str) -> None:
    column_map = tmp_path / "map.toml"
    column_map.write_text(text)
    with pytest.raises(ValueError, match=message):
        load_column_map(column_map)


def test_a_map_naming_columns_a_file_lacks_is_refused_naming_both(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    path = tmp_path / "recorded.csv"
    path.write_text("stamp,e\n0,1\n10,2\n")
    with pytest.raises(
        ValueError,
        match=rf"^{re.escape(str(path))}: row 1 \(header\), column 'elbow': no such column \(the column map <columns> reads q1 from it\) \(the header has 'stamp', 'e'\)$",
    ):
        read_log(path, columns={"time": {"column": "stamp", "unit": "ms"}, "joints": {"q1": "elbow"}})
    with pytest.raises(ValueError, match=r"column 'time': no such column"):
        read_log(path, columns={"joints": {"q1": "e"}})
    # A value the map's unit makes overflow, names are never code, a stream's missing file.
    path.write_text("time,e\n0,1e308\n1,2\n")
    with pytest.raises(ValueError, match=r"row 2, column 'e': z of it is not finite \(the column map's sign, unit and offset\)"):
        read_log(path, columns={"joints": {"q1": "e"}, "vehicle": {"x": "e", "y": "e", "z": {"column": "e", "offset": 1e308}}})
    with pytest.raises(ValueError, match=r"'__import__\(\"os\"\)' is not a uwml column"):
        read_log(path, columns={"joints": {'__import__("os")': "e"}})
    with pytest.raises(ValueError, match=r"absent\.csv: the log file cannot be read|absent\.csv: no such file"):
        read_log(path, columns={"streams": [{"joints": {"q1": "e"}}, {"file": str(tmp_path / "absent.csv"), "vehicle": {"x": "e"}}]})
    # The command line says the same, exit status 2.
    column_map = tmp_path / "map.toml"
    column_map.write_text('[joints]\nq1 = { column = "e", offset = -3.07, unit = "degrees" }\n')
    status, _, err = in_process(["torques", str(path), "--columns", str(column_map), "--joints", "1"], capsys)
    assert (
        status == 2
        and err == f"uwml: error: {column_map}: [joints] q1, key 'unit': 'degrees' is not a unit of q1 (allowed: rad, deg, m, cm, mm)\n"
    )


@pytest.mark.parametrize(
    ("header", "message"),
    [
        ("time,q1,x,y", r"column 'z': missing column \(the vehicle's position is x, y, z; the header has x, y\)"),
        ("time,q1,qw,qx,qy", r"column 'qz': missing column \(the vehicle's orientation \(a quaternion\) is qw, qx, qy, qz"),
        ("time,q1,roll,yaw", r"column 'pitch': missing column \(the vehicle's orientation \(Euler angles\)"),
        ("time,q1,u_dot", r"column 'v_dot': missing column \(the vehicle's twist rate"),
        ("time,q1,fx,fy,fz,mx,my", r"column 'mz': missing column \(the wrench on the vehicle is"),
        ("time,q1,u1,u3", r"column 'u2': missing column \(thruster commands u1 … u3, numbered without a gap\)"),
        ("time,q1,u01", r"column 'u01': thruster numbers have no leading zero"),
        ("time,q1,u,v,w,p,q,r,u", r"column 'u': the column appears twice \(columns 3 and 9\)"),
        ("time,q1,fx,fy,fz,mx,my,mz,fx_land,fy_land,fz_land,mx_land,my_land,mz_land", r"column 'fx_water': a log carries either"),
    ],
)
def test_vehicle_columns_given_in_part_are_refused(tmp_path: Path, header: str, message: str) -> None:
    path = tmp_path / "log.csv"
    path.write_text(header + "\n" + ",".join(["0"] * len(header.split(","))) + "\n")
    with pytest.raises(ValueError, match=message):
        read_log(path)


def test_a_quaternion_beyond_the_tolerance_is_refused_and_one_within_is_normalized(tmp_path: Path) -> None:
    path = tmp_path / "log.csv"
    path.write_text(f"time,q1,qw,qx,qy,qz\n0,0,1.0009,0,0,0\n0.01,0,{math.sqrt(0.5)!r},0,0,0.7\n")
    with pytest.raises(
        ValueError, match=rf"^{re.escape(str(path))}: row 3, column 'qw': the vehicle's orientation .* of norm 1 within 0\.001, got 0\.99"
    ):
        read_log(path)
    path.write_text("time,q1,qw,qx,qy,qz\n0,0,1.0009,0,0,0\n")
    assert np.array_equal(read_log(path).base_motion()["orientation"], [[1.0, 0.0, 0.0, 0.0]])
