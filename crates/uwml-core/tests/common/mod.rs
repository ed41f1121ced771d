//! Helpers shared by the integration tests.
#![allow(dead_code, missing_docs)]

use uwml_core::nalgebra::{SVector, Vector3};
use uwml_core::{Chain, Coefficients, Joint, Link, Segment};

pub mod trees;

/// xorshift64: deterministic random numbers in [-1, 1) without a dependency.
pub struct Rng(pub u64);
impl Rng {
    pub fn next(&mut self) -> f64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        (self.0 >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
    }
    pub fn vector<const N: usize>(&mut self, scale: f64) -> SVector<f64, N> {
        SVector::from_fn(|_, _| scale * self.next())
    }
    pub fn unit(&mut self) -> Vector3<f64> {
        loop {
            let v = Vector3::new(self.next(), self.next(), self.next());
            if v.norm() > 0.2 {
                return v.normalize();
            }
        }
    }
}

/// A random chain of 4 joints with arbitrary axes, offsets, segment directions and normals (the
/// general body frames and the full recursion, which the paper leg does not reach).
pub fn random_chain(rng: &mut Rng) -> Chain<f64, 4> {
    let joints = core::array::from_fn(|_| Joint { origin: rng.vector::<3>(0.5), axis: rng.unit() });
    let links = core::array::from_fn(|i| {
        let axis = rng.unit();
        let n1 = axis.cross(&rng.unit()).normalize();
        let segment = (i != 1).then(|| Segment {
            start: rng.vector::<3>(0.2),
            axis,
            length: 0.2 + rng.next().abs(),
            normals: [n1, axis.cross(&n1)],
            widths: [0.05 + 0.1 * rng.next().abs(), 0.05 + 0.2 * rng.next().abs()],
            area: 0.01 + 0.02 * rng.next().abs(),
        });
        Link {
            mass: 5.0 + 10.0 * rng.next().abs(),
            com: rng.vector::<3>(0.4),
            volume: 0.001 + 0.004 * rng.next().abs(),
            cob: rng.vector::<3>(0.4),
            segment,
        }
    });
    Chain::new(joints, links).expect("a valid random chain")
}

/// Random drag (0.5 to 2.5) and added-mass (0.1 to 1.1) coefficients per link and direction for
/// a 4-joint chain.
pub fn random_coefficients(rng: &mut Rng) -> Coefficients<f64, 4> {
    let mut draw = || core::array::from_fn(|_| [0.5 + 2.0 * rng.next().abs(), 0.1 + rng.next().abs()]);
    Coefficients::per_direction(draw(), draw()).expect("valid coefficients")
}
