/*
 * The C API end to end, as firmware would use it (static storage, no malloc): the paper's leg
 * in double and float against the reference values of the model spec (docs/model.md section 5:
 * rho = 1000, g = 9.81, Cd = 2.2, Cm = 0.5), the same leg built from parameters, joint losses,
 * and the error paths. Prints every check; exits non-zero if any fails.
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

/* Table II of the paper as parameters (link density 2700 kg/m^3, volume = mass / 2700). */
static void paper_params(UwmlJointParamsF64 joints[3], UwmlLinkParamsF64 links[3]) {
    static const UwmlJointParamsF64 j[3] = {
        {{0.0, 0.0, 0.0}, {0.0, 0.0, 1.0}},
        {{0.0, 0.0, 0.0}, {0.0, -1.0, 0.0}},
        {{0.660, 0.0, 0.0}, {0.0, -1.0, 0.0}},
    };
    memcpy(joints, j, sizeof j);
    memset(links, 0, 3 * sizeof links[0]);
    links[0].mass = 10.758;
    links[0].volume = 10.758 / 2700.0;
    links[0].has_segment = 0;

    links[1].mass = 19.261;
    links[1].com[0] = 0.506;
    links[1].volume = 19.261 / 2700.0;
    links[1].cob[0] = 0.506;
    links[1].has_segment = 1;
    links[1].segment.axis[0] = 1.0;
    links[1].segment.length = 0.660;
    links[1].segment.normals[0][1] = 1.0;
    links[1].segment.normals[1][2] = 1.0;
    links[1].segment.widths[0] = 0.131;
    links[1].segment.widths[1] = 0.238;
    links[1].segment.area = 0.131 * 0.238;

    links[2].mass = 10.375;
    links[2].com[2] = -0.560;
    links[2].volume = 10.375 / 2700.0;
    links[2].cob[2] = -0.560;
    links[2].has_segment = 1;
    links[2].segment.axis[2] = -1.0;
    links[2].segment.length = 0.714;
    links[2].segment.normals[0][1] = 1.0;
    links[2].segment.normals[1][0] = 1.0;
    links[2].segment.widths[0] = 0.131;
    links[2].segment.widths[1] = 0.279;
    links[2].segment.area = 0.131 * 0.279;
}

static void to_f32(const double *in, float *out, size_t n) {
    for (size_t i = 0; i < n; i++) {
        out[i] = (float)in[i];
    }
}

static void paper_params_f32(UwmlJointParamsF32 joints[3], UwmlLinkParamsF32 links[3]) {
    UwmlJointParamsF64 j[3];
    UwmlLinkParamsF64 l[3];
    paper_params(j, l);
    for (int i = 0; i < 3; i++) {
        to_f32(j[i].origin, joints[i].origin, 3);
        to_f32(j[i].axis, joints[i].axis, 3);
        links[i].mass = (float)l[i].mass;
        to_f32(l[i].com, links[i].com, 3);
        links[i].volume = (float)l[i].volume;
        to_f32(l[i].cob, links[i].cob, 3);
        to_f32(l[i].segment.start, links[i].segment.start, 3);
        to_f32(l[i].segment.axis, links[i].segment.axis, 3);
        to_f32(l[i].segment.normals[0], links[i].segment.normals[0], 3);
        to_f32(l[i].segment.normals[1], links[i].segment.normals[1], 3);
        links[i].segment.length = (float)l[i].segment.length;
        to_f32(l[i].segment.widths, links[i].segment.widths, 2);
        links[i].segment.area = (float)l[i].segment.area;
        links[i].has_segment = l[i].has_segment;
    }
}

/* Static storage, as in firmware. */
static UwmlLeg3F64 leg64;
static UwmlLeg3F64 built64;
static UwmlLeg3F64 never_initialized;
static UwmlLeg3F32 leg32;
static UwmlLeg3F32 built32;

