"""A study's results (:func:`read_results`): one row per run, its parameters and metrics, read
from the Parquet files of ``OUT/runs/``; a summary and figures of each metric against each
parameter."""

from __future__ import annotations

import json
import math
from pathlib import Path
from typing import Any

import numpy as np

from .store import INFRASTRUCTURE, error_kinds, parts

__all__ = ["done_runs", "figures", "read_results", "summary"]


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


def summary(out: str | Path) -> dict[str, Any]:
    """The study in ``out`` as JSON-safe numbers: its runs, those with a row (``done``), those
    failed (``failed``; ``lost``: of them, those Ray lost, which ``--resume`` runs again), and
    each metric's mean, minimum and maximum over the runs that did not fail."""
    record = json.loads((Path(out) / "study.json").read_text(encoding="utf-8"))
    table = read_results(out)
    done = 0 if table is None else table.num_rows
    failed = 0 if table is None else sum(error is not None for error in table.column("error").to_pylist())
    lost = 0 if table is None else sum(kind == INFRASTRUCTURE for kind in table.column("error_kind").to_pylist())
    metrics: dict[str, dict[str, float | None]] = {}
    for name in record["metrics"]:
        values = np.array([] if table is None else table.column(name).to_numpy(zero_copy_only=False), dtype=np.float64)
        values = values[np.isfinite(values)]

        def number(x: float) -> float | None:
            return float(x) if math.isfinite(x) else None

        metrics[name] = {
            "mean": number(float(np.mean(values))) if values.size else None,
            "min": number(float(np.min(values))) if values.size else None,
            "max": number(float(np.max(values))) if values.size else None,
        }
    return {
        "source": record["source"],
        "out": str(out),
        "runs": record["n_runs"],
        "done": done,
        "failed": failed,
        "lost": lost,
        "metrics": metrics,
    }


def figures(out: str | Path) -> list[Path]:
    """One figure per metric, ``OUT/figures/<metric>.png``: the metric of every run that did not
    fail against each parameter (a text parameter's values side by side)."""
    from matplotlib.figure import Figure

    record = json.loads((Path(out) / "study.json").read_text(encoding="utf-8"))
    table = read_results(out)
    if table is None:
        return []
    ok = np.array([error is None for error in table.column("error").to_pylist()], dtype=bool)
    folder = Path(out) / "figures"
    folder.mkdir(parents=True, exist_ok=True)
    written = []
    parameters = record["parameters"]
    for metric in record["metrics"]:
        values = np.asarray(table.column(metric).to_numpy(zero_copy_only=False), dtype=np.float64)
        figure = Figure(figsize=(4.0 * max(len(parameters), 1), 3.2), layout="constrained")
        axes = np.atleast_1d(figure.subplots(1, max(len(parameters), 1), squeeze=False)[0])
        for ax, name in zip(axes, parameters, strict=False):
            column = table.column(name).to_pylist()
            if all(isinstance(v, int | float) for v in column):
                x = np.asarray(column, dtype=np.float64)
                ax.plot(x[ok], values[ok], ".", ms=4, alpha=0.7)
            else:
                labels = sorted({str(v) for v in column})
                x = np.array([labels.index(str(v)) for v in column], dtype=np.float64)
                ax.plot(x[ok] + np.random.default_rng(0).uniform(-0.15, 0.15, int(ok.sum())), values[ok], ".", ms=4, alpha=0.7)
                ax.set_xticks(range(len(labels)), labels, rotation=20, fontsize="small")
            ax.set_xlabel(name)
            ax.set_ylabel(metric)
            ax.grid(alpha=0.3)
        figure.suptitle(f"{metric}: {int(ok.sum())} runs of {record['source']}", fontsize="small")
        path = folder / f"{metric}.png"
        figure.savefig(path, dpi=90)
        written.append(path)
    return written
