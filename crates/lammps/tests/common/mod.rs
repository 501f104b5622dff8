//! Fixtures shared by the integration tests (`list.rs`, `store.rs`, `remap.rs`): a model made
//! through the C ABI, a store handle that frees itself, the per-atom arrays of a test
//! cluster and its pseudo-random numbers.
#![allow(unsafe_code)] // calls the C ABI as C++ would
#![allow(dead_code)] // each test file uses its own part

use creep_lammps::ffi::{
    CREEP_LAMMPS_ROLLING_EPSD, CreepLammpsModel, CreepLammpsSettings, CreepLammpsStore,
    creep_lammps_model_new, creep_lammps_store_free,
};
use std::ffi::c_char;

/// A glass-like model of `tier` (`CREEP_LAMMPS_TIER_*`) with creep and EPSD rolling
/// resistance, made through the C ABI.
pub fn model(tier: u32) -> *mut CreepLammpsModel {
    let s = CreepLammpsSettings {
        young_modulus: 69.6e6,
        poisson_ratio: 0.2,
        restitution: 0.5,
        friction: 0.5,
        tier,
        creep: 1,
        rolling: CREEP_LAMMPS_ROLLING_EPSD,
        rolling_friction: 0.2,
        rolling_damping: 0.3,
    };
    let mut err = [0 as c_char; 256];
    // SAFETY: valid settings and error buffer.
    let m = unsafe { creep_lammps_model_new(&s, err.as_mut_ptr(), err.len()) };
    assert!(!m.is_null());
    m
}

/// A store made by `creep_lammps_store_new`, freed on drop.
pub struct Store(pub *mut CreepLammpsStore);
impl Drop for Store {
    fn drop(&mut self) {
        // SAFETY: created by creep_lammps_store_new, freed once.
        unsafe { creep_lammps_store_free(self.0) };
    }
}

/// Per-atom arrays of a test cluster: positions \[m\], velocities \[m/s\], angular velocities
/// \[rad/s\], radii \[m\], masses \[kg\] and atom types.
#[derive(Default)]
pub struct Cluster {
    pub x: Vec<[f64; 3]>,
    pub v: Vec<[f64; 3]>,
    pub w: Vec<[f64; 3]>,
    pub r: Vec<f64>,
    pub m: Vec<f64>,
    pub kind: Vec<i32>,
}

impl Cluster {
    /// The arrays as the safe API's [`creep_lammps::Atoms`].
    pub fn atoms(&self) -> creep_lammps::Atoms<'_> {
        creep_lammps::Atoms {
            x: &self.x,
            v: &self.v,
            omega: &self.w,
            radius: &self.r,
            mass: &self.m,
            kind: &self.kind,
        }
    }
}

/// Marsaglia's (2003) xorshift64 from `seed`, as uniform numbers in `[-0.5, 0.5)`.
pub fn xorshift(mut seed: u64) -> impl FnMut() -> f64 {
    move || {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        (seed >> 11) as f64 / (1u64 << 53) as f64 - 0.5
    }
}
