"""Numeric CSV tables through pyarrow: float64 columns parsed fast, and, only when that fails,
a scan that names the row and column of the first bad cell.

A cell is good when Python's ``float`` reads the stripped cell and the value is finite (the
rule of the pure-Python reader this replaces). pyarrow parses the columns straight into float64
(``ConvertOptions.column_types``); a parse that fails, or a column with an empty or non-finite
cell, is read again as text, one block at a time, to find the cell and quote it: the slow path
runs on bad files only. Rows are numbered as in a spreadsheet (the header is row 1, blank lines
are not counted); errors are ``ValueError`` starting with a prefix (the file's name and ``": "``).

A row with fewer cells than the header is an error naming the row and the first missing
column. A row with more cells than the header, which pyarrow refuses, is read by the old
pure-Python reader (``_checks.read_csv_columns``), slowly, as before; the streaming reader
refuses it with the row named.
"""

from __future__ import annotations

import csv
import io
import os
from collections.abc import Iterator, Sequence
from typing import IO, Any

import numpy as np
import pyarrow as pa
import pyarrow.compute as pc
import pyarrow.csv as pacsv
from numpy.typing import NDArray

from ._checks import cell_number, read_csv_columns

Array = NDArray[np.float64]

#: Bytes of CSV text per block of pyarrow's reader of a whole file.
BLOCK_BYTES = 1 << 24
#: The same for the streaming reader, whose read-ahead holds some tens of blocks: 1 MiB blocks
#: keep it near 40 MB (16 MiB: about 600 MB) and parse as fast.
STREAM_BLOCK_BYTES = 1 << 20


def float_cells(cells: Sequence[Any], name: str, prefix: str, first_row: int) -> Array:
    """Cells (text, numbers or None) as float64, or a ValueError naming the row (``first_row``
    for the first cell) and column ``name`` of the first cell that is not a finite number."""
    return np.array([cell_number(cell, f"{prefix}row {first_row + i}, column {name!r}") for i, cell in enumerate(cells)], dtype=np.float64)


def finite_float64(values: pa.Array | pa.ChunkedArray) -> bool:
    """Whether an Arrow array of float64 has no null and only finite values."""
    return values.null_count == 0 and bool(pc.all(pc.is_finite(values)).as_py() is not False)


def float64_column(values: pa.Array | pa.ChunkedArray, name: str, prefix: str, first_row: int) -> pa.Array | pa.ChunkedArray | Array:
    """An Arrow column of any type (text, numbers) as float64 by the cell rule: Arrow's cast when
    it is clean (an Arrow array, not copied if already float64), else cell by cell (a numpy
    array, or a ValueError naming the row, ``first_row`` for the first cell, and the column)."""
    try:
        cast = pc.cast(values, pa.float64())
    except (pa.ArrowInvalid, pa.ArrowNotImplementedError):
        cast = None
    if cast is not None and finite_float64(cast):
        return cast
    return float_cells(values.to_pylist(), name, prefix, first_row)


def _text_to_float(values: pa.Array, name: str, prefix: str, first_row: int) -> Array:
    """A block of a text column as a float64 numpy array (:func:`float64_column`)."""
    return np.asarray(float64_column(values, name, prefix, first_row), dtype=np.float64)


