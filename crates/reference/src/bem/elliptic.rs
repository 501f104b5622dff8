//! Steady rolling of an **elliptic** Hertz contact (semi-axes `a` along the rolling direction `x`,
//! `b` along `y`) with longitudinal, lateral and spin creepage: the boundary elements of
//! [`crate::bem`] on the elliptic grid of [`Grid::elliptic`], and Kalker's linear creep
//! coefficients `C11`, `C22`, `C23`, `C33` recovered from them.
//!
//! Normalisation (Kalker 1967; Kalker 1990, *Three-dimensional elastic bodies in rolling
//! contact*, §E; Vollebregt, *User guide for CONTACT*): `c = sqrt(a b)`, creepages
//! `xi_n = xi G c^2/(mu P)`, `eta_n = eta G c^2/(mu P)`, `phi_n = phi G c^3/(mu P)`, forces over
//! `mu P`, moment over `mu P c`. The linear theory, in this crate's signs (creepage of q relative
//! to p, force on p, see [`crate::bem`]), reads
//!
//! `Fx = G c^2 C11 xi`, `Fy = G c^2 C22 eta + G c^3 C23 phi`, `Mz = -G c^3 C23 eta + G c^4 C33 phi`
//!
//! (Kalker's own signs are the opposite for every creepage: `Fx = -G c^2 C11 xi`, ...,
//! `Mz = G c^3 C23 eta - G c^4 C33 phi`).
//!
//! The pressure is Hertz's for the ellipse, `p = p0 sqrt(1 - x^2/a^2 - y^2/b^2)` with
//! `p0 = 3 P/(2 pi a b)` (Hertz 1882; Johnson 1985, *Contact Mechanics*, eq. 4.37), evaluated at
//! the unstretched lattice positions and rescaled to carry `P` exactly (as [`Grid::pressure`]).

use super::steady_gs::SteadyGs;
use super::{Creepage, SolverOptions, TractionField};
use crate::error::{RefError, check_positive, check_range};
use crate::grid::Grid;
use crate::influence::Kernel;
use std::f64::consts::PI;

/// An elliptic Hertz contact between two quasi-identical elastic bodies (validated inputs).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EllipticContact {
    a: f64,
    b: f64,
    p: f64,
    g: f64,
    nu: f64,
    mu: f64,
}

impl EllipticContact {
    /// Validates and builds a contact: `a` semi-axis along the rolling direction \[m\], `b` the
    /// lateral semi-axis \[m\], `p` normal force \[N\], `g` combined shear modulus \[Pa\] (all
    /// finite and > 0), `nu` combined Poisson ratio in `[0, 0.5]`, `mu` friction coefficient
    /// (finite, > 0).
    pub fn new(a: f64, b: f64, p: f64, g: f64, nu: f64, mu: f64) -> Result<Self, RefError> {
        Ok(EllipticContact {
            a: check_positive("a", a)?,
            b: check_positive("b", b)?,
            p: check_positive("p", p)?,
            g: check_positive("g", g)?,
            nu: check_range("nu", nu, 0.0, 0.5, "in [0, 0.5]")?,
            mu: check_positive("mu", mu)?,
        })
    }

    /// The contact in normalised units: `c = sqrt(a b) = 1`, `G = 1`, `mu = P = 1`, with the
    /// ratio `a/b` (`ab`, in `[0.05, 20]`): `a = sqrt(ab)`, `b = 1/sqrt(ab)`.
    pub fn normalised(nu: f64, ab: f64) -> Result<Self, RefError> {
        let ab = check_range("a/b", ab, 0.05, 20.0, "in [0.05, 20]")?;
        Self::new(ab.sqrt(), 1.0 / ab.sqrt(), 1.0, 1.0, nu, 1.0)
    }

    /// Semi-axis along the rolling direction `a` \[m\].
    pub fn a(&self) -> f64 {
        self.a
    }
    /// Lateral semi-axis `b` \[m\].
    pub fn b(&self) -> f64 {
        self.b
    }
    /// `c = sqrt(a b)` \[m\].
    pub fn c(&self) -> f64 {
        (self.a * self.b).sqrt()
    }
    /// Normal force `P` \[N\].
    pub fn p(&self) -> f64 {
        self.p
    }
    /// Combined shear modulus `G` \[Pa\].
    pub fn g(&self) -> f64 {
        self.g
    }
    /// Combined Poisson ratio `nu`.
    pub fn nu(&self) -> f64 {
        self.nu
    }
    /// Friction coefficient `mu`.
    pub fn mu(&self) -> f64 {
        self.mu
    }
    /// `mu P` \[N\].
    pub fn mu_p(&self) -> f64 {
        self.mu * self.p
    }
    /// Hertz pressure at `(x, y)`, `p0 sqrt(1 - x^2/a^2 - y^2/b^2)`, `p0 = 3 P/(2 pi a b)` \[Pa\]
    /// (Johnson 1985, eq. 4.37); 0 outside.
    pub fn pressure(&self, x: f64, y: f64) -> f64 {
        let s = 1.0 - (x / self.a).powi(2) - (y / self.b).powi(2);
        if s > 0.0 {
            1.5 * self.p / (PI * self.a * self.b) * s.sqrt()
        } else {
            0.0
        }
    }
}

