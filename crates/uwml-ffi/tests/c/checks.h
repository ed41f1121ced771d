/*
 * The checks the robot programs share (robot.c, robot_losses.c): each prints one line, "ok" or
 * "FAIL", and counts the failures; the double and float parameters of the robots; float results
 * as double. Static inline: a program uses what it needs.
 */
#ifndef UWML_TEST_CHECKS_H
#define UWML_TEST_CHECKS_H

#include "uwml.h"

#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <string.h>

static int failures = 0;

static inline void check(int ok, const char *what) {
    printf("%s %s\n", ok ? "ok  " : "FAIL", what);
    if (!ok) {
        failures++;
    }
}

static inline void check_error(const char *what, int32_t code, const UwmlError *e, int32_t want_code, int64_t want_index,
                        const char *want_field) {
    int ok = code == want_code && e->code == want_code && e->index == want_index && strcmp(e->field, want_field) == 0;
    printf("%s %s: code %d (%s), index %lld, field \"%s\" (expected %d, %lld, \"%s\")\n", ok ? "ok  " : "FAIL", what,
           (int)code, uwml_error_message(code), (long long)e->index, e->field, (int)want_code, (long long)want_index,
           want_field);
    if (!ok) {
        failures++;
    }
}

/* Tolerances, relative to the largest |value| of the same quantity (a component of the joint
 * forces over the joints, or the force or the moment of a wrench component): double agrees
 * with the core to 1e-12; float, given the same parameters rounded to float, to 1e-5. */
#define F64_REL 1e-12
#define F32_REL 1e-5

/* got[i] against want[i] for i < n, within rel times the largest |want| (NaN fails). */
static inline void check_values(const char *what, const double *got, const double *want, int n, double rel) {
    double scale = 0.0, worst = 0.0;
    int ok = 1;
    for (int i = 0; i < n; i++) {
        scale = fmax(scale, fabs(want[i]));
    }
    for (int i = 0; i < n; i++) {
        double error = fabs(got[i] - want[i]);
        if (!(error <= rel * scale)) {
            ok = 0;
        }
        worst = fmax(worst, scale > 0.0 ? error / scale : error);
        if (isnan(got[i])) {
            worst = NAN;
        }
    }
    printf("%s %-40s worst error %.1e of %.6g (tolerance %.0e)\n", ok ? "ok  " : "FAIL", what, worst, scale, rel);
    if (!ok) {
        failures++;
    }
}

static inline double component(const UwmlJointForcesF64 *f, int c) {
    switch (c) {
    case 0: return f->drag;
    case 1: return f->added_mass;
    case 2: return f->buoyancy;
    case 3: return f->gravity;
    default: return f->total;
    }
}

/* The name of component `c` of a force (0 drag, 1 added mass, 2 buoyancy, 3 gravity, 4 total). */
static inline const char *component_name(int c) {
    static const char *const names[5] = {"drag", "added_mass", "buoyancy", "gravity", "total"};
    return names[c];
}

static inline void check_forces(const char *what, const UwmlJointForcesF64 *got, const UwmlJointForcesF64 *want, int n,
                         double rel) {
    double g[UWML_ROBOT_MAX_JOINTS], w[UWML_ROBOT_MAX_JOINTS];
    char label[96];
    for (int c = 0; c < 5; c++) {
        for (int i = 0; i < n; i++) {
            g[i] = component(&got[i], c);
            w[i] = component(&want[i], c);
        }
        snprintf(label, sizeof label, "%s joints %s", what, component_name(c));
        check_values(label, g, w, n, rel);
    }
}

static inline void check_wrench(const char *what, const UwmlBaseWrenchF64 *got, const UwmlBaseWrenchF64 *want, double rel) {
    const double *g[5] = {got->drag, got->added_mass, got->buoyancy, got->gravity, got->total};
    const double *w[5] = {want->drag, want->added_mass, want->buoyancy, want->gravity, want->total};
    char label[96];
    for (int c = 0; c < 5; c++) {
        snprintf(label, sizeof label, "%s base %s force", what, component_name(c));
        check_values(label, g[c], w[c], 3, rel);
        snprintf(label, sizeof label, "%s base %s moment", what, component_name(c));
        check_values(label, g[c] + 3, w[c] + 3, 3, rel);
    }
}

/* Float parameters from the double ones, as firmware would round them. */
static inline void to_f32(const double *in, float *out, int n) {
    for (int i = 0; i < n; i++) {
        out[i] = (float)in[i];
    }
}

static inline UwmlTreeJointF32 joint_f32(const UwmlTreeJointF64 *j) {
    UwmlTreeJointF32 out = {.parent = j->parent, .kind = j->kind};
    to_f32(j->origin, out.origin, 3);
    to_f32(j->axis, out.axis, 3);
    return out;
}

static inline UwmlBodyF32 body_f32(const UwmlBodyF64 *b) {
    UwmlBodyF32 out = {.mass = (float)b->mass, .volume = (float)b->volume};
    to_f32(b->com, out.com, 3);
    to_f32(b->cob, out.cob, 3);
    return out;
}

static inline UwmlRobotSegmentF32 segment_f32(const UwmlRobotSegmentF64 *s) {
    UwmlRobotSegmentF32 out = {.owner = s->owner,
                               .section = s->section,
                               .length = (float)s->length,
                               .area = (float)s->area,
                               .diameter = (float)s->diameter,
                               .cd_axial = (float)s->cd_axial,
                               .axial_area = (float)s->axial_area};
    to_f32(s->start, out.start, 3);
    to_f32(s->axis, out.axis, 3);
    to_f32(s->normals[0], out.normals[0], 3);
    to_f32(s->normals[1], out.normals[1], 3);
    to_f32(s->widths, out.widths, 2);
    to_f32(s->cd, out.cd, 2);
    to_f32(s->cm, out.cm, 2);
    return out;
}

static inline UwmlBaseMotionF32 motion_f32(const UwmlBaseMotionF64 *m) {
    UwmlBaseMotionF32 out;
    to_f32(m->orientation, out.orientation, 4);
    to_f32(m->velocity, out.velocity, 3);
    to_f32(m->angular_velocity, out.angular_velocity, 3);
    to_f32(m->acceleration, out.acceleration, 3);
    to_f32(m->angular_acceleration, out.angular_acceleration, 3);
    return out;
}

static inline UwmlCurrentF32 current_f32(const UwmlCurrentF64 *c) {
    UwmlCurrentF32 out;
    to_f32(c->velocity, out.velocity, 3);
    to_f32(c->acceleration, out.acceleration, 3);
    return out;
}

/* Float results as double, to compare with the expected values. */
static inline void forces_f64(const UwmlJointForcesF32 *in, UwmlJointForcesF64 *out, int n) {
    for (int i = 0; i < n; i++) {
        out[i].drag = in[i].drag;
        out[i].added_mass = in[i].added_mass;
        out[i].buoyancy = in[i].buoyancy;
        out[i].gravity = in[i].gravity;
        out[i].total = in[i].total;
    }
}

static inline UwmlBaseWrenchF64 wrench_f64(const UwmlBaseWrenchF32 *in) {
    UwmlBaseWrenchF64 out;
    for (int k = 0; k < 6; k++) {
        out.drag[k] = in->drag[k];
        out.added_mass[k] = in->added_mass[k];
        out.buoyancy[k] = in->buoyancy[k];
        out.gravity[k] = in->gravity[k];
        out.total[k] = in->total[k];
    }
    return out;
}

#endif
