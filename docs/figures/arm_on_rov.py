"""The figure of docs/model.md section 10: what the water does to the 7-joint arm of
``uwml.examples.arm_on_rov`` and, through it, to the vehicle, while the arm swings through a
reach and the ROV surges at 0.5 m/s with a slow pitch oscillation in a 0.3 m/s cross current.

Run: ``python docs/figures/arm_on_rov.py`` (writes ``docs/figures/arm_on_rov.png``).
"""

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np
import uwml
from uwml.examples import arm_on_rov


def main() -> None:
    arm = arm_on_rov()
    t = np.linspace(0.0, 10.0, 2001)
    # A reach: shoulder yaw and pitch, elbow, wrist, smooth (one period of 10 s).
    phase = 2 * np.pi * t / 10.0
    amplitude = np.array([0.8, 0.6, -1.0, 0.5, 0.6, 0.8, 0.05])
    offset = np.array([0.0, 0.3, -0.6, 0.0, 0.2, 0.0, 0.05])
    q = offset + amplitude * np.sin(phase)[:, None]
    qd = amplitude * (2 * np.pi / 10.0) * np.cos(phase)[:, None]
    qdd = -amplitude * (2 * np.pi / 10.0) ** 2 * np.sin(phase)[:, None]
    pitch = 0.08 * np.sin(2 * np.pi * t / 4.0)
    pitch_rate = 0.08 * (2 * np.pi / 4.0) * np.cos(2 * np.pi * t / 4.0)
    pitch_acceleration = -0.08 * (2 * np.pi / 4.0) ** 2 * np.sin(2 * np.pi * t / 4.0)
    zeros = np.zeros_like(t)
    motion = uwml.BaseMotion(
        orientation=np.stack([np.cos(pitch / 2), zeros, np.sin(pitch / 2), zeros], axis=1),
        velocity=np.stack([0.5 + zeros, zeros, zeros], axis=1),
        angular_velocity=np.stack([zeros, pitch_rate, zeros], axis=1),
        angular_acceleration=np.stack([zeros, pitch_acceleration, zeros], axis=1),
    )
    water = uwml.Water(density=1025.0)
    result = arm.hydro(q, qd, qdd, water=water, base_motion=motion, current=(0.0, 0.3, 0.0))
    still = arm.hydro(q, qd, qdd, water=water)

    fig, axes = plt.subplots(3, 1, figsize=(8, 8), sharex=True)
    base = result.base
    axes[0].plot(t, base.drag[:, 0], label="drag, surge force $F_x$ (cross-flow only: the hull's axial drag is not modelled)")
    axes[0].plot(t, base.drag[:, 1], label="drag, sway force $F_y$ (cross current)")
    axes[0].plot(t, base.added_mass[:, 0], label="added mass, $F_x$")
    axes[0].set_ylabel("force on the vehicle [N]")
    axes[0].legend(fontsize=8)
    axes[0].set_title("7-joint arm on an ROV surging at 0.5 m/s in a 0.3 m/s cross current (sea water)")
    axes[1].plot(t, (base.drag + base.added_mass)[:, 4], label="drag + added mass")
    axes[1].plot(t, (base.buoyancy + base.gravity)[:, 4], "--", label="buoyancy + weight (arm reaching, hull pitching)")
    axes[1].set_ylabel("pitch moment $M_y$ on\nthe vehicle [N·m]")
    axes[1].legend(fontsize=8)
    for j, name in ((0, "shoulder yaw"), (1, "shoulder pitch"), (2, "elbow")):
        line = axes[2].plot(t, result.drag[:, j] + result.added_mass[:, j], label=f"{name}: moving ROV, current")[0]
        axes[2].plot(t, still.drag[:, j] + still.added_mass[:, j], ":", color=line.get_color(), label=f"{name}: fixed base, still water")
    axes[2].set_ylabel("drag + added mass\non the joint [N·m]")
    axes[2].set_xlabel("time [s]")
    axes[2].legend(fontsize=7, ncol=2)
    fig.tight_layout()
    out = Path(__file__).with_suffix(".png")
    fig.savefig(out, dpi=110)
    print(f"wrote {out}")


if __name__ == "__main__":
    main()
