"""The paper's control question, answered in simulation (``uwml simulate``).

The paper ends where a controller's designer begins: the leg's controller "must consider the
influence of the viscous resistance and dynamic seal resistance", and of the water. Here the
paper's leg, on a fixed stand, follows our walking gait in sea water at several depths, in MuJoCo
with uwml's forces (:mod:`uwml.sim.mujoco`: drag, added mass in the mass matrix, buoyancy, the joint
losses of :class:`uwml.JointLosses` at the depth's pressure), under five controllers:

* ``land``: PD on the joint error plus the land model's feedforward (the rigid body's inverse
  dynamics with gravity, ``mj_inverse``): a controller tuned on land;
* ``hydro``: ``land`` plus uwml's hydrodynamic feedforward ``−τ_hydro(q_d, q̇_d, q̈_d)``;
* ``hydro_losses``: ``hydro`` plus the joint losses' feedforward ``−(τ_visc + τ_seal)`` at the
  depth's pressure;
* ``hydro_wrong`` and ``hydro_losses_wrong``: ``hydro`` and ``hydro_losses`` with every Cd and
  Cm 30 % too high (robustness).

**The plant** (stated, the paper gives no inertias): the links' masses and centres of mass of
Table II (``uwml.paper_leg()``); each link's inertia about its centre of mass that of a uniform
box of its section sizes and length (the hip housing, without a segment: a uniform cube of its
displaced volume); Cd = 2.2, Cm = 0.5 (the paper's fit); sea water of 1025 kg/m³ at 4 °C; the
illustrative ``JointLosses()`` on every joint. PD gains: a critically damped 4 Hz loop on each
joint's rigid inertia at the start (``Kp = I ω²``, ``Kd = 2 I ω``), tuned on land and kept.
MuJoCo's semi-implicit Euler at 1 ms.

**Outputs** per depth and controller, over the last gait cycle: RMS and peak tracking error per
joint [rad], and the motor's positive mechanical work per cycle ``∫ Σ max(τ_i q̇_i, 0) dt`` [J].

The tracking is :func:`uwml.sim.control.track`'s. **The preset** (:func:`preset`): the study of
``uwml simulate``, the grid depth × controller of the ``paper_leg`` scenario
(:mod:`uwml.study.scenarios`) as a study file; its rows, with MuJoCo's fluid models against uwml's
(:func:`fluid_models`) and an arm on a drifting ROV (:func:`uwml.sim.control.rov_drift`), make
:func:`write_report`'s report.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from ..model.joint_losses import JointLosses
from ..robot.presets import paper_leg
from ..robot.tree import Robot
from ..sim.control import ROV_CURRENT, SEA, TEMPERATURE_C, Drift, track
from ..sim.mujoco import Simulation
from . import synthetic
from .gait import WalkingGait

__all__ = [
    "CONTROLLERS",
    "DEPTHS",
    "MAX_CYCLES",
    "FluidComparison",
    "Run",
    "fluid_models",
    "leg_model",
    "preset",
    "run",
    "study",
    "write_report",
]

FloatArray = NDArray[np.float64]

#: The controllers compared (module docstring).
CONTROLLERS = ("land", "hydro", "hydro_losses", "hydro_wrong", "hydro_losses_wrong")
#: The depths of the study [m].
DEPTHS = (0.0, 1000.0, 3000.0, 6000.0)
#: Sea water's dynamic viscosity at 4 °C [Pa·s] (for MuJoCo's fluid models only).
SEA_VISCOSITY = 1.6e-3
#: The PD loop's natural frequency [Hz] (critically damped).
PD_HZ = 4.0
TIMESTEP = 1e-3
#: Most gait cycles of a run: each holds its trajectories in memory (about 0.2 MB a cycle).
MAX_CYCLES = 100


def leg_model(leg: Robot | None = None, fluid: str | None = None) -> str:
    """The MJCF of the paper's leg on a fixed stand (module docstring, "The plant"), its frames
    those of ``uwml.paper_leg()`` (parallel to the base at ``q = 0``). Each link carries
    its box as a geom without contacts. ``fluid``: None (no fluid: uwml is the water), or
    ``"box"`` / ``"ellipsoid"`` for MuJoCo's own fluid models in the study's sea water (for the
    comparison of :func:`fluid_models`)."""
    leg = paper_leg() if leg is None else leg
    bodies = []
    for joint, link in zip(leg.joints, leg.links, strict=True):
        segment = link.segments[0] if link.segments else None
        if segment is None:
            side = link.volume ** (1.0 / 3.0)
            extents = np.array([side, side, side])
        else:
            # Drag along n_k uses the extent along the other normal: widths = (along n1, along n0).
            axes = [np.abs(segment.axis), np.abs(segment.normals[0]), np.abs(segment.normals[1])]
            sizes = [segment.length, segment.widths[1], segment.widths[0]]
            extents = sum((a * s for a, s in zip(axes, sizes, strict=True)), np.zeros(3))
        a, b, c = extents
        inertia = link.mass / 12.0 * np.array([b * b + c * c, a * a + c * c, a * a + b * b])
        centre = np.asarray(link.com) if segment is None else np.asarray(segment.start) + np.asarray(segment.axis) * (segment.length / 2.0)
        bodies.append((joint, link, inertia, extents, centre))
    water = "" if fluid is None else f' density="{SEA.density!r}" viscosity="{SEA_VISCOSITY!r}"'
    shape = ' fluidshape="ellipsoid"' if fluid == "ellipsoid" else ""
    xml = [
        '<mujoco model="uwml_paper_leg">',
        f'  <option timestep="{TIMESTEP}" gravity="0 0 -{SEA.gravity}"{water}/>',
        "  <worldbody>",
        '    <body name="stand">',
    ]
    depth = 3
    for i, (joint, link, inertia, extents, centre) in enumerate(bodies):
        pad = "  " * depth
        xml.append(f'{pad}<body name="link{i}" pos="{" ".join(map(repr, joint.origin))}">')
        xml.append(f'{pad}  <joint name="joint{i + 1}" type="hinge" axis="{" ".join(map(repr, joint.axis))}"/>')
        xml.append(
            f'{pad}  <inertial pos="{" ".join(map(repr, link.com))}" mass="{link.mass!r}" diaginertia="{" ".join(repr(float(x)) for x in inertia)}"/>'
        )
        half = " ".join(repr(float(x) / 2.0) for x in extents)
        where = " ".join(repr(float(x)) for x in centre)
        xml.append(f'{pad}  <geom type="box" size="{half}" pos="{where}" contype="0" conaffinity="0"{shape}/>')
        depth += 1
    for i in reversed(range(len(bodies))):
        xml.append("  " * (3 + i) + "</body>")
    xml += ["    </body>", "  </worldbody>", "</mujoco>"]
    return "\n".join(xml)


@dataclass(frozen=True)
class Run:
    """One simulated run: a controller at a depth, over ``cycles`` gait cycles."""

    controller: str
    depth: float
    time: FloatArray
    q: FloatArray
    q_desired: FloatArray
    torque: FloatArray
    qd: FloatArray
    #: Samples of the last cycle (the metrics' window).
    window: slice = field(default_factory=lambda: slice(None))

    @property
    def error(self) -> FloatArray:
        return self.q - self.q_desired

    def rms_error(self) -> FloatArray:
        rms: FloatArray = np.sqrt(np.mean(self.error[self.window] ** 2, axis=0))
        return rms

    def peak_error(self) -> FloatArray:
        peak: FloatArray = np.max(np.abs(self.error[self.window]), axis=0)
        return peak

    def positive_work(self) -> float:
        power = np.maximum(self.torque[self.window] * self.qd[self.window], 0.0).sum(axis=1)
        return float(np.sum(power) * TIMESTEP)

    def energy(self) -> float:
        """The motors' mechanical energy over the window, ``∫ Σ |τ_i q̇_i| dt`` [J]."""
        return float(np.sum(np.abs(self.torque[self.window] * self.qd[self.window])) * TIMESTEP)

    def summary(self) -> dict[str, Any]:
        return {
            "controller": self.controller,
            "depth_m": self.depth,
            "rms_error_rad": self.rms_error().tolist(),
            "peak_error_rad": self.peak_error().tolist(),
            "positive_work_per_cycle_j": self.positive_work(),
        }


