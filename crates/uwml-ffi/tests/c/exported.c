/* The C initializers that `uwml export --c` writes (exported_arm.h, the arm of
 * uwml.examples.arm_on_rov) build a robot through the C ABI; prints its forces at one state on a
 * moving ROV in a current, for tests/c_program.rs to hold against the Rust core. */
#include <stdio.h>

#include "exported_arm.h"

int main(void) {
    static UwmlRobotF64 robot;
    static UwmlWorkspaceF64 workspace;
    UwmlError err;
    if (uwml_robot_new_f64(&robot, ARM_JOINTS, ARM_N_JOINTS, ARM_LINKS, ARM_BASE, ARM_SEGMENTS, ARM_N_SEGMENTS,
                           ARM_WATER_DENSITY, ARM_GRAVITY, &err) != UWML_OK) {
        printf("construction failed: %s %lld\n", err.field, (long long)err.index);
        return 1;
    }
    if (uwml_robot_workspace_init_f64(&workspace) != UWML_OK) {
        return 1;
    }
    const double q[7] = {0.3, -0.4, 0.6, 0.2, -0.5, 0.1, 0.05};
    const double qd[7] = {0.5, 0.3, -0.4, 0.8, 0.2, -0.6, 0.02};
    const double qdd[7] = {1.0, -0.5, 0.3, 0.2, -1.0, 0.7, 0.1};
    /* Roll 0.06 rad, then pitch 0.1 rad: q = q_pitch (x) q_roll, as benches/common/arm.rs. */
    const UwmlBaseMotionF64 motion = {
        .orientation = {0.99875026039496628 * 0.99955003374898754, 0.99875026039496628 * 0.029995500202495664,
                        0.049979169270678331 * 0.99955003374898754, -0.049979169270678331 * 0.029995500202495664},
        .velocity = {0.5, 0.02, -0.05},
        .angular_velocity = {0.01, 0.03, 0.05},
        .acceleration = {0.1, 0.0, 0.02},
        .angular_acceleration = {0.0, 0.01, 0.0},
    };
    const UwmlCurrentF64 current = {.velocity = {0.3, 0.1, 0.0}, .acceleration = {0.0, 0.0, 0.0}};
    UwmlJointForcesF64 forces[7];
    UwmlBaseWrenchF64 wrench;
    if (uwml_robot_hydro_f64(&robot, &workspace, q, qd, qdd, ARM_N_JOINTS, &motion, &current, forces, &wrench, &err) !=
        UWML_OK) {
        printf("evaluation failed: %s %lld\n", err.field, (long long)err.index);
        return 1;
    }
    for (int i = 0; i < 7; ++i) {
        printf("joint %d %.17g %.17g\n", i, forces[i].total, forces[i].gravity);
    }
    for (int k = 0; k < 6; ++k) {
        printf("base %d %.17g\n", k, wrench.total[k]);
    }
    return 0;
}
