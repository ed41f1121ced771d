"""Loss-experiment data: the CSV format (see :mod:`uwml.fit`), read, checked and written; group
means with pooled standard errors.
"""

from __future__ import annotations

import csv
import os
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from .._checks import cell_number, read_csv_columns
from ._types import Array, Columns, PathOrFile

#: Valid values of the ``configuration`` column.
CONFIGURATIONS = ("dry", "oil", "oil_seal")
_REQUIRED = ("configuration", "speed_rpm", "pressure_mpa", "current_a")
_OPTIONAL = ("startup", "temperature_c")
#: The temperature of data without a ``temperature_c`` column, unless told otherwise [°C].
_DEFAULT_TEMPERATURE_C = 20.0


# --------------------------------------------------------------------------------------------
# Data: reading, validating, writing
# --------------------------------------------------------------------------------------------


def _cell_number(value: Any, row: int, column: str) -> float:
    return cell_number(value, f"row {row}, column {column!r}")


def _key_text(speed_rpm: float | None, pressure_mpa: float | None, temperature_c: float | None) -> str:
    parts = [] if speed_rpm is None else [f"{speed_rpm:g} r/min"]
    parts += [] if pressure_mpa is None else [f"{pressure_mpa:g} MPa"]
    parts += [] if temperature_c is None else [f"{temperature_c:g} °C"]
    return ", ".join(parts)


def validate_loss_data(columns: Mapping[str, ArrayLike], pairs: bool = True) -> Columns:
    """Check loss-experiment columns and return them as numpy arrays.

    Parameters
    ----------
    columns : mapping of str to array_like
        The columns of the CSV format (module docstring), of equal length; values may be
        numbers or their text. Extra columns are ignored.

    Returns
    -------
    dict of ndarray
        ``configuration`` (str), ``speed_rpm``, ``pressure_mpa``, ``current_a`` (float),
        ``startup`` (int, 0 or 1) and, if given, ``temperature_c`` (float).

    Raises
    ------
    ValueError
        Naming the row (the header is row 1) and the column: a missing column, columns of
        unequal length, no data rows, an unknown configuration, a speed or pressure that is not
        a number or negative, a current or temperature that is not a finite number, a start-up
        flag other than 0 or 1, or a configuration without the one it is compared with (``oil``
        without ``dry`` at its speed, ``oil_seal`` without ``oil`` at its speed, pressure and
        temperature).
    """
    for name in _REQUIRED:
        if name not in columns:
            raise ValueError(f"row 1 (header), column {name!r}: missing column (required: {', '.join(_REQUIRED)})")
    present = [name for name in (*_REQUIRED, *_OPTIONAL) if name in columns]
    cells = {name: list(np.asarray(columns[name], dtype=object).ravel()) for name in present}
    n_rows = len(cells["configuration"])
    for name in present:
        if len(cells[name]) != n_rows:
            raise ValueError(f"row {min(n_rows, len(cells[name])) + 2}, column {name!r}: has {len(cells[name])} values, expected {n_rows}")
    if n_rows == 0:
        raise ValueError("row 2, column 'configuration': no data rows")

    configuration: list[str] = []
    speed: list[float] = []
    pressure: list[float] = []
    current: list[float] = []
    startup: list[int] = []
    temperature: list[float] | None = [] if "temperature_c" in cells else None
    for i in range(n_rows):
        row = i + 2
        value = cells["configuration"][i]
        text = value.strip() if isinstance(value, str) else value
        if text not in CONFIGURATIONS:
            raise ValueError(
                f"row {row}, column 'configuration': unknown configuration {value!r} (expected one of {', '.join(CONFIGURATIONS)})"
            )
        configuration.append(text)
        for name, values in (("speed_rpm", speed), ("pressure_mpa", pressure)):
            x = _cell_number(cells[name][i], row, name)
            if x < 0.0:
                raise ValueError(f"row {row}, column {name!r}: must be >= 0, got {cells[name][i]!r}")
            values.append(x)
        current.append(_cell_number(cells["current_a"][i], row, "current_a"))
        if "startup" in cells:
            flag = _cell_number(cells["startup"][i], row, "startup")
            if flag not in (0.0, 1.0):
                raise ValueError(f"row {row}, column 'startup': expected 0 or 1, got {cells['startup'][i]!r}")
            startup.append(int(flag))
        else:
            startup.append(0)
        if temperature is not None:
            theta = _cell_number(cells["temperature_c"][i], row, "temperature_c")
            if theta <= -273.15:
                raise ValueError(f"row {row}, column 'temperature_c': must be above -273.15 °C, got {cells['temperature_c'][i]!r}")
            temperature.append(theta)

    data: Columns = {
        "configuration": np.array(configuration, dtype=str),
        "speed_rpm": np.array(speed),
        "pressure_mpa": np.array(pressure),
        "current_a": np.array(current),
        "startup": np.array(startup, dtype=np.int64),
    }
    if temperature is not None:
        data["temperature_c"] = np.array(temperature)
    if pairs:
        _check_pairs(data)
    return data