def run(
    controller: str,
    depth: float,
    cycles: float = 2.0,
    model_xml: str | None = None,
    *,
    coefficient_scale: float | None = None,
    payload: float = 0.0,
    plant_losses: bool = True,
) -> Run:
    """Simulates the paper's leg following the gait under ``controller`` at ``depth`` [m], for
    ``cycles`` gait cycles (more than 0, at most ``MAX_CYCLES``). ``coefficient_scale``: the
    controller's Cd and Cm over the plant's (default 1.3 for the ``_wrong`` controllers, else
    1); ``payload``: a mass [kg, 0 to 100] the foot carries (at the last link's centre of mass,
    without volume), which the controller does not know; ``plant_losses``: False for a plant
    whose joints have no losses (the controllers' feedforward keeps them)."""
    if controller not in CONTROLLERS:
        raise ValueError(f"controller must be one of {', '.join(CONTROLLERS)}, got {controller!r}")
    if not (math.isfinite(depth) and 0.0 <= depth <= 11_000.0):
        raise ValueError(f"depth must be between 0 and 11000 m, got {depth!r}")
    if not (math.isfinite(cycles) and 0.0 < cycles <= MAX_CYCLES):
        raise ValueError(f"cycles must be finite and > 0, at most {MAX_CYCLES} (gait cycles), got {cycles!r}")
    if coefficient_scale is not None and not (math.isfinite(coefficient_scale) and 0.0 <= coefficient_scale <= 10.0):
        raise ValueError(f"coefficient_scale must be between 0 and 10, got {coefficient_scale!r}")
    if not (math.isfinite(payload) and 0.0 <= payload <= 100.0):
        raise ValueError(f"payload must be between 0 and 100 kg, got {payload!r}")
    import mujoco

    leg = paper_leg()
    robot = Robot(leg.joints, leg.links, losses=JointLosses(), water=SEA)
    plant = robot if plant_losses else Robot(leg.joints, leg.links, water=SEA)
    xml = model_xml or leg_model(leg)
    model = mujoco.MjModel.from_xml_string(xml)
    # The controller's model: the plant without the payload.
    known = mujoco.MjModel.from_xml_string(xml) if payload else model
    if payload:
        model.body_mass[model.nbody - 1] += payload
    sim = Simulation(model, plant, depth=depth, temperature_c=TEMPERATURE_C)
    gait = WalkingGait(nominal_foot=synthetic.YAW_STEP_FOOT)
    steps = round(cycles * gait.period / TIMESTEP)
    time = np.arange(steps + 1, dtype=np.float64) * TIMESTEP
    q_d, qd_d, qdd_d = gait.joint_states(time)
    # Feedforward along the desired trajectory, all at once.
    scale = (1.3 if controller.endswith("_wrong") else 1.0) if coefficient_scale is None else coefficient_scale
    hydro = robot.environment(q_d, qd_d, qdd_d, depth=depth, temperature_c=TEMPERATURE_C, cd=2.2 * scale, cm=0.5 * scale)
    feedforward = np.zeros_like(q_d)
    if controller != "land":
        feedforward -= hydro.hydro
    if controller.startswith("hydro_losses"):
        feedforward -= hydro.visc + hydro.seal
    q, qd, torque = track(sim, known, (q_d, qd_d, qdd_d), feedforward, PD_HZ)
    last = round(gait.period / TIMESTEP)
    return Run(controller, depth, time, q, q_d, torque, qd, window=slice(max(0, steps + 1 - last), None))


