//! Compiles `tests/c/paper_leg.c` (the paper's leg preset: reference torques, the model read
//! only, water and coefficients, losses, error paths) and
//! `tests/c/robot.c` (the robot API: an arm on a moving vehicle and the paper's leg against the
//! core's values in `tests/c/robot_expected.h`, error paths) and `tests/c/robot_losses.c` (the
//! arm with joint losses, the paper's leg with losses, the robot examples of docs/firmware.md)
//! against `include/uwml.h` and the static library that cargo built for this test run, runs
//! them, and checks that C sees every struct with the size, alignment and field offsets that
//! Rust gives it.
//!
//! The C compiler is `$CC`, else `cc`.
#![allow(missing_docs, clippy::expect_used, clippy::panic, clippy::indexing_slicing)]

use std::collections::HashMap;
use std::mem::{align_of, offset_of, size_of};
use std::path::{Path, PathBuf};
use std::process::Command;

use uwml_ffi::*;

/// The static library that cargo built for this test run. `cargo test` builds the library's
/// `staticlib` crate type next to the rlib the test links, as `target/<profile>/deps/
/// libuwml_ffi-<hash>.a` (and `cargo build` uplifts one to `target/<profile>/libuwml_ffi.a`).
/// Builds of other feature sets may sit beside it: take the newest one that is not newer than
/// this test executable (which is linked after the library it depends on).
fn static_library() -> PathBuf {
    let exe = std::env::current_exe().expect("the test executable has a path");
    let deps = exe.parent().expect("the test runs from target/<profile>/deps");
    let built = |path: &Path| std::fs::metadata(path).and_then(|m| m.modified()).ok();
    let exe_built = built(&exe).expect("the test executable has a modification time");
    let mut candidates: Vec<PathBuf> = std::fs::read_dir(deps)
        .expect("target/<profile>/deps is readable")
        .filter_map(|entry| entry.ok().map(|e| e.path()))
        .filter(|path| {
            let name = path.file_name().and_then(|n| n.to_str()).unwrap_or_default();
            name.starts_with("libuwml_ffi-") && name.ends_with(".a")
        })
        .collect();
    candidates.extend(deps.parent().map(|profile| profile.join("libuwml_ffi.a")).filter(|p| p.is_file()));
    let library = candidates
        .into_iter()
        .filter_map(|path| built(&path).filter(|&t| t <= exe_built).map(|t| (t, path)))
        .max()
        .map(|(_, path)| path);
    let library = library.unwrap_or_else(|| {
        panic!(
            "no libuwml_ffi-*.a in {}: cargo builds it (crate-type staticlib) with the tests of uwml-ffi; \
             run the test through `cargo test`",
            deps.display()
        )
    });
    println!("static library: {}", library.display());
    library
}

fn run(command: &mut Command) -> String {
    let output = command.output().unwrap_or_else(|e| panic!("cannot run {command:?}: {e}"));
    let stdout = String::from_utf8_lossy(&output.stdout).into_owned();
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(
        output.status.success(),
        "{command:?} failed ({})\n--- stdout\n{stdout}\n--- stderr\n{stderr}",
        output.status
    );
    stdout
}

/// Compiles `tests/c/<name>.c` against the header and the library, runs it, returns its output.
fn compile_and_run(name: &str) -> String {
    let crate_dir = Path::new(env!("CARGO_MANIFEST_DIR"));
    let exe = Path::new(env!("CARGO_TARGET_TMPDIR")).join(name);
    let compiler = std::env::var_os("CC").unwrap_or_else(|| "cc".into());
    run(Command::new(compiler)
        .args(["-std=c11", "-Wall", "-Wextra", "-Werror", "-pedantic", "-I"])
        .arg(crate_dir.join("include"))
        .arg(crate_dir.join(format!("tests/c/{name}.c")))
        .arg(static_library())
        .arg("-lm")
        .arg("-o")
        .arg(&exe));
    run(&mut Command::new(&exe))
}

/// The program's `size NAME SIZE ALIGN` and `offset NAME OFFSET` lines.
type Layouts = (HashMap<String, (usize, usize)>, HashMap<String, usize>);

fn layouts(stdout: &str) -> Layouts {
    let mut sizes = HashMap::new();
    let mut offsets = HashMap::new();
    for line in stdout.lines() {
        let words: Vec<&str> = line.split_whitespace().collect();
        let number = |i: usize| words.get(i).and_then(|w| w.parse::<usize>().ok()).expect("a number");
        match words.first() {
            Some(&"size") => {
                sizes.insert(words[1].to_owned(), (number(2), number(3)));
            }
            Some(&"offset") => {
                offsets.insert(words[1].to_owned(), number(2));
            }
            _ => {}
        }
    }
    (sizes, offsets)
}

