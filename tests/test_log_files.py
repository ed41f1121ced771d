"""Log files through pyarrow (uwml.io.logs, uwml.io._arrow_csv): exact round trips, the file format,
and bad cells found after the fast parse fails, in files of several blocks."""

from __future__ import annotations

import csv
import io
from pathlib import Path

import numpy as np
import pytest
from uwml.io import _arrow_csv, logs
from uwml.paper import synthetic

HEADER = "time,q1,q2,q3"


def _random_log(n: int, seed: int) -> logs.Log:
    """Values over the whole float64 range: tiny, subnormal, huge, negative, signed zero."""
    rng = np.random.default_rng(seed)
    exponents = rng.integers(-330, 308, size=(n, 6))
    values = rng.uniform(-10.0, 10.0, size=(n, 6)) * np.power(10.0, exponents.astype(float))
    values[np.isinf(values)] = -1.7976931348623157e308
    values.flat[:8] = [5e-324, -5e-324, 2.2250738585072014e-308, 1.7976931348623157e308, -0.0, 0.1, 1.0 / 3.0, -1e-300]
    time = np.cumsum(rng.uniform(1e-9, 1e3, n))
    return logs.Log(time=time, q=values[:, :3], tau=values[:, 3:])


def _bits(a: np.ndarray) -> np.ndarray:
    return np.ascontiguousarray(a).view(np.int64)


@pytest.mark.filterwarnings("ignore::uwml.PlausibilityWarning")  # values beyond plausible on purpose
@pytest.mark.parametrize("seed", (0, 1, 2))
def test_csv_round_trip_is_bit_for_bit(tmp_path: Path, seed: int) -> None:
    log = _random_log(500, seed)
    path = tmp_path / "random.csv"
    logs.write_log(log, path)
    back = logs.read_log(path)
    for name in ("time", "q", "tau"):
        np.testing.assert_array_equal(_bits(getattr(back, name)), _bits(getattr(log, name)), err_msg=name)
    stream = io.StringIO()
    logs.write_log(log, stream)
    assert stream.getvalue() == path.read_text(encoding="utf-8")
    np.testing.assert_array_equal(_bits(logs.read_log(io.StringIO(stream.getvalue())).q), _bits(log.q))


def test_csv_format_header_and_numbers(tmp_path: Path) -> None:
    log = logs.Log(time=np.array([0.0, 0.005]), q=np.array([[0.1, -2.5, 1e-300], [1.0, 3.0, -1e20]]), tau=np.zeros((2, 3)))
    path = tmp_path / "small.csv"
    logs.write_log(log, path)
    lines = path.read_text(encoding="utf-8").splitlines()
    assert lines[0] == "time,q1,q2,q3,tau1,tau2,tau3"  # no quotes
    assert [float(x) for x in lines[1].split(",")] == [0.0, 0.1, -2.5, 1e-300, 0.0, 0.0, 0.0]
    assert len(lines) == 3


def test_files_of_the_previous_writer_still_read(tmp_path: Path) -> None:
    """The previous writer: Python's csv module, every number as ``repr(float)``."""
    log = synthetic.land_water_experiment(cycles=0.5, seed=1)
    path = tmp_path / "old.csv"
    columns = [log.time[:, None], log.q, log.qd, log.qdd, log.tau_land, log.tau_water]
    names = ["time"] + [f"{f}{k}" for f in ("q", "qd", "qdd", "tau_land", "tau_water") for k in (1, 2, 3)]
    with open(path, "w", newline="", encoding="utf-8") as handle:
        writer = csv.writer(handle, lineterminator="\n")
        writer.writerow(names)
        writer.writerows([repr(float(x)) for x in row] for row in np.concatenate(columns, axis=1).tolist())
    back = logs.read_log(path)
    for name in ("time", "q", "qd", "qdd", "tau_land", "tau_water"):
        np.testing.assert_array_equal(getattr(back, name), getattr(log, name))


@pytest.mark.filterwarnings("ignore::uwml.PlausibilityWarning")  # values beyond plausible on purpose
def test_lenient_cells_as_before(tmp_path: Path) -> None:
    """Spaces around cells and names, blank lines, extra columns and cells beyond the header's:
    read as the pure-Python reader did."""
    text = "\n time , q1,q2,q3,note\n0, 1 ,2,3,a\n\n0.5,4,5,6,b,extra\n1,7,8,9,c\n"
    log = logs.read_log(io.StringIO(text))
    np.testing.assert_array_equal(log.time, [0.0, 0.5, 1.0])
    np.testing.assert_array_equal(log.q, [[1, 2, 3], [4, 5, 6], [7, 8, 9]])


def _long_file(tmp_path: Path, n: int, bad: dict[tuple[int, int], str] | None = None, drop: int | None = None) -> Path:
    """A log of ``n`` rows with cells replaced (data row index, column index) and one row cut short."""
    rows = [[repr(0.01 * i), repr(0.1 * i), repr(-0.2 * i), repr(0.3 * i)] for i in range(n)]
    for (i, j), cell in (bad or {}).items():
        rows[i][j] = cell
    if drop is not None:
        rows[drop] = rows[drop][:2]
    path = tmp_path / "long.csv"
    path.write_text(HEADER + "\n" + "\n".join(",".join(r) for r in rows) + "\n", encoding="utf-8")
    return path


