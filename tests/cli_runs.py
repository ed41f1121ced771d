"""Running the ``uwml`` command line for the tests of its commands (``test_cli*.py``): in a
subprocess (one or several at once) or in this process, and reading and editing the CSV files
they take and write."""

from __future__ import annotations

import csv
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
import uwml.cli


def command(args: tuple[str | os.PathLike[str], ...]) -> list[str]:
    return [sys.executable, "-m", "uwml", *(os.fspath(a) for a in args)]


ENV = {**os.environ, "PYTHONIOENCODING": "utf-8", "PYTHONWARNINGS": "error"}


def run_uwml(*args: str | os.PathLike[str]) -> subprocess.CompletedProcess:
    """``python -m uwml ARGS`` in a subprocess."""
    return subprocess.run(command(args), capture_output=True, text=True, encoding="utf-8", env=ENV, timeout=120, check=False)


def run_uwml_all(*commands: tuple[str | os.PathLike[str], ...]) -> list[subprocess.CompletedProcess]:
    """Several ``python -m uwml`` runs in concurrent subprocesses (each pays the start-up once)."""
    processes = [
        subprocess.Popen(command(args), stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, encoding="utf-8", env=ENV)
        for args in commands
    ]
    results = []
    try:
        for process in processes:
            stdout, stderr = process.communicate(timeout=120)
            results.append(subprocess.CompletedProcess(process.args, process.returncode, stdout, stderr))
    finally:
        for process in processes:
            if process.poll() is None:
                process.kill()
                process.wait()
    return results


def in_process(args: list[str], capsys: pytest.CaptureFixture[str]) -> tuple[int, str, str]:
    """``uwml.cli.main(args)`` in this process: the exit status (argparse's SystemExit too), stdout, stderr."""
    try:
        status = uwml.cli.main(args)
    except SystemExit as exit_info:
        status = exit_info.code if isinstance(exit_info.code, int) else 0
    captured = capsys.readouterr()
    return status, captured.out, captured.err


def read_csv(path: Path) -> tuple[list[str], np.ndarray]:
    with open(path, newline="", encoding="utf-8") as handle:
        rows = list(csv.reader(handle))
    return rows[0], np.array(rows[1:], dtype=np.float64)


def assert_bad_file(result: subprocess.CompletedProcess, path: Path, row: int, column: str) -> None:
    assert result.returncode == 2, (result.stdout, result.stderr)
    assert "Traceback" not in result.stderr, result.stderr
    message = result.stderr.strip()
    assert message.startswith("uwml: error: "), message
    assert str(path) in message and f"row {row}" in message and repr(column) in message, message


def replace_cell(path: Path, out: Path, row: int, column: str, value: str) -> None:
    """Copy a CSV file with one cell (spreadsheet row, header = 1) replaced."""
    with open(path, newline="", encoding="utf-8") as handle:
        rows = list(csv.reader(handle))
    rows[row - 1][rows[0].index(column)] = value
    with open(out, "w", newline="", encoding="utf-8") as handle:
        csv.writer(handle, lineterminator="\n").writerows(rows)
