/*
 * The robot C API's joint losses end to end (static storage, no malloc): the arm of robot.c with
 * losses on four joints, moved to other conditions and cleared, against what uwml-core computes
 * (robot_expected.h); the paper's leg preset with losses; the error paths; and the robot examples
 * of docs/firmware.md, verbatim between the markers below (tests/c_program.rs holds the page to
 * them). Prints every check; exits non-zero if any fails.
 *
 * Built and run by tests/c_program.rs:
 *   cc -std=c11 -Wall -Wextra -Werror -pedantic -I include tests/c/robot_losses.c libuwml_ffi.a -lm ...
 */
#include "uwml.h"

#include "checks.h"
/* This program reads some of the expected values only (robot.c the others). */
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-const-variable"
#include "robot_expected.h"
#pragma GCC diagnostic pop

/* Static storage, as in firmware. */
static UwmlRobotF64 never_initialized;
static UwmlRobotF64 losses64;
static UwmlRobotF32 losses32;
static UwmlRobotF64 paper_losses64;
static UwmlWorkspaceF64 workspace64; /* one workspace per precision: the evaluations write it */
static UwmlWorkspaceF32 workspace32;

static double environment_component(const UwmlJointEnvironmentF64 *e, int c) {
    switch (c) {
    case 0: return e->drag;
    case 1: return e->added_mass;
    case 2: return e->buoyancy;
    case 3: return e->gravity;
    case 4: return e->visc;
    case 5: return e->seal;
    case 6: return e->current;
    default: return e->total;
    }
}

static const char *const ENVIRONMENT_COMPONENTS[8] = {"drag", "added_mass", "buoyancy", "gravity",
                                                      "visc", "seal",       "current",  "total"};

static void check_environment(const char *what, const UwmlJointEnvironmentF64 *got,
                              const UwmlJointEnvironmentF64 *want, int n, double rel) {
    double g[UWML_ROBOT_MAX_JOINTS], w[UWML_ROBOT_MAX_JOINTS];
    char label[96];
    for (int c = 0; c < 8; c++) {
        for (int i = 0; i < n; i++) {
            g[i] = environment_component(&got[i], c);
            w[i] = environment_component(&want[i], c);
        }
        snprintf(label, sizeof label, "%s joints %s", what, ENVIRONMENT_COMPONENTS[c]);
        check_values(label, g, w, n, rel);
    }
}

static UwmlJointLossParamsF32 losses_f32(const UwmlJointLossParamsF64 *p) {
    UwmlJointLossParamsF32 out = {.drive = {.torque_constant = (float)p->drive.torque_constant,
                                            .ratio = (float)p->drive.ratio,
                                            .efficiency = (float)p->drive.efficiency,
                                            .rated_current = (float)p->drive.rated_current},
                                  .oil = {.k_oil = (float)p->oil.k_oil,
                                          .exponent = (float)p->oil.exponent,
                                          .pressure_sensitivity = (float)p->oil.pressure_sensitivity,
                                          .temperature_sensitivity = (float)p->oil.temperature_sensitivity,
                                          .reference_pressure = (float)p->oil.reference_pressure,
                                          .reference_temperature = (float)p->oil.reference_temperature},
                                  .seal = {.stribeck_speed = (float)p->seal.stribeck_speed},
                                  .epsilon = (float)p->epsilon,
                                  .has_oil = p->has_oil,
                                  .has_seal = p->has_seal};
    to_f32(p->seal.c, out.seal.c, 2);
    to_f32(p->seal.s, out.seal.s, 2);
    to_f32(p->seal.d, out.seal.d, 2);
    return out;
}

/* The arm with joint losses (uwml_robot_set_losses_*, _set_conditions_*, _clear_losses_*,
 * _environment_*) against the core's values, in double and float; the paper's robot with the
 * leg's losses against the leg API; the new functions' error paths. */
