//! `uwml._core.MujocoCoupling`: what `uwml.mujoco.Simulation` does between MuJoCo's `mj_makeM`
//! and `mj_factorM`, in one native call per step. It reads the state from the `MjData`'s own
//! arrays (numpy views kept from the start), evaluates the robot's environment (hydrodynamics
//! and joint losses) at zero MuJoCo acceleration and the added-mass matrix `M_A`, maps both to
//! MuJoCo's degrees of freedom, adds `M_A` into MuJoCo's sparse inertia and writes the forces
//! into `qfrc_applied`. The Python class keeps every check and the map's construction; this is
//! only the per-step arithmetic, so that a step costs about the evaluation and `M_A`.

use numpy::{PyArray1, PyArrayDyn, PyArrayMethods, PyReadonlyArray2, PyUntypedArrayMethods};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use uwml_core::nalgebra::{Matrix3, Vector3};
use uwml_core::{
    BaseMotion, Conditions, Current, LossState, Water, robot_added_mass_matrix, robot_hydro,
    robot_joint_added_mass_matrix,
};

use super::inputs::StateRow;
use super::rk4::Rk4;
use super::{Data, MAX_ROBOT_JOINTS, PyRobot, added_mass_form};
use crate::parse_losses;
use crate::single::fill_values;

/// The `MjData` arrays the coupling reads and writes (kept for the coupling's life).
struct Views {
    qpos: Py<PyArrayDyn<f64>>,
    qvel: Py<PyArrayDyn<f64>>,
    qacc: Py<PyArrayDyn<f64>>,
    xquat: Py<PyArrayDyn<f64>>,
    xmat: Py<PyArrayDyn<f64>>,
    mass_matrix: Py<PyArrayDyn<f64>>,
    qfrc_applied: Py<PyArrayDyn<f64>>,
    /// The `MjModel`'s `dof_damping` and `dof_frictionloss`: the joint losses go there.
    dof_damping: Py<PyArrayDyn<f64>>,
    dof_frictionloss: Py<PyArrayDyn<f64>>,
}

/// Where uwml's coordinates `(ν, q̇)` sit among MuJoCo's degrees of freedom.
struct DofMap {
    /// For each MuJoCo degree of freedom, its uwml coordinate (0-5 the base, 6 + i joint i).
    uwml_of_dof: Vec<Option<usize>>,
    /// The joints' entries of `qpos`.
    joint_qpos: Vec<usize>,
    /// The joints' degrees of freedom.
    joint_dofs: Vec<usize>,
    /// The free joint's first degree of freedom (a floating base).
    free_dof: Option<usize>,
    /// The root body (its `xquat` and `xmat` rows), or `None` when the base is the world frame.
    root: Option<usize>,
    /// `(row, column)` degrees of freedom of each entry of MuJoCo's sparse inertia `data.M`.
    mass_pairs: Vec<(usize, usize)>,
}

/// The per-step coupling of a robot to MuJoCo (see the module documentation).
#[pyclass(module = "uwml._core", name = "MujocoCoupling")]
pub(crate) struct MujocoCoupling {
    robot: Py<PyRobot>,
    views: Views,
    map: DofMap,
    data: Box<Data>,
    losses: [Option<LossState<f64>>; MAX_ROBOT_JOINTS],
    /// The model's own `dof_damping` and `dof_frictionloss` of each joint, which the losses add to.
    own_damping: Vec<f64>,
    own_frictionloss: Vec<f64>,
    water: Water<f64>,
    current: Current<f64>,
    kirchhoff: bool,
    /// `(ν̇, q̈)` of the previous step, subtracted through `M_A` (the lagged scheme), if any.
    lagged: Option<Vec<f64>>,
    /// `M_A` over uwml's coordinates, `(6 + n)²`; on a fixed base only its joint block is
    /// evaluated (into `joint_added_mass`, `n²`) and the base's rows and columns stay zero.
    added_mass: Vec<f64>,
    joint_added_mass: Vec<f64>,
    /// The Runge-Kutta step under way (`integrator="rk4"`), made on its first use.
    rk4: Option<Rk4>,
}

