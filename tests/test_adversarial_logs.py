"""Hostile log files (docs/domains.md, "Log files"): at :func:`uwml.read_log` followed by the
derivative estimation (what ``uwml fit hydro`` does) and at the streaming reader of
``uwml torques`` (``uwml.io._log_stream.log_chunks``, every chunk consumed).

What must hold: a correct read, or a ``ValueError`` whose message starts with the file's name,
says what is wrong and is short (under ``MAX_MESSAGE`` characters); never another exception
(``OverflowError``, ``UnicodeDecodeError``, pyarrow's errors, ``csv.Error``, ``KeyError``,
``RecursionError``, ``MemoryError``) and never a warning (pytest turns warnings into errors).
"""

from __future__ import annotations

import io
import math
from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np
import pytest
import uwml
from hypothesis import given
from hypothesis import strategies as st
from uwml._checks import cell_number
from uwml.io import _arrow_csv, logs
from uwml.io._log_stream import log_chunks

#: Hostile logs may hold time steps that look like milliseconds: the reading is under test here,
#: not uwml.plausibility (tests/test_plausibility.py).
pytestmark = pytest.mark.filterwarnings("ignore::uwml.PlausibilityWarning")

MAX_MESSAGE = 500
HEADER = "time,q1,q2,q3"


def _rows(n: int = 40, time: Callable[[int], float] = lambda i: 0.005 * i) -> list[list[str]]:
    """``n`` rows of a smooth log at 200 Hz (enough for the Savitzky-Golay window of 21)."""
    return [[repr(time(i)), repr(0.2 * math.sin(0.1 * i)), repr(-0.3 + 0.1 * math.cos(0.1 * i)), repr(0.01 * i)] for i in range(n)]


def _csv(rows: list[list[str]], header: str = HEADER, newline: str = "\n") -> bytes:
    return (newline.join([header] + [",".join(row) for row in rows]) + newline).encode("utf-8")


GOOD = _csv(_rows())


def _cell(row: int, column: int, value: str) -> bytes:
    """GOOD with one cell replaced (spreadsheet row: the header is row 1; column from 0)."""
    rows = _rows()
    rows[row - 2][column] = value
    return _csv(rows)


def _write(tmp_path: Path, content: bytes, name: str = "log.csv") -> Path:
    path = tmp_path / name
    path.write_bytes(content)
    return path


def _read_and_differentiate(path: Any) -> logs.Log:
    return logs.read_log(path).with_derivatives()


def _stream(path: Any) -> logs.Log:
    """The streaming reader of ``uwml torques``: every chunk, joined."""
    _, _, chunks = log_chunks(path, rows=16)
    parts = list(chunks)
    return logs.Log(
        time=np.concatenate([p.time for p in parts]),
        q=np.concatenate([p.q for p in parts]),
        qd=np.concatenate([p.qd for p in parts]),  # type: ignore[misc]
        qdd=np.concatenate([p.qdd for p in parts]),  # type: ignore[misc]
        source=parts[0].source,
    )


READERS = [_read_and_differentiate, _stream]


def _outcome(reader: Callable[[Any], logs.Log], path: Any, source: str) -> logs.Log | str:
    """The log read, or the message of the ValueError, checked: it starts with the source and is short.
    Any other exception fails the test."""
    try:
        return reader(path)
    except ValueError as exc:
        message = str(exc)
        assert type(exc).__module__.split(".")[0] in ("builtins", "uwml"), (type(exc), message)  # not pyarrow's ArrowInvalid
        assert message.startswith(f"{source}: "), message
        assert len(message) < MAX_MESSAGE, (len(message), message[:1000])
        return message


def _refused(path: Any, *words: str, source: str | None = None, readers: list[Callable[[Any], logs.Log]] = READERS) -> None:
    for reader in readers:
        outcome = _outcome(reader, path, str(path) if source is None else source)
        assert isinstance(outcome, str), f"{reader.__name__} read {path}"
        for word in words:
            assert word in outcome, (word, outcome)