class CsvTable:
    """A CSV file with a header row, whose named columns are read as float64.

    Parameters
    ----------
    path_or_file : str, path or text stream
        The file; a stream is read into memory at once.
    prefix : str
        The start of every error message (the file's name and ``": "``).
    first_column : str
        The column an empty file's error names.
    """

    def __init__(self, path_or_file: str | os.PathLike[str] | IO[str], prefix: str, first_column: str) -> None:
        self.prefix = prefix
        self._path: str | None = None
        self._data = b""
        if isinstance(path_or_file, str | os.PathLike):
            self._path = os.fspath(path_or_file)
        else:
            text = path_or_file.read()
            self._data = text.encode("utf-8") if isinstance(text, str) else bytes(text)
        with self._text() as handle:
            reader = csv.reader(handle)
            for record in reader:
                if any(cell.strip() for cell in record):
                    break
            else:
                raise ValueError(f"{prefix}row 1 (header), column {first_column!r}: empty file, expected a header row")
            #: The column names, stripped.
            self.header = [cell.strip() for cell in record]
            self._skip = reader.line_num

    # ---- sources ---------------------------------------------------------------------------

    def _text(self) -> IO[str]:
        if self._path is not None:
            return open(self._path, newline="", encoding="utf-8")
        return io.StringIO(self._data.decode("utf-8"), newline="")

    def _binary(self) -> Any:
        return self._path if self._path is not None else pa.BufferReader(self._data)

    def _options(self, names: Sequence[str], kind: pa.DataType, block_bytes: int) -> dict[str, Any]:
        return {
            "read_options": pacsv.ReadOptions(column_names=self.header, skip_rows=self._skip, block_size=block_bytes),
            "convert_options": pacsv.ConvertOptions(include_columns=list(names), column_types={name: kind for name in names}),
        }

    # ---- the whole file --------------------------------------------------------------------

    def read(self, names: Sequence[str]) -> dict[str, Any]:
        """The columns ``names`` (in the header), each an array-like of float64 (``numpy.asarray``).

        Raises a ValueError naming the first bad cell of the first column (in ``names`` order)
        that has one, or the first row with fewer cells than the header.
        """
        try:
            table = pacsv.read_csv(self._binary(), **self._options(names, pa.float64(), BLOCK_BYTES))
        except pa.ArrowInvalid:
            return self._scan(names)
        if not all(finite_float64(table.column(name)) for name in names):
            return self._scan(names)
        return {name: table.column(name) for name in names}

    def _scan(self, names: Sequence[str]) -> dict[str, Any]:
        """The slow path of :meth:`read`: every block as text, each column checked by the cell rule."""
        chunks: dict[str, list[Array]] = {name: [] for name in names}
        first_error: tuple[int, ValueError] | None = None
        row = 2
        try:
            reader = pacsv.open_csv(self._binary(), **self._options(names, pa.string(), STREAM_BLOCK_BYTES))
            for batch in reader:
                for j, name in enumerate(names):
                    if first_error is not None and j >= first_error[0]:
                        break
                    try:
                        chunks[name].append(_text_to_float(batch.column(name), name, self.prefix, row))
                    except ValueError as exc:
                        first_error = (j, exc)
                if first_error is not None and first_error[0] == 0:
                    break
                row += batch.num_rows
        except pa.ArrowInvalid:  # text columns cannot fail to convert: a row of the wrong length
            return self._rows_of_wrong_length(names)
        if first_error is not None:
            raise first_error[1]
        return {name: np.concatenate(parts) if parts else np.empty(0) for name, parts in chunks.items()}

    def _first_row_of_wrong_length(self) -> tuple[int, int] | None:
        """(row, number of cells) of the first non-blank row whose length is not the header's."""
        with self._text() as handle:
            records = (record for record in csv.reader(handle) if any(cell.strip() for cell in record))
            next(records, None)  # the header
            for row, record in enumerate(records, start=2):
                if len(record) != len(self.header):
                    return row, len(record)
        return None

    def _wrong_length(self, row: int, cells: int) -> ValueError:
        """The error of a row with ``cells`` cells where the header has another number."""
        column = self.header[min(cells, len(self.header) - 1)]
        what = "missing value" if cells < len(self.header) else "too many cells"
        return ValueError(f"{self.prefix}row {row}, column {column!r}: {what} ({cells} cells, header has {len(self.header)})")

    def _rows_of_wrong_length(self, names: Sequence[str]) -> dict[str, Any]:
        wrong = self._first_row_of_wrong_length()
        if wrong is not None and wrong[1] < len(self.header):
            raise self._wrong_length(*wrong)
        # Rows with cells beyond the header's: the pure-Python reader ignores them, as it always did.
        source: Any = self._path if self._path is not None else self._text()
        columns = read_csv_columns(source, self.prefix, self.header[0])
        return {name: float_cells(columns[name], name, self.prefix, 2) for name in names}

    # ---- streaming -------------------------------------------------------------------------

    def batches(self, names: Sequence[str], block_bytes: int | None = None) -> Iterator[dict[str, Array]]:
        """The columns ``names`` block by block, as float64 arrays, in bounded memory.

        A bad cell raises a ValueError naming its row and column when its block is reached (the
        blocks before it have been yielded), as does a row with another number of cells than
        the header.
        """
        block_bytes = STREAM_BLOCK_BYTES if block_bytes is None else block_bytes  # read when called
        done = 0
        try:
            reader = pacsv.open_csv(self._binary(), **self._options(names, pa.float64(), block_bytes))
            for batch in reader:
                if not all(finite_float64(batch.column(name)) for name in names):
                    break
                yield {name: np.asarray(batch.column(name).to_numpy(), dtype=np.float64) for name in names}
                done += batch.num_rows
            else:
                return
        except pa.ArrowInvalid:
            pass
        # A block that did not parse as numbers: from there on, as text, by the cell rule.
        yield from self._text_batches(names, done, block_bytes)

    def _text_batches(self, names: Sequence[str], skip: int, block_bytes: int) -> Iterator[dict[str, Array]]:
        row = 2
        try:
            reader = pacsv.open_csv(self._binary(), **self._options(names, pa.string(), block_bytes))
            for batch in reader:
                first = max(0, min(skip + 2 - row, batch.num_rows))
                if first < batch.num_rows:
                    part = batch.slice(first)
                    yield {name: _text_to_float(part.column(name), name, self.prefix, row + first) for name in names}
                row += batch.num_rows
        except pa.ArrowInvalid:
            wrong = self._first_row_of_wrong_length()
            if wrong is None:
                raise ValueError(f"{self.prefix}cannot parse the file as CSV") from None
            raise self._wrong_length(*wrong) from None


class CsvColumnsWriter:
    """Float64 columns written as CSV block after block: the header once, unquoted, then each
    number in its shortest round-trip form (pyarrow's writer). ``sink`` is a binary file (or
    ``sys.stdout.buffer``); :meth:`close` finishes the CSV and leaves the sink open."""

    def __init__(self, sink: Any, names: Sequence[str]) -> None:
        sink.write((",".join(names) + "\n").encode("utf-8"))
        self._schema = pa.schema([(name, pa.float64()) for name in names])
        options = pacsv.WriteOptions(include_header=False, quoting_style="none")
        self._writer = pacsv.CSVWriter(sink, self._schema, write_options=options)

    def write(self, columns: Sequence[NDArray[np.float64]]) -> None:
        """Append rows: one array per column, all of one length."""
        self._writer.write_batch(
            pa.record_batch([pa.array(np.ascontiguousarray(c, dtype=np.float64)) for c in columns], schema=self._schema)
        )

    def close(self) -> None:
        self._writer.close()


def write_table(sink: Any, names: Sequence[str], columns: Sequence[NDArray[np.float64]], batch_rows: int = 1 << 20) -> None:
    """Write float64 columns as CSV (see :class:`CsvColumnsWriter`), ``batch_rows`` rows at a
    time (bounded extra memory)."""
    n = len(columns[0]) if columns else 0
    writer = CsvColumnsWriter(sink, names)
    try:
        for first in range(0, n, batch_rows):
            rows = slice(first, min(first + batch_rows, n))
            writer.write([c[rows] for c in columns])
    finally:
        writer.close()