static void robot_losses(void) {
    UwmlError err;
    UwmlJointEnvironmentF64 env[ARM_JOINTS];
    UwmlBaseWrenchF64 wrench;
    int32_t code = uwml_robot_new_f64(&losses64, ARM_JOINT, ARM_JOINTS, ARM_LINK, &ARM_BASE, ARM_SEGMENT,
                                      ARM_SEGMENTS, ARM_DENSITY, ARM_GRAVITY, &err);
    check(code == UWML_OK, "uwml_robot_new_f64: the arm, for its losses");
    /* First at other conditions, then all moved to the expected ones. */
    int ok = 1;
    for (int k = 0; k < ARM_LOSSES; k++) {
        ok &= uwml_robot_set_losses_f64(&losses64, ARM_LOSS_JOINT[k], &ARM_LOSS[k], 1e6, 20.0, &err) == UWML_OK;
        ok &= err.code == UWML_OK && err.index == -1 && err.field[0] == '\0';
    }
    check(ok, "uwml_robot_set_losses_f64 on joints 0 to 3");
    code = uwml_robot_set_conditions_f64(&losses64, ARM_LOSS_PRESSURE, ARM_LOSS_TEMPERATURE, &err);
    check(code == UWML_OK, "uwml_robot_set_conditions_f64: 3000 m, 4 degC");
    code = uwml_robot_environment_f64(&losses64, &workspace64, ARM_Q, ARM_QD, ARM_QDD, ARM_JOINTS, &ARM_MOTION, &ARM_CURRENT, env,
                                      &wrench, &err);
    check(code == UWML_OK, "uwml_robot_environment_f64: vehicle moving in a current");
    check_environment("f64 arm with losses:", env, ARM_LOSSES_ENVIRONMENT, ARM_JOINTS, F64_REL);
    check_wrench("f64 arm with losses:", &wrench, &ARM_MOVING_WRENCH, F64_REL);
    int sums = 1;
    for (int i = 0; i < ARM_JOINTS; i++) {
        sums &= env[i].total == env[i].drag + env[i].added_mass + env[i].buoyancy + env[i].visc + env[i].seal;
    }
    check(sums, "f64 arm: total = drag + added mass + buoyancy + visc + seal");

    /* Float, from the same parameters rounded to float. */
    UwmlTreeJointF32 joints[ARM_JOINTS];
    UwmlBodyF32 links[ARM_JOINTS];
    UwmlRobotSegmentF32 segments[ARM_SEGMENTS];
    for (int i = 0; i < ARM_JOINTS; i++) {
        joints[i] = joint_f32(&ARM_JOINT[i]);
        links[i] = body_f32(&ARM_LINK[i]);
    }
    for (int i = 0; i < ARM_SEGMENTS; i++) {
        segments[i] = segment_f32(&ARM_SEGMENT[i]);
    }
    const UwmlBodyF32 base = body_f32(&ARM_BASE);
    const UwmlBaseMotionF32 motion = motion_f32(&ARM_MOTION);
    const UwmlCurrentF32 current = current_f32(&ARM_CURRENT);
    float q[ARM_JOINTS], qd[ARM_JOINTS], qdd[ARM_JOINTS];
    to_f32(ARM_Q, q, ARM_JOINTS);
    to_f32(ARM_QD, qd, ARM_JOINTS);
    to_f32(ARM_QDD, qdd, ARM_JOINTS);
    code = uwml_robot_new_f32(&losses32, joints, ARM_JOINTS, links, &base, segments, ARM_SEGMENTS,
                              (float)ARM_DENSITY, (float)ARM_GRAVITY, &err);
    ok = code == UWML_OK;
    for (int k = 0; k < ARM_LOSSES; k++) {
        const UwmlJointLossParamsF32 loss = losses_f32(&ARM_LOSS[k]);
        ok &= uwml_robot_set_losses_f32(&losses32, ARM_LOSS_JOINT[k], &loss, (float)ARM_LOSS_PRESSURE,
                                        (float)ARM_LOSS_TEMPERATURE, &err) == UWML_OK;
    }
    check(ok, "uwml_robot_new_f32, uwml_robot_set_losses_f32: the arm with losses in float");
    UwmlJointEnvironmentF32 env32[ARM_JOINTS];
    UwmlBaseWrenchF32 wrench32;
    code = uwml_robot_environment_f32(&losses32, &workspace32, q, qd, qdd, ARM_JOINTS, &motion, &current, env32, &wrench32, &err);
    check(code == UWML_OK, "uwml_robot_environment_f32");
    for (int i = 0; i < ARM_JOINTS; i++) {
        env[i] = (UwmlJointEnvironmentF64){env32[i].drag, env32[i].added_mass, env32[i].buoyancy, env32[i].gravity,
                                           env32[i].visc, env32[i].seal,       env32[i].current,  env32[i].total};
    }
    wrench = wrench_f64(&wrench32);
    check_environment("f32 arm with losses:", env, ARM_LOSSES_ENVIRONMENT, ARM_JOINTS, F32_REL);
    check_wrench("f32 arm with losses:", &wrench, &ARM_MOVING_WRENCH, F32_REL);

    /* Clearing every joint gives uwml_robot_hydro_f64's forces and no loss. */
    ok = 1;
    for (uint32_t i = 0; i < ARM_JOINTS; i++) {
        ok &= uwml_robot_clear_losses_f64(&losses64, i, &err) == UWML_OK;
    }
    code = uwml_robot_environment_f64(&losses64, &workspace64, ARM_Q, ARM_QD, ARM_QDD, ARM_JOINTS, &ARM_MOTION, &ARM_CURRENT, env,
                                      NULL, NULL);
    for (int i = 0; i < ARM_JOINTS; i++) {
        ok &= env[i].visc == 0.0 && env[i].seal == 0.0 && env[i].current == 0.0;
        ok &= fabs(env[i].total - ARM_MOVING_FORCES[i].total) <= F64_REL * fabs(ARM_MOVING_FORCES[0].total);
    }
    check(code == UWML_OK && ok, "uwml_robot_clear_losses_f64: every joint cleared, the hydrodynamic forces alone");

    /* The paper's leg with losses: the losses are the joints' own, evaluated at their speeds;
     * the forces those of uwml_robot_hydro_f64. */
    UwmlJointLossParamsF64 defaults;
    check(uwml_robot_default_losses_f64(&defaults) == UWML_OK, "uwml_robot_default_losses_f64");
    double pressure;
    ok = uwml_robot_paper_leg_f64(&paper_losses64) == UWML_OK;
    ok &= uwml_pressure_at_depth_f64(1000.0, 1025.0, 9.81, &pressure, &err) == UWML_OK;
    for (uint32_t i = 1; i < 3; i++) {
        ok &= uwml_robot_set_losses_f64(&paper_losses64, i, &defaults, pressure, 4.0, &err) == UWML_OK;
    }
    check(ok, "the paper's leg, losses on joints 1 and 2 at 1000 m");
    UwmlJointEnvironmentF64 robot_env[PAPER_JOINTS];
    UwmlJointForcesF64 paper_forces[PAPER_JOINTS];
    ok = uwml_robot_environment_f64(&paper_losses64, &workspace64, PAPER_Q, PAPER_QD, PAPER_QDD, PAPER_JOINTS, NULL,
                                    NULL, robot_env, NULL, &err) == UWML_OK;
    ok &= uwml_robot_hydro_f64(&paper_losses64, &workspace64, PAPER_Q, PAPER_QD, PAPER_QDD, PAPER_JOINTS, NULL, NULL,
                               paper_forces, NULL, &err) == UWML_OK;
    for (int i = 0; i < 3; i++) {
        ok &= robot_env[i].drag == paper_forces[i].drag && robot_env[i].buoyancy == paper_forces[i].buoyancy;
        ok &= robot_env[i].total == (paper_forces[i].total + robot_env[i].visc) + robot_env[i].seal;
    }
    check(ok && robot_env[1].visc < 0.0 && robot_env[2].seal != 0.0 && robot_env[0].current == 0.0,
          "f64 paper leg with losses: the forces plus the joints' losses");

    /* Errors. */
    UwmlJointLossParamsF64 bad = ARM_LOSS[1];
    bad.seal.s[0] = 0.0;
    code = uwml_robot_set_losses_f64(&losses64, 2, &bad, 1e6, 20.0, &err);
    check_error("seal breakaway below its running level", code, &err, UWML_ERR_OUT_OF_ORDER, 2, "seal.s0");
    bad = ARM_LOSS[1];
    bad.oil.exponent = 3.0;
    code = uwml_robot_set_losses_f64(&losses64, 4, &bad, 1e6, 20.0, &err);
    check_error("oil exponent 3", code, &err, UWML_ERR_OUT_OF_RANGE, 4, "oil.exponent (1 to 2)");
    code = uwml_robot_set_losses_f64(&losses64, ARM_JOINTS, &ARM_LOSS[1], 1e6, 20.0, &err);
    check_error("joint 6 of 6", code, &err, UWML_ERR_INDEX_OUT_OF_RANGE, ARM_JOINTS, "joint_index");
    code = uwml_robot_clear_losses_f64(&losses64, 16, &err);
    check_error("clear joint 16", code, &err, UWML_ERR_INDEX_OUT_OF_RANGE, 16, "joint_index");
    code = uwml_robot_set_losses_f64(&losses64, 1, NULL, 1e6, 20.0, &err);
    check_error("params = NULL", code, &err, UWML_ERR_NULL_POINTER, -1, "params");
    code = uwml_robot_set_losses_f64(&losses64, 1, &ARM_LOSS[1], -1.0, 20.0, &err);
    check_error("negative pressure", code, &err, UWML_ERR_NEGATIVE, -1, "pressure_pa");
    code = uwml_robot_set_conditions_f64(&losses64, 1.3e8, 4.0, &err);
    check_error("pressure beyond the deepest ocean", code, &err, UWML_ERR_BEYOND_DEEPEST_OCEAN, -1, "pressure_pa");
    code = uwml_robot_set_conditions_f64(&losses64, 1e6, -300.0, &err);
    check_error("-300 degC", code, &err, UWML_ERR_BELOW_ABSOLUTE_ZERO, -1, "temperature_c");
    code = uwml_robot_set_conditions_f64(&losses64, NAN, 4.0, &err);
    check_error("NaN pressure", code, &err, UWML_ERR_NON_FINITE, -1, "pressure_pa");
    code = uwml_pressure_at_depth_f64(12000.0, 1025.0, 9.81, &pressure, &err);
    check_error("12000 m", code, &err, UWML_ERR_BEYOND_DEEPEST_OCEAN, -1, "depth");
    code = uwml_pressure_at_depth_f64(-5.0, 1025.0, 9.81, &pressure, &err);
    check_error("-5 m", code, &err, UWML_ERR_NEGATIVE, -1, "depth");
    code = uwml_robot_set_conditions_f64(NULL, 1e6, 4.0, &err);
    check_error("robot = NULL", code, &err, UWML_ERR_NULL_POINTER, -1, "robot");
    code = uwml_robot_clear_losses_f64(&never_initialized, 0, &err);
    check_error("zeroed robot", code, &err, UWML_ERR_UNINITIALIZED, -1, "robot");
    code = uwml_robot_environment_f64(&losses64, &workspace64, ARM_Q, ARM_QD, ARM_QDD, ARM_JOINTS, NULL, NULL, NULL, NULL, &err);
    check_error("joint_environment = NULL", code, &err, UWML_ERR_NULL_POINTER, -1, "joint_environment");
    double fast[ARM_JOINTS];
    memcpy(fast, ARM_QD, sizeof fast);
    fast[1] = 1e200;
    code = uwml_robot_environment_f64(&losses64, &workspace64, ARM_Q, fast, ARM_QDD, ARM_JOINTS, NULL, NULL, env, NULL, &err);
    check_error("a speed of 1e200 rad/s", code, &err, UWML_ERR_OVERFLOW, 0, "total");
}