def _reads(path: Any, expected: bytes = GOOD, readers: list[Callable[[Any], logs.Log]] = READERS) -> None:
    """Read by every reader as the plain file ``expected`` is."""
    reference = logs.read_log(io.BytesIO(expected)).with_derivatives()
    for reader in readers:
        log = reader(path)
        for name in ("time", "q", "qd", "qdd"):
            np.testing.assert_array_equal(getattr(log, name), getattr(reference, name), err_msg=f"{reader.__name__}: {name}")


# --------------------------------------------------------------------------------------------
# The time column's domain: finite, strictly increasing, within ±MAX_TIME_S
# --------------------------------------------------------------------------------------------


@pytest.mark.parametrize(
    ("time", "words"),
    [
        pytest.param(lambda i: 5e297 * i, ["row 3, column 'time'", "5e+297", "seconds"], id="steps of 5e297"),
        pytest.param(lambda i: 1e300 * (i - 20), ["row 2, column 'time'", "-2e+301"], id="huge negative"),
        pytest.param(lambda i: 0.005 * i if i < 30 else 2e10 + i, ["row 32, column 'time'"], id="beyond 1e10 s late"),
        pytest.param(lambda i: 1.7e18 + 5e6 * i, ["row 2, column 'time'", "seconds"], id="nanosecond timestamps"),
        pytest.param(lambda i: 1e-300 * i, ["column 'time'", "step"], id="steps of 1e-300"),
        pytest.param(lambda i: 5e-324 * i, ["column 'time'", "step"], id="subnormal steps"),
        pytest.param(lambda i: 0.005 * (i if i != 17 else 16), ["row 19, column 'time'", "increase strictly"], id="repeated"),
        pytest.param(lambda i: 0.005 * (i if i != 17 else 3), ["row 19, column 'time'", "increase strictly"], id="decreasing"),
    ],
)
def test_time_outside_its_domain(tmp_path: Path, time: Callable[[int], float], words: list[str]) -> None:
    _refused(_write(tmp_path, _csv(_rows(time=time))), *words)


def test_unix_time_in_seconds_is_inside_the_domain(tmp_path: Path) -> None:
    rows = _rows(time=lambda i: 1_700_000_000.0 + 0.005 * i)
    path = _write(tmp_path, _csv(rows))
    for reader in READERS:
        assert reader(path).time[0] == 1.7e9


def test_huge_time_steps_of_a_log_built_in_python() -> None:
    """The OverflowError of scipy's Savitzky-Golay filter (delta ** 2) is refused before it."""
    log = logs.Log(time=5e297 * np.arange(40.0), q=np.zeros((40, 3)), source="built.csv")
    with pytest.raises(ValueError, match=r"^built\.csv: row 3, column 'time': 5e\+297 s"):
        log.with_derivatives()
    with pytest.raises(ValueError, match=r"^<log>: row 2, column 'time': expected a finite number, got nan"):
        logs.estimate_derivatives(np.full(40, np.nan), np.zeros((40, 3)))
    with pytest.raises(ValueError, match=r"^<log>: row 3, column 'time': time must increase strictly"):
        logs.estimate_derivatives(np.zeros(40), np.zeros((40, 3)))


def test_estimated_derivatives_that_overflow(tmp_path: Path) -> None:
    """Positions so large that their estimated velocity or acceleration exceeds float64."""
    rows = _rows()
    for i, row in enumerate(rows):
        row[2] = repr(1e307 * (-1) ** i)
    _refused(_write(tmp_path, _csv(rows)), "column 'q2'", "not finite")


# --------------------------------------------------------------------------------------------
# Files that are not readable logs
# --------------------------------------------------------------------------------------------


def test_missing_file_and_directory(tmp_path: Path) -> None:
    _refused(tmp_path / "absent.csv", "no such file")
    _refused(tmp_path / "absent.parquet", "no such file")
    (tmp_path / "folder.csv").mkdir()
    _refused(tmp_path / "folder.csv", "is a directory")


