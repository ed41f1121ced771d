"""Input checks (arguments, table cells, overflowing outputs) and the CSV reader shared by the modules."""

import csv
import math
import os
import re
from collections.abc import Iterable, Sequence
from typing import IO, Any, SupportsFloat, SupportsIndex

import numpy as np
from numpy.typing import ArrayLike, NDArray

#: Three numbers: a point or a vector.
Vec3 = tuple[float, float, float]


def to_float(value: object) -> float:
    """``float(value)`` for a value of any type: a TypeError for one that ``float`` does not take
    (a string, bytes, or anything with ``__float__`` or ``__index__``), a ValueError for text
    that is not a number."""
    if isinstance(value, (str, bytes, bytearray, SupportsFloat, SupportsIndex)):
        return float(value)
    raise TypeError(f"float() argument must be a string or a real number, not {type(value).__name__!r}")


def real_array(value: ArrayLike, name: str, what: str) -> NDArray[np.float64]:
    """``value`` as a float64 array, or a TypeError naming the argument."""
    try:
        array = np.asarray(value)
        if np.iscomplexobj(array):
            raise TypeError("complex values are not allowed")
        return array.astype(np.float64, copy=False)
    except (TypeError, ValueError) as exc:
        raise TypeError(f"{name} must be {what}: {exc}") from None


def finite_array(value: ArrayLike, name: str) -> NDArray[np.float64]:
    """``value`` as a float64 array of finite numbers, or a ValueError naming ``name``."""
    try:
        a = np.asarray(value)
        if np.iscomplexobj(a) or a.dtype.kind not in "biuf":
            raise TypeError("not real numbers")
        a = a.astype(np.float64, copy=False)
    except (TypeError, ValueError) as exc:
        raise ValueError(f"{name} must be a number or an array of numbers, got {value!r}") from exc
    if not np.all(np.isfinite(a)):
        raise ValueError(f"{name} must be finite")
    return a


#: A number as a CSV cell spells it (pyarrow's reading): ASCII digits, an optional sign, decimal
#: point and exponent; or a non-finite one (which the readers refuse as such).
_DECIMAL = re.compile(r"[+-]?(?:[0-9]+\.?[0-9]*|\.[0-9]+)(?:[eE][+-]?[0-9]+)?|[+-]?(?:nan|inf|infinity)", re.IGNORECASE)


def cell_float(cell: Any) -> float:
    """A table's cell (text, or a number) as a float: text is stripped and must be a decimal
    number in ASCII digits (``_DECIMAL``), else a ValueError. Python's ``float`` alone would also
    read ``'1_0'`` as 10.0 and other scripts' digits (``'١٠'``, ``'１０'``) as ours, which no CSV
    reader does. The value may be infinite or NaN: the caller refuses it, saying so."""
    if isinstance(cell, str):
        text = cell.strip()
        if not _DECIMAL.fullmatch(text):
            raise ValueError(f"not a decimal number: {text!r}")
        return float(text)
    return float(cell)


def not_a_number(cell: Any) -> str:
    """What an error says of a cell that :func:`cell_float` refused, after ``got <cell>``: a word
    on digits grouped with '_' (which Python reads), else nothing."""
    return " (digits grouped with '_' are not a number in a table)" if isinstance(cell, str) and "_" in cell else ""


def cell_number(cell: Any, where: str) -> float:
    """One cell of a table (text, a number or None) as a finite float (:func:`cell_float`), or a
    ValueError that says ``where`` it is (``"row 7, column 'q1'"``) and what it holds."""
    try:
        x = cell_float(cell)
    except (TypeError, ValueError):
        raise ValueError(f"{where}: expected a number, got {cell!r}{not_a_number(cell)}") from None
    if not math.isfinite(x):
        raise ValueError(f"{where}: expected a finite number, got {cell!r}")
    return x


def read_csv_columns(path_or_file: "str | os.PathLike[str] | IO[str]", prefix: str, first_column: str) -> dict[str, list[str]]:
    """The cells of a CSV file with a header row, column by column (blank rows skipped).

    Errors are ValueErrors starting with ``prefix`` (e.g. the file's name) and naming the row
    (header = row 1) and column: an empty file (reported at ``first_column``), or a row with
    fewer cells than the header.
    """
    if isinstance(path_or_file, str | os.PathLike):
        with open(path_or_file, newline="", encoding="utf-8") as handle:
            return read_csv_columns(handle, prefix, first_column)
    records: list[list[Any]] = [record for record in csv.reader(path_or_file) if any(cell.strip() for cell in record)]
    if not records:
        raise ValueError(f"{prefix}row 1 (header), column {first_column!r}: empty file, expected a header row")
    header = [cell.strip() for cell in records[0]]
    columns: dict[str, list[str]] = {name: [] for name in header}
    for row, record in enumerate(records[1:], start=2):
        if len(record) < len(header):
            raise ValueError(
                f"{prefix}row {row}, column {header[len(record)]!r}: missing value ({len(record)} cells, header has {len(header)})"
            )
        for name, cell in zip(header, record, strict=False):
            columns[name].append(cell)
    return columns


