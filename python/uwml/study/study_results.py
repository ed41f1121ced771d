"""A study's results (:func:`read_results`): one row per run, its parameters and metrics, read
from the Parquet files of ``OUT/runs/``; a summary (per group of runs that share the values of
the categorical parameters, a controller: :func:`groups`) and figures of each metric, in its
unit, against each parameter, each group in its colour."""

from __future__ import annotations

import json
import math
from pathlib import Path
from typing import Any

import numpy as np

from .store import INFRASTRUCTURE, error_kinds, parts

__all__ = ["axis_label", "categorical", "done_runs", "figures", "groups", "metric_figure", "read_results", "summary", "units"]


def read_results(out: str | Path) -> Any:
    """Every finished run of the study in ``out``, by run number, as a ``pyarrow.Table`` (None
    before any): columns ``run``, the parameters, the metrics, ``error`` and ``error_kind``
    (:mod:`uwml.study.store`). One row per run: were a run in two parts (uwml writes none so),
    its own row would stand over a row of Ray's failure, and the later part's over the earlier."""
    import pyarrow
    import pyarrow.parquet

    tables = []
    for path in parts(Path(out)):
        table = pyarrow.parquet.read_table(path)
        if "error_kind" not in table.column_names:  # written by an earlier uwml
            table = table.append_column("error_kind", pyarrow.array(error_kinds(table), type=pyarrow.string()))
        tables.append(table)
    if not tables:
        return None
    table = pyarrow.concat_tables(tables, promote_options="permissive")
    runs = np.asarray(table.column("run").to_numpy(), dtype=np.int64)
    if np.unique(runs).size < runs.size:
        own = np.array([kind != INFRASTRUCTURE for kind in table.column("error_kind").to_pylist()], dtype=bool)
        order = np.lexsort((np.arange(runs.size), own, runs))  # by run; its best row last
        last = np.append(runs[order][1:] != runs[order][:-1], True)
        table = table.take(order[last])
    return table.sort_by("run")


def done_runs(out: str | Path) -> set[int]:
    """The numbers of the runs finished in ``out``: with a row of their own, a result or their
    own error (a run Ray lost is not done; ``--resume`` runs it again)."""
    from .store import ledger

    record = json.loads((Path(out) / "study.json").read_text(encoding="utf-8"))
    return {int(run) for run in np.flatnonzero(ledger(Path(out), int(record["n_runs"])).done)}


def _record(out: str | Path) -> dict[str, Any]:
    record: dict[str, Any] = json.loads((Path(out) / "study.json").read_text(encoding="utf-8"))
    return record


def units(record: dict[str, Any]) -> dict[str, str]:
    """Each metric's unit in a study's record (``study.json``; ``""``: a custom scenario's metric
    declared without one). A study begun by an earlier uwml kept none: its scenario's
    (:data:`uwml.study.scenarios.METRICS`; a ``robot`` study's errors taken as rad)."""
    from .scenarios import METRICS

    kept = record.get("units")
    if isinstance(kept, dict):
        return {name: str(kept.get(name, "")) for name in record["metrics"]}
    table = METRICS.get(str(record.get("kind")), {})
    robot = {"positive_work": "J", "energy": "J"} if record.get("kind") == "robot" else {}
    return {
        name: table.get(name, robot.get(name, "rad" if robot and name.startswith(("rms_error_", "peak_error_")) else ""))
        for name in record["metrics"]
    }


def axis_label(metric: str, unit: str) -> str:
    """A metric's axis label with its unit: ``rms_drift [m]``."""
    return f"{metric} [{unit}]" if unit else f"{metric} [no unit declared]"


def categorical(table: Any, parameters: list[str]) -> list[str]:
    """The parameters whose values are not all numbers (a controller, a station keeping): the
    runs' groups, which a study's summary and figures keep apart rather than average."""
    return [name for name in parameters if not all(isinstance(v, int | float) for v in table.column(name).to_pylist())]


