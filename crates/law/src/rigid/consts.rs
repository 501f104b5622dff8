//! Per-pair constants of the rigid kernel, computed once per pair of materials and friction
//! coefficient ([`RigidPair`]): the combined moduli of [`PairMaterial`] (Hertz's `E*`,
//! Mindlin's `G*`, Kalker's combined `G` and `nu`, `C11(nu)`), the steady law ([`SteadyLaw`])
//! and the 3-D law ([`Steady3d`] at `a/b = 1`, Kalker's `C11/C22`). Building them per contact
//! and step would cost six divisions and Kalker's table in `nu` each time.
//!
//! Only the effective radius depends on the contact's shapes (`1/R* = 1/R_p + 1/R_q`, Hertz;
//! Johnson 1985, §4.2): it is set per contact by [`RigidPair::pair_for`], with the same
//! operations as `PairMaterial::with_rule`, so the pair is bit for bit the one
//! `PairMaterial::new(..).with_friction(mu)` builds.
//!
//! [`RigidPairCache`] keeps them in a short list (no hashing, no allocation once every pair of
//! materials has been seen) keyed by the two materials and the friction coefficient, compared
//! bit for bit; a scene with more than [`PAIR_CACHE_LEN`] distinct pairs replaces entries
//! round-robin (then pays the construction on a miss).

use crate::material::{Material, PairMaterial, Surface};
use crate::steady_law::{CreepModel, SteadyLaw};
use crate::steady3d::Steady3d;

/// Largest number of distinct material pairs kept.
pub const PAIR_CACHE_LEN: usize = 16;

/// What the rigid kernel needs of one pair of materials at one friction coefficient.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RigidPair {
    /// The combined pair (its `r_star` and surfaces are placeholders: see [`Self::pair_for`]).
    template: PairMaterial,
    /// The configured steady law at the pair's `nu` and `C11`.
    pub law: SteadyLaw,
    /// The 3-D law of a circular contact at the pair's `nu` clamped to `[0, 0.5]` (`None`
    /// outside Kalker's table: such a contact is left to Coulomb).
    pub law3: Option<Steady3d>,
    /// `C11/C22` of [`Self::law3`] (the lateral ratio of the anisotropic solve, parent module
    /// docs).
    pub r: f64,
}

impl RigidPair {
    /// The constants of materials `p`, `q` at friction `mu` \[-\] with the steady law of
    /// `model`; `None` if the pair is invalid (a NaN or negative `mu`: the engine then leaves
    /// the contact to Coulomb).
    pub fn new(p: &Material, q: &Material, mu: f64, model: CreepModel) -> Option<Self> {
        // Any valid shapes: only r_star and the surfaces depend on them (pair_for).
        let template = PairMaterial::new(p, q, Surface::Sphere(1.0), Surface::Plane)
            .and_then(|pair| pair.with_friction(mu))
            .ok()?;
        let law = SteadyLaw::with_c11(model, template.nu, template.c11);
        let law3 = Steady3d::new(1.0, template.nu.clamp(0.0, 0.5)).ok();
        let r = law3.map_or(1.0, |l| {
            let c = l.coefficients();
            c.c11 / c.c22
        });
        Some(Self {
            template,
            law,
            law3,
            r,
        })
    }

    /// The pair for the surfaces `s1`, `s2` (at least one of them curved), bit for bit what
    /// `PairMaterial::new(p, q, s1, s2)?.with_friction(mu)` returns; `None` for a bad radius
    /// or two planes (the errors of `PairMaterial::with_rule`).
    #[inline]
    pub fn pair_for(&self, s1: Surface, s2: Surface) -> Option<PairMaterial> {
        let valid = |s: Surface| match s {
            Surface::Sphere(r) => r.is_finite() && r > 0.0,
            Surface::Plane => true,
        };
        if !(valid(s1) && valid(s2)) {
            return None;
        }
        let curvature = s1.curvature() + s2.curvature();
        if curvature <= 0.0 {
            return None;
        }
        Some(PairMaterial {
            r_star: 1.0 / curvature,
            surface_p: s1,
            surface_q: s2,
            ..self.template
        })
    }
}

/// The key of an entry: both materials' fields and the friction coefficient, as bits.
type Key = ([u64; 4], [u64; 4], u64);

