"""Tests of ``uwml.viz.plot``: figures are built under Agg, saved as PNG, and show the right numbers."""

import math

import matplotlib
import numpy as np
import pytest
from matplotlib.figure import Figure
from uwml import fit
from uwml.model import losses
from uwml.paper import synthetic
from uwml.viz import plot

matplotlib.use("Agg")

OIL, SEAL, DRIVE = losses.OilDrag(), losses.Seal(), losses.Drive()
PNG_SIGNATURE = b"\x89PNG\r\n\x1a\n"


def _assert_png(path) -> None:
    content = path.read_bytes()
    assert content.startswith(PNG_SIGNATURE)
    assert len(content) > 10_000  # a drawn figure, not an empty canvas


def test_loss_maps(tmp_path) -> None:
    path = tmp_path / "maps.png"
    figure = plot.loss_maps(OIL, SEAL, DRIVE, pressures_mpa=(0.0, 10.0), path=path)
    assert isinstance(figure, Figure)
    _assert_png(path)
    oil_axes, seal_axes = figure.axes[:2]
    assert [len(ax.lines) for ax in (oil_axes, seal_axes)] == [2, 2]
    # The 10 MPa curves end at 10 r/min on the loss currents worked out by hand:
    # oil  3.3234e-3 · e^{0.2} · 160 · 10 · 2π/60 / 0.4,
    # seal (16 + 3.7·10 + (2.2 + 0.34·10) · 10 · 2π/60) / (160 · 0.8 · 0.4); together 2.85 A.
    omega = 10.0 * 2.0 * math.pi / 60.0
    oil_current = 3.3234e-3 * math.exp(0.2) * 160.0 * omega / 0.4
    seal_current = (53.0 + 5.6 * omega) / 51.2
    assert oil_axes.lines[1].get_ydata()[-1] == pytest.approx(oil_current, rel=1e-12)
    assert seal_axes.lines[1].get_ydata()[-1] == pytest.approx(seal_current, rel=1e-12)
    assert oil_current + seal_current == pytest.approx(2.85, abs=1e-3)


def test_loss_maps_with_one_model(tmp_path) -> None:
    path = tmp_path / "oil_only.png"
    figure = plot.loss_maps(OIL, None, path=path)
    _assert_png(path)
    assert len(figure.axes[1].lines) == 0
    assert "no seal model" in figure.axes[1].texts[0].get_text()


def test_efficiency_map(tmp_path) -> None:
    path = tmp_path / "efficiency.png"
    figure = plot.efficiency_map(OIL, SEAL, DRIVE, speeds_rpm=np.linspace(1.0, 10.0, 10), depths_m=np.linspace(0.0, 1000.0, 11), path=path)
    assert isinstance(figure, Figure)
    _assert_png(path)
    # The colour scale spans the share left: from the cold (2 °C) deep fast corner to the
    # shallow slow one; at 2 °C it drops below the paper's 72.6 % (20 °C, 10 MPa).
    low, high = figure.axes[0].collections[0].get_clim()
    assert low < 72.6 < high <= 100.0


def test_efficiency_map_rejects_bad_grids() -> None:
    with pytest.raises(ValueError, match="depths_m"):
        plot.efficiency_map(OIL, SEAL, depths_m=[-10.0, 100.0])


@pytest.mark.parametrize("method", ["oil_drag", "seal"])
def test_fit_plot(tmp_path, method: str) -> None:
    data = synthetic.three_configuration_experiment(speeds_rpm=(0.5, 1.0, 2.0, 5.0, 10.0), startup=2, repeats=3, rng=5)
    result = getattr(fit, method)(data, DRIVE)
    path = tmp_path / f"{method}.png"
    figure = plot.fit_plot(result, path=path)
    assert isinstance(figure, Figure)
    _assert_png(path)
    data_axes, residual_axes = figure.axes[:2]
    # Every point's normalized residual is drawn.
    drawn = np.concatenate([line.get_ydata() for line in residual_axes.lines if line.get_marker() == "o"])
    np.testing.assert_allclose(np.sort(drawn), np.sort((result.data - result.best_fit) / result.sigma))
    assert "R²" in data_axes.get_title()


def _text_boxes(figure: Figure) -> list[tuple[str, object]]:
    """Every visible, non-empty text of ``figure`` with its extent on the drawn canvas."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg

    canvas = FigureCanvasAgg(figure)
    canvas.draw()
    renderer = canvas.get_renderer()
    texts = [figure._suptitle] if figure._suptitle is not None else []
    for ax in figure.axes:
        texts += [ax.title, ax.xaxis.label, ax.yaxis.label]
    return [(t.get_text(), t.get_window_extent(renderer)) for t in texts if t.get_visible() and t.get_text().strip()]


@pytest.mark.parametrize("per", ["leg", "direction"])
def test_the_hydro_fit_figures_texts_stay_inside_it_and_apart(per: str) -> None:
    """A fit per direction has a dozen parameters: their values wrap above the panels; no title
    or axis label overlaps another or leaves the figure (extents after the constrained layout is
    drawn)."""
    result = fit.hydro_coefficients(synthetic.land_water_experiment(seed=0), joints=(0, 1, 2), per=per)
    figure = plot.hydro_fit_plot(result)
    boxes = _text_boxes(figure)
    page = figure.bbox
    for text, box in boxes:
        assert page.x0 - 1 <= box.x0 and box.x1 <= page.x1 + 1, f"{text!r} leaves the figure"
    for i, (a, box_a) in enumerate(boxes):
        for b, box_b in boxes[i + 1 :]:
            assert not box_a.overlaps(box_b), f"{a!r} overlaps {b!r}"
    assert any("COD" in text for text, _ in boxes)


def test_the_efficiency_map_resolves_the_breakaway_below_one_rpm() -> None:
    figure = plot.efficiency_map(losses.OilDrag(), losses.Seal())
    ax = figure.axes[0]
    assert ax.get_xscale() == "log"
    speeds = plot._MAP_SPEEDS_RPM
    assert np.count_nonzero(speeds < 1.0) >= 50 and speeds.min() <= 0.05