@pytest.mark.parametrize(
    ("content", "words"),
    [
        pytest.param(b"", ["empty file"], id="empty"),
        pytest.param(b"\n  \n\n", ["empty file"], id="blank lines"),
        pytest.param(HEADER.encode() + b"\n", ["row 2, column 'time'", "no data rows"], id="header only"),
        pytest.param(_cell(3, 1, "\u00b1").replace("\u00b1".encode(), b"\xb1"), ["row 3", "UTF-8", "0xb1"], id="latin-1 cell"),
        pytest.param("time,q1,q2,q3,\u00e9t\u00e9\n".encode("latin-1") + GOOD[len(HEADER) + 1 :], ["row 1", "UTF-8"], id="latin-1 header"),
        pytest.param(GOOD.decode().encode("utf-16"), ["UTF-16"], id="UTF-16"),
        pytest.param(bytes(range(256)) * 4, [], id="binary"),
        pytest.param(b"\x00" * 100, [], id="NUL bytes"),
        pytest.param(b"time,q1,q2,q3," + b"x" * 200_000 + b"\n" + GOOD[len(HEADER) + 1 :], ["row 1"], id="header cell of 200 kB"),
        pytest.param(_cell(3, 1, "7" * 200_000), ["row 3, column 'q1'"], id="cell of 200 kB"),
        pytest.param(_cell(3, 1, '"0.5'), ["row 3, column 'q1'"], id="unclosed quote"),
        pytest.param(_cell(4, 1, "nan"), ["row 4, column 'q1'", "finite"], id="nan"),
        pytest.param(_cell(4, 1, "-inf"), ["row 4, column 'q1'", "finite"], id="inf"),
        pytest.param(_cell(4, 1, "1e400"), ["row 4, column 'q1'", "1e400"], id="1e400"),
        pytest.param(_cell(4, 1, ""), ["row 4, column 'q1'"], id="empty cell"),
        pytest.param(_cell(4, 0, "nan"), ["row 4, column 'time'", "finite"], id="nan time"),
    ],
)
def test_unreadable_files(tmp_path: Path, content: bytes, words: list[str]) -> None:
    _refused(_write(tmp_path, content), *words)


def test_byte_order_mark_is_accepted(tmp_path: Path) -> None:
    """Excel writes CSV as UTF-8 with a byte-order mark: read as without one."""
    _reads(_write(tmp_path, b"\xef\xbb\xbf" + GOOD))
    _reads(_write(tmp_path, b"\xef\xbb\xbf\n\n" + GOOD.replace(b"\n", b"\r\n"), "blank.csv"))
    _reads(io.StringIO("\ufeff" + GOOD.decode()), readers=[_read_and_differentiate])
    # With rows longer than the header, read by the pure-Python reader.
    long_rows = _csv([row + ["x", "y"] for row in _rows()])
    _reads(_write(tmp_path, b"\xef\xbb\xbf" + long_rows, "long.csv"), readers=[_read_and_differentiate])


def test_line_endings(tmp_path: Path) -> None:
    _reads(_write(tmp_path, GOOD.replace(b"\n", b"\r\n")))
    _reads(_write(tmp_path, GOOD.replace(b"\n", b"\r"), "cr.csv"))


def test_text_streams(tmp_path: Path) -> None:
    bad = _cell(3, 1, "\u00b1" + repr(0.2 * math.sin(0.1))).replace("\u00b1".encode(), b"\xb1")
    with pytest.raises(ValueError, match=r"^<stream>: row 3, column 'q1': not UTF-8 text"):
        logs.read_log(io.BytesIO(bad))
    expected = r"log\.csv: row 3, column 'q1': expected a number, got '±0\.01"
    with open(_write(tmp_path, bad), encoding="latin-1") as handle, pytest.raises(ValueError, match=expected):
        logs.read_log(handle)  # decoded by the caller: read as such