/// `array`'s values, C-contiguous, with at least `n` of them.
fn values<'a>(array: &'a numpy::PyReadonlyArrayDyn<'_, f64>, name: &str, n: usize) -> PyResult<&'a [f64]> {
    let slice = array
        .as_slice()
        .map_err(|_| PyValueError::new_err(format!("data.{name} must be a C-contiguous float64 array")))?;
    if slice.len() < n {
        return Err(PyValueError::new_err(format!("data.{name} must have at least {n} entries, got {}", slice.len())));
    }
    Ok(slice)
}

#[pymethods]
impl MujocoCoupling {
    /// The coupling of `robot` to one `MjData`'s arrays (checked here; the Python caller builds
    /// the map). `mass_pairs`: `(nM, 2)` degrees of freedom of each entry of `data.M`;
    /// `losses`: a `Losses` of `N` joints or None, evaluated at the pressure of `depth` in
    /// water of `sea_density` and at `temperature`.
    #[new]
    #[allow(clippy::too_many_arguments)]
    #[pyo3(signature = (robot, qpos, qvel, qacc, xquat, xmat, mass_matrix, qfrc_applied, dof_damping, dof_frictionloss, root, joint_qpos, joint_dofs, free_dof, mass_pairs, losses, depth, temperature, density, gravity, sea_density, current, current_acceleration, kirchhoff, lagged))]
    fn new(
        robot: Bound<'_, PyRobot>,
        qpos: Bound<'_, PyArrayDyn<f64>>,
        qvel: Bound<'_, PyArrayDyn<f64>>,
        qacc: Bound<'_, PyArrayDyn<f64>>,
        xquat: Bound<'_, PyArrayDyn<f64>>,
        xmat: Bound<'_, PyArrayDyn<f64>>,
        mass_matrix: Bound<'_, PyArrayDyn<f64>>,
        qfrc_applied: Bound<'_, PyArrayDyn<f64>>,
        dof_damping: Bound<'_, PyArrayDyn<f64>>,
        dof_frictionloss: Bound<'_, PyArrayDyn<f64>>,
        root: Option<usize>,
        joint_qpos: Vec<usize>,
        joint_dofs: Vec<usize>,
        free_dof: Option<usize>,
        mass_pairs: PyReadonlyArray2<'_, i64>,
        losses: Option<PyRef<'_, crate::PyLosses>>,
        depth: f64,
        temperature: f64,
        density: f64,
        gravity: f64,
        sea_density: f64,
        current: [f64; 3],
        current_acceleration: [f64; 3],
        kirchhoff: bool,
        lagged: bool,
    ) -> PyResult<Self> {
        let n = robot.get().robot.joint_count();
        if joint_qpos.len() != n || joint_dofs.len() != n {
            return Err(PyValueError::new_err(format!("the map must give {n} joints' qpos and dof entries")));
        }
        let nv = qvel.len();
        let nq = qpos.len();
        if qacc.len() != nv || qfrc_applied.len() != nv || dof_damping.len() != nv || dof_frictionloss.len() != nv {
            return Err(PyValueError::new_err(
                "data.qacc, data.qfrc_applied, model.dof_damping and model.dof_frictionloss must have nv entries, as data.qvel",
            ));
        }
        let bodies = xquat.len() / 4;
        if xmat.len() != 9 * bodies || root.is_some_and(|r| r >= bodies) {
            return Err(PyValueError::new_err("data.xquat and data.xmat must hold the root body"));
        }
        let mut uwml_of_dof = vec![None; nv];
        if let Some(free) = free_dof {
            for k in 0..6 {
                *uwml_of_dof.get_mut(free + k).ok_or_else(|| PyValueError::new_err("free joint outside qvel"))? =
                    Some(k);
            }
        }
        for (i, (&dof, &position)) in joint_dofs.iter().zip(&joint_qpos).enumerate() {
            let slot = uwml_of_dof.get_mut(dof).filter(|_| position < nq);
            *slot.ok_or_else(|| PyValueError::new_err(format!("joint {i} outside qpos or qvel")))? = Some(6 + i);
        }
        let pairs = mass_pairs.as_array();
        if pairs.ncols() != 2 || pairs.nrows() != mass_matrix.len() {
            return Err(PyValueError::new_err("mass_pairs must have shape (nM, 2), one row per entry of data.M"));
        }
        let mut mass_entries = Vec::with_capacity(pairs.nrows());
        for row in pairs.rows() {
            let dof = |k: usize| row.get(k).and_then(|&d| usize::try_from(d).ok()).filter(|&d| d < nv);
            match (dof(0), dof(1)) {
                (Some(r), Some(c)) => mass_entries.push((r, c)),
                _ => return Err(PyValueError::new_err("mass_pairs must name degrees of freedom in 0..nv")),
            }
        }
        let water = crate::water(density, gravity)?;
        let current =
            Current::new(Vector3::from(current), Vector3::from(current_acceleration)).map_err(crate::model_error)?;
        if !(depth.is_finite()
            && depth >= 0.0
            && temperature.is_finite()
            && sea_density.is_finite()
            && sea_density > 0.0)
        {
            return Err(PyValueError::new_err("depth (>= 0), temperature and sea_density (> 0) must be finite"));
        }
        let mut states = [None; MAX_ROBOT_JOINTS];
        if let Some(compiled) = &losses {
            let pressure = sea_density * water.gravity() * depth;
            for (slot, joint) in states.iter_mut().zip(parse_losses(compiled, n)?) {
                *slot = joint.map(|l| l.at(pressure, temperature)).transpose().map_err(crate::model_error)?;
            }
        }
        let own = |array: &Bound<'_, PyArrayDyn<f64>>, name: &str| -> PyResult<Vec<f64>> {
            let array = array.try_readonly()?;
            let all = values(&array, name, nv)?;
            Ok(joint_dofs.iter().map(|&d| all.get(d).copied().unwrap_or(0.0)).collect())
        };
        let (own_damping, own_frictionloss) =
            (own(&dof_damping, "dof_damping")?, own(&dof_frictionloss, "dof_frictionloss")?);
        let size = 6 + n;
        Ok(Self {
            robot: robot.unbind(),
            views: Views {
                qpos: qpos.unbind(),
                qvel: qvel.unbind(),
                qacc: qacc.unbind(),
                xquat: xquat.unbind(),
                xmat: xmat.unbind(),
                mass_matrix: mass_matrix.unbind(),
                qfrc_applied: qfrc_applied.unbind(),
                dof_damping: dof_damping.unbind(),
                dof_frictionloss: dof_frictionloss.unbind(),
            },
            map: DofMap { uwml_of_dof, joint_qpos, joint_dofs, free_dof, root, mass_pairs: mass_entries },
            data: Box::new(Data::new()),
            losses: states,
            own_damping,
            own_frictionloss,
            water,
            current,
            kirchhoff,
            lagged: lagged.then(|| vec![0.0; size]),
            added_mass: vec![0.0; size * size],
            joint_added_mass: vec![0.0; n * n],
            rk4: None,
        })
    }

    /// One step's coupling, after `mj_makeM`: `M_A` added into `data.M` (unless lagged), the
    /// environment's forces (plus `torque` on the joints, if given) written to
    /// `data.qfrc_applied`. Returns 0 when done, 1 when the state (`qpos`, `qvel`) is not finite
    /// (nothing written), 2 when `torque` is not a list, tuple or float64 array of N finite
    /// numbers (nothing written: the caller converts or refuses it).
    #[pyo3(signature = (torque=None))]
    fn apply(&mut self, py: Python<'_>, torque: Option<&Bound<'_, PyAny>>) -> PyResult<u8> {
        let robot = self.robot.get();
        let n = robot.robot.joint_count();
        let size = 6 + n;
        let mut motor = [0.0; MAX_ROBOT_JOINTS];
        if let Some(torque) = torque
            && fill_values(torque, motor.get_mut(..n).unwrap_or_default()).is_none()
        {
            return Ok(2);
        }
        let (row, motion) = {
            let qpos = self.views.qpos.bind(py).try_readonly()?;
            let qvel = self.views.qvel.bind(py).try_readonly()?;
            let (qpos, qvel) = (values(&qpos, "qpos", 0)?, values(&qvel, "qvel", 0)?);
            if !(qpos.iter().all(|x| x.is_finite()) && qvel.iter().all(|x| x.is_finite())) {
                return Ok(1);
            }
            let mut row = StateRow::new();
            for (i, (&p, &d)) in self.map.joint_qpos.iter().zip(&self.map.joint_dofs).enumerate() {
                if let (Some(q), Some(qd), Some(&x), Some(&v)) =
                    (row.q.get_mut(i), row.qd.get_mut(i), qpos.get(p), qvel.get(d))
                {
                    (*q, *qd) = (x, v);
                }
            }
            (row, self.base_motion(py, qvel)?)
        };
        if self.map.free_dof.is_some() {
            robot_added_mass_matrix(&robot.robot, &self.water, None, &row.q, &mut self.added_mass);
        } else {
            // A fixed base: ν̇ = 0 and the base has no degree of freedom in MuJoCo, so only the
            // joints' block of M_A acts.
            robot_joint_added_mass_matrix(&robot.robot, &self.water, None, &row.q, &mut self.joint_added_mass);
            for (i, block_row) in self.joint_added_mass.chunks(n.max(1)).enumerate().take(n) {
                let start = (6 + i) * size + 6;
                if let Some(slots) = self.added_mass.get_mut(start..start + n) {
                    slots.copy_from_slice(block_row);
                }
            }
        }
        let form = added_mass_form(self.kirchhoff);
        let conditions =
            Conditions { water: self.water, motion, current: self.current, coefficients: None, form, losses: None };
        robot_hydro(&robot.robot, &conditions, [&row.q, &row.qd, &row.qdd], &mut self.data);
        // uwml's generalized forces: the base wrench's hydrodynamic part, then the joints'
        // hydrodynamics and motor torques. The joint losses are MuJoCo's: the seal's dry
        // friction a friction constraint, the smooth rest a damping (`write_losses`).
        let mut forces = [0.0; 6 + MAX_ROBOT_JOINTS];
        for (slot, value) in forces.iter_mut().zip(self.data.base_wrench().total().to_array()) {
            *slot = value;
        }
        for (i, joint) in self.data.joint_forces().iter().enumerate() {
            if let (Some(slot), Some(m)) = (forces.get_mut(6 + i), motor.get(i)) {
                *slot = joint.total() + m;
            }
        }
        self.write_losses(py, &row.qd)?;
        if let Some(previous) = &self.lagged {
            for (r, slot) in forces.iter_mut().take(size).enumerate() {
                let row = self.added_mass.get(r * size..(r + 1) * size).unwrap_or_default();
                *slot -= row.iter().zip(previous).map(|(m, a)| m * a).sum::<f64>();
            }
        }
        // MuJoCo's coordinates: the free joint's linear velocity is world-frame, uwml's ν base
        // frame, so its rows and columns turn by R (MuJoCo's = T · uwml's, T = diag(R, I, I)).
        let rotation = self.rotation(py)?;
        if self.map.free_dof.is_some() {
            turn_rows(&rotation, &mut forces, 1);
            turn_rows(&rotation, &mut self.added_mass, size);
            turn_columns(&rotation, &mut self.added_mass, size);
        }
        let mut qfrc = self.views.qfrc_applied.bind(py).try_readwrite()?;
        let qfrc = qfrc.as_slice_mut().map_err(|_| PyValueError::new_err("data.qfrc_applied must be contiguous"))?;
        for (slot, u) in qfrc.iter_mut().zip(&self.map.uwml_of_dof) {
            *slot = u.and_then(|u| forces.get(u)).copied().unwrap_or(0.0);
        }
        if self.lagged.is_none() {
            let mut mass = self.views.mass_matrix.bind(py).try_readwrite()?;
            let mass = mass.as_slice_mut().map_err(|_| PyValueError::new_err("data.M must be contiguous"))?;
            for (slot, &(r, c)) in mass.iter_mut().zip(&self.map.mass_pairs) {
                let (ur, uc) =
                    (self.map.uwml_of_dof.get(r).copied().flatten(), self.map.uwml_of_dof.get(c).copied().flatten());
                if let (Some(ur), Some(uc)) = (ur, uc) {
                    *slot += self.added_mass.get(ur * size + uc).copied().unwrap_or(0.0);
                }
            }
        }
        Ok(0)
    }

    /// A Runge-Kutta step begins at the data's `qpos` and `qvel` (see `Rk4`).
    fn rk4_begin(&mut self, py: Python<'_>) -> PyResult<()> {
        let (qpos, qvel) = (self.views.qpos.bind(py), self.views.qvel.bind(py));
        let nv = qvel.len();
        self.rk4.get_or_insert_with(|| Rk4::new(py, nv)).begin(qpos, qvel)
    }

    /// Stage `stage` (0-3), `offset` (its fraction of the step times the step) into the step:
    /// `data.qpos` back to the start, `data.qvel` the stage's velocity; the previous stage's
    /// velocity (None at stage 0), for `mj_integratePos` over `offset`.
    fn rk4_stage<'py>(
        &mut self,
        py: Python<'py>,
        stage: usize,
        offset: f64,
    ) -> PyResult<Option<Bound<'py, PyArray1<f64>>>> {
        let (qpos, qvel) = (self.views.qpos.bind(py), self.views.qvel.bind(py));
        match self.rk4.as_mut() {
            Some(rk4) => rk4.stage(py, stage, offset, qpos, qvel),
            None => Err(PyValueError::new_err("rk4_begin must come first")),
        }
    }

    /// Keeps stage `stage`'s acceleration (`data.qacc` after its forward pass).
    fn rk4_keep(&mut self, py: Python<'_>, stage: usize) -> PyResult<()> {
        let qacc = self.views.qacc.bind(py);
        match self.rk4.as_mut() {
            Some(rk4) => rk4.keep(stage, qacc),
            None => Err(PyValueError::new_err("rk4_begin must come first")),
        }
    }

    /// The step's end: `data.qpos` back to the start, `data.qvel` the step's; the weighted
    /// velocity, for `mj_integratePos` over `h`.
    fn rk4_finish<'py>(&mut self, py: Python<'py>, h: f64) -> PyResult<Bound<'py, PyArray1<f64>>> {
        let (qpos, qvel) = (self.views.qpos.bind(py), self.views.qvel.bind(py));
        match self.rk4.as_mut() {
            Some(rk4) => rk4.finish(py, h, qpos, qvel),
            None => Err(PyValueError::new_err("rk4_begin must come first")),
        }
    }

    /// For the lagged scheme: keep `(ν̇, q̈)` of the step just computed (`data.qacc` in uwml's
    /// coordinates, with `ν̇ = Rᵀ v̇_world − ω × v`), to subtract `M_A` times it next step.
    fn remember_acceleration(&mut self, py: Python<'_>) -> PyResult<()> {
        let rotation = self.rotation(py)?;
        let qacc = self.views.qacc.bind(py).try_readonly()?;
        let qvel = self.views.qvel.bind(py).try_readonly()?;
        let (qacc, qvel) = (values(&qacc, "qacc", 0)?, values(&qvel, "qvel", 0)?);
        let motion = self.base_motion(py, qvel)?;
        let Some(previous) = self.lagged.as_mut() else { return Ok(()) };
        previous.fill(0.0);
        for (d, u) in self.map.uwml_of_dof.iter().enumerate() {
            if let (Some(u), Some(&a)) = (u, qacc.get(d))
                && let Some(slot) = previous.get_mut(*u)
            {
                *slot = a;
            }
        }
        if self.map.free_dof.is_some() {
            let at = |k: usize| previous.get(k).copied().unwrap_or(0.0);
            let linear = rotation.transpose() * Vector3::new(at(0), at(1), at(2)) + motion.twist_derivative().0;
            for (slot, value) in previous.iter_mut().zip(linear.iter()) {
                *slot = *value;
            }
        }
        Ok(())
    }
}