def groups(table: Any, parameters: list[str]) -> tuple[list[str], list[tuple[str, ...]], np.ndarray]:
    """The categorical parameters (:func:`categorical`), their combinations that the runs take
    (each a group: in the order the runs first take them, so the grid's order) and each run's
    group's index. Without categorical parameters, one group of every run."""
    names = categorical(table, parameters)
    columns = [[str(v) for v in table.column(name).to_pylist()] for name in names]
    keys = list(zip(*columns, strict=True)) if names else [()] * table.num_rows
    found: list[tuple[str, ...]] = list(dict.fromkeys(keys))
    index = {key: i for i, key in enumerate(found)}
    return names, found, np.array([index[key] for key in keys], dtype=np.int64)


def _statistics(values: np.ndarray) -> dict[str, float | None]:
    values = values[np.isfinite(values)]

    def number(x: float) -> float | None:
        return float(x) if math.isfinite(x) else None

    if not values.size:
        return {"mean": None, "min": None, "max": None}
    return {"mean": number(float(np.mean(values))), "min": number(float(np.min(values))), "max": number(float(np.max(values)))}


def summary(out: str | Path) -> dict[str, Any]:
    """The study in ``out`` as JSON-safe numbers: its runs, those with a row (``done``), those
    failed (``failed``; ``lost``: of them, those Ray lost, which ``--resume`` runs again), each
    metric's ``units``, and each metric's mean, minimum and maximum over the runs that did not
    fail: over all of them (``metrics``), and per group of runs (``groups``), a group being the
    runs that share the values of every categorical parameter (a controller, a station keeping:
    :func:`groups`), each with its ``parameters``, ``runs``, ``failed`` and ``metrics``. Averaging
    over controllers mixes what a study compares: read ``groups`` where it has more than one."""
    record = _record(out)
    table = read_results(out)
    done = 0 if table is None else table.num_rows
    errors = np.array([] if table is None else [error is not None for error in table.column("error").to_pylist()], dtype=bool)
    failed = int(errors.sum())
    lost = 0 if table is None else sum(kind == INFRASTRUCTURE for kind in table.column("error_kind").to_pylist())
    values = {
        name: np.array([] if table is None else table.column(name).to_numpy(zero_copy_only=False), dtype=np.float64)
        for name in record["metrics"]
    }
    per_group: list[dict[str, Any]] = []
    if table is not None:
        names, keys, index = groups(table, list(record["parameters"]))
        for number, key in enumerate(keys):
            mine = index == number
            per_group.append(
                {
                    "parameters": dict(zip(names, key, strict=True)),
                    "runs": int(mine.sum()),
                    "failed": int((mine & errors).sum()),
                    "metrics": {name: _statistics(column[mine]) for name, column in values.items()},
                }
            )
    return {
        "source": record["source"],
        "out": str(out),
        "runs": record["n_runs"],
        "done": done,
        "failed": failed,
        "lost": lost,
        "units": units(record),
        "metrics": {name: _statistics(column) for name, column in values.items()},
        "groups": per_group,
    }


#: The most groups coloured apart in a figure (the colour cycle's); more share the grey of "others".
MAX_COLOURED_GROUPS = 20


def _colours(count: int) -> list[Any]:
    from matplotlib import colormaps

    palette = colormaps["tab10" if count <= 10 else "tab20"]
    return [palette(i) if i < MAX_COLOURED_GROUPS else (0.6, 0.6, 0.6, 1.0) for i in range(count)]


def figures(out: str | Path) -> list[Path]:
    """One figure per metric, ``OUT/figures/<metric>.png`` (:func:`metric_figure`), for every
    metric of the study in ``out``; none before any run."""
    record = _record(out)
    table = read_results(out)
    if table is None:
        return []
    folder = Path(out) / "figures"
    folder.mkdir(parents=True, exist_ok=True)
    written = []
    for metric in record["metrics"]:
        path = folder / f"{metric}.png"
        metric_figure(out, metric, record=record, table=table).savefig(path, dpi=90)
        written.append(path)
    return written


