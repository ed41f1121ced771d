/*
 * The C API end to end on the paper's leg, as firmware would use it (static storage, no malloc):
 * the preset (uwml_robot_paper_leg_*) in double and float against the reference values of the
 * model spec (docs/model.md section 5: rho = 1000, g = 9.81, Cd = 2.2, Cm = 0.5), the same leg
 * built from plain structs, the model read only by the evaluations (two workspaces, the robot's
 * bytes unchanged), other water and coefficients, joint losses, and the error paths. Prints every
 * check; exits non-zero if any fails.
 *
 * Built and run by tests/c_program.rs:
 *   cc -std=c11 -Wall -Wextra -Werror -pedantic -I include tests/c/paper_leg.c libuwml_ffi.a -lm ...
 */
#include "uwml.h"

#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <string.h>

static int failures = 0;

static void check(int ok, const char *what) {
    printf("%s %s\n", ok ? "ok  " : "FAIL", what);
    if (!ok) {
        failures++;
    }
}

/* |got - want| <= abs_tol + rel_tol |want| (NaN fails). */
static void check_close(const char *what, int joint, double got, double want, double rel_tol, double abs_tol) {
    double tol = abs_tol + rel_tol * fabs(want);
    int ok = fabs(got - want) <= tol;
    printf("%s %-18s joint %d: %+.9g (reference %+.9g, tolerance %.1e)\n", ok ? "ok  " : "FAIL", what, joint + 1,
           got, want, tol);
    if (!ok) {
        failures++;
    }
}

static void check_error(const char *what, int32_t code, const UwmlError *e, int32_t want_code, int64_t want_index,
                        const char *want_field) {
    int ok = code == want_code && e->code == want_code && e->index == want_index && strcmp(e->field, want_field) == 0;
    printf("%s %s: code %d (%s), index %lld, field \"%s\" (expected %d, %lld, \"%s\")\n", ok ? "ok  " : "FAIL", what,
           (int)code, uwml_error_message(code), (long long)e->index, e->field, (int)want_code, (long long)want_index,
           want_field);
    if (!ok) {
        failures++;
    }
}

/* docs/model.md section 5: the state and the published torques (7 significant digits). */
static const double Q[3] = {0.3, -0.4, 0.6};
static const double QD[3] = {0.8, 0.5, -0.7};
static const double QDD[3] = {1.0, -2.0, 0.5};
static const double DRAG[3] = {-24.24084, -5.060505, -0.7383118};
static const double ADDED_MASS[3] = {-8.525438, 21.77596, 9.484545};
static const double BUOYANCY[3] = {0.0, 59.72457, 4.193843};

/* Tolerances: half a unit of the last printed digit of each reference value (joint 1's
 * buoyancy is exactly 0: its axis is vertical); float adds its own rounding over about a
 * hundred operations on values of order 10. */
static const double DRAG_HALF_UNIT[3] = {5e-6, 5e-7, 5e-8};
static const double ADDED_MASS_HALF_UNIT[3] = {5e-7, 5e-6, 5e-7};
static const double BUOYANCY_HALF_UNIT[3] = {1e-12, 5e-6, 5e-7};
#define F64_REL 0.0
#define F32_REL 2e-5

static void check_reference(const char *precision, const double drag[3], const double added_mass[3],
                            const double buoyancy[3], double rel) {
    char what[64];
    for (int i = 0; i < 3; i++) {
        snprintf(what, sizeof what, "%s drag", precision);
        check_close(what, i, drag[i], DRAG[i], rel, DRAG_HALF_UNIT[i]);
        snprintf(what, sizeof what, "%s added mass", precision);
        check_close(what, i, added_mass[i], ADDED_MASS[i], rel, ADDED_MASS_HALF_UNIT[i]);
        snprintf(what, sizeof what, "%s buoyancy", precision);
        check_close(what, i, buoyancy[i], BUOYANCY[i], rel, BUOYANCY_HALF_UNIT[i]);
    }
}