impl MujocoCoupling {
    /// The joint losses at joint speeds `qd` into the model, for MuJoCo to solve: each joint's
    /// `dof_frictionloss` is its own plus the seal's dry-friction level, its `dof_damping` its own
    /// plus the secant damping of the oil drag and the seal's viscous term
    /// (`LossState::dry_friction_split`). MuJoCo solves the friction as a constraint (it sticks
    /// at rest, stably at any step) and its Euler integrator the damping implicitly.
    fn write_losses(&self, py: Python<'_>, qd: &[f64]) -> PyResult<()> {
        if self.losses.iter().all(Option::is_none) {
            return Ok(());
        }
        let mut damping = self.views.dof_damping.bind(py).try_readwrite()?;
        let damping =
            damping.as_slice_mut().map_err(|_| PyValueError::new_err("model.dof_damping must be contiguous"))?;
        let mut friction = self.views.dof_frictionloss.bind(py).try_readwrite()?;
        let friction =
            friction.as_slice_mut().map_err(|_| PyValueError::new_err("model.dof_frictionloss must be contiguous"))?;
        let joints =
            self.map.joint_dofs.iter().zip(&self.losses).zip(self.own_damping.iter().zip(&self.own_frictionloss));
        for (i, ((&dof, state), (&own_damping, &own_friction))) in joints.enumerate() {
            let Some(state) = state else { continue };
            let split = state.dry_friction_split(qd.get(i).copied().unwrap_or(0.0));
            if let (Some(d), Some(f)) = (damping.get_mut(dof), friction.get_mut(dof)) {
                (*d, *f) = (own_damping + split.damping, own_friction + split.friction);
            }
        }
        Ok(())
    }