fn material_bits(m: &Material) -> [u64; 4] {
    [
        m.shear_modulus().to_bits(),
        m.poisson_ratio().to_bits(),
        m.friction().to_bits(),
        m.density().to_bits(),
    ]
}

/// The per-pair constants seen so far (module docs).
#[derive(Debug, Clone, Default)]
pub struct RigidPairCache {
    entries: Vec<(Key, Option<RigidPair>)>,
    /// The entry found last (piles meet the same pair many times in a row).
    last: usize,
    /// The next entry replaced once the list is full.
    next: usize,
}

impl RigidPairCache {
    /// The constants of materials `p`, `q` at friction `mu` with the steady law of `model`
    /// (`None`: an invalid pair, remembered as such). The model is the engine's setting, fixed
    /// for the cache's lifetime, so it is not part of the key.
    #[inline]
    pub fn get(
        &mut self,
        p: &Material,
        q: &Material,
        mu: f64,
        model: CreepModel,
    ) -> Option<&RigidPair> {
        let key = (material_bits(p), material_bits(q), mu.to_bits());
        let i = if self.entries.get(self.last).is_some_and(|e| e.0 == key) {
            self.last
        } else if let Some(i) = self.entries.iter().position(|e| e.0 == key) {
            i
        } else {
            let consts = RigidPair::new(p, q, mu, model);
            if self.entries.len() < PAIR_CACHE_LEN {
                self.entries.push((key, consts));
                self.entries.len() - 1
            } else {
                let i = self.next;
                self.next = (self.next + 1) % PAIR_CACHE_LEN;
                self.entries[i] = (key, consts);
                i
            }
        };
        self.last = i;
        self.entries[i].1.as_ref()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cached_pair_is_bit_for_bit_the_constructed_one() {
        let (steel, glass) = (Material::steel(), Material::glass());
        let mut cache = RigidPairCache::default();
        for model in CreepModel::ALL {
            for (s1, s2) in [
                (Surface::Sphere(0.05), Surface::Plane),
                (Surface::Plane, Surface::Sphere(0.2)),
                (Surface::Sphere(0.05), Surface::Sphere(0.07)),
            ] {
                for mu in [0.0, 0.3, 0.9] {
                    let direct = PairMaterial::new(&steel, &glass, s1, s2)
                        .and_then(|p| p.with_friction(mu))
                        .unwrap();
                    let c = *cache.get(&steel, &glass, mu, model).unwrap();
                    let pair = c.pair_for(s1, s2).unwrap();
                    assert_eq!(pair, direct);
                    assert_eq!(c.law, SteadyLaw::with_c11(model, direct.nu, direct.c11));
                    let law3 = Steady3d::new(1.0, direct.nu.clamp(0.0, 0.5)).unwrap();
                    assert_eq!(c.law3, Some(law3));
                    let k = law3.coefficients();
                    assert_eq!(c.r, k.c11 / k.c22);
                }
            }
            cache = RigidPairCache::default();
        }
    }

    #[test]
    fn refuses_what_the_constructor_refuses_and_keeps_a_bounded_list() {
        let m = Material::steel();
        let mut cache = RigidPairCache::default();
        let c = *cache.get(&m, &m, 0.5, CreepModel::Kuhn).unwrap();
        assert!(c.pair_for(Surface::Plane, Surface::Plane).is_none());
        assert!(c.pair_for(Surface::Sphere(0.0), Surface::Plane).is_none());
        assert!(
            c.pair_for(Surface::Sphere(f64::NAN), Surface::Plane)
                .is_none()
        );
        assert!(cache.get(&m, &m, -1.0, CreepModel::Kuhn).is_none());
        assert!(cache.get(&m, &m, f64::NAN, CreepModel::Kuhn).is_none());
        for i in 0..3 * PAIR_CACHE_LEN {
            let mu = 0.01 * i as f64;
            let c = *cache.get(&m, &m, mu, CreepModel::Kuhn).unwrap();
            assert_eq!(c.template.mu, mu);
        }
        assert_eq!(cache.entries.len(), PAIR_CACHE_LEN);
        // A hit after eviction of others still returns the right pair.
        let c = *cache.get(&m, &m, 0.5, CreepModel::Kuhn).unwrap();
        assert_eq!(c.template.mu, 0.5);
    }
}
