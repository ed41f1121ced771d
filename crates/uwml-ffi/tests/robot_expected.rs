//! `tests/c/robot_expected.h` is what uwml-core computes for the robots of `tests/robots/mod.rs`:
//! their parameters (joint losses included) as C initializers and the core's results
//! (`robot_hydro` and `loss_torques` called directly, in f64), which `tests/c/robot.c` checks the
//! C ABI against.
//!
//! After a change of the robots or of the core's results:
//! `UWML_BLESS=1 cargo test -p uwml-ffi --test robot_expected` rewrites the file; review the diff
//! and commit it with the change.
#![allow(missing_docs, clippy::unwrap_used, clippy::expect_used, clippy::indexing_slicing)]

use std::fmt::Write as _;
use std::path::Path;

use uwml_core::Water;
use uwml_ffi::{
    UWML_BASE, UWML_JOINT_PRISMATIC, UWML_SECTION_CIRCULAR, UwmlBaseMotionF64, UwmlBaseWrenchF64, UwmlBodyF64,
    UwmlCurrentF64, UwmlJointEnvironmentF64, UwmlJointForcesF64, UwmlJointLossParamsF64, UwmlRobotSegmentF64,
    UwmlTreeJointF64,
};

mod robots;
use robots::{
    ARM_CURRENT, ARM_STATE, DENSITY, GRAVITY, PAPER_CURRENT, PAPER_STATE, Params, arm, arm_conditions, arm_losses,
    arm_motion, core_current, core_environment, core_hydro, core_loss_states, core_motion, core_robot, environment64,
    forces64, paper, paper_motion, wrench64,
};

/// A double as C reads it back exactly: Rust's shortest representation that round-trips.
fn num(x: f64) -> String {
    assert!(x.is_finite(), "a finite value");
    format!("{x:?}")
}

fn list(xs: &[f64]) -> String {
    let items: Vec<String> = xs.iter().map(|&x| num(x)).collect();
    format!("{{{}}}", items.join(", "))
}

fn index(i: i32) -> String {
    if i == UWML_BASE { "UWML_BASE".to_owned() } else { i.to_string() }
}

fn joint(j: &UwmlTreeJointF64) -> String {
    let kind = if j.kind == UWML_JOINT_PRISMATIC { "UWML_JOINT_PRISMATIC" } else { "UWML_JOINT_REVOLUTE" };
    format!(
        "{{.parent = {}, .kind = {kind}, .origin = {}, .axis = {}}}",
        index(j.parent),
        list(&j.origin),
        list(&j.axis)
    )
}

fn body(b: &UwmlBodyF64) -> String {
    format!(".mass = {}, .com = {}, .volume = {}, .cob = {}", num(b.mass), list(&b.com), num(b.volume), list(&b.cob))
}

/// Only the fields the segment's section reads, in the struct's order.
fn segment(s: &UwmlRobotSegmentF64) -> String {
    let (section, shape) = if s.section == UWML_SECTION_CIRCULAR {
        ("UWML_SECTION_CIRCULAR", format!(".diameter = {}", num(s.diameter)))
    } else {
        (
            "UWML_SECTION_RECTANGULAR",
            format!(".normals = {{{}, {}}}, .widths = {}", list(&s.normals[0]), list(&s.normals[1]), list(&s.widths)),
        )
    };
    format!(
        "{{.owner = {}, .section = {section},\n     .start = {}, .axis = {}, .length = {}, .area = {},\n     {shape},\n     \
         .cd = {}, .cm = {}}}",
        index(s.owner),
        list(&s.start),
        list(&s.axis),
        num(s.length),
        num(s.area),
        list(&s.cd),
        list(&s.cm)
    )
}

fn motion(m: &UwmlBaseMotionF64) -> String {
    format!(
        "{{.orientation = {},\n    .velocity = {},\n    .angular_velocity = {},\n    .acceleration = {},\n    \
         .angular_acceleration = {}}}",
        list(&m.orientation),
        list(&m.velocity),
        list(&m.angular_velocity),
        list(&m.acceleration),
        list(&m.angular_acceleration)
    )
}