/* --- docs/firmware.md: robot */
static UwmlRobotF32 robot;         /* the model: built once, then only read (static storage: no heap) */
static UwmlWorkspaceF32 workspace; /* what an evaluation writes: one per task that evaluates */

int robot_init(void) {
    /* A vehicle (base body and hull) with a turret and a sliding arm. */
    static const UwmlTreeJointF32 joints[2] = {
        {.parent = UWML_BASE, .kind = UWML_JOINT_REVOLUTE, .origin = {0.4f, 0.0f, -0.25f}, .axis = {0.0f, 0.0f, 1.0f}},
        {.parent = 0, .kind = UWML_JOINT_PRISMATIC, .origin = {0.0f, 0.0f, -0.1f}, .axis = {1.0f, 0.0f, 0.0f}},
    };
    static const UwmlBodyF32 links[2] = {
        {.mass = 3.0f, .com = {0.0f, 0.0f, -0.05f}, .volume = 0.0012f, .cob = {0.0f, 0.0f, -0.04f}},
        {.mass = 1.5f, .com = {0.2f, 0.0f, 0.0f}, .volume = 0.0008f, .cob = {0.2f, 0.0f, 0.0f}},
    };
    static const UwmlBodyF32 vehicle = {
        .mass = 140.0f, .com = {0.0f, 0.0f, -0.06f}, .volume = 0.142f, .cob = {0.0f, 0.0f, 0.05f}};
    static const UwmlRobotSegmentF32 segments[3] = {
        {.owner = UWML_BASE, .section = UWML_SECTION_CIRCULAR, .start = {-0.7f, 0.0f, 0.0f},
         .axis = {1.0f, 0.0f, 0.0f}, .length = 1.4f, .area = 0.196f, .diameter = 0.5f,
         .cd = {0.9f, 0.9f}, .cm = {1.0f, 1.0f}},
        {.owner = 0, .section = UWML_SECTION_CIRCULAR, .axis = {0.0f, 0.0f, -1.0f}, .length = 0.1f,
         .area = 0.0113f, .diameter = 0.12f, .cd = {1.1f, 1.1f}, .cm = {1.0f, 1.0f}},
        {.owner = 1, .section = UWML_SECTION_RECTANGULAR, .axis = {1.0f, 0.0f, 0.0f}, .length = 0.4f,
         .area = 0.008f, .normals = {{0.0f, 1.0f, 0.0f}, {0.0f, 0.0f, 1.0f}}, .widths = {0.08f, 0.1f},
         .cd = {1.9f, 2.1f}, .cm = {0.9f, 1.1f}},
    };
    UwmlError err;
    if (uwml_robot_new_f32(&robot, joints, 2, links, &vehicle, segments, 3, 1025.0f, 9.81f, &err) != UWML_OK) {
        /* err.code, err.index (joint, link or segment), err.field, e.g. "segment.diameter" */
        return -1;
    }
    return uwml_robot_workspace_init_f32(&workspace) == UWML_OK ? 0 : -1;
}