static void print_sizes(void) {
#define SIZE(T) printf("size %s %zu %zu\n", #T, sizeof(T), _Alignof(T))
    SIZE(UwmlError);
    SIZE(UwmlLeg3F64);
    SIZE(UwmlJointParamsF64);
    SIZE(UwmlSegmentParamsF64);
    SIZE(UwmlLinkParamsF64);
    SIZE(UwmlDriveParamsF64);
    SIZE(UwmlOilParamsF64);
    SIZE(UwmlSealParamsF64);
    SIZE(UwmlJointLossParamsF64);
    SIZE(UwmlHydro3F64);
    SIZE(UwmlEnvironment3F64);
    SIZE(UwmlLeg3F32);
    SIZE(UwmlJointParamsF32);
    SIZE(UwmlSegmentParamsF32);
    SIZE(UwmlLinkParamsF32);
    SIZE(UwmlDriveParamsF32);
    SIZE(UwmlOilParamsF32);
    SIZE(UwmlSealParamsF32);
    SIZE(UwmlJointLossParamsF32);
    SIZE(UwmlHydro3F32);
    SIZE(UwmlEnvironment3F32);
#undef SIZE
    printf("offset UwmlError.field %zu\n", offsetof(UwmlError, field));
    printf("offset UwmlLinkParamsF64.segment %zu\n", offsetof(UwmlLinkParamsF64, segment));
    printf("offset UwmlLinkParamsF64.has_segment %zu\n", offsetof(UwmlLinkParamsF64, has_segment));
    printf("offset UwmlJointLossParamsF64.has_seal %zu\n", offsetof(UwmlJointLossParamsF64, has_seal));
    printf("offset UwmlLinkParamsF32.has_segment %zu\n", offsetof(UwmlLinkParamsF32, has_segment));
    printf("offset UwmlJointLossParamsF32.has_seal %zu\n", offsetof(UwmlJointLossParamsF32, has_seal));
}

static void paper_f64(void) {
    UwmlError err;
    UwmlEnvironment3F64 env;
    check(uwml_leg3_paper_f64(&leg64) == UWML_OK, "uwml_leg3_paper_f64");
    check(uwml_leg3_environment_f64(&leg64, Q, QD, QDD, &env, &err) == UWML_OK && err.code == UWML_OK,
          "uwml_leg3_environment_f64");
    check_reference("f64", env.drag, env.added_mass, env.buoyancy, F64_REL);
    int no_losses = 1;
    for (int i = 0; i < 3; i++) {
        no_losses &= env.visc[i] == 0.0 && env.seal[i] == 0.0 && env.current[i] == 0.0;
        no_losses &= env.total[i] == env.drag[i] + env.added_mass[i] + env.buoyancy[i];
    }
    check(no_losses, "f64 paper preset: no losses, total = drag + added mass + buoyancy");

    UwmlHydro3F64 hydro;
    check(uwml_leg3_hydro_f64(&leg64, Q, QD, QDD, &hydro, NULL) == UWML_OK, "uwml_leg3_hydro_f64");
    check(memcmp(hydro.drag, env.drag, sizeof hydro.drag) == 0 && memcmp(hydro.total, env.total, sizeof hydro.total) == 0,
          "f64 hydro equals environment without losses");

    /* The same leg from parameters gives the same torques, bit for bit. */
    UwmlJointParamsF64 joints[3];
    UwmlLinkParamsF64 links[3];
    paper_params(joints, links);
    UwmlEnvironment3F64 built;
    check(uwml_leg3_new_f64(joints, links, &built64, &err) == UWML_OK, "uwml_leg3_new_f64 (Table II)");
    check(uwml_leg3_environment_f64(&built64, Q, QD, QDD, &built, NULL) == UWML_OK &&
              memcmp(&built, &env, sizeof env) == 0,
          "f64 leg from parameters equals the paper preset");
}

static void paper_f32(void) {
    static const float q[3] = {0.3f, -0.4f, 0.6f};
    static const float qd[3] = {0.8f, 0.5f, -0.7f};
    static const float qdd[3] = {1.0f, -2.0f, 0.5f};
    UwmlError err;
    UwmlEnvironment3F32 env;
    check(uwml_leg3_paper_f32(&leg32) == UWML_OK, "uwml_leg3_paper_f32");
    check(uwml_leg3_environment_f32(&leg32, q, qd, qdd, &env, &err) == UWML_OK, "uwml_leg3_environment_f32");
    double drag[3], added_mass[3], buoyancy[3];
    for (int i = 0; i < 3; i++) {
        drag[i] = env.drag[i];
        added_mass[i] = env.added_mass[i];
        buoyancy[i] = env.buoyancy[i];
    }
    check_reference("f32", drag, added_mass, buoyancy, F32_REL);

    UwmlJointParamsF32 joints[3];
    UwmlLinkParamsF32 links[3];
    memset(links, 0, sizeof links);
    paper_params_f32(joints, links);
    UwmlEnvironment3F32 built;
    check(uwml_leg3_new_f32(joints, links, &built32, &err) == UWML_OK, "uwml_leg3_new_f32 (Table II)");
    check(uwml_leg3_environment_f32(&built32, q, qd, qdd, &built, NULL) == UWML_OK &&
              memcmp(&built, &env, sizeof env) == 0,
          "f32 leg from parameters equals the paper preset");
}

