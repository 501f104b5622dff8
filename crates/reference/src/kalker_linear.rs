//! Kalker's linear theory of rolling contact for a circular contact: creep coefficients
//! `C11`, `C22`, `C23` as functions of Poisson's ratio.
//!
//! Values for `a/b = 1` from Kalker's table of creepage and spin coefficients (Kalker 1967, "On
//! the rolling contact of two elastic bodies in the presence of dry friction", thesis, Delft;
//! Kalker 1990, *Three-dimensional elastic bodies in rolling contact*, Table E.3; reproduced in
//! Johnson 1985, *Contact Mechanics*, Table 8.1):
//!
//! | nu   | C11  | C22  | C23  |
//! |------|------|------|------|
//! | 0    | 3.40 | 3.40 | 1.33 |
//! | 0.25 | 4.12 | 3.67 | 1.47 |
//! | 0.5  | 5.20 | 3.98 | 1.63 |
//!
//! In the crate's sign convention (creepage of body q relative to body p, force on body p, see
//! [`crate::bem`]) the linear laws read `Fx = G a^2 C11 xi` and `Fy = G a^2 C22 eta + G a^3 C23 phi`.

use crate::error::{RefError, check_range};

/// Kalker's table for the circular contact: `(nu, C11, C22, C23)`.
pub const TABLE_CIRCULAR: [(f64, f64, f64, f64); 3] = [
    (0.0, 3.40, 3.40, 1.33),
    (0.25, 4.12, 3.67, 1.47),
    (0.5, 5.20, 3.98, 1.63),
];

/// Lagrange interpolation through the three tabulated `nu` (exact at the table).
fn interpolate(nu: f64, col: impl Fn(&(f64, f64, f64, f64)) -> f64) -> Result<f64, RefError> {
    let nu = check_range("nu", nu, 0.0, 0.5, "in [0, 0.5]")?;
    let t = &TABLE_CIRCULAR;
    let (x0, x1, x2) = (t[0].0, t[1].0, t[2].0);
    let l0 = (nu - x1) * (nu - x2) / ((x0 - x1) * (x0 - x2));
    let l1 = (nu - x0) * (nu - x2) / ((x1 - x0) * (x1 - x2));
    let l2 = (nu - x0) * (nu - x1) / ((x2 - x0) * (x2 - x1));
    Ok(l0 * col(&t[0]) + l1 * col(&t[1]) + l2 * col(&t[2]))
}

/// `C11(nu)` for circular contact, `nu` in `[0, 0.5]` (quadratic through Kalker's table).
pub fn c11(nu: f64) -> Result<f64, RefError> {
    interpolate(nu, |r| r.1)
}

/// `C22(nu)` for circular contact, `nu` in `[0, 0.5]` (quadratic through Kalker's table).
pub fn c22(nu: f64) -> Result<f64, RefError> {
    interpolate(nu, |r| r.2)
}

/// `C23(nu)` for circular contact, `nu` in `[0, 0.5]` (quadratic through Kalker's table).
pub fn c23(nu: f64) -> Result<f64, RefError> {
    interpolate(nu, |r| r.3)
}

/// Linear-theory forces on body p `(Fx, Fy)` \[N\] of a circular contact of radius `a` \[m\] (> 0),
/// combined shear modulus `g` \[Pa\] (> 0), Poisson ratio `nu` in `[0, 0.5]`, for creepages `xi`,
/// `eta` \[dimensionless\] and spin `phi` \[1/m\] (finite): `Fx = G a^2 C11 xi`,
/// `Fy = G a^2 C22 eta + G a^3 C23 phi` (Kalker 1967; valid for small creepages, no Coulomb
/// limit).
pub fn linear_forces(
    a: f64,
    g: f64,
    nu: f64,
    xi: f64,
    eta: f64,
    phi: f64,
) -> Result<(f64, f64), RefError> {
    let a = crate::error::check_positive("a", a)?;
    let g = crate::error::check_positive("g", g)?;
    crate::error::check_finite("xi", xi)?;
    crate::error::check_finite("eta", eta)?;
    crate::error::check_finite("phi", phi)?;
    let fx = g * a * a * c11(nu)? * xi;
    let fy = g * a * a * c22(nu)? * eta + g * a * a * a * c23(nu)? * phi;
    Ok((fx, fy))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn interpolation_is_exact_at_the_table_and_monotone() {
        for (nu, a, b, c) in TABLE_CIRCULAR {
            assert!((c11(nu).unwrap() - a).abs() < 1e-12);
            assert!((c22(nu).unwrap() - b).abs() < 1e-12);
            assert!((c23(nu).unwrap() - c).abs() < 1e-12);
        }
        let mut prev = 0.0;
        for i in 0..=50 {
            let v = c11(i as f64 / 100.0).unwrap();
            assert!(v > prev);
            prev = v;
        }
        assert!(c11(0.6).is_err());
        // nu = 0: longitudinal and lateral coefficients coincide (isotropy of the kernel).
        assert_eq!(c11(0.0).unwrap(), c22(0.0).unwrap());
    }

    #[test]
    fn linear_forces_scale() {
        let (fx, fy) = linear_forces(2.0, 3.0, 0.25, 0.01, 0.0, 0.0).unwrap();
        assert!((fx - 3.0 * 4.0 * 4.12 * 0.01).abs() < 1e-12 && fy == 0.0);
        let (_, fy) = linear_forces(2.0, 3.0, 0.25, 0.0, 0.0, 0.01).unwrap();
        assert!((fy - 3.0 * 8.0 * 1.47 * 0.01).abs() < 1e-12);
    }
}