/* Table II of the paper as plain structs (link density 2700 kg/m^3, volume = mass / 2700). */
static const UwmlTreeJointF64 JOINTS[3] = {
    {.parent = UWML_BASE, .kind = UWML_JOINT_REVOLUTE, .axis = {0.0, 0.0, 1.0}},
    {.parent = 0, .kind = UWML_JOINT_REVOLUTE, .axis = {0.0, -1.0, 0.0}},
    {.parent = 1, .kind = UWML_JOINT_REVOLUTE, .origin = {0.660, 0.0, 0.0}, .axis = {0.0, -1.0, 0.0}},
};
static const UwmlBodyF64 LINKS[3] = {
    {.mass = 10.758, .volume = 10.758 / 2700.0},
    {.mass = 19.261, .com = {0.506, 0.0, 0.0}, .volume = 19.261 / 2700.0, .cob = {0.506, 0.0, 0.0}},
    {.mass = 10.375, .com = {0.0, 0.0, -0.560}, .volume = 10.375 / 2700.0, .cob = {0.0, 0.0, -0.560}},
};
static const UwmlRobotSegmentF64 SEGMENTS[2] = {
    {.owner = 1, .section = UWML_SECTION_RECTANGULAR, .axis = {1.0, 0.0, 0.0}, .length = 0.660,
     .area = 0.131 * 0.238, .normals = {{0.0, 1.0, 0.0}, {0.0, 0.0, 1.0}}, .widths = {0.131, 0.238},
     .cd = {2.2, 2.2}, .cm = {0.5, 0.5}},
    {.owner = 2, .section = UWML_SECTION_RECTANGULAR, .axis = {0.0, 0.0, -1.0}, .length = 0.714,
     .area = 0.131 * 0.279, .normals = {{0.0, 1.0, 0.0}, {1.0, 0.0, 0.0}}, .widths = {0.131, 0.279},
     .cd = {2.2, 2.2}, .cm = {0.5, 0.5}},
};

/* Static storage, as in firmware: the models, and the workspaces the evaluations write. */
static UwmlRobotF64 leg64;
static UwmlRobotF64 built64;
static UwmlRobotF64 copy64;
static UwmlRobotF64 never_initialized;
static UwmlRobotF32 leg32;
static UwmlWorkspaceF64 workspace64;
static UwmlWorkspaceF64 other_workspace64;
static UwmlWorkspaceF64 never_initialized_workspace;
static UwmlWorkspaceF32 workspace32;

static void print_sizes(void) {
#define SIZE(T) printf("size %s %zu %zu\n", #T, sizeof(T), _Alignof(T))
    SIZE(UwmlError);
    SIZE(UwmlDriveParamsF64);
    SIZE(UwmlOilParamsF64);
    SIZE(UwmlSealParamsF64);
    SIZE(UwmlJointLossParamsF64);
    SIZE(UwmlWorkspaceF64);
    SIZE(UwmlDriveParamsF32);
    SIZE(UwmlOilParamsF32);
    SIZE(UwmlSealParamsF32);
    SIZE(UwmlJointLossParamsF32);
    SIZE(UwmlWorkspaceF32);
#undef SIZE
    printf("offset UwmlError.field %zu\n", offsetof(UwmlError, field));
    printf("offset UwmlJointLossParamsF64.has_seal %zu\n", offsetof(UwmlJointLossParamsF64, has_seal));
    printf("offset UwmlJointLossParamsF32.has_seal %zu\n", offsetof(UwmlJointLossParamsF32, has_seal));
}

/* The leg's environment at (q, qd, qdd) on a fixed base in still water. */
static int32_t environment64(const UwmlRobotF64 *robot, UwmlWorkspaceF64 *workspace, const double q[3],
                             const double qd[3], const double qdd[3], UwmlJointEnvironmentF64 out[3], UwmlError *err) {
    return uwml_robot_environment_f64(robot, workspace, q, qd, qdd, 3, NULL, NULL, out, NULL, err);
}

