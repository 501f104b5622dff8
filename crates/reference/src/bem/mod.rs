//! Boundary-element solver of Kalker's exact theory of rolling contact for two quasi-identical
//! elastic bodies in circular Hertz contact (the method of Kalker's program CONTACT: Kalker 1990,
//! *Three-dimensional elastic bodies in rolling contact*, ch. 5; Vollebregt, *User guide for
//! CONTACT*).
//!
//! # Discretisation and conventions
//!
//! * The contact circle of radius `a` is covered by square elements of side `h = 2a/N` (see
//!   [`Grid`](crate::grid::Grid)); the traction is constant on each element and collocated at its
//!   centre; the normal pressure is Hertz's at the element centre, rescaled to carry `P` exactly.
//! * Influence coefficients are Cerruti's for a uniform traction on a rectangle, summed for the two
//!   bodies with the combined `G`, `nu` ([`crate::influence`]); normal-tangential coupling is
//!   neglected (quasi-identical bodies).
//! * `x` is the rolling direction: the contact moves in `+x` over both surfaces, so material
//!   enters the contact at its **leading edge `x = +a`** and leaves at `x = -a`.
//! * Traction `t` is the traction **on body p from body q** (the project's `Q` is its integral).
//!   Creepage is the rigid slip velocity of **q relative to p** divided by the rolling speed
//!   (`v_disp / |v_roll|` of docs/ARCHITECTURE.md §4), so the rigid slip per unit rolling distance at
//!   `(x, y)` is `w = (xi - phi y, eta + phi x)` with `xi` longitudinal, `eta` lateral
//!   \[dimensionless\] and `phi` the spin creepage \[1/m\] (relative angular velocity of q with
//!   respect to p about the normal from p to q, over the rolling speed).
//!   With these signs the linear theory reads `Fx = G a^2 C11 xi`, `Fy = G a^2 C22 eta + G a^3
//!   C23 phi` (Kalker's `Fx = -G a b C11 xi` with his creepage of the opposite sign), and the
//!   dissipation `Q . v_disp` is positive.
//! * Steady state: the slip per unit rolling distance is `s = w + du/dx`, `u = u_p - u_q`, with
//!   the derivative taken upwind, `du/dx ~ (u(x + h) - u(x))/h` (CONTACT's steady-state
//!   discretisation with time step `h / V`).
//! * Transient: per step of rolling distance `dq`, the slip distance is `s = dW - (u - u')`, with
//!   `dW` the rigid shift of the step and `u'` the previous displacement difference at the
//!   material point's previous position `x + dq` (computed exactly with influence coefficients at
//!   the shifted offsets, so `dq` need not be a multiple of `h`).
//! * Coulomb friction with the bound `mu p`, full non-linear slip direction, solved by a
//!   non-linear Gauss-Seidel (module `steady_gs` for steady rolling, module `convex_gs` for transient steps).
//!
//! # Cost
//!
//! The influence matrix is never stored: translation invariance makes it a lookup in a
//! `(2N) x (2N)` table. One Gauss-Seidel sweep costs `4 n^2` multiply-adds for `n ~ pi N^2 / 4`
//! elements (about 6 million at `N = 40`).

pub(crate) mod convex_gs;
pub mod elliptic;
pub(crate) mod local;
pub(crate) mod root;
pub mod steady;
pub(crate) mod steady_gs;
pub mod transient;

pub use elliptic::{
    EllipticCoefficients, EllipticContact, EllipticOutput, EllipticSteadySolver,
    elliptic_creep_coefficients,
};
pub use steady::{
    CreepCoefficients, SteadyInput, SteadyOutput, SteadySolver, creep_coefficients, steady,
};
pub use transient::{
    TransientInput, TransientRecord, TransientSolver, mindlin_loading, transient_hold_creepage,
    transient_hold_force,
};

use crate::error::{RefError, check_finite};

/// Rigid creepages of body q relative to body p (see the module's sign conventions).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Creepage {
    /// Longitudinal creepage `xi` (rolling direction `x`) \[dimensionless\].
    pub longitudinal: f64,
    /// Lateral creepage `eta` \[dimensionless\].
    pub lateral: f64,
    /// Spin creepage `phi` \[1/m\].
    pub spin: f64,
}