@pytest.mark.parametrize(
    ("cell", "words"),
    [
        pytest.param("1_0", ["expected a number, got '1_0'", "'_'"], id="underscores"),
        pytest.param("0.000_001", ["expected a number, got '0.000_001'"], id="underscores in the fraction"),
        pytest.param("\u0661\u0660", ["expected a number"], id="Arabic-Indic digits"),
        pytest.param("\uff11\uff10", ["expected a number"], id="full-width digits"),
        pytest.param(" nan ", ["expected a finite number"], id="nan with spaces"),
        pytest.param("infinity", ["expected a finite number"], id="infinity"),
        pytest.param("-Infinity", ["expected a finite number"], id="minus Infinity"),
        pytest.param("1e400", ["expected a finite number"], id="overflow"),
    ],
)
def test_numbers_python_reads_but_a_csv_does_not_spell(tmp_path: Path, cell: str, words: list[str]) -> None:
    """Python's float() reads '1_0' as 10.0 and other scripts' digits as ours; pyarrow does not:
    a cell of a log is a decimal number in ASCII digits, else an error naming its row and column."""
    _refused(_write(tmp_path, _cell(5, 2, cell)), "row 5, column 'q2'", *words)
    # The same rule for the tables read cell by cell (uwml fit losses).
    with pytest.raises(ValueError, match=r"^row 5, column 'q2': ") as info:
        cell_number(cell, "row 5, column 'q2'")
    assert words[0] in str(info.value), info.value


@pytest.mark.parametrize("cell", ["1e-3", "-0.5", "10", "+0.25", ".5", "5.", " 7 ", "1E+2", "-0"])
def test_numbers_as_a_csv_spells_them_are_read(tmp_path: Path, cell: str) -> None:
    _reads(_write(tmp_path, _cell(5, 2, cell)), _cell(5, 2, repr(float(cell))))
    # The slow path, which a bad cell later in the column sends every cell of its block to, reads it too.
    rows = _rows()
    rows[3][2], rows[20][2] = cell, "1_0"
    _refused(_write(tmp_path, _csv(rows), "late.csv"), "row 22, column 'q2'", "'1_0'")
    assert _arrow_csv.float_cells([cell], "q2", "", 5)[0] == float(cell)


# --------------------------------------------------------------------------------------------
# Headers
# --------------------------------------------------------------------------------------------


@pytest.mark.parametrize(
    ("header", "words"),
    [
        pytest.param("time,q1,q1,q2,q3", ["row 1 (header), column 'q1'", "twice", "columns 2 and 3"], id="duplicated q1"),
        pytest.param("time,q1,q2,time", ["column 'time'", "twice"], id="duplicated time"),
        pytest.param("time,q01,q2,q3", ["column 'q01'", "leading zero"], id="leading zero"),
        pytest.param("time,q0,q1,q2", ["column 'q0'", "from 1"], id="joint 0"),
        pytest.param("time,q1,q2,q" + "9" * 5000, ["column 'q999"], id="5000-digit joint"),
        pytest.param("Time,q1,q2,q3", ["column 'time': missing column", "'Time'"], id="capital T"),
        pytest.param("time;q1;q2;q3", ["column 'time': missing column", "comma"], id="semicolons"),
        pytest.param("time\tq1\tq2\tq3", ["column 'time': missing column", "comma"], id="tabs"),
    ],
)
def test_bad_headers(tmp_path: Path, header: str, words: list[str]) -> None:
    rows = _rows()
    if ";" in header or "\t" in header:
        text = "\n".join([header] + [header[4].join(row) for row in rows]) + "\n"
        content = text.encode()
    else:
        content = _csv(rows, header)
    _refused(_write(tmp_path, content), *words)


def test_more_joints_than_a_robot_has(tmp_path: Path) -> None:
    n = uwml.robot.MAX_ROBOT_JOINTS + 1
    header = ",".join(["time"] + [f"q{k}" for k in range(1, n + 1)])
    rows = [[repr(0.005 * i)] + ["0"] * n for i in range(40)]
    _refused(_write(tmp_path, _csv(rows, header)), f"column 'q{n}'", f"at most {n - 1}")
    _refused(_write(tmp_path, b"time,q1,q1000000\n0,0,0\n1,0,0\n", "far.csv"), "column 'q1000000'", f"at most {n - 1}")
    with pytest.raises(ValueError, match=r"^n_joints must be 1 to 64, got 1000000"):
        logs.read_log(io.BytesIO(GOOD), n_joints=1_000_000)


