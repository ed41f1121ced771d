"""Numeric CSV tables through pyarrow: float64 columns parsed fast, and, only when that fails,
a scan that names the row and column of the first bad cell.

A cell is good when it is a finite decimal number in ASCII digits once stripped
(``_checks.cell_float``: the numbers both pyarrow and the pure-Python reader this replaces read;
Python's ``float`` alone also reads ``'1_0'`` as 10.0). pyarrow parses the columns straight into float64
(``ConvertOptions.column_types``); a parse that fails, or a column with an empty or non-finite
cell, is read again as text, one block at a time, to find the cell and quote it: the slow path
runs on bad files only. Rows are numbered as in a spreadsheet (the header is row 1, blank lines
are not counted); errors are ``ValueError`` starting with a prefix (the file's name and ``": "``).

A row with fewer cells than the header is an error naming the row and the first missing
column (or the cell that runs over several lines, when a quote is not closed). A row with more
cells than the header, which pyarrow refuses, is read by the old pure-Python reader
(``_checks.read_csv_columns``), slowly, as before; the streaming reader refuses it with the row
named.

Text is UTF-8; a leading byte-order mark (Excel's "CSV UTF-8") is skipped. A file that is not
UTF-8 is an error naming the row and column of its first bad byte. A row longer than pyarrow's
block is read with larger blocks (up to ``MAX_BLOCK_BYTES``). Cells quoted in errors are cut to
``QUOTE_CHARS`` characters.
"""

from __future__ import annotations

import csv
import io
import math
import os
import re
from collections.abc import Callable, Iterator, Sequence
from typing import IO, Any

import numpy as np
import pyarrow as pa
import pyarrow.compute as pc
import pyarrow.csv as pacsv
from numpy.typing import NDArray

from .._checks import cell_float, not_a_number, read_csv_columns, shown

Array = NDArray[np.float64]

#: Bytes of CSV text per block of pyarrow's reader of a whole file.
BLOCK_BYTES = 1 << 24
#: The same for the streaming reader, whose read-ahead holds some tens of blocks: 1 MiB blocks
#: keep it near 40 MB (16 MiB: about 600 MB) and parse as fast.
STREAM_BLOCK_BYTES = 1 << 20
#: The largest block tried for a file whose rows are longer than a block (pyarrow refuses a row
#: across two blocks): past it, such a row is an error.
MAX_BLOCK_BYTES = 1 << 28
#: The longest part of a cell quoted in an error message [characters].
QUOTE_CHARS = 40
#: Bytes that are not UTF-8, as Python's "surrogateescape" decoder shows them.
_ESCAPED_BYTE = re.compile("[\udc80-\udcff]")


def _quote(cell: Any) -> str:
    """A cell for an error message: its repr, cut to ``QUOTE_CHARS`` characters (``_checks.shown``)."""
    text = shown(cell, QUOTE_CHARS)
    if isinstance(cell, str) and ("\n" in cell or "\r" in cell):
        text += " (a cell over several lines: is a quote not closed?)"
    return text


def float_cells(cells: Sequence[Any], name: str, prefix: str, first_row: int) -> Array:
    """Cells (text, numbers or None) as float64, or a ValueError naming the row (``first_row``
    for the first cell) and column ``name`` of the first cell that is not a finite number: a
    cell is good when it is a finite decimal number in ASCII digits (``_checks.cell_float``:
    what pyarrow reads; Python's ``float`` also reads ``'1_0'`` and other scripts' digits)."""
    values = np.empty(len(cells))
    for i, cell in enumerate(cells):
        try:
            x = cell_float(cell)
        except (TypeError, ValueError, OverflowError):
            raise ValueError(
                f"{prefix}row {first_row + i}, column {name!r}: expected a number, got {_quote(cell)}{not_a_number(cell)}"
            ) from None
        if not math.isfinite(x):
            raise ValueError(f"{prefix}row {first_row + i}, column {name!r}: expected a finite number, got {_quote(cell)}")
        values[i] = x
    return values


