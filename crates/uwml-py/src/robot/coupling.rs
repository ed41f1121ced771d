//! `uwml._core.MujocoCoupling`: what `uwml.mujoco.Simulation` does after MuJoCo's position stage
//! and before the mass matrix is factored again, in one native call per step (and the joint
//! losses, written before the position stage). It reads the state from the `MjData`'s own
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
    AddedMassForm, BaseMotion, Conditions, Current, LossState, Water, robot_added_mass_matrix, robot_hydro,
    robot_joint_added_mass_matrix,
};

use super::conditions::{LossStates, PyConditions};
use super::inputs::StateRow;
use super::prescribed::{OUTSIDE, Pieces, PrescribedMotion};
use super::rk4::Rk4;
use super::view::View;
use super::{Coefficients, Data, MAX_ROBOT_JOINTS, PyRobot};
use crate::single::fill_values;

/// The `MjData` arrays the coupling reads and writes (kept for the coupling's life).
struct Views {
    qpos: View,
    qvel: View,
    qacc: View,
    xquat: View,
    xmat: View,
    mass_matrix: View,
    qfrc_applied: View,
    /// The `MjModel`'s `dof_damping` and `dof_frictionloss`: the joint losses go there.
    dof_damping: View,
    dof_frictionloss: View,
    /// The `MjModel`'s `opt.gravity`, read each step: uwml's buoyancy is for the gravity the
    /// coupling was made with, so a change is reported (`apply`), not followed by the weight alone.
    gravity: View,
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
    /// `opt.gravity` when the coupling was made.
    gravity: [f64; 3],
    current: Current<f64>,
    form: AddedMassForm,
    /// The conditions' coefficients (None: the segments' own).
    coefficients: Option<Box<Coefficients>>,
    /// `(ν̇, q̈)` of the previous step, subtracted through `M_A` (the lagged scheme), if any.
    lagged: Option<Vec<f64>>,
    /// `M_A` over uwml's coordinates, `(6 + n)²`; on a fixed base only its joint block is
    /// evaluated (into `joint_added_mass`, `n²`) and the base's rows and columns stay zero.
    added_mass: Vec<f64>,
    joint_added_mass: Vec<f64>,
    /// The Runge-Kutta step under way (`integrator="rk4"`), made on its first use.
    rk4: Option<Rk4>,
    /// `qpos` and `qvel` as last read, and any other array's numbers (kept to copy into without
    /// allocating).
    qpos: Vec<f64>,
    qvel: Vec<f64>,
    scratch: Vec<f64>,
    scratch2: Vec<f64>,
    /// The prescribed joints and their motion, if any (`prescribe`).
    prescribed: Option<PrescribedMotion>,
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
    /// `conditions`: the simulation's (made for `robot`, one value of each for every step: the
    /// water, the coefficients, the added-mass form, the current, and the joint losses at their
    /// depth and temperature); the base's motion is MuJoCo's.
    #[new]
    #[allow(clippy::too_many_arguments)]
    #[pyo3(signature = (robot, qpos, qvel, qacc, xquat, xmat, mass_matrix, qfrc_applied, dof_damping, dof_frictionloss, model_gravity, root, joint_qpos, joint_dofs, free_dof, mass_pairs, conditions, lagged))]
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
        model_gravity: Bound<'_, PyArrayDyn<f64>>,
        root: Option<usize>,
        joint_qpos: Vec<usize>,
        joint_dofs: Vec<usize>,
        free_dof: Option<usize>,
        mass_pairs: PyReadonlyArray2<'_, i64>,
        conditions: PyRef<'_, PyConditions>,
        lagged: bool,
    ) -> PyResult<Self> {
        let n = robot.get().robot.joint_count();
        conditions.check_robot(&robot.get().robot)?;
        let Some((_, current)) = conditions.constant() else {
            return Err(PyValueError::new_err("a simulation's conditions are one value of each for every step"));
        };
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
        // The joint losses at the conditions' pressure (the core's, from their depth) and
        // temperature.
        let states =
            conditions.losses.as_ref().map_or([None; MAX_ROBOT_JOINTS], |losses| *LossStates::new().at(losses, 0));
        let own = |array: &Bound<'_, PyArrayDyn<f64>>, name: &str| -> PyResult<Vec<f64>> {
            let array = array.try_readonly()?;
            let all = values(&array, name, nv)?;
            Ok(joint_dofs.iter().map(|&d| all.get(d).copied().unwrap_or(0.0)).collect())
        };
        let views = Views {
            qpos: View::new(&qpos, "data.qpos")?,
            qvel: View::new(&qvel, "data.qvel")?,
            qacc: View::new(&qacc, "data.qacc")?,
            xquat: View::new(&xquat, "data.xquat")?,
            xmat: View::new(&xmat, "data.xmat")?,
            mass_matrix: View::new(&mass_matrix, "data.M")?,
            qfrc_applied: View::new(&qfrc_applied, "data.qfrc_applied")?,
            dof_damping: View::new(&dof_damping, "model.dof_damping")?,
            dof_frictionloss: View::new(&dof_frictionloss, "model.dof_frictionloss")?,
            gravity: View::new(&model_gravity, "model.opt.gravity")?,
        };
        let mut initial = Vec::new();
        views.gravity.copy_into(model_gravity.py(), &mut initial)?;
        let gravity_at_start = match initial.as_slice() {
            &[x, y, z] => [x, y, z],
            _ => return Err(PyValueError::new_err("model.opt.gravity must hold 3 numbers")),
        };
        let (own_damping, own_frictionloss) =
            (own(&dof_damping, "dof_damping")?, own(&dof_frictionloss, "dof_frictionloss")?);
        let size = 6 + n;
        Ok(Self {
            robot: robot.unbind(),
            views,
            map: DofMap { uwml_of_dof, joint_qpos, joint_dofs, free_dof, root, mass_pairs: mass_entries },
            data: Box::new(Data::new()),
            losses: states,
            own_damping,
            own_frictionloss,
            water: conditions.water,
            gravity: gravity_at_start,
            current,
            form: conditions.form,
            coefficients: conditions.coefficients.clone(),
            lagged: lagged.then(|| vec![0.0; size]),
            added_mass: vec![0.0; size * size],
            joint_added_mass: vec![0.0; n * n],
            rk4: None,
            qpos: Vec::with_capacity(nq),
            qvel: Vec::with_capacity(nv),
            scratch: Vec::new(),
            scratch2: Vec::new(),
            prescribed: None,
        })
    }

    /// The joint losses at the data's joint speeds into the model's `dof_damping` and
    /// `dof_frictionloss` (see `write_losses`), before MuJoCo's position stage, whose friction
    /// constraints take those levels. Nothing when no joint has losses, or when a speed is not
    /// finite (`apply` then reports the state).
    fn write_joint_losses(&mut self, py: Python<'_>) -> PyResult<()> {
        if self.losses.iter().all(Option::is_none) {
            return Ok(());
        }
        self.views.qvel.copy_into(py, &mut self.qvel)?;
        let mut speeds = [0.0; MAX_ROBOT_JOINTS];
        for (slot, &dof) in speeds.iter_mut().zip(&self.map.joint_dofs) {
            *slot = self.qvel.get(dof).copied().unwrap_or(f64::NAN);
        }
        let speeds = speeds.get(..self.map.joint_dofs.len()).unwrap_or_default();
        if !speeds.iter().all(|x| x.is_finite()) {
            return Ok(());
        }
        self.write_losses(py, speeds)
    }

    /// One step's coupling, after MuJoCo's position stage: `M_A` added into `data.M` (unless lagged), the
    /// environment's forces (plus `torque` on the joints, if given) written to
    /// `data.qfrc_applied`. Returns 0 when done, 1 when the state (`qpos`, `qvel`) is not finite
    /// (nothing written), 2 when `torque` is not a list, tuple or float64 array of N finite
    /// numbers (nothing written: the caller converts or refuses it), 3 when `model.opt.gravity`
    /// is no longer what it was when the coupling was made (nothing written).
    #[pyo3(signature = (torque=None))]
    fn apply(&mut self, py: Python<'_>, torque: Option<&Bound<'_, PyAny>>) -> PyResult<u8> {
        let n = self.robot.get().robot.joint_count();
        let size = 6 + n;
        let mut motor = [0.0; MAX_ROBOT_JOINTS];
        if let Some(torque) = torque
            && fill_values(torque, motor.get_mut(..n).unwrap_or_default()).is_none()
        {
            return Ok(2);
        }
        self.views.gravity.copy_into(py, &mut self.scratch)?;
        if self.scratch.as_slice() != self.gravity.as_slice() {
            return Ok(3);
        }
        self.views.qpos.copy_into(py, &mut self.qpos)?;
        self.views.qvel.copy_into(py, &mut self.qvel)?;
        if !(self.qpos.iter().all(|x| x.is_finite()) && self.qvel.iter().all(|x| x.is_finite())) {
            return Ok(1);
        }
        let mut row = StateRow::new();
        for (i, (&p, &d)) in self.map.joint_qpos.iter().zip(&self.map.joint_dofs).enumerate() {
            if let (Some(q), Some(qd), Some(&x), Some(&v)) =
                (row.q.get_mut(i), row.qd.get_mut(i), self.qpos.get(p), self.qvel.get(d))
            {
                (*q, *qd) = (x, v);
            }
        }
        let pose = self.root_pose(py)?;
        let motion = self.base_motion(pose.as_ref(), &self.qvel)?;
        let robot = self.robot.get();
        if self.map.free_dof.is_some() {
            robot_added_mass_matrix(
                &robot.robot,
                &self.water,
                self.coefficients.as_deref(),
                &row.q,
                &mut self.added_mass,
            );
        } else {
            // A fixed base: ν̇ = 0 and the base has no degree of freedom in MuJoCo, so only the
            // joints' block of M_A acts.
            let coefficients = self.coefficients.as_deref();
            robot_joint_added_mass_matrix(&robot.robot, &self.water, coefficients, &row.q, &mut self.joint_added_mass);
            for (i, block_row) in self.joint_added_mass.chunks(n.max(1)).enumerate().take(n) {
                let start = (6 + i) * size + 6;
                if let Some(slots) = self.added_mass.get_mut(start..start + n) {
                    slots.copy_from_slice(block_row);
                }
            }
        }
        let conditions = Conditions {
            water: self.water,
            motion,
            current: self.current,
            coefficients: self.coefficients.as_deref(),
            form: self.form,
            losses: None,
        };
        robot_hydro(&robot.robot, &conditions, [&row.q, &row.qd, &row.qdd], &mut self.data);
        // uwml's generalized forces: the base wrench's hydrodynamic part, then the joints'
        // hydrodynamics and motor torques. The joint losses are MuJoCo's: the seal's dry
        // friction a friction constraint, the smooth rest a damping (`write_joint_losses`).
        let mut forces = [0.0; 6 + MAX_ROBOT_JOINTS];
        for (slot, value) in forces.iter_mut().zip(self.data.base_wrench().total().to_array()) {
            *slot = value;
        }
        for (i, joint) in self.data.joint_forces().iter().enumerate() {
            if let (Some(slot), Some(m)) = (forces.get_mut(6 + i), motor.get(i)) {
                *slot = joint.total() + m;
            }
        }
        if let Some(previous) = &self.lagged {
            for (r, slot) in forces.iter_mut().take(size).enumerate() {
                let row = self.added_mass.get(r * size..(r + 1) * size).unwrap_or_default();
                *slot -= row.iter().zip(previous).map(|(m, a)| m * a).sum::<f64>();
            }
        }
        // MuJoCo's coordinates: the free joint's linear velocity is world-frame, uwml's ν base
        // frame, so its rows and columns turn by R (MuJoCo's = T · uwml's, T = diag(R, I, I)).
        let rotation = pose.map_or_else(Matrix3::identity, |(rotation, _)| rotation);
        if self.map.free_dof.is_some() {
            turn_rows(&rotation, &mut forces, 1);
            turn_rows(&rotation, &mut self.added_mass, size);
            turn_columns(&rotation, &mut self.added_mass, size);
        }
        self.scratch.clear();
        self.scratch.extend(self.map.uwml_of_dof.iter().map(|u| u.and_then(|u| forces.get(u)).copied().unwrap_or(0.0)));
        self.views.qfrc_applied.write(py, &self.scratch)?;
        if self.lagged.is_none() {
            self.views.mass_matrix.copy_into(py, &mut self.scratch)?;
            for (slot, &(r, c)) in self.scratch.iter_mut().zip(&self.map.mass_pairs) {
                let (ur, uc) =
                    (self.map.uwml_of_dof.get(r).copied().flatten(), self.map.uwml_of_dof.get(c).copied().flatten());
                if let (Some(ur), Some(uc)) = (ur, uc) {
                    *slot += self.added_mass.get(ur * size + uc).copied().unwrap_or(0.0);
                }
            }
            self.views.mass_matrix.write(py, &self.scratch)?;
        }
        Ok(0)
    }

    /// A Runge-Kutta step begins at the data's `qpos` and `qvel` (see `Rk4`).
    fn rk4_begin(&mut self, py: Python<'_>) -> PyResult<()> {
        let nv = self.views.qvel.len();
        if self.rk4.is_none() {
            self.rk4 = Some(Rk4::new(py, nv)?);
        }
        match self.rk4.as_mut() {
            Some(rk4) => rk4.begin(py, &self.views.qpos, &self.views.qvel),
            None => Ok(()),
        }
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
        match self.rk4.as_mut() {
            Some(rk4) => rk4.stage(py, stage, offset, &self.views.qpos, &self.views.qvel),
            None => Err(PyValueError::new_err("rk4_begin must come first")),
        }
    }

    /// Keeps stage `stage`'s acceleration (`data.qacc` after its forward pass).
    fn rk4_keep(&mut self, py: Python<'_>, stage: usize) -> PyResult<()> {
        match self.rk4.as_mut() {
            Some(rk4) => rk4.keep(py, stage, &self.views.qacc),
            None => Err(PyValueError::new_err("rk4_begin must come first")),
        }
    }

    /// The step's end: `data.qpos` back to the start, `data.qvel` the step's; the weighted
    /// velocity, for `mj_integratePos` over `h`.
    fn rk4_finish<'py>(&mut self, py: Python<'py>, h: f64) -> PyResult<Bound<'py, PyArray1<f64>>> {
        match self.rk4.as_mut() {
            Some(rk4) => rk4.finish(py, h, &self.views.qpos, &self.views.qvel),
            None => Err(PyValueError::new_err("rk4_begin must come first")),
        }
    }

    /// Prescribe the joints at degrees of freedom `dofs` (their `qpos` entries `qpos`), their
    /// motion the piecewise cubics `coefficients` (`q`, `q̇`, `q̈`, each `(4, len(knots) − 1,
    /// k)` flattened, highest degree first) over `knots`, times within `slack` past an end being
    /// that end; without `knots`, the caller gives the motion's values to `impose` and
    /// `put_on_motion`. `solved`: the `(k, nv)` array that receives `M⁻¹[:, p]` each step.
    /// `dofs` empty: no prescribed motion.
    #[pyo3(signature = (dofs, qpos, solved, knots=None, coefficients=None, slack=0.0))]
    fn prescribe(
        &mut self,
        dofs: Vec<usize>,
        qpos: Vec<usize>,
        solved: Bound<'_, PyArrayDyn<f64>>,
        knots: Option<Vec<f64>>,
        coefficients: Option<[numpy::PyReadonlyArray1<'_, f64>; 3]>,
        slack: f64,
    ) -> PyResult<()> {
        if dofs.is_empty() {
            self.prescribed = None;
            return Ok(());
        }
        let nv = self.views.qvel.len();
        if dofs.len() != qpos.len() || dofs.iter().any(|&d| d >= nv) || qpos.iter().any(|&p| p >= self.views.qpos.len())
        {
            return Err(PyValueError::new_err("dofs and qpos must name as many degrees of freedom and qpos entries"));
        }
        let view = View::new(&solved, "solved")?;
        if view.len() != dofs.len() * nv {
            return Err(PyValueError::new_err("solved must hold k x nv numbers"));
        }
        let pieces = match (knots, coefficients) {
            (Some(knots), Some(arrays)) => {
                let [q, qd, qdd] = arrays.map(|a| a.as_slice().map(<[f64]>::to_vec).unwrap_or_default());
                Some(Pieces::new(knots, [q, qd, qdd], dofs.len(), slack).map_err(PyValueError::new_err)?)
            }
            (None, None) => None,
            _ => return Err(PyValueError::new_err("give both knots and coefficients, or neither")),
        };
        self.prescribed = Some(PrescribedMotion::new(dofs, qpos, pieces, view));
        Ok(())
    }

    /// The imposing torque of the prescribed motion at `time` (see `prescribed.rs`; `target`: the
    /// accelerations, for a motion the caller evaluates), after a forward pass whose `M` is
    /// factored and `solved` written. 0 done, 1 `time` outside the motion, 2 singular.
    #[pyo3(signature = (time, target=None))]
    fn impose(&mut self, py: Python<'_>, time: f64, target: Option<Vec<f64>>) -> PyResult<u8> {
        let Some(motion) = self.prescribed.as_mut() else { return Ok(0) };
        motion.impose(py, &self.views.qacc, &self.views.qfrc_applied, time, target.as_deref())
    }

    /// The prescribed joints put on the motion at `time` (or on `q`, `qd` given). 0 done, 1
    /// `time` outside the motion.
    #[pyo3(signature = (time, q=None, qd=None))]
    fn put_on_motion(&mut self, py: Python<'_>, time: f64, q: Option<Vec<f64>>, qd: Option<Vec<f64>>) -> PyResult<u8> {
        let Some(motion) = self.prescribed.as_mut() else { return Ok(0) };
        let given = match (&q, &qd) {
            (Some(q), Some(qd)) => Some((q.as_slice(), qd.as_slice())),
            (None, None) => None,
            _ => return Ok(OUTSIDE),
        };
        motion.put_on_motion(py, &self.views.qpos, &self.views.qvel, time, given)
    }

    /// The last imposing torque, one per prescribed joint (empty without a prescribed motion).
    fn prescribed_torque<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_slice(py, self.prescribed.as_ref().map_or(&[][..], |m| m.torque.as_slice()))
    }

    /// For the lagged scheme: keep `(ν̇, q̈)` of the step just computed (`data.qacc` in uwml's
    /// coordinates, with `ν̇ = Rᵀ v̇_world − ω × v`), to subtract `M_A` times it next step.
    fn remember_acceleration(&mut self, py: Python<'_>) -> PyResult<()> {
        let pose = self.root_pose(py)?;
        let rotation = pose.map_or_else(Matrix3::identity, |(rotation, _)| rotation);
        self.views.qvel.copy_into(py, &mut self.qvel)?;
        self.views.qacc.copy_into(py, &mut self.scratch)?;
        let motion = self.base_motion(pose.as_ref(), &self.qvel)?;
        let qacc = &self.scratch;
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
    fn write_losses(&mut self, py: Python<'_>, qd: &[f64]) -> PyResult<()> {
        if self.losses.iter().all(Option::is_none) {
            return Ok(());
        }
        let (damping, friction) = (&mut self.scratch, &mut self.scratch2);
        self.views.dof_damping.copy_into(py, damping)?;
        self.views.dof_frictionloss.copy_into(py, friction)?;
        let joints =
            self.map.joint_dofs.iter().zip(&self.losses).zip(self.own_damping.iter().zip(&self.own_frictionloss));
        for (i, ((&dof, state), (&own_damping, &own_friction))) in joints.enumerate() {
            let Some(state) = state else { continue };
            let split = state.dry_friction_split(qd.get(i).copied().unwrap_or(0.0));
            if let (Some(d), Some(f)) = (damping.get_mut(dof), friction.get_mut(dof)) {
                (*d, *f) = (own_damping + split.damping, own_friction + split.friction);
            }
        }
        self.views.dof_damping.write(py, damping)?;
        self.views.dof_frictionloss.write(py, friction)
    }

    /// The root body's orientation, world from base, as `xmat` and as `xquat` (`None` when the
    /// base is the world frame).
    fn root_pose(&mut self, py: Python<'_>) -> PyResult<Option<(Matrix3<f64>, [f64; 4])>> {
        let Some(root) = self.map.root else { return Ok(None) };
        self.views.xmat.copy_into(py, &mut self.scratch)?;
        let at = |k: usize| self.scratch.get(9 * root + k).copied().unwrap_or(f64::NAN);
        let rotation = Matrix3::from_fn(|r, c| at(3 * r + c));
        self.views.xquat.copy_into(py, &mut self.scratch)?;
        let quaternion = [0, 1, 2, 3].map(|k| self.scratch.get(4 * root + k).copied().unwrap_or(f64::NAN));
        Ok(Some((rotation, quaternion)))
    }

    /// The base's motion for uwml at the root's `pose` ([`Self::root_pose`]) and velocities
    /// `qvel`: the root's orientation; on a free joint `v = Rᵀ v_world`, `ω` (MuJoCo's is
    /// body-frame already) and `ν̇ = −ω × v`, what zero MuJoCo acceleration means.
    fn base_motion(&self, pose: Option<&(Matrix3<f64>, [f64; 4])>, qvel: &[f64]) -> PyResult<BaseMotion<f64>> {
        let Some((rotation, orientation)) = pose else { return Ok(BaseMotion::fixed()) };
        let zero = Vector3::zeros();
        let (v, w) = match self.map.free_dof {
            Some(free) => {
                let at = |k: usize| qvel.get(free + k).copied().unwrap_or(f64::NAN);
                (rotation.transpose() * Vector3::new(at(0), at(1), at(2)), Vector3::new(at(3), at(4), at(5)))
            }
            None => (zero, zero),
        };
        BaseMotion::new(*orientation, v, w, -w.cross(&v), zero).map_err(crate::model_error)
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