static void paper_f64(void) {
    UwmlError err;
    UwmlJointEnvironmentF64 env[3];
    check(uwml_robot_paper_leg_f64(&leg64) == UWML_OK, "uwml_robot_paper_leg_f64");
    check(uwml_robot_workspace_init_f64(&workspace64) == UWML_OK, "uwml_robot_workspace_init_f64");
    check(environment64(&leg64, &workspace64, Q, QD, QDD, env, &err) == UWML_OK && err.code == UWML_OK,
          "uwml_robot_environment_f64");
    double drag[3], added_mass[3], buoyancy[3];
    int no_losses = 1;
    for (int i = 0; i < 3; i++) {
        drag[i] = env[i].drag;
        added_mass[i] = env[i].added_mass;
        buoyancy[i] = env[i].buoyancy;
        no_losses &= env[i].visc == 0.0 && env[i].seal == 0.0 && env[i].current == 0.0;
        no_losses &= env[i].total == env[i].drag + env[i].added_mass + env[i].buoyancy;
    }
    check_reference("f64", drag, added_mass, buoyancy, F64_REL);
    check(no_losses, "f64 paper preset: no losses, total = drag + added mass + buoyancy");

    UwmlJointForcesF64 hydro[3];
    check(uwml_robot_hydro_f64(&leg64, &workspace64, Q, QD, QDD, 3, NULL, NULL, hydro, NULL, NULL) == UWML_OK,
          "uwml_robot_hydro_f64");
    int same = 1;
    for (int i = 0; i < 3; i++) {
        same &= hydro[i].drag == env[i].drag && hydro[i].total == env[i].total;
    }
    check(same, "f64 hydro equals environment without losses");

    /* The same leg from plain structs gives the same forces, bit for bit. */
    UwmlJointEnvironmentF64 built[3];
    check(uwml_robot_new_f64(&built64, JOINTS, 3, LINKS, NULL, SEGMENTS, 2, 1000.0, 9.81, &err) == UWML_OK,
          "uwml_robot_new_f64 (Table II)");
    check(environment64(&built64, &workspace64, Q, QD, QDD, built, NULL) == UWML_OK &&
              memcmp(built, env, sizeof env) == 0,
          "f64 leg from plain structs equals the paper preset");

    /* The model is only read: a second workspace gives the same bits, and the robot's bytes are
     * what they were before the evaluations. */
    memcpy(&copy64, &leg64, sizeof leg64);
    UwmlJointEnvironmentF64 other[3];
    check(uwml_robot_workspace_init_f64(&other_workspace64) == UWML_OK, "a second workspace");
    check(environment64(&leg64, &other_workspace64, Q, QD, QDD, other, NULL) == UWML_OK &&
              environment64(&leg64, &workspace64, QDD, QD, Q, built, NULL) == UWML_OK &&
              memcmp(other, env, sizeof env) == 0,
          "two workspaces, one robot: the same forces");
    check(memcmp(&copy64, &leg64, sizeof leg64) == 0, "evaluations leave the robot as it was");
}

static void paper_f32(void) {
    static const float q[3] = {0.3f, -0.4f, 0.6f};
    static const float qd[3] = {0.8f, 0.5f, -0.7f};
    static const float qdd[3] = {1.0f, -2.0f, 0.5f};
    UwmlError err;
    UwmlJointForcesF32 forces[3];
    check(uwml_robot_paper_leg_f32(&leg32) == UWML_OK, "uwml_robot_paper_leg_f32");
    check(uwml_robot_workspace_init_f32(&workspace32) == UWML_OK, "uwml_robot_workspace_init_f32");
    check(uwml_robot_hydro_f32(&leg32, &workspace32, q, qd, qdd, 3, NULL, NULL, forces, NULL, &err) == UWML_OK,
          "uwml_robot_hydro_f32");
    double drag[3], added_mass[3], buoyancy[3];
    for (int i = 0; i < 3; i++) {
        drag[i] = forces[i].drag;
        added_mass[i] = forces[i].added_mass;
        buoyancy[i] = forces[i].buoyancy;
    }
    check_reference("f32", drag, added_mass, buoyancy, F32_REL);
}

