"""Figures of the joint losses: loss maps (the paper's Figs. 13-14), efficiency over speed and
depth, and a fit against its data; the hydrodynamic fit's measured and fitted torque (Fig. 7).

Every function builds a :class:`matplotlib.figure.Figure` directly (no pyplot, no global state,
so it works under any backend, Agg included), returns it, and saves it when given a path (the
format follows the file's extension).
"""

from __future__ import annotations

import os
import textwrap
from collections.abc import Sequence

import numpy as np
from matplotlib import colormaps
from matplotlib.figure import Figure
from numpy.typing import ArrayLike, NDArray

from ..fit import HydroFit, LossFit
from ..model.joint_losses import JointLosses
from ..model.losses import RPM, Drive, OilDrag, Seal
from ..sea import seawater

__all__ = ["efficiency_map", "fit_plot", "hydro_fit_plot", "loss_maps"]

#: Speeds of the loss curves [r/min]: up to the paper's 10 r/min, from just above 0 so that the
#: seal's breakaway peak shows.
_SPEEDS_RPM = np.linspace(0.0, 10.0, 201)[1:]
#: The paper's pressures [MPa].
_PRESSURES_MPA = (0.0, 2.0, 4.0, 6.0, 8.0, 10.0)
#: Speed and depth grid of the efficiency map [r/min, m]: the paper's speeds, and depths to
#: twice its kilometre (the illustrative defaults are calibrated at 10 MPa only).
#: The seal's breakaway makes the losses change fastest below 1 r/min: the speeds are
#: geometric there (from 0.05 r/min), even beyond it.
_MAP_SPEEDS_RPM = np.unique(np.concatenate([np.geomspace(0.05, 1.0, 60), np.linspace(1.0, 10.0, 73)]))
_MAP_DEPTHS_M = np.linspace(0.0, 2000.0, 81)
#: The default drive (the paper's hip-roll joint, illustrative K_t and η).
_DRIVE = Drive()


def _save(figure: Figure, path: str | os.PathLike[str] | None) -> Figure:
    if path is not None:
        figure.savefig(path, dpi=120)
    return figure


def _positive_grid(values: ArrayLike, name: str, *, allow_zero: bool) -> NDArray[np.float64]:
    a = np.asarray(values, dtype=np.float64)
    if a.ndim != 1 or a.size < 2 or not np.all(np.isfinite(a)) or np.any(a < 0.0 if allow_zero else a <= 0.0):
        raise ValueError(f"{name} must be at least 2 finite numbers {'>= 0' if allow_zero else '> 0'}, got {values!r}")
    return np.sort(a)


def loss_maps(
    oil: OilDrag | None,
    seal: Seal | None,
    drive: Drive = _DRIVE,
    *,
    speeds_rpm: ArrayLike = _SPEEDS_RPM,
    pressures_mpa: Sequence[float] = _PRESSURES_MPA,
    temperature_c: float = 20.0,
    path: str | os.PathLike[str] | None = None,
) -> Figure:
    """Loss current against output speed, one curve per pressure: oil (left) and seal (right).

    The paper's Figs. 13 and 14: ``T_oil/K_t`` and ``T_seal/(N η K_t)`` [A] at steady speed
    (hard sign), the seal's curves rising to the breakaway level near 0.

    Parameters
    ----------
    oil, seal
        Loss models; None leaves that panel empty.
    drive
        The joint's drive (turns torques into current).
    speeds_rpm : array_like
        Output speeds [r/min], ≥ 0.
    pressures_mpa : sequence of float
        One curve per pressure [MPa], ≥ 0.
    temperature_c : float
        Oil temperature [°C].
    path : str or path, optional
        Where to save the figure.

    Returns
    -------
    matplotlib.figure.Figure
    """
    speeds = _positive_grid(speeds_rpm, "speeds_rpm", allow_zero=True)
    figure = Figure(figsize=(10.0, 4.2), layout="constrained")
    axes = figure.subplots(1, 2)
    colors = colormaps["viridis"](np.linspace(0.0, 0.9, len(pressures_mpa)))
    panels = (
        (axes[0], "oil", oil, None, "Oil viscous loss (paper Fig. 13)"),
        (axes[1], "seal", None, seal, "Dynamic seal loss (paper Fig. 14)"),
    )
    for ax, name, panel_oil, panel_seal, title in panels:
        ax.set_title(title)
        ax.set_xlabel("output speed [r/min]")
        ax.set_ylabel("loss current [A]")
        if panel_oil is None and panel_seal is None:
            ax.text(0.5, 0.5, f"no {name} model given", ha="center", va="center", transform=ax.transAxes)
            continue
        losses = JointLosses(drive=drive, oil=panel_oil, seal=panel_seal, epsilon=0.0)
        for pressure, color in zip(pressures_mpa, colors, strict=True):
            loss = losses.torques(speeds * RPM, pressure, temperature_c)
            ax.plot(speeds, loss.current, color=color, label=f"{pressure:g} MPa")
        ax.set_xlim(0.0, speeds.max())
        ax.set_ylim(bottom=0.0)
        ax.grid(alpha=0.3)
        ax.legend(title=f"{temperature_c:g} °C", fontsize="small")
    return _save(figure, path)


