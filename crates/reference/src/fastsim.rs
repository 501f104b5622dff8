//! Kalker's simplified theory of rolling contact and its algorithm FASTSIM, for the circular
//! contact, with longitudinal, lateral and spin creepage.
//!
//! Sources: Kalker 1982, "A fast algorithm for the simplified theory of rolling contact", Vehicle
//! System Dynamics 11; Kalker 1990, *Three-dimensional elastic bodies in rolling contact*, ch. 3.
//! The simplified theory replaces the half-space by independent springs, `u = L t`, with one
//! flexibility per creepage chosen so that the linear limit reproduces Kalker's linear theory
//! (Kalker 1982; the same expressions are used by CONTACT, Vollebregt's *User guide for CONTACT*):
//!
//! `L1 = 8 a / (3 G C11)`, `L2 = 8 a / (3 G C22)`, `L3 = pi a sqrt(a/b) / (4 G C23)`
//!
//! (`b = a` here). In steady rolling the slip `w + du/dx` vanishes in stick, so along each strip
//! `y = const`, from the leading edge `x = +a_y` towards the trailing edge, the traction grows by
//! `dt = (xi/L1 - phi y/L3, eta/L2 + phi x/L3) dx` and is scaled back onto the traction bound
//! `mu p` where it exceeds it (slip). The bound is Kalker's parabolic pressure
//! `p = 2 P / (pi a b) (1 - x^2/a^2 - y^2/b^2)` by default (Kalker 1982), or Hertz's.
//!
//! Sign convention as in [`crate::bem`]: creepage of body q relative to body p, traction on body
//! p, leading edge at `x = +a`, spin `phi` \[1/m\] with rigid slip `(xi - phi y, eta + phi x)`.
//! Tractions and bounds are evaluated at the element midpoints (the first half an element from the
//! leading edge), which makes the linear limit exact along each strip and keeps the zero bound
//! of the contact edge out of the elements.

use crate::bem::Creepage;
use crate::contact::CircularContact;
use crate::error::RefError;
use crate::kalker_linear;
use std::f64::consts::PI;

/// Pressure distribution used as the traction bound `mu p`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum TractionBound {
    /// Kalker's parabolic pressure `2 P/(pi a^2) (1 - r^2/a^2)` (FASTSIM's standard choice).
    #[default]
    Parabolic,
    /// Hertz's ellipsoidal pressure `3 P/(2 pi a^2) sqrt(1 - r^2/a^2)`.
    Hertz,
}

/// Discretisation of FASTSIM.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FastsimOptions {
    /// Number of strips across the contact (in `y`), in `[2, 100000]` (default 100).
    pub strips: usize,
    /// Number of elements along each strip (in `x`), in `[2, 100000]` (default 100).
    pub elements: usize,
    /// Pressure used for the traction bound.
    pub bound: TractionBound,
}

impl Default for FastsimOptions {
    fn default() -> Self {
        FastsimOptions {
            strips: 100,
            elements: 100,
            bound: TractionBound::Parabolic,
        }
    }
}

/// Result of a FASTSIM evaluation.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FastsimOutput {
    /// Longitudinal force on body p \[N\].
    pub fx: f64,
    /// Lateral force on body p \[N\].
    pub fy: f64,
    /// Spin moment on body p about the contact centre \[N m\].
    pub mz: f64,
    /// Fraction of the contact area in slip.
    pub slip_fraction: f64,
}

/// Kalker's flexibilities `(L1, L2, L3)` \[m/Pa\] of the simplified theory for the circular contact
/// (Kalker 1982): `L1 = 8a/(3 G C11)`, `L2 = 8a/(3 G C22)`, `L3 = pi a/(4 G C23)`, with `C_ij` from
/// [`kalker_linear`].
pub fn flexibilities(contact: &CircularContact) -> Result<(f64, f64, f64), RefError> {
    let (a, g, nu) = (contact.a(), contact.g(), contact.nu());
    Ok((
        8.0 * a / (3.0 * g * kalker_linear::c11(nu)?),
        8.0 * a / (3.0 * g * kalker_linear::c22(nu)?),
        PI * a / (4.0 * g * kalker_linear::c23(nu)?),
    ))
}