/* Every control period, with the vehicle's attitude and twist from its navigation filter. */
int control_step(const float q[2], const float qd[2], const float qdd[2], const UwmlBaseMotionF32 *vehicle_motion,
                 const UwmlCurrentF32 *current, float tau_ff[2], float on_vehicle[6]) {
    UwmlJointForcesF32 forces[2];
    UwmlBaseWrenchF32 wrench;
    int32_t code =
        uwml_robot_hydro_f32(&robot, &workspace, q, qd, qdd, 2, vehicle_motion, current, forces, &wrench, NULL);
    for (int i = 0; i < 2; i++) {
        tau_ff[i] = -forces[i].total; /* the joint's motor supplies -total */
    }
    for (int k = 0; k < 6; k++) {
        /* water and gravity on the whole robot: force, moment about the vehicle's origin */
        on_vehicle[k] = wrench.total[k] + wrench.gravity[k];
    }
    return code; /* UWML_ERR_NON_FINITE for a NaN state; base.orientation not unit; ... */
}
/* --- end */

/* --- docs/firmware.md: robot losses */
#include <stddef.h> /* NULL */
#include "uwml.h"

extern UwmlRobotF32 robot;         /* the robot of robot_init() above */
extern UwmlWorkspaceF32 workspace; /* and its workspace */