def efficiency_map(
    oil: OilDrag | None,
    seal: Seal | None,
    drive: Drive = _DRIVE,
    *,
    speeds_rpm: ArrayLike = _MAP_SPEEDS_RPM,
    depths_m: ArrayLike = _MAP_DEPTHS_M,
    temperature_c: float = 2.0,
    latitude_deg: float = 0.0,
    path: str | os.PathLike[str] | None = None,
) -> Figure:
    """Share of the rated current left after the joint losses, over output speed and depth.

    ``1 − I_loss / I_rated`` (the paper's 72.6 % at 10 r/min, 10 MPa, 20 °C), with the pressure
    at each depth from TEOS-10 (:func:`uwml.sea.seawater.pressure_at_depth_mpa`) and the oil at
    ``temperature_c`` (the deep sea: about 2 °C).

    Parameters
    ----------
    oil, seal
        Loss models (None: that loss is left out).
    drive
        The joint's drive (``rated_current``).
    speeds_rpm : array_like
        Output speeds [r/min], ≥ 0, at least 2.
    depths_m : array_like
        Depths [m], ≥ 0, at least 2.
    temperature_c : float
        Oil temperature [°C].
    latitude_deg : float
        Latitude for the pressure at depth [degrees].
    path : str or path, optional
        Where to save the figure.

    Returns
    -------
    matplotlib.figure.Figure
    """
    speeds = _positive_grid(speeds_rpm, "speeds_rpm", allow_zero=True)
    depths = _positive_grid(depths_m, "depths_m", allow_zero=True)
    pressure = seawater.pressure_at_depth_mpa(depths, latitude_deg)
    loss = JointLosses(drive=drive, oil=oil, seal=seal, epsilon=0.0).torques(speeds[None, :] * RPM, pressure[:, None], temperature_c)
    share = 100.0 * (1.0 - loss.current / drive.rated_current)
    figure = Figure(figsize=(7.0, 5.0), layout="constrained")
    ax = figure.subplots()
    filled = ax.contourf(speeds, depths, share, levels=12, cmap="viridis")
    lines = ax.contour(speeds, depths, share, levels=filled.levels, colors="k", linewidths=0.5)
    ax.clabel(lines, fmt="%.0f %%", fontsize="small")
    figure.colorbar(filled, ax=ax, label="rated current left after losses [%]")
    ax.invert_yaxis()
    ax.set_xscale("log")  # the breakaway below 1 r/min, where the share changes fastest
    ax.set_xlabel("output speed [r/min]")
    ax.set_ylabel("depth [m]")
    ax.set_title(f"Joint current budget at depth (oil at {temperature_c:g} °C, TEOS-10 pressure)")
    return _save(figure, path)