def study(
    depths: Sequence[float] = DEPTHS,
    controllers: Sequence[str] = CONTROLLERS,
    cycles: float = 2.0,
    progress: Callable[[int, int], None] | None = None,
) -> list[Run]:
    """Every controller at every depth (``progress(done, total)`` after each run)."""
    model_xml = leg_model()
    runs, total = [], len(depths) * len(controllers)
    for depth in depths:
        for controller in controllers:
            runs.append(run(controller, float(depth), cycles, model_xml))
            if progress is not None:
                progress(len(runs), total)
    return runs


def preset(depths: Sequence[float], cycles: float) -> str:
    """The study of ``uwml simulate`` as a study file (docs/scale.md): the ``paper_leg`` scenario,
    ``cycles`` gait cycles a run, every controller at every depth [m]. ``uwml.study.loads`` makes
    it a study; saved, ``uwml study`` runs the same runs."""
    grid = ", ".join(repr(float(d)) for d in depths)
    controllers = ", ".join(f'"{c}"' for c in CONTROLLERS)
    return f'[scenario]\nkind = "paper_leg"\ncycles = {float(cycles)!r}\n[parameters]\ndepth = [{grid}]\ncontroller = [{controllers}]\n'


@dataclass(frozen=True)
class FluidComparison:
    """The paper leg's water torques along one gait cycle: uwml's drag plus added mass and MuJoCo's
    fluid models' (``qfrc_fluid``, inertia box and ellipsoid), each ``(n, 3)`` [N·m], in the
    study's sea water. MuJoCo's fluid models have no buoyancy (zero at rest), so uwml's buoyancy is
    kept apart (``buoyancy``) and left out of the comparison."""

    time: FloatArray
    uwml: FloatArray
    box: FloatArray
    ellipsoid: FloatArray
    buoyancy: FloatArray

    def rms(self) -> dict[str, FloatArray]:
        return {name: np.sqrt(np.mean(getattr(self, name) ** 2, axis=0)) for name in ("uwml", "box", "ellipsoid")}

    def relative_difference(self, name: str) -> FloatArray:
        """RMS of (model − uwml) per joint over uwml's RMS."""
        difference = getattr(self, name) - self.uwml
        relative: FloatArray = np.sqrt(np.mean(difference**2, axis=0)) / self.rms()["uwml"]
        return relative


