//! Helpers shared by the integration tests.
#![allow(dead_code, missing_docs)]

use uwml_core::nalgebra::{SVector, Vector3};

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