impl Creepage {
    /// Pure longitudinal creepage `xi` \[dimensionless\].
    pub fn longitudinal(xi: f64) -> Self {
        Creepage {
            longitudinal: xi,
            ..Default::default()
        }
    }

    /// Checks that every component is finite.
    pub fn validate(&self) -> Result<(), RefError> {
        check_finite("creepage", self.longitudinal)?;
        check_finite("lateral", self.lateral)?;
        check_finite("spin", self.spin)?;
        Ok(())
    }
}

/// Discretisation and iteration parameters of the boundary-element solver.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SolverOptions {
    /// Elements across the contact diameter `N`, in `[4, 256]` (32 by default).
    pub grid: usize,
    /// Convergence tolerance: a Gauss-Seidel sweep that changes no traction by more than
    /// `tolerance * mu p0` ends the iteration. In `(0, 0.1]`; `1e-10` by default.
    pub tolerance: f64,
    /// Maximum number of Gauss-Seidel sweeps per solve, >= 1 (20 000 by default).
    pub max_sweeps: usize,
}

impl Default for SolverOptions {
    fn default() -> Self {
        SolverOptions {
            grid: 32,
            tolerance: 1e-10,
            max_sweeps: 20_000,
        }
    }
}

impl SolverOptions {
    /// Default options with `grid` elements across the diameter.
    pub fn with_grid(grid: usize) -> Self {
        SolverOptions {
            grid,
            ..Default::default()
        }
    }

    /// Checks the ranges documented on the fields.
    pub fn validate(&self) -> Result<(), RefError> {
        crate::error::check_range(
            "tolerance",
            self.tolerance,
            f64::MIN_POSITIVE,
            0.1,
            "in (0, 0.1]",
        )?;
        if self.max_sweeps == 0 {
            return Err(RefError::InvalidGrid {
                name: "max_sweeps",
                value: 0,
                expected: ">= 1",
            });
        }
        Ok(())
    }
}

/// The traction field of a solution, element by element (for plots of stick and slip zones).
#[derive(Debug, Clone, PartialEq)]
pub struct TractionField {
    /// Element centres' `x` \[m\] (rolling direction; leading edge at `+a`).
    pub x: Vec<f64>,
    /// Element centres' `y` \[m\].
    pub y: Vec<f64>,
    /// Element side `h` \[m\].
    pub h: f64,
    /// Normal pressure \[Pa\].
    pub pressure: Vec<f64>,
    /// Tangential traction on body p, `x` component \[Pa\].
    pub tx: Vec<f64>,
    /// Tangential traction on body p, `y` component \[Pa\].
    pub ty: Vec<f64>,
    /// Whether the element slips (`|t| = mu p`); otherwise it sticks.
    pub slip: Vec<bool>,
}

impl TractionField {
    pub(crate) fn new(
        grid: &crate::grid::Grid,
        pressure: &[f64],
        mu: f64,
        tx: &[f64],
        ty: &[f64],
    ) -> Self {
        let slip = (0..tx.len())
            .map(|e| {
                let g = mu * pressure[e];
                tx[e].hypot(ty[e]) >= g * (1.0 - 1e-9)
            })
            .collect();
        TractionField {
            x: grid.x().to_vec(),
            y: grid.y().to_vec(),
            h: grid.h(),
            pressure: pressure.to_vec(),
            tx: tx.to_vec(),
            ty: ty.to_vec(),
            slip,
        }
    }

    /// Total tangential force on body p `(Fx, Fy)` \[N\].
    pub fn force(&self) -> (f64, f64) {
        let a = self.h * self.h;
        (
            self.tx.iter().sum::<f64>() * a,
            self.ty.iter().sum::<f64>() * a,
        )
    }

    /// Moment of the tangential traction about the contact centre, `Mz = sum (x ty - y tx) h^2`
    /// \[N m\].
    pub fn moment(&self) -> f64 {
        let a = self.h * self.h;
        (0..self.tx.len())
            .map(|e| self.x[e] * self.ty[e] - self.y[e] * self.tx[e])
            .sum::<f64>()
            * a
    }

    /// Fraction of the contact area that slips, in `[0, 1]`.
    pub fn slip_fraction(&self) -> f64 {
        self.slip.iter().filter(|&&s| s).count() as f64 / self.slip.len().max(1) as f64
    }
}
