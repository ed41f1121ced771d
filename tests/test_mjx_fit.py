"""A free-floating vehicle's hull and trim by gradients through MJX (``uwml.sim.mjx_fit``;
docs/batched.md, "A fit by gradients through MJX"), in float64 on the CPU: pool trials of the
BlueROV2 example made by the CPU simulation (tests/test_identification_free_floating.py's
``record``: roll and pitch damping 0.5 and 1.2 N·m·s, the centre of buoyancy 5 mm up, the arm
waving) but 3 s long at 10 ms steps.

- The hull's entries and trim enter an MJX step as :class:`uwml.sim.mjx.Parameters` and act as the
  CPU simulation's hull with them (``with_parameters``): agreement to rounding.
- An MJX replay equals the CPU fit's replay (``uwml.sim.free_floating``) at the same parameters and
  start offsets, and its Jacobian from ``jax.jacfwd`` equals central differences of its values
  (the "gradients are exact" check).
- The fit gives the parameters back within 1 % from a noise-free trial (with a held-out one), the
  CPU fit's values and standard errors (its Jacobian by forward differences); with noise, the
  truth within 3 standard errors. One compilation of the replays serves every test.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
import uwml

jax = pytest.importorskip("jax")
pytest.importorskip("mujoco.mjx")
jax.config.update("jax_enable_x64", True)
import jax.numpy as jnp
from test_identification_free_floating import HYDRO, STEP, TRUE, URDF, noisy, record, write
from uwml.errors import UwmlError
from uwml.fit.vehicle_parameters import with_parameters
from uwml.robot.files import model_and_robot
from uwml.sim import mjx as umjx
from uwml.sim import mjx_fit
from uwml.sim.free_floating import _read_trial, _Replayer, vehicle_from_trials
from uwml.sim.mujoco import Simulation as CpuSimulation
from uwml.sim.prescribed import Trajectory
from uwml.sim.replay_inputs import MAX_GAP_S, SMOOTHING_S, START_WINDOW_S

NAMES = list(TRUE)
SECONDS = 3.0
SETTINGS = {"max_gap": MAX_GAP_S, "columns": None, "smoothing": SMOOTHING_S, "start_window": START_WINDOW_S}


@pytest.fixture(scope="module")
def sim() -> umjx.Simulation:
    return mjx_fit.replay_simulation(URDF, HYDRO, timestep=STEP)


@pytest.fixture(scope="module")
def trials(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """``clean0``, ``clean1`` noise-free; ``noisy0``, ``noisy1`` with 0.1° and 0.5 mm of noise."""
    folder = tmp_path_factory.mktemp("trials")
    for k in range(2):
        table = record(k, seconds=SECONDS)
        write(folder / f"clean{k}.csv", table)
        write(folder / f"noisy{k}.csv", noisy(table, 100 + k))
    return folder


def test_the_hull_parameters_act_in_an_mjx_step_as_in_the_cpu_simulation(sim: umjx.Simulation) -> None:
    """Every new field of the parameters at once (the hull's roll added mass, pitch damping, roll
    quadratic damping, its centre of buoyancy and volume): 0.5 s of the arm waving, the vehicle's
    pose and twist within 1e-9 of the CPU simulation with that hull, and far from the described one's."""
    model, robot = model_and_robot(URDF, HYDRO, True)
    assert robot.base is not None and robot.base.lumped is not None
    names, values = ["added_mass[3]", "linear_damping[4]", "quadratic_damping[3]", "cob_z", "volume"], [0.3, 2.0, 3.0, 0.02, 0.0115]
    hull = with_parameters(robot.base, names, values)
    lumped = hull.lumped
    assert lumped is not None
    defaults = sim.parameters()
    cob = np.array(defaults.cob)
    cob[0] = hull.cob
    volume = np.array(defaults.volume)
    volume[0] = hull.volume
    t = np.linspace(0.0, 0.6, 61)
    angles = np.stack([0.8 * np.sin(3.0 * t), 0.6 * np.sin(2.0 * t)], axis=1)
    motion = umjx.spline(t, angles)
    changed = sim.parameters(
        lumped_added_mass=np.asarray(lumped.added_mass)[None], lumped_linear_damping=np.asarray(lumped.linear_damping)[None],
        lumped_quadratic_damping=np.asarray(lumped.quadratic_damping)[None], cob=cob, volume=volume, motion=motion,
    )  # fmt: skip
    steps = 50

    @jax.jit
    def run(params: umjx.Parameters) -> jax.Array:
        last, _ = sim.rollout(params, sim.reset(params), jnp.zeros((steps, sim.action_size)), lambda s: s.data.time)
        return jnp.concatenate([last.data.qpos, last.data.qvel])

    cpu = CpuSimulation(model, uwml.Robot(robot.joints, robot.links, base=hull, losses=robot.losses, water=robot.water))
    cpu.model.opt.timestep = STEP
    cpu.prescribe(["shoulder", "elbow"], Trajectory(t, angles))
    for _ in range(steps):
        cpu.step()
    expected = np.concatenate([cpu.data.qpos, cpu.data.qvel])
    np.testing.assert_allclose(np.asarray(run(changed)), expected, rtol=0, atol=1e-9)
    described = np.asarray(run(changed._replace(**{f: getattr(defaults, f) for f in ("lumped_added_mass", "cob", "volume")})))
    assert np.max(np.abs(described - expected)) > 1e-3


