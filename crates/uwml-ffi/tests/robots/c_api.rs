//! Building robots through the C API and reading its outputs, and the core's results as the C
//! API's structs (for `robot_api.rs`, `robot_losses.rs` and the other tests of the C ABI).

use super::*;

/// The core's results in the C API's structs (`total` as the core sums it).
pub fn forces64(data: &RobotData<f64, J>) -> Vec<UwmlJointForcesF64> {
    data.joint_forces()
        .iter()
        .map(|f| UwmlJointForcesF64 {
            drag: f.drag,
            added_mass: f.added_mass,
            buoyancy: f.buoyancy,
            gravity: f.gravity,
            total: f.total(),
        })
        .collect()
}

pub fn wrench64(data: &RobotData<f64, J>) -> UwmlBaseWrenchF64 {
    let w = data.base_wrench();
    UwmlBaseWrenchF64 {
        drag: w.drag.to_array(),
        added_mass: w.added_mass.to_array(),
        buoyancy: w.buoyancy.to_array(),
        gravity: w.gravity.to_array(),
        total: w.total().to_array(),
    }
}

pub fn forces32(data: &RobotData<f32, J>) -> Vec<UwmlJointForcesF32> {
    data.joint_forces()
        .iter()
        .map(|f| UwmlJointForcesF32 {
            drag: f.drag,
            added_mass: f.added_mass,
            buoyancy: f.buoyancy,
            gravity: f.gravity,
            total: f.total(),
        })
        .collect()
}

pub fn wrench32(data: &RobotData<f32, J>) -> UwmlBaseWrenchF32 {
    let w = data.base_wrench();
    UwmlBaseWrenchF32 {
        drag: w.drag.to_array(),
        added_mass: w.added_mass.to_array(),
        buoyancy: w.buoyancy.to_array(),
        gravity: w.gravity.to_array(),
        total: w.total().to_array(),
    }
}

// --- building robots through the C API and reading its outputs (robot_api.rs, robot_losses.rs) ---

pub fn zeroed64() -> Box<UwmlRobotF64> {
    Box::new(UwmlRobotF64 { opaque_tag: 0, opaque: [0; UWML_ROBOT_F64_WORDS] })
}

pub fn zeroed32() -> Box<UwmlRobotF32> {
    Box::new(UwmlRobotF32 { opaque_tag: 0, opaque: [0; UWML_ROBOT_F32_WORDS] })
}

/// A workspace written by the library, for any robot's evaluation in f64.
pub fn workspace64() -> Box<UwmlWorkspaceF64> {
    let mut workspace = Box::new(UwmlWorkspaceF64 { opaque_tag: 0, opaque: [0; UWML_WORKSPACE_F64_WORDS] });
    // SAFETY: a live, writable workspace.
    assert_eq!(unsafe { uwml_robot_workspace_init_f64(&mut *workspace) }, UWML_OK);
    workspace
}

/// A workspace written by the library, in f32.
pub fn workspace32() -> Box<UwmlWorkspaceF32> {
    let mut workspace = Box::new(UwmlWorkspaceF32 { opaque_tag: 0, opaque: [0; UWML_WORKSPACE_F32_WORDS] });
    // SAFETY: a live, writable workspace.
    assert_eq!(unsafe { uwml_robot_workspace_init_f32(&mut *workspace) }, UWML_OK);
    workspace
}

pub fn count(n: usize) -> u32 {
    u32::try_from(n).unwrap()
}

pub fn built32(p: &Params) -> Box<UwmlRobotF32> {
    let p = params32(p);
    let mut robot = zeroed32();
    let base = p.base.as_ref().map_or(null(), |b| b as *const UwmlBodyF32);
    // SAFETY: live locals; the arrays hold their counts of elements.
    let code = unsafe {
        uwml_robot_new_f32(
            &mut *robot,
            p.joints.as_ptr(),
            count(p.joints.len()),
            p.links.as_ptr(),
            base,
            p.segments.as_ptr(),
            count(p.segments.len()),
            DENSITY as f32,
            GRAVITY as f32,
            null_mut(),
        )
    };
    assert_eq!(code, UWML_OK);
    robot
}

pub const WRENCH_SENTINEL64: UwmlBaseWrenchF64 = UwmlBaseWrenchF64 {
    drag: [-7.0; 6],
    added_mass: [-7.0; 6],
    buoyancy: [-7.0; 6],
    gravity: [-7.0; 6],
    total: [-7.0; 6],
};

pub fn wrench_bits64(w: &UwmlBaseWrenchF64) -> [[u64; 6]; 5] {
    [w.drag, w.added_mass, w.buoyancy, w.gravity, w.total].map(|x| x.map(f64::to_bits))
}

pub fn wrench_bits32(w: &UwmlBaseWrenchF32) -> [[u32; 6]; 5] {
    [w.drag, w.added_mass, w.buoyancy, w.gravity, w.total].map(|x| x.map(f32::to_bits))
}

pub fn built64(p: &Params) -> Box<UwmlRobotF64> {
    let mut robot = zeroed64();
    let base = p.base.as_ref().map_or(null(), |b| b as *const UwmlBodyF64);
    // SAFETY: live locals; the arrays hold their counts of elements.
    let code = unsafe {
        uwml_robot_new_f64(
            &mut *robot,
            p.joints.as_ptr(),
            count(p.joints.len()),
            p.links.as_ptr(),
            base,
            p.segments.as_ptr(),
            count(p.segments.len()),
            DENSITY,
            GRAVITY,
            null_mut(),
        )
    };
    assert_eq!(code, UWML_OK);
    robot
}