def not_utf8_error(open_binary: Callable[[], IO[bytes]], prefix: str) -> ValueError:
    """The error of a CSV file that is not UTF-8 text (``open_binary()`` opens it): the row and
    column of its first bad byte, or that it is UTF-16."""
    with open_binary() as raw:
        if raw.read(2) in (b"\xff\xfe", b"\xfe\xff"):
            return ValueError(f"{prefix}row 1 (header): UTF-16 text (a UTF-16 byte-order mark); save the file as UTF-8")
    header: list[str] | None = None
    row = 1
    try:
        with io.TextIOWrapper(open_binary(), encoding="utf-8-sig", errors="surrogateescape", newline="") as handle:
            for record in csv.reader(handle):
                if not any(cell.strip() for cell in record):
                    continue
                for j, cell in enumerate(record):
                    bad = _ESCAPED_BYTE.search(cell)
                    if bad:
                        where = f"row 1 (header), column {j + 1}"
                        if header is not None:
                            where = f"row {row}, column " + (repr(header[j]) if j < len(header) else str(j + 1))
                        byte = ord(bad.group()) - 0xDC00
                        return ValueError(f"{prefix}{where}: not UTF-8 text (byte 0x{byte:02x}); save the file as UTF-8")
                header = header if header is not None else [cell.strip() for cell in record]
                row += 1
    except csv.Error:
        pass
    return ValueError(f"{prefix}not UTF-8 text; save the file as UTF-8")


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
            # Lone surrogates (a str decoded with "surrogateescape") become bytes that are not UTF-8: reported as such.
            self._data = text.encode("utf-8", errors="surrogatepass") if isinstance(text, str) else bytes(text)
        try:
            with self._text() as handle:
                reader = csv.reader(handle)
                for record in reader:
                    if any(cell.strip() for cell in record):
                        break
                else:
                    raise ValueError(f"{prefix}row 1 (header), column {first_column!r}: empty file, expected a header row")
        except UnicodeDecodeError:
            raise self._not_utf8() from None
        except csv.Error as exc:
            raise ValueError(f"{prefix}row 1 (header): not a CSV header ({exc})") from None
        #: The column names, stripped.
        self.header = [cell.strip() for cell in record]
        self._skip = reader.line_num
        # Blocks of at least four header lines: a row as long as the header fits (a million columns too).
        self._least_block = 4 * sum(len(cell) + 1 for cell in record)

    # ---- sources ---------------------------------------------------------------------------

    def _raw(self) -> IO[bytes]:
        return open(self._path, "rb") if self._path is not None else io.BytesIO(self._data)

    def _text(self, errors: str = "strict") -> IO[str]:
        """The file as text; "utf-8-sig" skips a leading byte-order mark."""
        return io.TextIOWrapper(self._raw(), encoding="utf-8-sig", errors=errors, newline="")

    def _binary(self) -> Any:
        return self._path if self._path is not None else pa.BufferReader(self._data)

    def _larger(self, exc: pa.ArrowInvalid, block_bytes: int) -> bool:
        """Whether pyarrow refused a row longer than ``block_bytes`` and a larger block may do."""
        size = os.path.getsize(self._path) if self._path is not None else len(self._data)
        too_long = "straddl" in str(exc) or "larger than block size" in str(exc)
        return too_long and block_bytes < min(size, MAX_BLOCK_BYTES)

    def _column(self, index: int) -> str:
        """The column ``index`` (from 0) for an error message: its name, or its number beyond the header."""
        return shown(self.header[index]) if index < len(self.header) else str(index + 1)

    def _not_utf8(self) -> ValueError:
        return not_utf8_error(self._raw, self.prefix)

    def _csv_error(self, exc: csv.Error, row: int | None) -> ValueError:
        where = "" if row is None else f"row {row}: "
        return ValueError(f"{self.prefix}{where}not CSV ({exc}; is a quote not closed?)")

    def _options(self, names: Sequence[str], kind: pa.DataType, block_bytes: int) -> dict[str, Any]:
        block_bytes = max(block_bytes, self._least_block)
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
            return self._read(names)
        except UnicodeDecodeError:
            raise self._not_utf8() from None

    def _read(self, names: Sequence[str]) -> dict[str, Any]:
        block_bytes = BLOCK_BYTES
        while True:
            try:
                table = pacsv.read_csv(self._binary(), **self._options(names, pa.float64(), block_bytes))
                break
            except pa.ArrowInvalid as exc:
                if self._larger(exc, block_bytes):
                    block_bytes *= 4
                    continue
                return self._scan(names, STREAM_BLOCK_BYTES)
        if not all(finite_float64(table.column(name)) for name in names):
            return self._scan(names, STREAM_BLOCK_BYTES)
        return {name: table.column(name) for name in names}

    def _scan(self, names: Sequence[str], block_bytes: int) -> dict[str, Any]:
        """The slow path of :meth:`read`: every block as text, each column checked by the cell rule."""
        chunks: dict[str, list[Array]] = {name: [] for name in names}
        first_error: tuple[int, ValueError] | None = None
        row = 2
        try:
            reader = pacsv.open_csv(self._binary(), **self._options(names, pa.string(), block_bytes))
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
        except pa.ArrowInvalid as exc:  # text columns cannot fail to convert: a long row, not UTF-8, a row of the wrong length
            if self._larger(exc, block_bytes):
                return self._scan(names, 4 * block_bytes)
            return self._rows_of_wrong_length(names)
        if first_error is not None:
            raise first_error[1]
        return {name: np.concatenate(parts) if parts else np.empty(0) for name, parts in chunks.items()}

    def _first_row_of_wrong_length(self) -> tuple[int, list[str]] | None:
        """(row, cells) of the first non-blank row whose length is not the header's."""
        row = 1
        try:
            with self._text() as handle:
                records = (record for record in csv.reader(handle) if any(cell.strip() for cell in record))
                next(records, None)  # the header
                for row, record in enumerate(records, start=2):
                    if len(record) != len(self.header):
                        return row, record
        except csv.Error as exc:
            raise self._csv_error(exc, row + 1) from None
        return None

    def _wrong_length(self, row: int, record: list[str]) -> ValueError:
        """The error of a row of cells ``record`` whose number is not the header's."""
        cells = len(record)
        for j, cell in enumerate(record):
            if "\n" in cell or "\r" in cell:
                return ValueError(
                    f"{self.prefix}row {row}, column {self._column(j)}: a quoted cell runs over {len(cell.splitlines())} lines "
                    "(is a quote not closed?)"
                )
        column = self.header[min(cells, len(self.header) - 1)]
        what = "missing value" if cells < len(self.header) else "too many cells"
        return ValueError(f"{self.prefix}row {row}, column {shown(column)}: {what} ({cells} cells, header has {len(self.header)})")

    def _rows_of_wrong_length(self, names: Sequence[str]) -> dict[str, Any]:
        wrong = self._first_row_of_wrong_length()
        if wrong is not None and len(wrong[1]) < len(self.header):
            raise self._wrong_length(*wrong)
        # Rows with cells beyond the header's: the pure-Python reader ignores them, as it always did.
        try:
            with self._text() as handle:
                columns = read_csv_columns(handle, self.prefix, self.header[0])
        except csv.Error as exc:
            raise self._csv_error(exc, None) from None
        return {name: float_cells(columns[name], name, self.prefix, 2) for name in names}

    # ---- streaming -------------------------------------------------------------------------

    def batches(self, names: Sequence[str], block_bytes: int | None = None) -> Iterator[dict[str, Array]]:
        """The columns ``names`` block by block, as float64 arrays, in bounded memory.

        A bad cell raises a ValueError naming its row and column when its block is reached (the
        blocks before it have been yielded), as does a row with another number of cells than
        the header.
        """
        block_bytes = STREAM_BLOCK_BYTES if block_bytes is None else block_bytes  # read when called
        try:
            yield from self._batches(names, block_bytes)
        except UnicodeDecodeError:
            raise self._not_utf8() from None

    def _batches(self, names: Sequence[str], block_bytes: int) -> Iterator[dict[str, Array]]:
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
        # A block that did not parse as numbers (or a row longer than a block): from there on, as
        # text, by the cell rule.
        yield from self._text_batches(names, done, block_bytes)

    def _text_batches(self, names: Sequence[str], skip: int, block_bytes: int) -> Iterator[dict[str, Array]]:
        """The rows after the first ``skip`` as text, checked by the cell rule; a row longer than
        a block: again, with larger blocks, from the first row not yet yielded."""
        while True:
            row = 2
            try:
                reader = pacsv.open_csv(self._binary(), **self._options(names, pa.string(), block_bytes))
                for batch in reader:
                    first = max(0, min(skip + 2 - row, batch.num_rows))
                    if first < batch.num_rows:
                        part = batch.slice(first)
                        values = {name: _text_to_float(part.column(name), name, self.prefix, row + first) for name in names}
                        skip += part.num_rows
                        yield values
                    row += batch.num_rows
                return
            except pa.ArrowInvalid as exc:
                if self._larger(exc, block_bytes):
                    block_bytes *= 4
                    continue
                wrong = self._first_row_of_wrong_length()
                if wrong is None:
                    reason = " ".join(str(exc).split())
                    raise ValueError(f"{self.prefix}cannot parse the file as CSV ({reason[:200]})") from None
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