/// Steady rolling by FASTSIM for the circular contact.
pub fn fastsim(
    contact: &CircularContact,
    creepage: Creepage,
    options: &FastsimOptions,
) -> Result<FastsimOutput, RefError> {
    creepage.validate()?;
    for (name, v) in [("strips", options.strips), ("elements", options.elements)] {
        if !(2..=100_000).contains(&v) {
            return Err(RefError::InvalidGrid {
                name,
                value: v,
                expected: "in [2, 100000]",
            });
        }
    }
    let (l1, l2, l3) = flexibilities(contact)?;
    let a = contact.a();
    let (mu, p) = (contact.mu(), contact.p());
    let bound = |x: f64, y: f64| -> f64 {
        let s = 1.0 - (x * x + y * y) / (a * a);
        if s <= 0.0 {
            return 0.0;
        }
        mu * match options.bound {
            TractionBound::Parabolic => 2.0 * p / (PI * a * a) * s,
            TractionBound::Hertz => 1.5 * p / (PI * a * a) * s.sqrt(),
        }
    };
    let (xi, eta, phi) = (creepage.longitudinal, creepage.lateral, creepage.spin);
    let dy = 2.0 * a / options.strips as f64;
    let (mut fx, mut fy, mut mz) = (0.0, 0.0, 0.0);
    let (mut slip_area, mut area) = (0.0, 0.0);
    for j in 0..options.strips {
        let y = -a + (j as f64 + 0.5) * dy;
        let ay = (a * a - y * y).max(0.0).sqrt();
        let dx = 2.0 * ay / options.elements as f64;
        // Tractions at the element midpoints: half an element from the leading edge first.
        let (mut tx, mut ty) = (0.0, 0.0);
        for i in 0..options.elements {
            let x = ay - (i as f64 + 0.5) * dx;
            let step = if i == 0 { 0.5 * dx } else { dx };
            let x_inc = x + 0.5 * step; // midpoint of the increment, for the spin term
            let (nx, ny) = (
                tx + (xi / l1 - phi * y / l3) * step,
                ty + (eta / l2 + phi * x_inc / l3) * step,
            );
            let g = bound(x, y);
            let n = nx.hypot(ny);
            let slip = n > g;
            let s = if slip && n > 0.0 { g / n } else { 1.0 };
            tx = nx * s;
            ty = ny * s;
            let da = dx * dy;
            fx += tx * da;
            fy += ty * da;
            mz += (x * ty - y * tx) * da;
            area += da;
            if slip {
                slip_area += da;
            }
        }
    }
    Ok(FastsimOutput {
        fx,
        fy,
        mz,
        slip_fraction: slip_area / area,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn linear_limit_reproduces_kalkers_coefficients() {
        // By construction of L1, L2, L3 the small-creepage forces are Kalker's linear theory, up
        // to the strip discretisation (midpoint rule in y, O(1/strips^2)).
        for nu in [0.0, 0.25, 0.5] {
            let c = CircularContact::normalised(nu).unwrap();
            let o = FastsimOptions::default();
            let e = 1e-7;
            let fx = fastsim(&c, Creepage::longitudinal(e), &o).unwrap().fx;
            let fy = fastsim(
                &c,
                Creepage {
                    lateral: e,
                    ..Default::default()
                },
                &o,
            )
            .unwrap()
            .fy;
            let fs = fastsim(
                &c,
                Creepage {
                    spin: e,
                    ..Default::default()
                },
                &o,
            )
            .unwrap()
            .fy;
            let (c11, c22, c23) = (
                kalker_linear::c11(nu).unwrap(),
                kalker_linear::c22(nu).unwrap(),
                kalker_linear::c23(nu).unwrap(),
            );
            assert!((fx / e / c11 - 1.0).abs() < 1e-3, "nu={nu}: {}", fx / e);
            assert!((fy / e / c22 - 1.0).abs() < 1e-3, "nu={nu}: {}", fy / e);
            assert!((fs / e / c23 - 1.0).abs() < 1e-3, "nu={nu}: {}", fs / e);
        }
    }

    #[test]
    fn full_slip_and_symmetry() {
        let c = CircularContact::normalised(0.3).unwrap();
        let o = FastsimOptions::default();
        // Full slip: the parabolic bound integrates to mu P.
        let big = fastsim(&c, Creepage::longitudinal(100.0), &o).unwrap();
        assert!((big.fx - 1.0).abs() < 1e-3, "{}", big.fx);
        assert!(big.slip_fraction > 0.99);
        // Odd in the creepage, no lateral force from longitudinal creepage.
        let p = fastsim(&c, Creepage::longitudinal(0.2), &o).unwrap();
        let m = fastsim(&c, Creepage::longitudinal(-0.2), &o).unwrap();
        assert!((p.fx + m.fx).abs() < 1e-12 && p.fy.abs() < 1e-12);
        assert!(p.fx > 0.0 && p.fx < 1.0);
        // Hertz bound: also mu P in full slip (up to discretisation).
        let oh = FastsimOptions {
            bound: TractionBound::Hertz,
            ..o
        };
        let h = fastsim(&c, Creepage::longitudinal(100.0), &oh).unwrap();
        assert!((h.fx - 1.0).abs() < 5e-3, "{}", h.fx);
        assert!(fastsim(&c, Creepage::longitudinal(f64::NAN), &o).is_err());
        assert!(
            fastsim(
                &c,
                Creepage::longitudinal(0.1),
                &FastsimOptions { strips: 1, ..o }
            )
            .is_err()
        );
    }
}