fn current(c: &UwmlCurrentF64) -> String {
    format!("{{.velocity = {}, .acceleration = {}}}", list(&c.velocity), list(&c.acceleration))
}

fn forces(f: &[UwmlJointForcesF64]) -> String {
    let rows: Vec<String> = f
        .iter()
        .map(|f| {
            format!(
                "    {{.drag = {}, .added_mass = {}, .buoyancy = {},\n     .gravity = {}, .total = {}}},\n",
                num(f.drag),
                num(f.added_mass),
                num(f.buoyancy),
                num(f.gravity),
                num(f.total)
            )
        })
        .collect();
    format!("{{\n{}}}", rows.concat())
}

fn wrench(w: &UwmlBaseWrenchF64) -> String {
    format!(
        "{{\n    .drag = {},\n    .added_mass = {},\n    .buoyancy = {},\n    .gravity = {},\n    .total = {},\n}}",
        list(&w.drag),
        list(&w.added_mass),
        list(&w.buoyancy),
        list(&w.gravity),
        list(&w.total)
    )
}

/// A joint's losses, every field.
fn losses(p: &UwmlJointLossParamsF64) -> String {
    let (d, o, s) = (&p.drive, &p.oil, &p.seal);
    format!(
        "{{.drive = {{.torque_constant = {}, .ratio = {}, .efficiency = {}, .rated_current = {}}},\n     \
         .oil = {{.k_oil = {}, .exponent = {}, .pressure_sensitivity = {}, .temperature_sensitivity = {},\n             \
         .reference_pressure = {}, .reference_temperature = {}}},\n     \
         .seal = {{.c = {}, .s = {}, .d = {}, .stribeck_speed = {}}},\n     \
         .epsilon = {}, .has_oil = {}, .has_seal = {}}}",
        num(d.torque_constant),
        num(d.ratio),
        num(d.efficiency),
        num(d.rated_current),
        num(o.k_oil),
        num(o.exponent),
        num(o.pressure_sensitivity),
        num(o.temperature_sensitivity),
        num(o.reference_pressure),
        num(o.reference_temperature),
        list(&s.c),
        list(&s.s),
        list(&s.d),
        num(s.stribeck_speed),
        num(p.epsilon),
        p.has_oil,
        p.has_seal
    )
}

fn environment(e: &[UwmlJointEnvironmentF64]) -> String {
    let rows: Vec<String> = e
        .iter()
        .map(|e| {
            format!(
                "    {{.drag = {}, .added_mass = {}, .buoyancy = {}, .gravity = {},\n     .visc = {}, .seal = {}, \
                 .current = {}, .total = {}}},\n",
                num(e.drag),
                num(e.added_mass),
                num(e.buoyancy),
                num(e.gravity),
                num(e.visc),
                num(e.seal),
                num(e.current),
                num(e.total)
            )
        })
        .collect();
    format!("{{\n{}}}", rows.concat())
}

/// The parameters of a robot, under the names `PREFIX_JOINT`, `PREFIX_LINK`, `PREFIX_BASE` (if
/// it has a base body) and `PREFIX_SEGMENT`.
fn params(out: &mut String, prefix: &str, p: &Params) {
    let (nj, ns) = (p.joints.len(), p.segments.len());
    writeln!(out, "#define {prefix}_JOINTS {nj}\n#define {prefix}_SEGMENTS {ns}").unwrap();
    let joints: Vec<String> = p.joints.iter().map(|j| format!("    {},\n", joint(j))).collect();
    writeln!(out, "static const UwmlTreeJointF64 {prefix}_JOINT[{prefix}_JOINTS] = {{\n{}}};", joints.concat())
        .unwrap();
    let links: Vec<String> = p.links.iter().map(|b| format!("    {{{}}},\n", body(b))).collect();
    writeln!(out, "static const UwmlBodyF64 {prefix}_LINK[{prefix}_JOINTS] = {{\n{}}};", links.concat()).unwrap();
    if let Some(b) = &p.base {
        writeln!(out, "static const UwmlBodyF64 {prefix}_BASE = {{{}}};", body(b)).unwrap();
    }
    let segments: Vec<String> = p.segments.iter().map(|s| format!("    {},\n", segment(s))).collect();
    writeln!(
        out,
        "static const UwmlRobotSegmentF64 {prefix}_SEGMENT[{prefix}_SEGMENTS] = {{\n{}}};",
        segments.concat()
    )
    .unwrap();
}

