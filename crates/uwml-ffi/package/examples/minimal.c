/*
 * minimal.c: uwml in a controller, in float (the precision of a Cortex-M4F's FPU). The paper's
 * leg, a preset of the robot API, is built once into static storage; every control period gives
 * the water's torque on each joint, and the motor supplies -total on top of its land torque.
 * uwml needs no heap and no C library. On a hosted build, main() evaluates the reference state of
 * docs/model.md section 5 and checks it against the published torques: exit status 0 if they
 * agree.
 *
 *   host:      make && ./minimal     (or: cmake -B build && cmake --build build && build/minimal)
 *   Cortex-M:  arm-none-eabi-gcc -mcpu=cortex-m4 -mthumb -mfloat-abi=hard -mfpu=fpv4-sp-d16 \
 *                  -ffreestanding -std=c11 -I../include -c minimal.c
 *              then link minimal.o into your firmware with ../lib/libuwml.a (README.md)
 */
#include <stddef.h>
#include <stdint.h>

#include "uwml.h"

static UwmlRobotF32 leg;             /* the model: written once, then only read */
static UwmlWorkspaceF32 workspace;   /* what an evaluation writes: one per task that evaluates */

/* Once, at start-up. */
int32_t leg_init(void) {
    int32_t code = uwml_robot_paper_leg_f32(&leg);
    return code != UWML_OK ? code : uwml_robot_workspace_init_f32(&workspace);
}

/* Every control period: joint angles, speeds and accelerations in; the water's forces out. */
int32_t leg_step(const float q[3], const float qd[3], const float qdd[3], UwmlJointForcesF32 forces[3]) {
    return uwml_robot_hydro_f32(&leg, &workspace, q, qd, qdd, 3, NULL, NULL, forces, NULL, NULL);
}

#if __STDC_HOSTED__
#include <stdio.h>

static int close_to(float value, double published) {
    double error = (double)value - published;
    double scale = published < 0.0 ? -published : published;
    return (error < 0.0 ? -error : error) <= 1e-4 * (scale > 1.0 ? scale : 1.0);
}

int main(void) {
    static const float q[3] = {0.3f, -0.4f, 0.6f}, qd[3] = {0.8f, 0.5f, -0.7f}, qdd[3] = {1.0f, -2.0f, 0.5f};
    static const double drag[3] = {-24.24084, -5.060505, -0.7383118};   /* N m, published */
    static const double added_mass[3] = {-8.525438, 21.77596, 9.484545};
    static const double buoyancy[3] = {0.0, 59.72457, 4.193843};
    UwmlJointForcesF32 forces[3];
    int32_t code = leg_init();
    if (code == UWML_OK) {
        code = leg_step(q, qd, qdd, forces);
    }
    if (code != UWML_OK) {
        printf("uwml: error %d (%s)\n", (int)code, uwml_error_message(code));
        return 1;
    }
    int agree = 1;
    for (int i = 0; i < 3; i++) {
        printf("joint %d: drag %+9.5f  added mass %+9.5f  buoyancy %+9.5f  total %+9.5f N m\n", i + 1,
               (double)forces[i].drag, (double)forces[i].added_mass, (double)forces[i].buoyancy, (double)forces[i].total);
        agree &= close_to(forces[i].drag, drag[i]) && close_to(forces[i].added_mass, added_mass[i]) &&
                 close_to(forces[i].buoyancy, buoyancy[i]);
    }
    puts(agree ? "the published torques, to 1e-4" : "NOT the published torques");
    return agree ? 0 : 1;
}
#endif