def shown(value: Any, limit: int = 60) -> str:
    """``value`` for an error message, short whatever it holds: its repr, but an array (list,
    tuple) or a table (dict) shows its first 3 items and how many it has, a string longer than
    ``limit`` its first ``limit`` characters and its length, and anything else is cut after
    about ``3 * limit`` characters. A million-element array or a megabyte string makes a short
    message."""
    if isinstance(value, list | tuple | dict):
        if limit < 6:
            return f"[... {len(value)} items]" if not isinstance(value, dict) else f"{{... {len(value)} keys}}"
        if isinstance(value, dict):
            inner = ", ".join(f"{shown(key, limit // 3)}: {shown(item, limit // 3)}" for key, item in list(value.items())[:3])
            text = "{" + inner + (f", ...}} ({len(value)} keys)" if len(value) > 3 else "}")
        else:
            inner = ", ".join(shown(item, limit // 3) for item in value[:3])
            text = "[" + inner + (f", ...] ({len(value)} items)" if len(value) > 3 else "]")
    elif isinstance(value, str) and len(value) > limit:
        return f"{value[:limit]!r}... ({len(value)} characters)"
    else:
        text = repr(value)
    return text if len(text) <= 3 * limit else text[: 3 * limit] + "..."


def check_overflow(
    outputs: Sequence[NDArray[np.float64]], n_samples: int, velocities: NDArray[np.float64], accelerations: NDArray[np.float64]
) -> None:
    """A ValueError naming the first sample whose outputs are not finite although its state is
    (the states are checked before): forces beyond float64's range, from speeds or accelerations
    far beyond any robot's. Cheap when nothing overflows (one sum per output array)."""
    with np.errstate(over="ignore", invalid="ignore"):
        if all(math.isfinite(float(np.sum(a))) for a in outputs):
            return
    bad = np.zeros(n_samples, dtype=bool)
    for a in outputs:
        bad |= ~np.all(np.isfinite(np.reshape(a, (n_samples, -1))), axis=1)
    if not bad.any():
        return  # only the sums overflowed
    i = int(np.flatnonzero(bad)[0])
    speed = float(np.max(np.abs(np.reshape(velocities, (n_samples, -1))[i])))
    acceleration = float(np.max(np.abs(np.reshape(accelerations, (n_samples, -1))[i])))
    where = f"sample {i}" if n_samples > 1 else "the state"
    raise ValueError(
        f"the forces of {where} overflow float64 (joint speeds up to {speed:.3g}, accelerations up to {acceleration:.3g}; "
        "or the base's motion, the current or the coefficients): the inputs are outside the physics' domain"
    )


def vec3(value: object, name: str) -> Vec3:
    """``value`` as three finite numbers, or an error naming ``name``."""
    try:
        if not isinstance(value, Iterable):
            raise TypeError(f"{type(value).__name__!r} object is not iterable")
        items = tuple(to_float(v) for v in value)
    except TypeError as exc:
        raise TypeError(f"{name} must be a sequence of 3 numbers, got {value!r}") from exc
    except ValueError as exc:
        raise ValueError(f"{name} must be a sequence of 3 numbers, got {value!r}") from exc
    if len(items) != 3:
        raise ValueError(f"{name} must have 3 components, got {len(items)}")
    if not all(math.isfinite(v) for v in items):
        raise ValueError(f"{name} must be finite, got {items}")
    return (items[0], items[1], items[2])


def scalar(value: object, name: str, *, positive: bool, signed: bool = False) -> float:
    """``value`` as a finite number: positive, or non-negative (``positive`` False), or of
    either sign (``signed``); or an error naming ``name``."""
    try:
        x = to_float(value)
    except (TypeError, ValueError) as exc:
        raise TypeError(f"{name} must be a number, got {value!r}") from exc
    if not math.isfinite(x):
        raise ValueError(f"{name} must be finite, got {x}")
    if signed:
        return x
    if positive and not x > 0.0:
        raise ValueError(f"{name} must be positive, got {x}")
    if not positive and x < 0.0:
        raise ValueError(f"{name} must be non-negative, got {x}")
    return x


def check_name(name: object, field_name: str) -> None:
    """A name: a non-empty string, or None."""
    if name is not None and (not isinstance(name, str) or not name):
        raise TypeError(f"{field_name} must be a non-empty string or None, got {name!r}")