/// Result of an elliptic steady solve (forces on body p \[N\], moment about the centre \[N m\]).
#[derive(Debug, Clone, PartialEq)]
pub struct EllipticOutput {
    /// Longitudinal force `Fx` \[N\].
    pub fx: f64,
    /// Lateral force `Fy` \[N\].
    pub fy: f64,
    /// Spin moment `Mz` \[N m\].
    pub mz: f64,
    /// Element-wise traction, stick and slip.
    pub traction: TractionField,
    /// Gauss-Seidel sweeps used.
    pub sweeps: usize,
}

/// A reusable steady-state solver for the elliptic contact (warm-started between solves).
#[derive(Debug, Clone)]
pub struct EllipticSteadySolver {
    contact: EllipticContact,
    options: SolverOptions,
    grid: Grid,
    kernel: Kernel,
    pressure: Vec<f64>,
    bound: Vec<f64>,
    tx: Vec<f64>,
    ty: Vec<f64>,
    stick: Vec<bool>,
}

impl EllipticSteadySolver {
    /// Builds the grid (`options.grid` elements across the shorter axis), the Hertz pressure and
    /// the Cerruti kernel divided by `h` (the steady operator of module `steady_gs`).
    pub fn new(contact: EllipticContact, options: SolverOptions) -> Result<Self, RefError> {
        options.validate()?;
        let grid = Grid::elliptic(contact.a(), contact.b(), options.grid)?;
        let (mx, my) = grid.extent();
        let h = grid.h();
        let kernel =
            Kernel::new(h, contact.g(), contact.nu(), -(mx + 2), mx + 2, my, 0.0).scaled(1.0 / h);
        let s = grid.stretch();
        let mut pressure: Vec<f64> = (0..grid.len())
            .map(|e| contact.pressure(grid.x()[e] / s, grid.y()[e] / s))
            .collect();
        let total: f64 = pressure.iter().sum::<f64>() * grid.area();
        pressure.iter_mut().for_each(|v| *v *= contact.p() / total);
        let bound = pressure.iter().map(|p| contact.mu() * p).collect();
        let len = grid.len();
        Ok(EllipticSteadySolver {
            contact,
            options,
            grid,
            kernel,
            pressure,
            bound,
            tx: vec![0.0; len],
            ty: vec![0.0; len],
            stick: vec![true; len],
        })
    }

    /// The grid in use.
    pub fn grid(&self) -> &Grid {
        &self.grid
    }

    /// The contact in use.
    pub fn contact(&self) -> &EllipticContact {
        &self.contact
    }

    /// Solves steady rolling at the given creepages (dimensional: `xi`, `eta` \[-\], `phi`
    /// \[1/m\]), warm-started from the last solution.
    pub fn solve(&mut self, creepage: Creepage) -> Result<EllipticOutput, RefError> {
        creepage.validate()?;
        let (wx, wy): (Vec<f64>, Vec<f64>) = (0..self.grid.len())
            .map(|e| {
                let (x, y) = (self.grid.x()[e], self.grid.y()[e]);
                (
                    creepage.longitudinal - creepage.spin * y,
                    creepage.lateral + creepage.spin * x,
                )
            })
            .unzip();
        let sweeps = SteadyGs::new(&self.grid, &self.kernel).solve(
            &wx,
            &wy,
            &self.bound,
            &self.options,
            &mut self.tx,
            &mut self.ty,
            &mut self.stick,
        )?;
        let traction = TractionField::new(
            &self.grid,
            &self.pressure,
            self.contact.mu(),
            &self.tx,
            &self.ty,
        );
        let (fx, fy) = traction.force();
        let mz = traction.moment();
        Ok(EllipticOutput {
            fx,
            fy,
            mz,
            traction,
            sweeps,
        })
    }