static void losses(void) {
    /* The default losses at 10 r/min and 10 MPa, 20 degC: 2.85 A (27.4 % of 10.4 A), the
     * figure the defaults are tuned to (docs/losses.md, "The defaults are illustrative"; printed
     * to 3 digits). */
    UwmlError err;
    UwmlJointLossParamsF64 params;
    check(uwml_leg3_default_losses_f64(&params) == UWML_OK, "uwml_leg3_default_losses_f64");
    check(uwml_leg3_set_losses_f64(&leg64, 1, &params, 10e6, 20.0, &err) == UWML_OK, "uwml_leg3_set_losses_f64");
    const double speed = 10.0 * 2.0 * 3.14159265358979323846 / 60.0;
    const double qd[3] = {0.0, speed, 0.0};
    const double zeros[3] = {0.0, 0.0, 0.0};
    UwmlEnvironment3F64 env;
    check(uwml_leg3_environment_f64(&leg64, Q, qd, zeros, &env, &err) == UWML_OK, "environment with losses");
    check_close("loss current [A]", 1, env.current[1], 2.85, 0.0, 0.005);
    check(env.visc[1] < 0.0 && env.seal[1] < 0.0, "losses oppose motion");
    check(env.current[0] == 0.0 && env.current[2] == 0.0, "joints without losses have none");
    check(fabs(env.total[1] - (env.drag[1] + env.added_mass[1] + env.buoyancy[1] + env.visc[1] + env.seal[1])) <= 1e-12,
          "total = hydro + visc + seal");

    /* Deeper: more seal friction. */
    double shallow_seal = env.seal[1];
    double deep = -1.0;
    check(uwml_pressure_at_depth_f64(2000.0, 1025.0, 9.81, &deep, &err) == UWML_OK && deep == 1025.0 * 9.81 * 2000.0,
          "uwml_pressure_at_depth_f64 (2 km)");
    check(uwml_leg3_set_conditions_f64(&leg64, deep, 4.0, &err) == UWML_OK, "uwml_leg3_set_conditions_f64 (2 km, 4 degC)");
    check(uwml_leg3_environment_f64(&leg64, Q, qd, zeros, &env, NULL) == UWML_OK && env.seal[1] < shallow_seal,
          "more seal friction at 2 km than at 10 MPa");
    check(uwml_leg3_clear_losses_f64(&leg64, 1, &err) == UWML_OK, "uwml_leg3_clear_losses_f64");
    check(uwml_leg3_environment_f64(&leg64, Q, qd, zeros, &env, NULL) == UWML_OK && env.current[1] == 0.0,
          "cleared losses");

    UwmlJointLossParamsF32 params32;
    check(uwml_leg3_default_losses_f32(&params32) == UWML_OK, "uwml_leg3_default_losses_f32");
    check(uwml_leg3_set_losses_f32(&leg32, 1, &params32, 10e6f, 20.0f, &err) == UWML_OK, "uwml_leg3_set_losses_f32");
    const float qd32[3] = {0.0f, (float)speed, 0.0f};
    const float zeros32[3] = {0.0f, 0.0f, 0.0f};
    const float q32[3] = {0.3f, -0.4f, 0.6f};
    UwmlEnvironment3F32 env32;
    check(uwml_leg3_environment_f32(&leg32, q32, qd32, zeros32, &env32, &err) == UWML_OK, "f32 environment with losses");
    check_close("f32 loss current [A]", 1, env32.current[1], 2.85, 0.0, 0.005);
    check(uwml_leg3_clear_losses_f32(&leg32, 1, NULL) == UWML_OK, "uwml_leg3_clear_losses_f32");
}