/// The state arrays `PREFIX_Q`, `PREFIX_QD`, `PREFIX_QDD`.
fn state(out: &mut String, prefix: &str, [q, qd, qdd]: [&[f64]; 3]) {
    for (name, values) in [("Q", q), ("QD", qd), ("QDD", qdd)] {
        writeln!(out, "static const double {prefix}_{name}[{prefix}_JOINTS] = {};", list(values)).unwrap();
    }
}

/// The core's joint forces and base wrench for `p` in `water` at `s`, under `PREFIX_FORCES` and
/// `PREFIX_WRENCH`.
fn results(
    out: &mut String,
    prefix: &str,
    what: &str,
    p: &Params,
    water: &Water<f64>,
    s: [&[f64]; 3],
    moving: Option<(&UwmlBaseMotionF64, &UwmlCurrentF64)>,
) {
    let data =
        core_hydro(&core_robot(p), water, &core_motion(moving.map(|m| m.0)), &core_current(moving.map(|m| m.1)), s);
    let joints = prefix.split('_').next().expect("a robot's name");
    writeln!(out, "\n/* {what} */").unwrap();
    writeln!(out, "static const UwmlJointForcesF64 {prefix}_FORCES[{joints}_JOINTS] = {};", forces(&forces64(&data)))
        .unwrap();
    writeln!(out, "static const UwmlBaseWrenchF64 {prefix}_WRENCH = {};", wrench(&wrench64(&data))).unwrap();
}