def _replay(sim: umjx.Simulation, trial_path: Path, z: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The MJX replay of one trial and its Jacobian at ``z`` (the hull's values, then the start
    offsets), the fit's own compiled function: ``(2 n,)`` and ``(2 n, 3 + 8)``."""
    trial = _read_trial(trial_path, sim.robot, "the example", SETTINGS)
    (padded,), steps = mjx_fit._padded([trial], sim, SMOOTHING_S)
    values, jacobian = mjx_fit._compiled(sim, tuple(NAMES))(jnp.asarray(z), padded, steps)
    n = trial.time.size
    return np.asarray(values)[:n].ravel(), np.asarray(jacobian)[:n].reshape(2 * n, z.size)


#: The hull's values and start offsets a replay is checked at: the truth, the start turned by
#: 0.01 rad in roll and -0.02 in pitch, its twist moved.
AT = np.array([*TRUE.values(), 0.01, -0.02, 0.01, -0.02, 0.005, 0.02, -0.01, 0.03])


def test_an_mjx_replay_is_the_cpu_fits_replay(sim: umjx.Simulation, trials: Path) -> None:
    """The same trial replayed by the CPU fit (uwml.sim.mujoco, Euler) and in MJX, at the truth
    with start offsets: roll and pitch within 1e-9 rad (measured: 1.5e-15)."""
    model, robot = model_and_robot(URDF, HYDRO, True)
    assert robot.base is not None
    trial = _read_trial(trials / "clean0.csv", robot, "the example", SETTINGS)
    settings = SETTINGS | {"integrator": "euler", "options": {}, "timestep": STEP, "description": "the example"}
    parts = (robot.joints, robot.links, robot.base, robot.losses, robot.water)
    cpu = _Replayer(model, parts, [trial], NAMES, settings).angles(AT[:3], AT[3:], 0)
    values, _ = _replay(sim, trials / "clean0.csv", AT)
    assert values.shape == cpu.shape == (2 * round(SECONDS / STEP),)
    np.testing.assert_allclose(values, cpu, rtol=0, atol=1e-9)


def test_the_jacobian_is_exact(sim: umjx.Simulation, trials: Path) -> None:
    """Columns of the JAX Jacobian against central differences of the replay's values (steps of
    1e-5 of each value's size, or of 0.01 m and 0.01 rad for an offset): within 1e-6 of each
    column's largest entry (measured: 4e-10 to 5e-8 over all eleven columns, the differences'
    own error)."""
    _, jacobian = _replay(sim, trials / "clean0.csv", AT)
    assert np.all(np.isfinite(jacobian)) and np.max(np.abs(jacobian[:, 2])) > 1.0  # cob_z moves the attitude
    for column in (0, 1, 2, 3, 4, 8, 9):  # roll and pitch damping, cob_z, the start's roll and pitch, vz and wx
        h = 1e-5 * max(abs(AT[column]), 0.01)
        step = np.zeros(AT.size)
        step[column] = h
        difference = (_replay(sim, trials / "clean0.csv", AT + step)[0] - _replay(sim, trials / "clean0.csv", AT - step)[0]) / (2 * h)
        size = np.max(np.abs(jacobian[:, column]))
        assert size > 0.0 and np.max(np.abs(difference - jacobian[:, column])) < 1e-6 * size, column


def test_a_noise_free_trial_gives_the_parameters_back(sim: umjx.Simulation, trials: Path) -> None:
    """One trial fitted from the description's values, one held out: each parameter within 1 %
    (measured: within 0.06 %), the CPU fit's values to 1e-6 and its standard errors to 1e-3
    (measured: 1e-9 and 1e-5; its Jacobian by forward differences, 134 replays against 13); the
    held-out trial's RMS far below the description's (0.05 to 6e-4 rad)."""
    result = mjx_fit.vehicle_by_gradients(trials / "clean0.csv", sim, parameters=NAMES, test=trials / "clean1.csv")
    assert result.success and result.errorbars and result.var_names == tuple(NAMES)
    for name, value in TRUE.items():
        assert result.params[name] == pytest.approx(value, rel=0.01), name
    assert result.init_values == {"linear_damping[3]": 0.0, "linear_damping[4]": 0.8, "cob_z": 0.0}
    assert result.nvarys == 3 + 8 and result.ndata == 2 * 300 and result.jacobian == mjx_fit.JACOBIAN
    assert result.rms("train") < 1e-5 and result.rms("train", fitted=False) > 0.01
    assert result.rms("test") < 0.05 * result.rms("test", fitted=False)
    report = result.fit_report()
    assert "euler (MJX), timestep 0.01 s; Jacobian by forward-mode derivatives through uwml.sim.mjx" in report
    assert result.summary()["jacobian"] == mjx_fit.JACOBIAN
    cpu = vehicle_from_trials(trials / "clean0.csv", URDF, HYDRO, parameters=NAMES, test=trials / "clean1.csv", timestep=STEP)
    for name in NAMES:
        assert result.params[name] == pytest.approx(cpu.params[name], rel=1e-6), name
        assert result.stderr[name] == pytest.approx(cpu.stderr[name], rel=1e-3), name
    assert result.nfev < cpu.nfev  # the Jacobian's columns are not replays


def test_noisy_trials_give_the_parameters_within_their_error_bars(sim: umjx.Simulation, trials: Path) -> None:
    """0.1° and 0.5 mm of noise on every pose, two trials: each parameter within 3 standard
    errors (measured: within 1.2), each error positive and below 5 % of the value; the
    residual's scale the noise's."""
    result = mjx_fit.vehicle_by_gradients([trials / "noisy0.csv", trials / "noisy1.csv"], sim, parameters=NAMES)
    for name, value in TRUE.items():
        error = result.stderr[name]
        assert error is not None and 0.0 < error < 0.05 * abs(value), (name, error)
        assert abs(result.params[name] - value) < 3.0 * error, (name, result.params[name], error)
    assert np.sqrt(result.redchi) == pytest.approx(np.radians(0.1), rel=0.2)


def test_refusals(sim: umjx.Simulation, trials: Path, tmp_path: Path) -> None:
    with pytest.raises(ValueError, match=r"unknown parameter 'roll_damping': choose from added_mass\[0\]"):
        mjx_fit.vehicle_by_gradients(trials / "clean0.csv", sim, parameters=["roll_damping"])
    with pytest.raises(ValueError, match="hydro, timestep and simulation options are the simulation's own"):
        mjx_fit.vehicle_by_gradients(trials / "clean0.csv", sim, timestep=0.02, parameters=NAMES)
    with pytest.raises(ValueError, match="every joint prescribed: make it with uwml.sim.mjx_fit.replay_simulation"):
        mjx_fit.vehicle_by_gradients(trials / "clean0.csv", umjx.Simulation.from_file(URDF, HYDRO), parameters=NAMES)
    with pytest.raises(ValueError, match=r"arm\.urdf: the base has no lumped model"):
        mjx_fit.replay_simulation(Path(__file__).parent / "data/arm.urdf", Path(__file__).parent / "data/arm.hydro.toml")
    with pytest.raises(ValueError, match="timestep must be at most 0.1 s"):
        mjx_fit.replay_simulation(URDF, HYDRO, timestep=0.2)
    table = record(0, seconds=0.5)
    commanded = write(tmp_path / "commanded.csv", np.column_stack([table, np.zeros((len(table), 8))]),
                      "time,q1,q2,x,y,z,qw,qx,qy,qz," + ",".join(f"u{k}" for k in range(1, 9)))  # fmt: skip
    with pytest.raises(UwmlError, match=r"commanded\.csv: the trial has thruster commands; a fit by gradients"):
        mjx_fit.vehicle_by_gradients(commanded, sim, parameters=NAMES)
    jax.config.update("jax_enable_x64", False)
    try:
        with pytest.raises(ValueError, match=r"replays in float64: call jax.config.update\(\"jax_enable_x64\", True\)"):
            mjx_fit.replay_simulation(URDF, HYDRO)
    finally:
        jax.config.update("jax_enable_x64", True)
