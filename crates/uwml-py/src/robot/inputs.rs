//! One sample's joint states in the core's fixed-size arrays.

use super::MAX_ROBOT_JOINTS;

/// One sample's joint states, in the core's fixed-size arrays.
pub(super) struct StateRow {
    pub(super) q: [f64; MAX_ROBOT_JOINTS],
    pub(super) qd: [f64; MAX_ROBOT_JOINTS],
    pub(super) qdd: [f64; MAX_ROBOT_JOINTS],
}

impl StateRow {
    pub(super) fn new() -> Self {
        Self { q: [0.0; MAX_ROBOT_JOINTS], qd: [0.0; MAX_ROBOT_JOINTS], qdd: [0.0; MAX_ROBOT_JOINTS] }
    }
}