def fluid_models(samples: int = 200) -> FluidComparison:
    """uwml's torques and MuJoCo's fluid models' on the same motion: one cycle of our gait."""
    import mujoco

    gait = WalkingGait(nominal_foot=synthetic.YAW_STEP_FOOT)
    time = np.linspace(0.0, gait.period, samples, endpoint=False)
    q, qd, qdd = gait.joint_states(time)
    leg = paper_leg()
    hydro = Robot(leg.joints, leg.links, water=SEA).hydro(q, qd, qdd)
    theirs = {}
    for fluid in ("box", "ellipsoid"):
        model = mujoco.MjModel.from_xml_string(leg_model(leg, fluid))
        data = mujoco.MjData(model)
        torques = np.zeros_like(q)
        for k in range(samples):
            data.qpos[:], data.qvel[:] = q[k], qd[k]
            mujoco.mj_forward(model, data)
            torques[k] = data.qfrc_fluid
        theirs[fluid] = torques
    return FluidComparison(time, hydro.drag + hydro.added_mass, theirs["box"], theirs["ellipsoid"], hydro.buoyancy)


#: The tracking figure's line styles, one per controller.
LINE_STYLES = ("-", "--", ":", "-.", (0, (5, 1, 1, 1, 1, 1)))
#: The depth sweep's markers, one per controller.
MARKERS = ("o", "s", "^", "D", "v")


def _errors(row: dict[str, Any], kind: str) -> list[float]:
    """A study row's RMS or peak tracking error per joint [rad]."""
    return [float(row[f"{kind}_error_{j}"]) for j in (1, 2, 3)]