fn generate() -> String {
    let mut out = String::from(
        "/* Generated by tests/robot_expected.rs from uwml-core: do not edit. Regenerate with\n \
         * UWML_BLESS=1 cargo test -p uwml-ffi --test robot_expected\n *\n \
         * The robots of tests/robots/mod.rs as C gives them, and what uwml-core computes for them\n \
         * (robot_hydro called directly, in double), for tests/c/robot.c: each number as Rust's\n \
         * shortest representation that reads back exactly. */\n\
         #ifndef UWML_ROBOT_EXPECTED_H\n#define UWML_ROBOT_EXPECTED_H\n\n#include \"uwml.h\"\n\n",
    );

    out.push_str("/* A 6-joint arm on a vehicle (tests/robots/mod.rs, arm()), in sea water. */\n");
    writeln!(out, "#define ARM_DENSITY {}\n#define ARM_GRAVITY {}", num(DENSITY), num(GRAVITY)).unwrap();
    let arm = arm();
    params(&mut out, "ARM", &arm);
    let [q, qd, qdd] = ARM_STATE;
    state(&mut out, "ARM", [&q, &qd, &qdd]);
    let (arm_motion, paper_motion) = (arm_motion(), paper_motion());
    writeln!(out, "static const UwmlBaseMotionF64 ARM_MOTION = {};", motion(&arm_motion)).unwrap();
    writeln!(out, "static const UwmlCurrentF64 ARM_CURRENT = {};", current(&ARM_CURRENT)).unwrap();
    let water = Water::new(DENSITY, GRAVITY).expect("sea water");
    let s = [&q[..], &qd[..], &qdd[..]];
    results(
        &mut out,
        "ARM_MOVING",
        "The arm's vehicle moving with ARM_MOTION in ARM_CURRENT.",
        &arm,
        &water,
        s,
        Some((&arm_motion, &ARM_CURRENT)),
    );
    results(&mut out, "ARM_FIXED", "The same state on a fixed, upright base in still water.", &arm, &water, s, None);

    out.push_str(
        "\n/* Joint losses on four of the arm's joints (tests/robots/mod.rs, arm_losses()): ARM_LOSS[k] on\n \
         * joint ARM_LOSS_JOINT[k], at ARM_LOSS_PRESSURE [Pa] (3000 m of sea water) and ARM_LOSS_TEMPERATURE\n \
         * [degC]; the environment with them of the arm moving with ARM_MOTION in ARM_CURRENT (its base\n \
         * wrench is ARM_MOVING_WRENCH: losses act inside the robot). */\n",
    );
    let (loss_list, conditions) = (arm_losses(), arm_conditions());
    writeln!(out, "#define ARM_LOSSES {}", loss_list.len()).unwrap();
    let joints: Vec<String> = loss_list.iter().map(|(j, _)| j.to_string()).collect();
    writeln!(out, "static const uint32_t ARM_LOSS_JOINT[ARM_LOSSES] = {{{}}};", joints.join(", ")).unwrap();
    let loss_params: Vec<String> = loss_list.iter().map(|(_, p)| format!("    {},\n", losses(p))).collect();
    writeln!(out, "static const UwmlJointLossParamsF64 ARM_LOSS[ARM_LOSSES] = {{\n{}}};", loss_params.concat())
        .unwrap();
    writeln!(
        out,
        "#define ARM_LOSS_PRESSURE {}\n#define ARM_LOSS_TEMPERATURE {}",
        num(conditions.0),
        num(conditions.1)
    )
    .unwrap();
    let data =
        core_hydro(&core_robot(&arm), &water, &core_motion(Some(&arm_motion)), &core_current(Some(&ARM_CURRENT)), s);
    let states = core_loss_states::<f64>(&loss_list, conditions);
    let with_losses = environment64(&core_environment(&data, &states, &qd));
    writeln!(
        out,
        "static const UwmlJointEnvironmentF64 ARM_LOSSES_ENVIRONMENT[ARM_JOINTS] = {};",
        environment(&with_losses)
    )
    .unwrap();

    out.push_str(
        "\n/* The paper's leg: what uwml_robot_paper_leg_* holds, fresh water 1000 kg/m^3, g = 9.81, at\n \
                  * the state whose torques docs/model.md section 5 publishes. */\n",
    );
    let paper = paper();
    params(&mut out, "PAPER", &paper);
    let [q, qd, qdd] = PAPER_STATE;
    state(&mut out, "PAPER", [&q, &qd, &qdd]);
    writeln!(out, "static const UwmlBaseMotionF64 PAPER_MOTION = {};", motion(&paper_motion)).unwrap();
    writeln!(out, "static const UwmlCurrentF64 PAPER_CURRENT = {};", current(&PAPER_CURRENT)).unwrap();

    let s = [&q[..], &qd[..], &qdd[..]];
    let water = Water::default();
    results(&mut out, "PAPER_FIXED", "On a fixed, upright base in still water.", &paper, &water, s, None);
    results(
        &mut out,
        "PAPER_MOVING",
        "Its base moving with PAPER_MOTION in PAPER_CURRENT.",
        &paper,
        &water,
        s,
        Some((&paper_motion, &PAPER_CURRENT)),
    );
    out.push_str("\n#endif /* UWML_ROBOT_EXPECTED_H */\n");
    out
}

#[test]
fn c_expected_values_are_the_cores() {
    let generated = generate();
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/c/robot_expected.h");
    if std::env::var_os("UWML_BLESS").is_some() {
        std::fs::write(&path, &generated).expect("tests/c/robot_expected.h is writable");
        return;
    }
    let checked_in = std::fs::read_to_string(&path).unwrap_or_default();
    assert!(
        checked_in == generated,
        "tests/c/robot_expected.h is out of date with uwml-core or tests/robots/mod.rs: regenerate it with\n    \
         UWML_BLESS=1 cargo test -p uwml-ffi --test robot_expected\nand review the diff"
    );
}