static void water_and_coefficients(void) {
    UwmlError err;
    UwmlJointEnvironmentF64 before[3], after[3];
    check(environment64(&built64, &workspace64, Q, QD, QDD, before, NULL) == UWML_OK, "before the setters");
    /* The segments' own coefficients again: nothing changes. */
    const double cd[2][2] = {{2.2, 2.2}, {2.2, 2.2}};
    const double cm[2][2] = {{0.5, 0.5}, {0.5, 0.5}};
    check(uwml_robot_set_coefficients_f64(&built64, cd, cm, 2, &err) == UWML_OK, "uwml_robot_set_coefficients_f64");
    check(environment64(&built64, &workspace64, Q, QD, QDD, after, NULL) == UWML_OK &&
              memcmp(before, after, sizeof after) == 0,
          "the same coefficients give the same forces");
    /* Twice the drag coefficients: twice the drag, the same added mass. */
    const double twice[2][2] = {{4.4, 4.4}, {4.4, 4.4}};
    check(uwml_robot_set_coefficients_f64(&built64, twice, cm, 2, &err) == UWML_OK, "Cd 4.4");
    check(environment64(&built64, &workspace64, Q, QD, QDD, after, NULL) == UWML_OK, "environment at Cd 4.4");
    for (int i = 0; i < 3; i++) {
        check_close("drag at Cd 4.4", i, after[i].drag, 2.0 * before[i].drag, 1e-12, 1e-300);
        check_close("added mass at Cd 4.4", i, after[i].added_mass, before[i].added_mass, 0.0, 0.0);
    }
    /* Sea water: buoyancy in proportion. */
    check(uwml_robot_set_water_f64(&built64, 1025.0, 9.81, &err) == UWML_OK, "uwml_robot_set_water_f64");
    check(environment64(&built64, &workspace64, Q, QD, QDD, after, NULL) == UWML_OK, "environment in sea water");
    for (int i = 1; i < 3; i++) {
        check_close("buoyancy at 1025 kg/m^3", i, after[i].buoyancy, 1.025 * before[i].buoyancy, 1e-12, 0.0);
    }
    /* Refused: nothing changes. */
    const double negative[2][2] = {{2.2, 2.2}, {-1.0, 2.2}};
    int32_t code = uwml_robot_set_coefficients_f64(&built64, negative, cm, 2, &err);
    check_error("a negative Cd of segment 1", code, &err, UWML_ERR_NEGATIVE, 1, "segment.cd");
    code = uwml_robot_set_coefficients_f64(&built64, cd, cm, 3, &err);
    check_error("three segments for two", code, &err, UWML_ERR_OUT_OF_RANGE, -1, "n_segments (the robot's segment count)");
    code = uwml_robot_set_coefficients_f64(&built64, NULL, cm, 2, &err);
    check_error("cd = NULL", code, &err, UWML_ERR_NULL_POINTER, -1, "cd");
    code = uwml_robot_set_water_f64(&built64, 0.0, 9.81, &err);
    check_error("zero water density", code, &err, UWML_ERR_NON_POSITIVE, -1, "water.density");
    UwmlJointEnvironmentF64 still[3];
    check(environment64(&built64, &workspace64, Q, QD, QDD, still, NULL) == UWML_OK &&
              memcmp(still, after, sizeof after) == 0,
          "failed setters change nothing");
    const float cd32[2][2] = {{2.2f, 2.2f}, {2.2f, 2.2f}};
    const float cm32[2][2] = {{0.5f, 0.5f}, {0.5f, 0.5f}};
    check(uwml_robot_set_coefficients_f32(&leg32, cd32, cm32, 2, NULL) == UWML_OK &&
              uwml_robot_set_water_f32(&leg32, 1000.0f, 9.81f, NULL) == UWML_OK,
          "uwml_robot_set_coefficients_f32, uwml_robot_set_water_f32");
}