    /// Solves at normalised creepages (`xi_n`, `eta_n` over `mu P/(G c^2)`, `phi_n` over
    /// `mu P/(G c^3)`) and returns `(Fx/(mu P), Fy/(mu P), Mz/(mu P c))` in this crate's signs.
    pub fn solve_normalised(
        &mut self,
        xi_n: f64,
        eta_n: f64,
        phi_n: f64,
    ) -> Result<(f64, f64, f64), RefError> {
        let k = &self.contact;
        let (c, mu_p, g) = (k.c(), k.mu_p(), k.g());
        let s = mu_p / (g * c * c);
        let o = self.solve(Creepage {
            longitudinal: xi_n * s,
            lateral: eta_n * s,
            spin: phi_n * s / c,
        })?;
        Ok((o.fx / mu_p, o.fy / mu_p, o.mz / (mu_p * c)))
    }

    /// Forgets the last solution.
    pub fn reset(&mut self) {
        self.tx.iter_mut().for_each(|v| *v = 0.0);
        self.ty.iter_mut().for_each(|v| *v = 0.0);
        self.stick.iter_mut().for_each(|v| *v = true);
    }
}

/// Kalker's linear creep coefficients of an elliptic contact recovered by the boundary elements,
/// normalised with `c = sqrt(a b)`, in this crate's signs (see the module documentation).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EllipticCoefficients {
    /// `C11`: `Fx = G c^2 C11 xi`.
    pub c11: f64,
    /// `C22`: `Fy = G c^2 C22 eta`.
    pub c22: f64,
    /// `C23`: `Fy = G c^3 C23 phi`.
    pub c23: f64,
    /// `C32`: `Mz = G c^3 C32 eta` (reciprocity: `C32 = -C23`).
    pub c32: f64,
    /// `C33`: `Mz = G c^4 C33 phi`.
    pub c33: f64,
}

/// The linear limit (normalised creepages `1e-7`, every element sticks) of the exact theory for
/// the ratio `ab = a/b` and Poisson ratio `nu` in `[0, 0.5]`, on the grid of `options`.
pub fn elliptic_creep_coefficients(
    nu: f64,
    ab: f64,
    options: SolverOptions,
) -> Result<EllipticCoefficients, RefError> {
    let mut s = EllipticSteadySolver::new(EllipticContact::normalised(nu, ab)?, options)?;
    let e = 1e-7;
    let x = s.solve_normalised(e, 0.0, 0.0)?;
    s.reset();
    let y = s.solve_normalised(0.0, e, 0.0)?;
    s.reset();
    let z = s.solve_normalised(0.0, 0.0, e)?;
    Ok(EllipticCoefficients {
        c11: x.0 / e,
        c22: y.1 / e,
        c23: z.1 / e,
        c32: y.2 / e,
        c33: z.2 / e,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bem::SteadySolver;
    use crate::contact::CircularContact;

    #[test]
    fn circle_reproduces_the_circular_solver() {
        // a/b = 1: the same grid, kernel and pressure as the circular solver, so the same forces.
        let mut e = EllipticSteadySolver::new(
            EllipticContact::normalised(0.3, 1.0).unwrap(),
            SolverOptions::with_grid(12),
        )
        .unwrap();
        let mut c = SteadySolver::new(
            CircularContact::normalised(0.3).unwrap(),
            SolverOptions::with_grid(12),
        )
        .unwrap();
        let cr = Creepage {
            longitudinal: 0.1,
            lateral: -0.05,
            spin: 0.2,
        };
        let (a, b) = (e.solve(cr).unwrap(), c.solve(cr).unwrap());
        assert!((a.fx - b.fx).abs() < 1e-12 && (a.fy - b.fy).abs() < 1e-12);
        assert!((a.mz - b.mz).abs() < 1e-12);
    }

    #[test]
    fn elliptic_grid_covers_the_ellipse_and_saturates_at_mu_p() {
        let c = EllipticContact::normalised(0.25, 0.5).unwrap();
        let mut s = EllipticSteadySolver::new(c, SolverOptions::with_grid(8)).unwrap();
        let area = s.grid().len() as f64 * s.grid().area();
        assert!((area / (PI * c.a() * c.b()) - 1.0).abs() < 1e-12);
        let (fx, fy, _) = s.solve_normalised(50.0, 0.0, 0.0).unwrap();
        assert!(fx < 1.0 + 1e-12 && fx > 0.99, "{fx}");
        assert!(fy.abs() < 1e-9);
        let (_, fy, _) = s.solve_normalised(0.0, 50.0, 0.0).unwrap();
        assert!(fy < 1.0 + 1e-12 && fy > 0.99, "{fy}");
        assert!(EllipticContact::normalised(0.25, 0.0).is_err());
        assert!(EllipticContact::new(1.0, 1.0, 1.0, 1.0, 0.6, 1.0).is_err());
    }
}