/* Once, after robot_init(): the turret's drive is oil-filled and sealed. */
int robot_losses_init(float depth_m, float oil_temperature_c) {
    UwmlError err;
    UwmlJointLossParamsF32 turret;
    float p;
    uwml_robot_default_losses_f32(&turret); /* or your fitted parameters */
    if (uwml_pressure_at_depth_f32(depth_m, 1025.0f, 9.81f, &p, &err) != UWML_OK) return -1; /* 0-11000 m */
    if (uwml_robot_set_losses_f32(&robot, 0, &turret, p, oil_temperature_c, &err) != UWML_OK) {
        /* err.index (the joint), err.field, e.g. "seal.s0", "joint_index", "temperature_c" */
        return -1;
    }
    return 0;
}

/* When the depth or the oil temperature changes (a dive, a thermocline). */
int robot_conditions(float depth_m, float oil_temperature_c) {
    float p;
    if (uwml_pressure_at_depth_f32(depth_m, 1025.0f, 9.81f, &p, NULL) != UWML_OK) return -1;
    return uwml_robot_set_conditions_f32(&robot, p, oil_temperature_c, NULL) == UWML_OK ? 0 : -1;
}

/* Every control period: hydrodynamics and joint losses. */
int control_step_with_losses(const float q[2], const float qd[2], const float qdd[2],
                             const UwmlBaseMotionF32 *vehicle_motion, const UwmlCurrentF32 *current,
                             float tau_ff[2], float loss_current[2]) {
    UwmlJointEnvironmentF32 joints[2];
    int32_t code =
        uwml_robot_environment_f32(&robot, &workspace, q, qd, qdd, 2, vehicle_motion, current, joints, NULL, NULL);
    for (int i = 0; i < 2; i++) {
        tau_ff[i] = -joints[i].total;        /* water, oil drag and seal: the motor supplies -total */
        loss_current[i] = joints[i].current; /* [A], signed like the motion */
    }
    return code;
}
/* --- end */