static void losses(void) {
    /* The default losses at 10 r/min and 10 MPa, 20 degC: 2.85 A (27.4 % of 10.4 A), the
     * figure the defaults are tuned to (docs/losses.md, "The defaults are illustrative"; printed
     * to 3 digits). */
    UwmlError err;
    UwmlJointLossParamsF64 params;
    check(uwml_robot_default_losses_f64(&params) == UWML_OK, "uwml_robot_default_losses_f64");
    check(uwml_robot_set_losses_f64(&leg64, 1, &params, 10e6, 20.0, &err) == UWML_OK, "uwml_robot_set_losses_f64");
    const double speed = 10.0 * 2.0 * 3.14159265358979323846 / 60.0;
    const double qd[3] = {0.0, speed, 0.0};
    const double zeros[3] = {0.0, 0.0, 0.0};
    UwmlJointEnvironmentF64 env[3];
    check(environment64(&leg64, &workspace64, Q, qd, zeros, env, &err) == UWML_OK, "environment with losses");
    check_close("loss current [A]", 1, env[1].current, 2.85, 0.0, 0.005);
    check(env[1].visc < 0.0 && env[1].seal < 0.0, "losses oppose motion");
    check(env[0].current == 0.0 && env[2].current == 0.0, "joints without losses have none");
    check(fabs(env[1].total - (env[1].drag + env[1].added_mass + env[1].buoyancy + env[1].visc + env[1].seal)) <= 1e-12,
          "total = hydro + visc + seal");

    /* Deeper: more seal friction. */
    double shallow_seal = env[1].seal;
    double deep = -1.0;
    check(uwml_pressure_at_depth_f64(2000.0, 1025.0, 9.81, &deep, &err) == UWML_OK && deep == 1025.0 * 9.81 * 2000.0,
          "uwml_pressure_at_depth_f64 (2 km)");
    check(uwml_robot_set_conditions_f64(&leg64, deep, 4.0, &err) == UWML_OK,
          "uwml_robot_set_conditions_f64 (2 km, 4 degC)");
    check(environment64(&leg64, &workspace64, Q, qd, zeros, env, NULL) == UWML_OK && env[1].seal < shallow_seal,
          "more seal friction at 2 km than at 10 MPa");
    check(uwml_robot_clear_losses_f64(&leg64, 1, &err) == UWML_OK, "uwml_robot_clear_losses_f64");
    check(environment64(&leg64, &workspace64, Q, qd, zeros, env, NULL) == UWML_OK && env[1].current == 0.0,
          "cleared losses");

    UwmlJointLossParamsF32 params32;
    check(uwml_robot_default_losses_f32(&params32) == UWML_OK, "uwml_robot_default_losses_f32");
    check(uwml_robot_set_losses_f32(&leg32, 1, &params32, 10e6f, 20.0f, &err) == UWML_OK, "uwml_robot_set_losses_f32");
    const float qd32[3] = {0.0f, (float)speed, 0.0f};
    const float zeros32[3] = {0.0f, 0.0f, 0.0f};
    const float q32[3] = {0.3f, -0.4f, 0.6f};
    UwmlJointEnvironmentF32 env32[3];
    check(uwml_robot_environment_f32(&leg32, &workspace32, q32, qd32, zeros32, 3, NULL, NULL, env32, NULL, &err) ==
              UWML_OK,
          "f32 environment with losses");
    check_close("f32 loss current [A]", 1, env32[1].current, 2.85, 0.0, 0.005);
    check(uwml_robot_clear_losses_f32(&leg32, 1, NULL) == UWML_OK, "uwml_robot_clear_losses_f32");
}