def metric_figure(out: str | Path, metric: str, *, record: dict[str, Any] | None = None, table: Any = None) -> Any:
    """The figure of one metric of the study in ``out`` (a ``matplotlib.figure.Figure``): the
    metric of every run that did not fail against each parameter, one panel per parameter, each
    y axis labelled with the metric's unit (:func:`units`), each numeric parameter's axis with its
    own (:data:`uwml.study.scenarios.PARAMETER_UNITS`). The runs are coloured by their group
    (:func:`groups`: the values of the categorical parameters, a controller), with a legend
    entry per group; a categorical parameter's values side by side, each group beside the
    others; on a numeric parameter that a grid varies, each group's mean joined by a line. A
    metric spanning more than three decades (all of it above zero) is drawn on a logarithmic
    axis. ``record`` and ``table``: the study's, if read already."""
    from matplotlib.figure import Figure
    from matplotlib.lines import Line2D

    from .scenarios import PARAMETER_UNITS

    record = _record(out) if record is None else record
    table = read_results(out) if table is None else table
    if table is None:
        raise ValueError(f"{out}: the study has no run yet")
    if metric not in record["metrics"]:
        raise ValueError(f"{metric!r} is not a metric of the study ({', '.join(record['metrics'])})")
    ok = np.array([error is None for error in table.column("error").to_pylist()], dtype=bool)
    parameters = list(record["parameters"])
    names, keys, index = groups(table, parameters)
    colours = _colours(len(keys))
    unit_of = units(record)
    values = np.asarray(table.column(metric).to_numpy(zero_copy_only=False), dtype=np.float64)
    shown = ok & np.isfinite(values)
    figure = Figure(figsize=(3.6 * max(len(parameters), 1) + (2.2 if names else 0.0), 3.4), layout="constrained")
    axes = np.atleast_1d(figure.subplots(1, max(len(parameters), 1), squeeze=False)[0])
    positive = values[shown]
    logarithmic = positive.size > 1 and bool(np.all(positive > 0.0)) and float(positive.max() / positive.min()) > 1e3
    for ax, name in zip(axes, parameters, strict=False):
        column = table.column(name).to_pylist()
        if name in names:
            labels = list(dict.fromkeys(str(v) for v in column))
            x = np.array([labels.index(str(v)) for v in column], dtype=np.float64)
            # Each group beside the others within its value's slot.
            sharing = {label: sorted({int(g) for g, v in zip(index, column, strict=True) if str(v) == label}) for label in labels}
            width = 0.7
            for row, (g, v) in enumerate(zip(index, column, strict=True)):
                slot = sharing[str(v)]
                x[row] += (slot.index(int(g)) - (len(slot) - 1) / 2) * (width / max(len(slot), 1))
            ax.set_xticks(range(len(labels)), labels, rotation=20 if max(map(len, labels)) > 6 else 0, fontsize="small")
            ax.set_xlim(-0.6, len(labels) - 0.4)
        else:
            x = np.asarray(column, dtype=np.float64)
        grid = name not in names and np.unique(x).size <= 12 and np.unique(x).size < x.size
        for g in range(len(keys)):
            mine = shown & (index == g)
            if not mine.any():
                continue
            ax.plot(x[mine], values[mine], "o", ms=4, alpha=0.8, color=colours[g], mec="none")
            if grid:
                points = np.unique(x[mine])
                means = [float(np.mean(values[mine & (x == point)])) for point in points]
                ax.plot(points, means, "-", lw=1.0, alpha=0.7, color=colours[g])
        unit = PARAMETER_UNITS.get(name, "") if record.get("kind") != "custom" else ""
        ax.set_xlabel(f"{name} [{unit}]" if unit and name not in names else name)
        ax.set_ylabel(axis_label(metric, unit_of[metric]))
        if logarithmic:
            ax.set_yscale("log")
        ax.grid(alpha=0.3)
    if names:
        handles = [
            Line2D([], [], marker="o", ls="-", color=colours[g], label=", ".join(key))
            for g, key in enumerate(keys)
            if g < MAX_COLOURED_GROUPS
        ]
        if len(keys) > MAX_COLOURED_GROUPS:
            handles.append(Line2D([], [], marker="o", ls="-", color=colours[-1], label=f"{len(keys) - MAX_COLOURED_GROUPS} others"))
        figure.legend(handles=handles, title=", ".join(names), loc="outside right upper", fontsize="small", title_fontsize="small")
    failed = int((~ok).sum())
    note = f", {failed} failed (not shown)" if failed else ""
    source = Path(str(record["source"])).name  # the study file's name, not where it was installed
    figure.suptitle(f"{axis_label(metric, unit_of[metric])}: {int(shown.sum())} runs of {source}{note}", fontsize="small")
    return figure