/// Runs the program, checks its summary line and that C's layouts are Rust's.
fn check_program(name: &str, expected: &[(&str, (usize, usize))], expected_offsets: &[(&str, usize)]) -> String {
    let stdout = compile_and_run(name);
    println!("{stdout}");
    assert!(stdout.lines().any(|line| line == "0 failed"), "no summary line in the C program's output");
    let (sizes, offsets) = layouts(&stdout);
    assert_eq!(sizes.len(), expected.len(), "the C program prints every struct once");
    for (name, layout) in expected {
        assert_eq!(sizes.get(*name), Some(layout), "{name}: (size, alignment) in C vs Rust");
    }
    assert_eq!(offsets.len(), expected_offsets.len());
    for (name, offset) in expected_offsets {
        assert_eq!(offsets.get(*name), Some(offset), "offset of {name} in C vs Rust");
    }
    stdout
}

macro_rules! layouts {
    ($($t:ident),* $(,)?) => {{
        let expected: Vec<(&str, (usize, usize))> =
            vec![$((stringify!($t), (size_of::<$t>(), align_of::<$t>()))),*];
        expected
    }};
}

#[test]
fn c_program_passes_and_sees_the_rust_layout() {
    let expected = layouts!(
        UwmlError,
        UwmlDriveParamsF64,
        UwmlOilParamsF64,
        UwmlSealParamsF64,
        UwmlJointLossParamsF64,
        UwmlWorkspaceF64,
        UwmlDriveParamsF32,
        UwmlOilParamsF32,
        UwmlSealParamsF32,
        UwmlJointLossParamsF32,
        UwmlWorkspaceF32,
    );
    let expected_offsets = [
        ("UwmlError.field", offset_of!(UwmlError, field)),
        ("UwmlJointLossParamsF64.has_seal", offset_of!(UwmlJointLossParamsF64, has_seal)),
        ("UwmlJointLossParamsF32.has_seal", offset_of!(UwmlJointLossParamsF32, has_seal)),
    ];
    check_program("paper_leg", &expected, &expected_offsets);
    // The sizes the header's preamble and docs/firmware.md state.
    assert_eq!(size_of::<UwmlWorkspaceF64>(), 7568);
    assert_eq!(size_of::<UwmlWorkspaceF32>(), 3792);
}

#[test]
fn c_robot_program_passes_and_sees_the_rust_layout() {
    let expected = layouts!(
        UwmlRobotF64,
        UwmlTreeJointF64,
        UwmlBodyF64,
        UwmlRobotSegmentF64,
        UwmlBaseMotionF64,
        UwmlCurrentF64,
        UwmlJointForcesF64,
        UwmlBaseWrenchF64,
        UwmlJointEnvironmentF64,
        UwmlRobotF32,
        UwmlTreeJointF32,
        UwmlBodyF32,
        UwmlRobotSegmentF32,
        UwmlBaseMotionF32,
        UwmlCurrentF32,
        UwmlJointForcesF32,
        UwmlBaseWrenchF32,
        UwmlJointEnvironmentF32,
    );
    let expected_offsets = [
        ("UwmlTreeJointF64.origin", offset_of!(UwmlTreeJointF64, origin)),
        ("UwmlRobotSegmentF64.start", offset_of!(UwmlRobotSegmentF64, start)),
        ("UwmlRobotSegmentF64.normals", offset_of!(UwmlRobotSegmentF64, normals)),
        ("UwmlRobotSegmentF64.diameter", offset_of!(UwmlRobotSegmentF64, diameter)),
        ("UwmlRobotSegmentF64.cm", offset_of!(UwmlRobotSegmentF64, cm)),
        ("UwmlBaseMotionF64.velocity", offset_of!(UwmlBaseMotionF64, velocity)),
        ("UwmlBaseWrenchF64.total", offset_of!(UwmlBaseWrenchF64, total)),
        ("UwmlTreeJointF32.origin", offset_of!(UwmlTreeJointF32, origin)),
        ("UwmlRobotSegmentF32.start", offset_of!(UwmlRobotSegmentF32, start)),
        ("UwmlRobotSegmentF32.diameter", offset_of!(UwmlRobotSegmentF32, diameter)),
        ("UwmlRobotSegmentF32.cm", offset_of!(UwmlRobotSegmentF32, cm)),
        ("UwmlBaseMotionF32.angular_acceleration", offset_of!(UwmlBaseMotionF32, angular_acceleration)),
        ("UwmlJointEnvironmentF64.visc", offset_of!(UwmlJointEnvironmentF64, visc)),
        ("UwmlJointEnvironmentF64.total", offset_of!(UwmlJointEnvironmentF64, total)),
        ("UwmlJointEnvironmentF32.current", offset_of!(UwmlJointEnvironmentF32, current)),
    ];
    let stdout = check_program("robot", &expected, &expected_offsets);
    assert!(stdout.lines().filter(|l| l.starts_with("ok ")).count() > 60, "the robot program runs its checks");
    // The sizes the header's preamble and docs/firmware.md state.
    assert_eq!(size_of::<UwmlRobotF64>(), 24448);
    assert_eq!(size_of::<UwmlRobotF32>(), 12872);
}