@pytest.fixture
def small_blocks(monkeypatch: pytest.MonkeyPatch) -> None:
    """pyarrow's blocks of 4 kB: a few thousand rows make many blocks."""
    monkeypatch.setattr(_arrow_csv, "BLOCK_BYTES", 4096)
    monkeypatch.setattr(_arrow_csv, "STREAM_BLOCK_BYTES", 4096)


@pytest.mark.parametrize(
    ("bad", "row", "column", "what"),
    [
        pytest.param({(2900, 2): "1.2.3"}, 2902, "q2", "expected a number, got '1.2.3'", id="not a number"),
        pytest.param({(2900, 3): ""}, 2902, "q3", "expected a number, got ''", id="empty"),
        pytest.param({(2950, 1): "nan"}, 2952, "q1", "expected a finite number, got 'nan'", id="nan"),
        pytest.param({(2950, 1): "-inf"}, 2952, "q1", "expected a finite number, got '-inf'", id="inf"),
        # Column by column, as before: the first bad cell of the first column with one.
        pytest.param({(2990, 1): "x", (2000, 3): "y"}, 2992, "q1", "got 'x'", id="first column first"),
        pytest.param({(2990, 0): "t", (10, 3): "y"}, 2992, "time", "got 't'", id="time first"),
    ],
)
def test_bad_cell_in_a_late_row(tmp_path: Path, small_blocks: None, bad: dict, row: int, column: str, what: str) -> None:
    path = _long_file(tmp_path, 3000, bad)
    assert path.stat().st_size > 20 * _arrow_csv.BLOCK_BYTES
    with pytest.raises(ValueError) as info:
        logs.read_log(path)
    assert str(info.value).startswith(f"{path}: row {row}, column {column!r}: ") and what in str(info.value), str(info.value)


def test_short_row_in_a_late_row(tmp_path: Path, small_blocks: None) -> None:
    path = _long_file(tmp_path, 3000, drop=2500)
    with pytest.raises(ValueError, match=r"long\.csv: row 2502, column 'q2': missing value \(2 cells, header has 4\)"):
        logs.read_log(path)


def test_time_not_increasing_in_a_late_row(tmp_path: Path, small_blocks: None) -> None:
    path = _long_file(tmp_path, 3000, {(2800, 0): "27.5"})
    with pytest.raises(
        ValueError, match=r"long\.csv: row 2802, column 'time': time must increase strictly \(27\.990000000000002 then 27\.5\)"
    ):
        logs.read_log(path)


def test_streaming_batches_equal_the_whole_read(tmp_path: Path) -> None:
    path = _long_file(tmp_path, 3000)
    table = _arrow_csv.CsvTable(path, "x: ", "time")
    names = ["time", "q1", "q2", "q3"]
    whole = {name: np.asarray(column) for name, column in table.read(names).items()}
    batches = list(table.batches(names, block_bytes=4096))
    assert len(batches) > 10
    for name in names:
        np.testing.assert_array_equal(np.concatenate([b[name] for b in batches]), whole[name])


@pytest.mark.parametrize(("bad", "row", "column"), [({(2900, 2): "abc"}, 2902, "q2"), ({(2950, 3): ""}, 2952, "q3")])
def test_streaming_names_a_late_bad_cell(tmp_path: Path, bad: dict, row: int, column: str) -> None:
    path = _long_file(tmp_path, 3000, bad)
    table = _arrow_csv.CsvTable(path, "x: ", "time")
    rows = 0
    with pytest.raises(ValueError, match=rf"^x: row {row}, column {column!r}: expected a number"):
        for batch in table.batches(["time", "q1", "q2", "q3"], block_bytes=4096):
            rows += batch["time"].size
    assert 0 < rows < row - 1  # the blocks before the bad one were yielded


def test_streaming_names_a_short_row(tmp_path: Path) -> None:
    path = _long_file(tmp_path, 3000, drop=2500)
    table = _arrow_csv.CsvTable(path, "x: ", "time")
    with pytest.raises(ValueError, match=r"^x: row 2502, column 'q2': missing value"):
        for _ in table.batches(["time", "q1"], block_bytes=4096):
            pass


def test_parquet_bad_cells_name_the_row(tmp_path: Path) -> None:
    pyarrow = pytest.importorskip("pyarrow")
    import pyarrow.parquet as pq

    q2 = np.arange(50.0)
    q2[37] = np.nan
    table = pyarrow.table({"time": np.arange(50.0), "q1": np.zeros(50), "q2": q2, "q3": pyarrow.array([0.0] * 49 + [None])})
    path = tmp_path / "bad.parquet"
    pq.write_table(table, path)
    with pytest.raises(ValueError, match=r"bad\.parquet: row 39, column 'q2': expected a finite number, got nan"):
        logs.read_log(path)
    pq.write_table(table.set_column(2, "q2", pyarrow.array(np.arange(50.0))), path)
    with pytest.raises(ValueError, match=r"bad\.parquet: row 51, column 'q3': expected a number, got None"):
        logs.read_log(path)
