"""``uwml fit losses``: the oil-drag and seal models fitted from a CSV of current measurements
(its report, JSON and figures), from several files or a pattern, on Ray; bad and hostile files
are one-line errors naming the file, row and column."""

from __future__ import annotations

import importlib.util
import json
from pathlib import Path

import pytest
from cli_runs import assert_bad_file, in_process, replace_cell, run_uwml_all
from uwml import fit
from uwml.paper import synthetic


@pytest.fixture(scope="module")
def loss_csv(tmp_path_factory: pytest.TempPathFactory) -> Path:
    path = tmp_path_factory.mktemp("losses") / "losses.csv"
    fit.write_loss_csv(synthetic.three_configuration_experiment(repeats=3, startup=3, rng=0), path)
    return path


def test_fit_losses_report_json_and_plots(tmp_path: Path, loss_csv: Path) -> None:
    figures = tmp_path / "figures"
    result, json_result = run_uwml_all(("fit", "losses", loss_csv, "--plot", figures), ("fit", "losses", loss_csv, "--json"))
    assert result.returncode == 0, result.stderr
    assert result.stdout.count("[[Fit Statistics]]") == 2
    for name in ("k_oil:", "exponent:", "c0:", "s0:", "stribeck_speed:"):
        assert name in result.stdout, name
    for name in ("oil_drag_fit.png", "seal_fit.png"):
        assert (figures / name).read_bytes()[:4] == b"\x89PNG", name

    result = json_result
    assert result.returncode == 0, result.stderr
    summary = json.loads(result.stdout)
    assert set(summary) == {"oil_drag", "seal"}
    assert {"k_oil", "exponent", "pressure_sensitivity_per_mpa"} <= set(summary["oil_drag"]["params"])
    assert {"c0", "s0", "stribeck_speed"} <= set(summary["seal"]["params"])
    assert all(isinstance(v, float) for v in summary["seal"]["params"].values())


def test_fit_losses_hostile_files(tmp_path: Path, loss_csv: Path, capsys: pytest.CaptureFixture[str]) -> None:
    bom = tmp_path / "bom.csv"
    bom.write_bytes(b"\xef\xbb\xbf" + loss_csv.read_bytes())  # Excel's "CSV UTF-8": read
    status, out, err = in_process(["fit", "losses", str(bom), "--json"], capsys)
    assert status == 0 and set(json.loads(out)) == {"oil_drag", "seal"}, err
    latin = tmp_path / "latin.csv"
    latin.write_bytes(loss_csv.read_bytes().replace(b"\n", b"\n\xb1", 1))
    long_cell = tmp_path / "long.csv"
    long_cell.write_bytes(loss_csv.read_bytes().replace(b"\n", b'\n"' + b"x" * 200_000, 1))
    for path, words in [
        (latin, [f"{latin}: row 2, column 'configuration': not UTF-8 text (byte 0xb1)"]),
        (long_cell, [f"{long_cell}: not CSV"]),
        (tmp_path / "absent.csv", [f"{tmp_path / 'absent.csv'}: no such file"]),
        (tmp_path, [f"{tmp_path}: is a directory"]),
    ]:
        status, _, err = in_process(["fit", "losses", str(path)], capsys)
        assert status == 2 and err.count("\n") == 1 and err.startswith("uwml: error: "), err
        for word in words:
            assert word in err, (word, err)


def test_fit_losses_bad_files(tmp_path: Path, loss_csv: Path) -> None:
    cell = tmp_path / "cell.csv"
    replace_cell(loss_csv, cell, 9, "current_a", "1,5A")
    missing = tmp_path / "missing.csv"
    missing.write_text(loss_csv.read_text(encoding="utf-8").replace("pressure_mpa", "pressure", 1), encoding="utf-8")
    results = run_uwml_all(("fit", "losses", cell), ("fit", "losses", missing))
    assert_bad_file(results[0], cell, 9, "current_a")
    assert_bad_file(results[1], missing, 1, "pressure_mpa")


def test_fit_losses_takes_several_files_and_patterns(tmp_path: Path, loss_csv: Path, capsys: pytest.CaptureFixture[str]) -> None:
    """Several CSV files (or a pattern) are their rows together: the fit of one file holding them."""
    lines = loss_csv.read_text().splitlines()
    header, rows = lines[0], lines[1:]
    half = len(rows) // 2
    (tmp_path / "part1.csv").write_text("\n".join([header, *rows[:half]]) + "\n")
    (tmp_path / "part2.csv").write_text("\n".join([header, *rows[half:]]) + "\n")
    status, out, err = in_process(["fit", "losses", str(loss_csv), "--json"], capsys)
    assert status == 0, err
    whole = json.loads(out)
    for arguments in ([str(tmp_path / "part1.csv"), str(tmp_path / "part2.csv")], [str(tmp_path / "part*.csv")]):
        status, out, err = in_process(["fit", "losses", *arguments, "--json"], capsys)
        assert status == 0, err
        split = json.loads(out)
        for model in ("oil_drag", "seal"):
            for name, value in whole[model]["params"].items():
                assert split[model]["params"][name] == pytest.approx(value, rel=1e-9), (model, name)
    status, out, err = in_process(["fit", "losses", str(tmp_path / "none*.csv")], capsys)
    assert status == 2 and "none*.csv: no file matches the pattern" in err
    if importlib.util.find_spec("ray") is not None:  # the files read by Ray's workers
        status, out, err = in_process(["fit", "losses", str(tmp_path / "part*.csv"), "--ray", "--workers", "2", "--json"], capsys)
        assert status == 0, err
        assert json.loads(out)["seal"]["params"] == pytest.approx(whole["seal"]["params"], rel=1e-9)