def write_report(
    rows: list[dict[str, Any]],
    series: list[Run],
    out: Path,
    fluid: FluidComparison | None = None,
    drifts: Sequence[Drift] = (),
    lossless: Sequence[Run] = (),
) -> Path:
    """The Markdown report and its figures in ``out``: the table and the depth sweep of the
    study's ``rows`` (``depth``, ``controller``, ``rms_error_<j>``, ``peak_error_<j>``,
    ``positive_work``), the tracking figure of the runs ``series`` (time series, the deepest
    depth's), and with ``fluid`` MuJoCo's fluid models against uwml; ``lossless``: runs of the
    ``hydro`` and ``hydro_wrong`` controllers on a plant without joint losses, which say why the
    wrong coefficients track better when the losses are left out of the feedforward."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    out.mkdir(parents=True, exist_ok=True)
    depths = sorted({float(r["depth"]) for r in rows})
    controllers = [c for c in CONTROLLERS if any(r["controller"] == c for r in rows)]
    deepest = series
    figure, axes = plt.subplots(3, 2, figsize=(11, 8), sharex=True)
    for joint in range(3):
        for index, r in enumerate(deepest):
            # Controllers whose lines would lie on each other: each its own dash and width.
            line: dict[str, Any] = {
                "linestyle": LINE_STYLES[index % len(LINE_STYLES)],
                "linewidth": 2.4 - 0.4 * index,
                "label": r.controller,
            }
            axes[joint, 0].plot(r.time, np.degrees(r.error[:, joint]), **line)
            axes[joint, 1].plot(r.time, r.torque[:, joint], **line)
        axes[joint, 0].set_ylabel(f"joint {joint + 1} error [°]")
        axes[joint, 1].set_ylabel(f"joint {joint + 1} torque [N·m]")
    axes[0, 0].legend(fontsize=8)
    axes[2, 0].set_xlabel("time [s]")
    axes[2, 1].set_xlabel("time [s]")
    figure.suptitle(f"Tracking error and motor torque at {depths[-1]:g} m")
    figure.tight_layout()
    figure.savefig(out / "tracking.png", dpi=110)
    plt.close(figure)
    figure, axis = plt.subplots(figsize=(7, 4))
    for index, controller in enumerate(controllers):
        values = [
            np.degrees(max(_errors(next(row for row in rows if row["controller"] == controller and row["depth"] == d), "rms")))
            for d in depths
        ]
        # Controllers that track alike (land and hydro) would hide each other: each its own dash,
        # marker and size, the first drawn widest.
        axis.plot(
            depths, values, linestyle=LINE_STYLES[index % len(LINE_STYLES)], marker=MARKERS[index % len(MARKERS)],
            markersize=max(9.0 - 1.2 * index, 3.0), linewidth=max(2.4 - 0.4 * index, 0.6), label=controller,
        )  # fmt: skip
    axis.set_xlabel("depth [m]")
    axis.set_ylabel("worst joint RMS error [°]")
    axis.set_title("Worst joint's RMS tracking error over the last gait cycle", fontsize="medium")
    axis.set_yscale("log")
    axis.legend(fontsize="small")
    figure.tight_layout()
    figure.savefig(out / "depth_sweep.png", dpi=110)
    plt.close(figure)
    lines = [
        "# uwml simulate: the paper's leg walking in sea water",
        "",
        "Simulated (MuJoCo with uwml's forces, added mass in the mass matrix): the paper's leg on a fixed",
        "stand follows our walking gait at 4 °C in sea water (1025 kg/m³) with the illustrative",
        "`JointLosses()` on every joint. The plant's inertias are assumed (uniform boxes of the links'",
        "sections, `uwml.paper.control_study`); the numbers compare controllers, they are not the paper's.",
        "",
        "| depth [m] | controller | RMS error per joint [°] | peak error per joint [°] | positive work per cycle [J] |",
        "|---|---|---|---|---|",
    ]
    for row in rows:
        rms = ", ".join(f"{x:.3f}" for x in np.degrees(_errors(row, "rms")))
        peak = ", ".join(f"{x:.3f}" for x in np.degrees(_errors(row, "peak")))
        lines.append(f"| {row['depth']:g} | {row['controller']} | {rms} | {peak} | {row['positive_work']:.1f} |")
    lines += [
        "",
        "Controllers: `land` PD + the rigid body's inverse dynamics; `hydro` + uwml's hydrodynamic",
        "feedforward; `hydro_losses` + the joint losses' feedforward; `*_wrong` as those with",
        "Cd and Cm 30 % too high.",
        "",
        f"![tracking error and torque at {depths[-1]:g} m](tracking.png)",
        "",
        "![worst joint RMS error against depth](depth_sweep.png)",
        "",
    ]
    if lossless:
        by_name = {r.controller: r for r in lossless}
        right, wrong = by_name["hydro"], by_name["hydro_wrong"]
        shallow = [row for row in rows if row["depth"] == depths[0]]
        with_losses = {row["controller"]: ", ".join(f"{x:.3f}" for x in np.degrees(_errors(row, "rms"))) for row in shallow}
        lines += [
            "## Why the wrong coefficients track better",
            "",
            (
                f"At {depths[0]:g} m the plant's joints have losses that `hydro` leaves out of its feedforward; "
                f"`hydro_wrong`'s 30 % too much drag stands in for part of them: RMS error per joint "
                f"{with_losses.get('hydro_wrong', '—')}° against `hydro`'s {with_losses.get('hydro', '—')}°."
            ),
            "On the same plant without joint losses, the right coefficients track better, as they should:",
            (
                f"`hydro` {np.degrees(max(right.rms_error())):.4f}° against `hydro_wrong`'s {np.degrees(max(wrong.rms_error())):.4f}° "
                f"({max(wrong.rms_error()) / max(right.rms_error()):.0f} times worse). With the losses in the feedforward"
            ),
            "(`hydro_losses`), the right coefficients track better too.",
            "",
        ]
    if fluid is not None:
        figure, axes = plt.subplots(3, 1, figsize=(8, 8), sharex=True)
        for joint in range(3):
            for name, style in (("uwml", "-"), ("box", "--"), ("ellipsoid", ":")):
                axes[joint].plot(fluid.time, getattr(fluid, name)[:, joint], style, label=name)
            axes[joint].set_ylabel(f"joint {joint + 1} [N·m]")
        axes[0].legend(fontsize=8)
        axes[2].set_xlabel("time [s]")
        figure.suptitle("Drag + added-mass torque on one gait cycle: uwml and MuJoCo's fluid models")
        figure.tight_layout()
        figure.savefig(out / "fluid_models.png", dpi=110)
        plt.close(figure)
        fluid_rms = fluid.rms()
        lines += [
            "## MuJoCo's fluid models on the same motion",
            "",
            "One cycle of the gait, prescribed; uwml's drag + added mass against MuJoCo's `qfrc_fluid`",
            "(inertia-box and ellipsoid models, same sea water, the links' boxes). MuJoCo's fluid models",
            "have no buoyancy, which here is "
            + ", ".join(f"{x:.1f}" for x in np.sqrt(np.mean(fluid.buoyancy**2, axis=0)))
            + " N·m RMS per joint, left out.",
            "",
            "| model | RMS torque per joint [N·m] | RMS difference from uwml / uwml's RMS |",
            "|---|---|---|",
        ]
        for name in ("uwml", "box", "ellipsoid"):
            difference = "—" if name == "uwml" else ", ".join(f"{100 * x:.0f} %" for x in fluid.relative_difference(name))
            lines.append(f"| {name} | {', '.join(f'{x:.2f}' for x in fluid_rms[name])} | {difference} |")
        lines += ["", "![uwml and MuJoCo's fluid models](fluid_models.png)", ""]
    if drifts:
        lines += [
            "## An arm on a free-floating ROV in a current",
            "",
            "The arm of `uwml.examples.arm_on_rov` (hull trimmed neutrally buoyant) moves its joints along sines",
            f"for {drifts[0].time[-1]:g} s in a {ROV_CURRENT:g} m/s current while a station-keeping PD (0.3 Hz) holds",
            "the vehicle, with and without the feedforward of uwml's predicted wrench on it.",
            "",
            "| station keeping | RMS drift [m] | max drift [m] | RMS attitude error [°] |",
            "|---|---|---|---|",
        ]
        for drift in drifts:
            row = drift.summary()
            lines.append(
                f"| {row['station_keeping']} | {row['rms_drift_m']:.4f} | {row['max_drift_m']:.4f} | {row['rms_attitude_deg']:.2f} |"
            )
        lines.append("")
    path = out / "report.md"
    path.write_text("\n".join(lines), encoding="utf-8")
    return path
