//! Hertz's normal contact of elastic spheres (Hertz 1882; Johnson 1985, *Contact Mechanics*, §4.2,
//! §4.2) and the Rayleigh time step of a particle.
//!
//! All functions take the pair's effective radius `R*` \[m\] and modulus `E*` \[Pa\] through a
//! [`PairMaterial`]; forces are in N, lengths in m. Non-positive loads or overlaps give zero (an
//! open contact), never NaN.

use crate::material::{Material, PairMaterial};

/// Contact radius `a = (3 P R* / (4 E*))^(1/3)` \[m\] for normal force `p` \[N\] (Johnson 1985,
/// §4.2). Zero for `p <= 0`.
#[inline]
pub fn contact_radius(pair: &PairMaterial, p: f64) -> f64 {
    if p > 0.0 {
        (0.75 * p * pair.r_star / pair.e_star).cbrt()
    } else {
        0.0
    }
}

/// Normal force `P = (4/3) E* sqrt(R*) delta^(3/2)` \[N\] for overlap `delta` \[m\] (Johnson 1985,
/// §4.2). Zero for `delta <= 0`.
#[inline]
pub fn normal_force(pair: &PairMaterial, delta: f64) -> f64 {
    if delta > 0.0 {
        4.0 / 3.0 * pair.e_star * (pair.r_star * delta).sqrt() * delta
    } else {
        0.0
    }
}

/// Overlap (approach of distant points) `delta = a^2 / R* = (3 P / (4 E* sqrt(R*)))^(2/3)` \[m\] for
/// normal force `p` \[N\] (Johnson 1985, §4.2, inverted). Zero for `p <= 0`.
#[inline]
pub fn overlap(pair: &PairMaterial, p: f64) -> f64 {
    let a = contact_radius(pair, p);
    a * a / pair.r_star
}

/// Contact radius from the overlap: `a = sqrt(R* delta)` \[m\] (Johnson 1985, §4.2).
#[inline]
pub fn contact_radius_from_overlap(pair: &PairMaterial, delta: f64) -> f64 {
    if delta > 0.0 {
        (pair.r_star * delta).sqrt()
    } else {
        0.0
    }
}

/// Normal stiffness `k_n = dP/d delta = 2 E* sqrt(R* delta) = 2 E* a` [N/m] at overlap `delta` \[m\].
#[inline]
pub fn normal_stiffness(pair: &PairMaterial, delta: f64) -> f64 {
    2.0 * pair.e_star * contact_radius_from_overlap(pair, delta)
}

/// Elastic energy stored in the normal contact, `W = (8/15) E* sqrt(R*) delta^(5/2)` \[J\]
/// (the integral of [`normal_force`] over the overlap).
#[inline]
pub fn normal_energy(pair: &PairMaterial, delta: f64) -> f64 {
    if delta > 0.0 {
        0.4 * normal_force(pair, delta) * delta
    } else {
        0.0
    }
}

/// Rayleigh time step of a sphere of radius `radius` \[m\] made of `material`:
/// `T_R = pi R sqrt(rho / G) / (0.1631 nu + 0.8766)` \[s\], the time a Rayleigh surface wave takes
/// to cross half the sphere (Li, Xu & Thornton 2005, "A comparison of discrete element simulations
/// and experiments for 'sandpiles' composed of spherical particles", Powder Technol. 160, 219-228;
/// the Rayleigh wave speed approximation is Thornton's). DEM codes use a fraction (0.1-0.3) of it.
/// Returns 0 for a massless body and an invalid (non-positive or non-finite) radius.
pub fn rayleigh_time_step(material: &Material, radius: f64) -> f64 {
    if !(radius.is_finite() && radius > 0.0) {
        return 0.0;
    }
    let nu = material.poisson_ratio();
    std::f64::consts::PI * radius * (material.density() / material.shear_modulus()).sqrt()
        / (0.1631 * nu + 0.8766)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn pair() -> PairMaterial {
        crate::material::steel_ball_on_plane()
    }

    #[test]
    fn force_overlap_radius_are_consistent() {
        let pair = pair();
        for p in [1e-3, 1.0, 10.0, 1e4] {
            let d = overlap(&pair, p);
            assert!((normal_force(&pair, d) / p - 1.0).abs() < 1e-12);
            let a = contact_radius(&pair, p);
            assert!((a * a - pair.r_star * d).abs() / (a * a) < 1e-12);
            // k_n = dP/d delta by central difference.
            let h = d * 1e-6;
            let fd = (normal_force(&pair, d + h) - normal_force(&pair, d - h)) / (2.0 * h);
            assert!((normal_stiffness(&pair, d) / fd - 1.0).abs() < 1e-8);
            // Energy is the integral of the force: dW/d delta = P.
            let fe = (normal_energy(&pair, d + h) - normal_energy(&pair, d - h)) / (2.0 * h);
            assert!((fe / p - 1.0).abs() < 1e-8);
        }
        assert_eq!(contact_radius(&pair, 0.0), 0.0);
        assert_eq!(contact_radius(&pair, -1.0), 0.0);
        assert_eq!(normal_force(&pair, -1e-6), 0.0);
        assert_eq!(overlap(&pair, f64::NAN), 0.0);
    }

    #[test]
    fn hertz_textbook_number() {
        // Johnson (1985, §4.2) written out: a^3 = 3 P R / (4 E*) for a 10 mm steel ball on a
        // steel flat at 100 N: E* = E / (2 (1 - nu^2)).
        let m = Material::steel();
        let e_star = m.young_modulus() / (2.0 * (1.0 - 0.29f64 * 0.29));
        let expect = (3.0 * 100.0 * 0.01 / (4.0 * e_star)).cbrt();
        assert!((contact_radius(&pair(), 100.0) / expect - 1.0).abs() < 1e-12);
    }

    #[test]
    fn rayleigh_time_step_of_glass_bead() {
        // 1 mm glass: pi * 1e-3 * sqrt(2500 / 29e9) / (0.1631 * 0.23 + 0.8766).
        let t = rayleigh_time_step(&Material::glass(), 1e-3);
        let expect =
            std::f64::consts::PI * 1e-3 * (2500.0f64 / 29e9).sqrt() / (0.1631 * 0.23 + 0.8766);
        assert!((t / expect - 1.0).abs() < 1e-14);
        assert!(t > 1.0e-6 && t < 1.02e-6, "t = {t}");
        assert_eq!(rayleigh_time_step(&Material::glass(), -1.0), 0.0);
    }
}