static void errors(void) {
    UwmlError err;
    UwmlJointEnvironmentF64 env[3];
    UwmlBodyF64 links[3];
    memcpy(links, LINKS, sizeof links);
    links[2].volume = -1e-3;
    memset(&copy64, 0xAB, sizeof copy64);
    int32_t code = uwml_robot_new_f64(&copy64, JOINTS, 3, links, NULL, SEGMENTS, 2, 1000.0, 9.81, &err);
    check_error("negative volume of link 2 (0-based)", code, &err, UWML_ERR_NEGATIVE, 2, "link.volume");
    check(environment64(&copy64, &workspace64, Q, QD, QDD, env, NULL) == UWML_ERR_UNINITIALIZED,
          "a failed construction leaves the robot unwritten");

    check(uwml_robot_paper_leg_f64(NULL) == UWML_ERR_NULL_POINTER, "uwml_robot_paper_leg_f64(NULL)");
    check(uwml_robot_workspace_init_f64(NULL) == UWML_ERR_NULL_POINTER, "uwml_robot_workspace_init_f64(NULL)");
    code = environment64(&leg64, &workspace64, NULL, QD, QDD, env, &err);
    check_error("q = NULL", code, &err, UWML_ERR_NULL_POINTER, -1, "q");
    code = environment64(NULL, &workspace64, Q, QD, QDD, env, &err);
    check_error("robot = NULL", code, &err, UWML_ERR_NULL_POINTER, -1, "robot");
    code = environment64(&leg64, NULL, Q, QD, QDD, env, &err);
    check_error("workspace = NULL", code, &err, UWML_ERR_NULL_POINTER, -1, "workspace");
    code = environment64(&leg64, &workspace64, Q, QD, QDD, NULL, &err);
    check_error("joint_environment = NULL", code, &err, UWML_ERR_NULL_POINTER, -1, "joint_environment");
    code = environment64(&never_initialized, &workspace64, Q, QD, QDD, env, &err);
    check_error("zeroed robot", code, &err, UWML_ERR_UNINITIALIZED, -1, "robot");
    code = environment64(&leg64, &never_initialized_workspace, Q, QD, QDD, env, &err);
    check_error("zeroed workspace", code, &err, UWML_ERR_UNINITIALIZED, -1, "workspace");

    const double bad_qd[3] = {0.8, NAN, -0.7};
    code = environment64(&leg64, &workspace64, Q, bad_qd, QDD, env, &err);
    check_error("NaN in qd", code, &err, UWML_ERR_NON_FINITE, 1, "qd");
    check(isnan(env[0].total), "NaN state gives NaN forces");

    UwmlJointLossParamsF64 params;
    uwml_robot_default_losses_f64(&params);
    code = uwml_robot_set_losses_f64(&leg64, 3, &params, 0.0, 20.0, &err);
    check_error("joint index 3", code, &err, UWML_ERR_INDEX_OUT_OF_RANGE, 3, "joint_index");
    code = uwml_robot_set_losses_f64(&leg64, UINT32_MAX, &params, 0.0, 20.0, &err);
    check_error("joint index UINT32_MAX", code, &err, UWML_ERR_INDEX_OUT_OF_RANGE, (int64_t)UINT32_MAX, "joint_index");
    code = uwml_robot_set_conditions_f64(&leg64, 1e7, -300.0, &err);
    check_error("below absolute zero", code, &err, UWML_ERR_BELOW_ABSOLUTE_ZERO, -1, "temperature_c");
    double pressure = -1.0;
    code = uwml_pressure_at_depth_f64(12000.0, 1025.0, 9.81, &pressure, &err);
    check_error("deeper than the ocean", code, &err, UWML_ERR_BEYOND_DEEPEST_OCEAN, -1, "depth");
    code = uwml_pressure_at_depth_f64(-5.0, 1025.0, 9.81, &pressure, &err);
    check_error("above the surface", code, &err, UWML_ERR_NEGATIVE, -1, "depth");
    check(pressure == -1.0, "a refused depth writes no pressure");
    params.seal.s[0] = params.seal.c[0] - 1.0;
    code = uwml_robot_set_losses_f64(&leg64, 2, &params, 0.0, 20.0, &err);
    check_error("seal breakaway below running", code, &err, UWML_ERR_OUT_OF_ORDER, 2, "seal.s0");

    /* The robot is unchanged by the failed setters. */
    check(environment64(&leg64, &workspace64, Q, QD, QDD, env, &err) == UWML_OK, "environment after errors");
    double drag[3], added_mass[3], buoyancy[3];
    for (int i = 0; i < 3; i++) {
        drag[i] = env[i].drag;
        added_mass[i] = env[i].added_mass;
        buoyancy[i] = env[i].buoyancy;
    }
    check_reference("f64 after errors", drag, added_mass, buoyancy, F64_REL);
}

int main(void) {
    print_sizes();
    paper_f64();
    paper_f32();
    water_and_coefficients();
    losses();
    errors();
    printf("%d failed\n", failures);
    return failures == 0 ? 0 : 1;
}