static void doc_example(void) {
    check(robot_init() == 0, "docs/firmware.md: robot_init");
    const float q[2] = {0.3f, 0.1f}, qd[2] = {0.5f, -0.2f}, qdd[2] = {0.0f, 0.0f};
    const UwmlBaseMotionF32 motion = {.orientation = {1.0f, 0.0f, 0.0f, 0.0f}, .velocity = {0.5f, 0.0f, 0.0f}};
    const UwmlCurrentF32 current = {.velocity = {0.0f, 0.2f, 0.0f}};
    float tau[2], on_vehicle[6];
    int32_t code = control_step(q, qd, qdd, &motion, &current, tau, on_vehicle);
    check(code == UWML_OK && isfinite(tau[0]) && isfinite(tau[1]) && on_vehicle[0] < 0.0f && on_vehicle[2] > 0.0f,
          "docs/firmware.md: control_step (surge drag backwards, net buoyancy up)");

    float with_losses[2], loss_current[2];
    check(robot_losses_init(1000.0f, 4.0f) == 0, "docs/firmware.md: robot_losses_init at 1000 m, 4 degC");
    code = control_step_with_losses(q, qd, qdd, &motion, &current, with_losses, loss_current);
    check(code == UWML_OK && loss_current[0] > 0.0f && loss_current[1] == 0.0f && with_losses[0] > tau[0] &&
              with_losses[1] == tau[1],
          "docs/firmware.md: control_step_with_losses (the turret's losses oppose its motion)");
    const float shallow_current = loss_current[0];
    check(robot_conditions(6000.0f, 2.0f) == 0, "docs/firmware.md: robot_conditions at 6000 m, 2 degC");
    code = control_step_with_losses(q, qd, qdd, &motion, &current, with_losses, loss_current);
    check(code == UWML_OK && loss_current[0] > shallow_current, "deeper and colder: more loss current");
    check(robot_conditions(12000.0f, 2.0f) == -1, "docs/firmware.md: robot_conditions refuses 12000 m");
}

int main(void) {
    check(uwml_robot_workspace_init_f64(&workspace64) == UWML_OK && uwml_robot_workspace_init_f32(&workspace32) == UWML_OK,
          "uwml_robot_workspace_init_f64, _f32");
    robot_losses();
    doc_example();
    printf("%d failed\n", failures);
    return failures == 0 ? 0 : 1;
}