def test_a_million_extra_columns(tmp_path: Path) -> None:
    """Columns beyond the log's are ignored, however many."""
    header = "time,q1,qd1,qdd1," + ",".join(f"x{k}" for k in range(1_000_000))
    rows = [f"{0.005 * i!r},{0.1 * i!r},1,0," + ",".join(["0"] * 1_000_000) for i in range(2)]
    path = _write(tmp_path, (header + "\n" + "\n".join(rows) + "\n").encode())
    for reader in (logs.read_log, _stream):
        log = reader(path)
        assert log.n_samples == 2 and log.n_joints == 1 and log.q[1, 0] == 0.1


# --------------------------------------------------------------------------------------------
# Parquet
# --------------------------------------------------------------------------------------------


def _parquet(tmp_path: Path, columns: dict[str, Any], name: str = "log.parquet") -> Path:
    import pyarrow
    import pyarrow.parquet

    path = tmp_path / name
    pyarrow.parquet.write_table(pyarrow.table(columns), path)
    return path


def _good_columns() -> dict[str, Any]:
    log = logs.read_log(io.BytesIO(GOOD))
    return {"time": log.time, **{f"q{k + 1}": log.q[:, k] for k in range(3)}}


def _integers() -> bytes:
    """GOOD with column q2 as the integers of micro-radians."""
    rows = _rows()
    for row in rows:
        row[2] = repr(float(int(1e6 * float(row[2]))))
    return _csv(rows)


def _singles() -> bytes:
    """GOOD with column q2 rounded to float32."""
    rows = _rows()
    for row in rows:
        row[2] = repr(float(np.float32(float(row[2]))))
    return _csv(rows)