def _check_pairs(data: Columns) -> None:
    """Every ``oil`` row has ``dry`` rows at its speed, every ``oil_seal`` row ``oil`` rows."""
    theta = data.get("temperature_c")
    keys = []
    for i, configuration in enumerate(data["configuration"]):
        t = None if theta is None else float(theta[i])
        s, p = float(data["speed_rpm"][i]), float(data["pressure_mpa"][i])
        keys.append((str(configuration), bool(data["startup"][i]), s, p, t))
    dry_speeds = {s for c, start, s, _, _ in keys if c == "dry" and not start}
    oil_steady = {(s, p, t) for c, start, s, p, t in keys if c == "oil" and not start}
    oil_startup = {(p, t) for c, start, _, p, t in keys if c == "oil" and start}
    for i, (c, start, s, p, t) in enumerate(keys):
        row = i + 2
        if c == "oil" and not start and s not in dry_speeds:
            raise ValueError(
                f"row {row}, column 'configuration': 'oil' at {_key_text(s, None, None)} needs 'dry' rows at the same speed; there are none"
            )
        if c == "oil_seal" and not start and (s, p, t) not in oil_steady:
            raise ValueError(
                f"row {row}, column 'configuration': 'oil_seal' at {_key_text(s, p, t)} needs 'oil' rows at the same point; there are none"
            )
        if c == "oil_seal" and start and (p, t) not in oil_startup:
            raise ValueError(
                f"row {row}, column 'configuration': start-up 'oil_seal' at {_key_text(None, p, t)} needs start-up 'oil' rows there; there are none"
            )


def read_loss_csv(path_or_file: PathOrFile, pairs: bool = True) -> Columns:
    """Read and check a loss-experiment CSV file (format in the module docstring).

    Parameters
    ----------
    path_or_file : str, path or text file
        The file, or an open text stream.

    Returns
    -------
    dict of ndarray
        The checked columns (:func:`validate_loss_data`).

    Raises
    ------
    ValueError
        Naming the row (header = row 1) and column of the first problem; also for an empty file
        or a row with fewer cells than the header. ``pairs=False`` leaves out the check that every
        ``oil`` row has its ``dry`` rows (and ``oil_seal`` its ``oil`` rows): for one of several
        files read to be fitted together, whose rows are checked together.
    """
    return validate_loss_data(read_csv_columns(path_or_file, "", _REQUIRED[0]), pairs)


def write_loss_csv(data: Mapping[str, ArrayLike], path_or_file: PathOrFile) -> None:
    """Write loss-experiment columns as CSV (format in the module docstring), after checking them.

    Numbers are written in their shortest round-trip form, so :func:`read_loss_csv` gives the
    same values back.

    Raises
    ------
    ValueError
        As :func:`validate_loss_data`.
    """
    checked = validate_loss_data(data)
    if isinstance(path_or_file, str | os.PathLike):
        with open(path_or_file, "w", newline="", encoding="utf-8") as handle:
            write_loss_csv(checked, handle)
        return
    names = [name for name in (*_REQUIRED, *_OPTIONAL) if name in checked]
    writer = csv.writer(path_or_file, lineterminator="\n")
    writer.writerow(names)
    for i in range(len(checked["configuration"])):
        writer.writerow(
            [str(checked[name][i]) if name in ("configuration", "startup") else repr(float(checked[name][i])) for name in names]
        )


def _load(data_or_path: Mapping[str, ArrayLike] | PathOrFile) -> Columns:
    if isinstance(data_or_path, Mapping):
        return validate_loss_data(data_or_path)
    return read_loss_csv(data_or_path)


# --------------------------------------------------------------------------------------------
# Group means and their standard errors
# --------------------------------------------------------------------------------------------


@dataclass(frozen=True)
class _Groups:
    """Means of the rows of one configuration and kind, per key, with their standard errors."""

    keys: list[tuple[float, ...]]
    mean: Array
    stderr: Array
    #: Whether the standard errors come from repeats (False: no repeats anywhere, unit σ).
    known: bool


def _groups(pools: list[tuple[Array, list[tuple[float, ...]]]]) -> list[_Groups]:
    """Group means of several pools (values, row keys), each pool's variance pooled over its groups.

    A pool without repeats (or without scatter) borrows the variance pooled over all pools;
    without any repeats (or exact repeats everywhere) the standard errors are 1 and ``known`` is
    False.
    """
    summaries = []
    total_ss, total_dof = 0.0, 0
    for values, row_keys in pools:
        keys = sorted(set(row_keys))
        index = {key: k for k, key in enumerate(keys)}
        labels = np.array([index[key] for key in row_keys], dtype=np.int64)
        count = np.bincount(labels, minlength=len(keys)).astype(np.float64)
        mean = np.bincount(labels, weights=values, minlength=len(keys)) / count
        ss = float(np.sum((values - mean[labels]) ** 2))
        dof = int(len(values) - len(keys))
        summaries.append((keys, mean, count, ss, dof))
        total_ss, total_dof = total_ss + ss, total_dof + dof
    result = []
    for keys, mean, count, ss, dof in summaries:
        if dof > 0 and ss > 0.0:
            variance, known = ss / dof, True
        elif total_dof > 0 and total_ss > 0.0:
            variance, known = total_ss / total_dof, True
        else:
            variance, known = 1.0, False
        result.append(_Groups(keys, mean, np.sqrt(variance / count), known))
    return result


def _temperatures(data: Columns, default_c: float) -> Array:
    theta = data.get("temperature_c")
    return np.full(len(data["configuration"]), default_c) if theta is None else theta


def _select(data: Columns, configuration: str, startup: bool) -> NDArray[np.bool_]:
    selected: NDArray[np.bool_] = (data["configuration"] == configuration) & (data["startup"] == int(startup))
    return selected