    /// World from base: the root body's `xmat` (identity when the base is the world frame).
    fn rotation(&self, py: Python<'_>) -> PyResult<Matrix3<f64>> {
        let Some(root) = self.map.root else { return Ok(Matrix3::identity()) };
        let xmat = self.views.xmat.bind(py).try_readonly()?;
        let m = values(&xmat, "xmat", 9 * (root + 1))?.get(9 * root..9 * root + 9).unwrap_or_default();
        Ok(Matrix3::from_row_slice(m))
    }

    /// The base's motion for uwml: the root's orientation; on a free joint `v = Rᵀ v_world`,
    /// `ω` (MuJoCo's is body-frame already) and `ν̇ = −ω × v`, what zero MuJoCo acceleration means.
    fn base_motion(&self, py: Python<'_>, qvel: &[f64]) -> PyResult<BaseMotion<f64>> {
        let Some(root) = self.map.root else { return Ok(BaseMotion::fixed()) };
        let xquat = self.views.xquat.bind(py).try_readonly()?;
        let quaternion = values(&xquat, "xquat", 4 * (root + 1))?.get(4 * root..4 * root + 4).unwrap_or_default();
        let orientation = [0, 1, 2, 3].map(|k| quaternion.get(k).copied().unwrap_or(f64::NAN));
        let zero = Vector3::zeros();
        let (v, w) = match self.map.free_dof {
            Some(free) => {
                let at = |k: usize| qvel.get(free + k).copied().unwrap_or(f64::NAN);
                let rotation = self.rotation(py)?;
                (rotation.transpose() * Vector3::new(at(0), at(1), at(2)), Vector3::new(at(3), at(4), at(5)))
            }
            None => (zero, zero),
        };
        BaseMotion::new(orientation, v, w, -w.cross(&v), zero).map_err(crate::model_error)
    }
}

/// Rows 0-2 of the `width`-column row-major `matrix` become `R` times themselves.
fn turn_rows(rotation: &Matrix3<f64>, matrix: &mut [f64], width: usize) {
    for c in 0..width {
        let at = |r: usize| matrix.get(r * width + c).copied().unwrap_or(0.0);
        let turned = rotation * Vector3::new(at(0), at(1), at(2));
        for (r, value) in turned.iter().enumerate() {
            if let Some(slot) = matrix.get_mut(r * width + c) {
                *slot = *value;
            }
        }
    }
}

/// Columns 0-2 of the square row-major `matrix` (side `size`) become themselves times `Rᵀ`.
fn turn_columns(rotation: &Matrix3<f64>, matrix: &mut [f64], size: usize) {
    for row in matrix.chunks_exact_mut(size) {
        let at = |c: usize| row.get(c).copied().unwrap_or(0.0);
        let turned = rotation * Vector3::new(at(0), at(1), at(2));
        for (slot, value) in row.iter_mut().zip(turned.iter()) {
            *slot = *value;
        }
    }
}