def test_parquet_files_that_are_not(tmp_path: Path) -> None:
    _refused(_write(tmp_path, GOOD, "csv.parquet"), "not a Parquet file")
    _refused(_write(tmp_path, b"", "empty.parquet"), "not a Parquet file")
    whole = _parquet(tmp_path, _good_columns()).read_bytes()
    _refused(_write(tmp_path, whole[: len(whole) // 2], "cut.parquet"), "not a Parquet file")
    _refused(_write(tmp_path, whole[:-12] + b"\xff" * 8 + whole[-4:], "damaged.parquet"), "Parquet")


def test_parquet_columns(tmp_path: Path) -> None:
    import pyarrow

    columns = _good_columns()
    _reads(_parquet(tmp_path, {**columns, "q2": pyarrow.array((1e6 * columns["q2"]).astype(np.int64))}, "integers.parquet"), _integers())
    _reads(_parquet(tmp_path, {**columns, "q2": pyarrow.array(columns["q2"].astype(np.float32))}, "singles.parquet"), _singles())
    # Numbers as text, booleans, times, lists: not a log's values, whatever a cast would make of them.
    text = pyarrow.array([repr(float(x)) for x in columns["q2"]])
    _refused(
        _parquet(tmp_path, {**columns, "q2": text}, "text.parquet"), "column 'q2'", "Parquet type string", "integers or floating point"
    )
    _refused(_parquet(tmp_path, {**columns, "q2": pyarrow.array([True] * 40)}, "bools.parquet"), "column 'q2'", "Parquet type bool")
    stamps = pyarrow.array(np.arange(40).astype("datetime64[s]"))
    _refused(_parquet(tmp_path, {**columns, "q1": stamps}, "stamps.parquet"), "column 'q1'", "Parquet type timestamp")
    _refused(_parquet(tmp_path, {**columns, "q3": pyarrow.array([[1.0]] * 40)}, "lists.parquet"), "column 'q3'", "Parquet type list")
    _refused(_parquet(tmp_path, {**columns, "time": 5e297 * np.arange(40.0)}, "huge.parquet"), "row 3, column 'time'")
    _refused(_parquet(tmp_path, {name: values[:0] for name, values in columns.items()}, "none.parquet"), "no data rows")
    table = pyarrow.table(columns).append_column("q1", pyarrow.array(columns["q1"]))
    import pyarrow.parquet

    pyarrow.parquet.write_table(table, tmp_path / "twice.parquet")
    _refused(tmp_path / "twice.parquet", "column 'q1'", "twice")


# --------------------------------------------------------------------------------------------
# Properties
# --------------------------------------------------------------------------------------------


def _contract(path: Path) -> None:
    for reader in READERS:
        _outcome(reader, path, str(path))


TOKENS = [
    "0", "1", "-1", "0.5", "1e-300", "5e-324", "1e308", "1e400", "-1e400", "nan", "NaN", "inf", "-Infinity", "", " ", '"', '""',
    "\x00", "\xb1", "\ufeff", "1,5", "1;5", "0x10", "1_0", "\r", "\n", "q1", "time", "9" * 400, "é",
]  # fmt: skip


@given(st.binary(max_size=400))
def test_random_bytes(tmp_path_factory: pytest.TempPathFactory, content: bytes) -> None:
    _contract(_write(tmp_path_factory.mktemp("bytes"), content))


@given(st.lists(st.tuples(st.integers(0, len(GOOD)), st.integers(0, 3), st.sampled_from(TOKENS)), min_size=1, max_size=6))
def test_mutated_logs(tmp_path_factory: pytest.TempPathFactory, edits: list[tuple[int, int, str]]) -> None:
    """A good log with a few spans replaced by hostile tokens (encoded as UTF-8 or Latin-1)."""
    content = GOOD
    for position, length, token in edits:
        encoded = token.encode("latin-1") if token == "\xb1" else token.encode("utf-8")
        content = content[:position] + encoded + content[position + length :]
    _contract(_write(tmp_path_factory.mktemp("mutated"), content))


NUMBERS = ["0", "1", "-1", "0.5", "1e-300", "5e-324", "1e308", "1e400", "-1e400", "nan", "NaN", "inf", "-Infinity", "", " ", "1_0"]


@given(st.lists(st.lists(st.sampled_from(NUMBERS), min_size=4, max_size=5), min_size=1, max_size=30))
def test_hostile_cells(tmp_path_factory: pytest.TempPathFactory, rows: list[list[str]]) -> None:
    """Any cells (time increasing where a time cell is "0" or "1"): a read gives exactly the
    numbers written, else a ValueError as above."""
    for i, row in enumerate(rows):
        row[0] = repr(0.005 * i) if row[0] in ("0", "1") else row[0]
    path = _write(tmp_path_factory.mktemp("cells"), _csv(rows))
    outcome = _outcome(logs.read_log, path, str(path))
    if isinstance(outcome, logs.Log):
        np.testing.assert_array_equal(outcome.q, [[float(c) for c in row[1:4]] for row in rows])
    _contract(path)


@pytest.mark.skipif(not hasattr(__import__("os"), "mkfifo"), reason="named pipes need os.mkfifo")
@pytest.mark.parametrize("call", ["uwml.read_log('log.csv')", "uwml.read_log('log.parquet')", "main(['torques', 'log.csv'])"])
def test_a_named_pipe_is_refused_not_waited_on(tmp_path: Path, call: str) -> None:
    """A log that is a named pipe with no writer: the readers and ``uwml torques`` waited forever."""
    import os

    from watchdog import run_with_watchdog

    os.mkfifo(tmp_path / "log.csv")
    os.mkfifo(tmp_path / "log.parquet")
    run = run_with_watchdog(
        f"""
        import uwml
        from uwml.cli import main
        try:
            print({call})
        except ValueError as exc:
            print(exc)
        """,
        tmp_path,
    )
    assert run.returncode == 0, run.stderr[-2000:]
    assert "is not a regular file (a named pipe); uwml reads regular files only" in run.stdout + run.stderr


def test_a_fit_of_values_whose_products_overflow_names_the_log() -> None:
    """Finite cells near 1e150 and 1e300 (speeds, torques): the fit's sums overflowed with a
    RuntimeWarning and then said "no coefficient has a regressor"; now a ValueError naming the log."""
    from uwml import fit

    n = 200
    rng = np.random.default_rng(0)
    log = uwml.Log(
        np.arange(n) * 0.01, rng.uniform(-1, 1, (n, 3)), np.full((n, 3), 1e150), np.zeros((n, 3)),
        tau_land=np.zeros((n, 3)), tau_water=np.full((n, 3), 1e300), source="big.csv",
    )  # fmt: skip
    with pytest.raises(ValueError, match=r"^big\.csv: the regressors' and torques' products overflow"):
        fit.hydro_coefficients(log)
