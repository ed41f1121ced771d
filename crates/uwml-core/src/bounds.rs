//! The bounds a model's numbers are checked against when it is built (docs/domains.md): the
//! largest value of each kind, which keeps every force of a finite state finite, in f32 too, and
//! the tolerances on directions and on the lumped models' matrices (docs/model.md section 12.1).

/// Tolerance on unit length and on orthogonality of axes and normals at construction.
pub const AXIS_TOLERANCE: f64 = 1e-6;

/// The largest length a model may hold [m]: every coordinate of a point (joint origins, centres
/// of mass and buoyancy, segment starts) and every length, width and diameter. A robot's
/// dimensions beyond 10 km are a unit mistake; the bounds keep every force of a finite state
/// finite (docs/domains.md), in f32 too.
pub const MAX_LENGTH: f64 = 1e4;
/// The largest mass of a body [kg] (the largest ships displace under 1e9 kg).
pub const MAX_MASS: f64 = 1e9;
/// The largest volume of a body [m³] (1e9 kg of water).
pub const MAX_VOLUME: f64 = 1e6;
/// The largest cross-section area of a segment [m²] (`MAX_LENGTH²`).
pub const MAX_AREA: f64 = 1e8;
/// The largest drag or added-mass coefficient (measured ones are of order 1).
pub const MAX_COEFFICIENT: f64 = 1e3;
/// The largest water density [kg/m³] (more than any liquid's).
pub const MAX_DENSITY: f64 = 1e5;
/// The largest gravity [m/s²].
pub const MAX_GRAVITY: f64 = 1e3;

/// The largest magnitude of an entry of a lumped model's matrices and quadratic damping (in its
/// SI units: kg, kg·m, kg·m², N·s/m, ...). A hull of a million tonnes is far below it; the bound
/// keeps every force of a finite state finite.
pub const MAX_LUMPED: f64 = 1e12;

/// How far from symmetric a lumped model's added mass may be, relative to its largest entry in
/// magnitude (docs/model.md section 12.1), but never more than [`LUMPED_ABSOLUTE_TOLERANCE`].
pub const LUMPED_SYMMETRY_TOLERANCE: f64 = 1e-9;
/// How negative the smallest eigenvalue of a lumped model's added mass (and of its linear
/// damping's symmetric part) may be, relative to its largest diagonal entry in magnitude
/// (docs/model.md section 12.1), but never more than [`LUMPED_ABSOLUTE_TOLERANCE`].
pub const LUMPED_EIGENVALUE_TOLERANCE: f64 = 1e-10;
/// The most either tolerance allows, in the entries' own units (kg, kg·m, kg·m², N·s/m, ...):
/// relative tolerances alone let a huge entry hide a wrong small one (at the 1e12 cap,
/// `diag(1e12, −99, …)` and an asymmetry of 900 passed). 1e-2 is ten times the rounding of
/// float64 at the cap (a singular semi-definite matrix at 1e12 rounds to eigenvalues down to about
/// −1e-3) and far below any physical entry.
pub const LUMPED_ABSOLUTE_TOLERANCE: f64 = 1e-2;