def fit_plot(result: LossFit, path: str | os.PathLike[str] | None = None) -> Figure:
    """A loss fit against its data: measured and fitted loss vs speed, and normalized residuals.

    Left: the measured loss torques (group-mean differences, ± one standard error) and the
    fitted model, one colour per pressure (and temperature); start-up points at speed 0 as open
    squares, their fitted values as crosses (both in the legend). Right: ``(data − fit) / σ`` against speed.

    Parameters
    ----------
    result : LossFit
        From :func:`uwml.fit.oil_drag` or :func:`uwml.fit.seal`.
    path : str or path, optional
        Where to save the figure.

    Returns
    -------
    matplotlib.figure.Figure
    """
    figure = Figure(figsize=(10.0, 4.2), layout="constrained")
    ax, ax_residual = figure.subplots(1, 2)
    speed_rpm = result.speed / RPM
    conditions = sorted(set(zip(result.pressure_mpa.tolist(), result.temperature_c.tolist(), strict=True)))
    several_temperatures = len({theta for _, theta in conditions}) > 1
    colors = colormaps["viridis"](np.linspace(0.0, 0.9, len(conditions)))
    dense = np.linspace(0.0, max(float(speed_rpm.max()), 1e-9), 201)[1:]
    normalized = (result.data - result.best_fit) / result.sigma
    for (pressure, theta), color in zip(conditions, colors, strict=True):
        here = (result.pressure_mpa == pressure) & (result.temperature_c == theta)
        steady, start = here & ~result.startup, here & result.startup
        label = f"{pressure:g} MPa" + (f", {theta:g} °C" if several_temperatures else "")
        ax.errorbar(speed_rpm[steady], result.data[steady], yerr=result.sigma[steady], fmt="o", color=color, ms=4, label=label)
        if np.any(steady):
            ax.plot(dense, result.eval(dense * RPM, pressure, theta), color=color, lw=1.2)
        if np.any(start):
            ax.errorbar(speed_rpm[start], result.data[start], yerr=result.sigma[start], fmt="s", mfc="none", color=color, ms=6)
            ax.plot(speed_rpm[start], result.best_fit[start], "x", color=color, ms=8)
        ax_residual.plot(speed_rpm[here], normalized[here], "o", color=color, ms=4)
    if np.any(result.startup):  # the legend says what the squares and crosses at speed 0 are
        ax.plot([], [], "s", mfc="none", color="0.4", ms=6, label="start-up (breakaway), measured")
        ax.plot([], [], "x", color="0.4", ms=8, label="start-up, fitted")
    name = type(result.model).__name__
    ax.set_title(f"{name} fit: measured (points) and fitted (lines), R² = {result.rsquared:.4f}")
    ax.set_xlabel("output speed [r/min]")
    ax.set_ylabel(f"loss torque [{result.unit}]")
    ax.grid(alpha=0.3)
    ax.legend(fontsize="small", ncol=2)  # short: over no curve
    ax_residual.axhline(0.0, color="k", lw=0.8)
    ax_residual.set_title(f"residuals, reduced χ² = {result.redchi:.3g}")
    ax_residual.set_xlabel("output speed [r/min]")
    ax_residual.set_ylabel("(measured − fitted) / standard error")
    ax_residual.grid(alpha=0.3)
    return _save(figure, path)


def hydro_fit_plot(result: HydroFit, path: str | os.PathLike[str] | None = None) -> Figure:
    """Measured and fitted hydrodynamic torque over time, as the paper's Fig. 7.

    One row per fitted joint: left, the measured ``−Δτ_motor − τ_buoy`` (points) and the fitted
    ``Σ Cd R_d + Cm R_m`` (line) against time; right, the residual ``measured − fitted``.

    Parameters
    ----------
    result : HydroFit
        From :func:`uwml.fit.hydro_coefficients`.
    path : str or path, optional
        Where to save the figure.

    Returns
    -------
    matplotlib.figure.Figure
    """
    # The joints' rows, then the base wrench's components (labelled -1 … -6).
    joints = [*result.joints, *(-1 - c for c in result.base)]
    figure = Figure(figsize=(11.0, 3.2 * len(joints)), layout="constrained")
    axes = np.atleast_2d(figure.subplots(len(joints), 2, squeeze=False))
    values = ", ".join(
        f"{name} = {result.params[name]:.4g}" + ("" if result.stderr[name] is None else f" ± {result.stderr[name]:.2g}")
        for name in result.var_names
    )
    for row, joint in enumerate(joints):
        ax, ax_residual = axes[row]
        here = result.joint == joint
        t = result.time[here]
        ax.plot(t, result.data[here], ".", ms=2.5, color="0.45", label="measured")
        ax.plot(t, result.best_fit[here], color="C3", lw=1.3, label="fitted")
        ax.set_xlabel("time [s]")
        component = ["fx", "fy", "fz", "mx", "my", "mz"][-1 - joint] if joint < 0 else ""
        unit = "N" if component.startswith("f") else "N·m"
        ax.set_ylabel(f"base {component} [{unit}]" if joint < 0 else f"joint {joint + 1} torque [N·m]")
        ax.grid(alpha=0.3)
        ax.legend(fontsize="small", loc="upper right")
        ax_residual.plot(t, result.data[here] - result.best_fit[here], ".", ms=2.5, color="C0")
        ax_residual.axhline(0.0, color="k", lw=0.8)
        ax_residual.set_xlabel("time [s]")
        ax_residual.set_ylabel(f"measured − fitted [{unit if joint < 0 else 'N·m'}]")
        ax_residual.grid(alpha=0.3)
        if row == 0:
            ax.set_title("hydrodynamic torque −Δτ − τ_buoy", fontsize="small")
            ax_residual.set_title("residuals", fontsize="small")
    # The values and statistics above the panels, wrapped to the figure's width (a fit per link
    # and direction has dozens of parameters).
    statistics = f"unweighted: reduced χ² = {result.redchi_unweighted:.4g} {result.squared_unit}, COD = {result.cod:.4f}"
    figure.suptitle("\n".join(textwrap.wrap(f"{values}; {statistics}", width=150)), fontsize="small")
    return _save(figure, path)