static void errors(void) {
    UwmlError err;
    UwmlJointParamsF64 joints[3];
    UwmlLinkParamsF64 links[3];
    UwmlEnvironment3F64 env;

    paper_params(joints, links);
    links[2].volume = -1e-3;
    memset(&built64, 0xAB, sizeof built64);
    int32_t code = uwml_leg3_new_f64(joints, links, &built64, &err);
    check_error("negative volume of link 2 (0-based)", code, &err, UWML_ERR_NEGATIVE, 2, "link.volume");
    check(uwml_leg3_environment_f64(&built64, Q, QD, QDD, &env, NULL) == UWML_ERR_UNINITIALIZED,
          "a failed construction leaves the leg unwritten");

    paper_params(joints, links);
    joints[1].axis[1] = -0.5;
    code = uwml_leg3_new_f64(joints, links, &built64, &err);
    check_error("non-unit axis of joint 1", code, &err, UWML_ERR_NOT_UNIT, 1, "joint.axis");

    UwmlJointParamsF32 joints32[3];
    UwmlLinkParamsF32 links32[3];
    memset(links32, 0, sizeof links32);
    paper_params_f32(joints32, links32);
    links32[1].volume = -1e-3f;
    code = uwml_leg3_new_f32(joints32, links32, &built32, &err);
    check_error("f32 negative volume of link 1", code, &err, UWML_ERR_NEGATIVE, 1, "link.volume");

    check(uwml_leg3_paper_f64(NULL) == UWML_ERR_NULL_POINTER, "uwml_leg3_paper_f64(NULL)");
    code = uwml_leg3_environment_f64(&leg64, NULL, QD, QDD, &env, &err);
    check_error("q = NULL", code, &err, UWML_ERR_NULL_POINTER, -1, "q");
    code = uwml_leg3_environment_f64(NULL, Q, QD, QDD, &env, &err);
    check_error("leg = NULL", code, &err, UWML_ERR_NULL_POINTER, -1, "leg");
    code = uwml_leg3_environment_f64(&leg64, Q, QD, QDD, NULL, &err);
    check_error("out = NULL", code, &err, UWML_ERR_NULL_POINTER, -1, "out");
    code = uwml_leg3_new_f64(joints, NULL, &built64, &err);
    check_error("links = NULL", code, &err, UWML_ERR_NULL_POINTER, -1, "links");
    code = uwml_leg3_environment_f64(&never_initialized, Q, QD, QDD, &env, &err);
    check_error("zeroed leg", code, &err, UWML_ERR_UNINITIALIZED, -1, "leg");

    const double bad_qd[3] = {0.8, NAN, -0.7};
    code = uwml_leg3_environment_f64(&leg64, Q, bad_qd, QDD, &env, &err);
    check_error("NaN in qd", code, &err, UWML_ERR_NON_FINITE, 1, "qd");
    check(isnan(env.total[0]), "NaN state gives NaN torques");

    code = uwml_leg3_set_water_f64(&leg64, 0.0, 9.81, &err);
    check_error("zero water density", code, &err, UWML_ERR_NON_POSITIVE, -1, "water.density");
    code = uwml_leg3_set_coefficients_f64(&leg64, -2.2, 0.5, &err);
    check_error("negative cd", code, &err, UWML_ERR_NEGATIVE, 0, "cd");
    UwmlJointLossParamsF64 params;
    uwml_leg3_default_losses_f64(&params);
    code = uwml_leg3_set_losses_f64(&leg64, 3, &params, 0.0, 20.0, &err);
    check_error("joint index 3", code, &err, UWML_ERR_INDEX_OUT_OF_RANGE, 3, "joint_index");
    code = uwml_leg3_set_losses_f64(&leg64, UINT32_MAX, &params, 0.0, 20.0, &err);
    check_error("joint index UINT32_MAX", code, &err, UWML_ERR_INDEX_OUT_OF_RANGE, (int64_t)UINT32_MAX, "joint_index");
    code = uwml_leg3_set_conditions_f64(&leg64, 1e7, -300.0, &err);
    check_error("below absolute zero", code, &err, UWML_ERR_BELOW_ABSOLUTE_ZERO, -1, "temperature_c");
    double pressure = -1.0;
    code = uwml_pressure_at_depth_f64(12000.0, 1025.0, 9.81, &pressure, &err);
    check_error("deeper than the ocean", code, &err, UWML_ERR_BEYOND_DEEPEST_OCEAN, -1, "depth");
    code = uwml_pressure_at_depth_f64(-5.0, 1025.0, 9.81, &pressure, &err);
    check_error("above the surface", code, &err, UWML_ERR_NEGATIVE, -1, "depth");
    check(pressure == -1.0, "a refused depth writes no pressure");
    params.seal.s[0] = params.seal.c[0] - 1.0;
    code = uwml_leg3_set_losses_f64(&leg64, 2, &params, 0.0, 20.0, &err);
    check_error("seal breakaway below running", code, &err, UWML_ERR_OUT_OF_ORDER, 2, "seal.s0");

    /* The leg is unchanged by the failed setters. */
    check(uwml_leg3_environment_f64(&leg64, Q, QD, QDD, &env, &err) == UWML_OK, "environment after errors");
    check_reference("f64 after errors", env.drag, env.added_mass, env.buoyancy, F64_REL);
}

int main(void) {
    print_sizes();
    paper_f64();
    paper_f32();
    losses();
    errors();
    printf("%d failed\n", failures);
    return failures == 0 ? 0 : 1;
}