/// The robot program's joint losses (`tests/c/robot_losses.c`): it prints no layout, the robot
/// program does.
#[test]
fn c_robot_losses_program_passes() {
    let stdout = check_program("robot_losses", &[], &[]);
    assert!(stdout.lines().filter(|l| l.starts_with("ok ")).count() > 30, "the losses program runs its checks");
}

/// The robot examples of docs/firmware.md (the robot, its joint losses) are the ones
/// `tests/c/robot_losses.c` compiles and runs.
#[test]
fn firmware_doc_c_robot_examples_are_tested() {
    let crate_dir = Path::new(env!("CARGO_MANIFEST_DIR"));
    let source = std::fs::read_to_string(crate_dir.join("tests/c/robot_losses.c")).expect("tests/c/robot_losses.c");
    let doc = std::fs::read_to_string(crate_dir.join("../../docs/firmware.md")).expect("docs/firmware.md");
    for name in ["robot", "robot losses"] {
        let (begin, end) = (format!("/* --- docs/firmware.md: {name} */\n"), "/* --- end */");
        let start = source.find(&begin).expect("the example's start marker") + begin.len();
        let example = &source[start..start + source[start..].find(end).expect("the example's end marker")];
        assert!(
            doc.contains(example),
            "docs/firmware.md does not show tests/c/robot_losses.c's {name} example verbatim:\n{example}"
        );
    }
}

#[path = "../../uwml-core/benches/common/arm.rs"]
mod arm;

/// The C initializers of `uwml export --c` (`tests/c/exported_arm.h`, kept equal to the
/// exporter's output by `tests/test_export.py`) compile, build a robot through the C ABI, and
/// give the forces of the same arm built in Rust by hand (`uwml-core/benches/common/arm.rs`).
#[test]
fn exported_c_initializers_build_the_arm() {
    let stdout = compile_and_run("exported");
    let (motion, current) = arm::rov_motion::<f64>();
    let robot = arm::arm_on_rov::<f64, 7, 15>();
    let q = [0.3, -0.4, 0.6, 0.2, -0.5, 0.1, 0.05];
    let qd = [0.5, 0.3, -0.4, 0.8, 0.2, -0.6, 0.02];
    let qdd = [1.0, -0.5, 0.3, 0.2, -1.0, 0.7, 0.1];
    let mut data = uwml_core::RobotData::new();
    uwml_core::robot_hydro(
        &robot,
        &uwml_core::Conditions {
            water: uwml_core::Water::default(),
            motion,
            current,
            coefficients: None,
            form: uwml_core::AddedMassForm::Morison,
            losses: None,
        },
        [&q, &qd, &qdd],
        &mut data,
    );
    let mut seen = 0;
    for line in stdout.lines() {
        let words: Vec<&str> = line.split_whitespace().collect();
        let number = |i: usize| words[i].parse::<f64>().expect("a number");
        let index = words[1].parse::<usize>().expect("an index");
        let (actual, expected, scale) = match words[0] {
            "joint" => {
                let f = data.joint_forces()[index];
                assert!((number(3) - f.gravity).abs() <= 1e-12 * f.gravity.abs().max(1.0), "{line}");
                (number(2), f.total(), data.joint_forces().iter().fold(1.0_f64, |m, f| m.max(f.total().abs())))
            }
            "base" => {
                let w = data.base_wrench().total().to_array();
                (number(2), w[index], w.iter().fold(1.0_f64, |m, x| m.max(x.abs())))
            }
            other => panic!("unexpected line {other}: {line}"),
        };
        assert!((actual - expected).abs() <= 1e-12 * scale, "{line}: C {actual} vs Rust {expected}");
        seen += 1;
    }
    assert_eq!(seen, 13, "7 joints and 6 base components:\n{stdout}");
}

/// Every C block of docs/firmware.md compiles as written (`-std=c11 -Wall -Wextra -Werror
/// -pedantic`, compile only: the blocks are fragments of a firmware, without `main`).
#[test]
fn firmware_doc_c_examples_compile() {
    let crate_dir = Path::new(env!("CARGO_MANIFEST_DIR"));
    let doc = std::fs::read_to_string(crate_dir.join("../../docs/firmware.md")).expect("docs/firmware.md is readable");
    let blocks: Vec<&str> =
        doc.split("```c\n").skip(1).map(|rest| rest.split("```").next().expect("a closed block")).collect();
    assert!(blocks.len() >= 2, "docs/firmware.md has its C examples");
    let compiler = std::env::var_os("CC").unwrap_or_else(|| "cc".into());
    for (k, block) in blocks.iter().enumerate() {
        let source = Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("firmware_doc_{k}.c"));
        std::fs::write(&source, block).expect("the temporary directory is writable");
        run(Command::new(&compiler)
            .args(["-std=c11", "-Wall", "-Wextra", "-Werror", "-pedantic", "-Wno-unused-function", "-c", "-I"])
            .arg(crate_dir.join("include"))
            .arg(&source)
            .arg("-o")
            .arg(source.with_extension("o")));
    }
}
