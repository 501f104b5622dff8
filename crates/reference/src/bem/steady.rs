//! Steady-state rolling: total tangential force, spin moment and traction field for given
//! longitudinal, lateral and spin creepages (Kalker's exact theory, see [`crate::bem`]).

use super::gauss_seidel::{self, Operator};
use super::{Creepage, SolverOptions, TractionField};
use crate::contact::CircularContact;
use crate::error::RefError;
use crate::grid::Grid;
use crate::influence::Kernel;

/// Input of one steady-state rolling solve.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SteadyInput {
    /// The contact (radius, normal force, elastic constants, friction).
    pub contact: CircularContact,
    /// Rigid creepages of body q relative to body p.
    pub creepage: Creepage,
    /// Grid and iteration parameters.
    pub options: SolverOptions,
}

/// Result of a steady-state rolling solve.
#[derive(Debug, Clone, PartialEq)]
pub struct SteadyOutput {
    /// Longitudinal tangential force on body p [N].
    pub fx: f64,
    /// Lateral tangential force on body p [N].
    pub fy: f64,
    /// Spin moment of the tangential traction on body p about the contact centre [N m].
    pub mz: f64,
    /// Element-wise traction, stick and slip.
    pub traction: TractionField,
    /// Gauss-Seidel sweeps used.
    pub sweeps: usize,
}

/// A reusable steady-state solver: grid, influence kernel and pressure are built once; each
/// [`SteadySolver::solve`] starts from the previous solution (useful for creepage sweeps).
#[derive(Debug, Clone)]
pub struct SteadySolver {
    contact: CircularContact,
    options: SolverOptions,
    grid: Grid,
    kernel: Kernel,
    pressure: Vec<f64>,
    bound: Vec<f64>,
    order: Vec<usize>,
    tx: Vec<f64>,
    ty: Vec<f64>,
}

impl SteadySolver {
    /// Builds the grid, the Hertz pressure and the steady rolling kernel
    /// `B(d) = (A(d + e_x) - A(d)) / h` (upwind derivative of the Cerruti displacements).
    pub fn new(contact: CircularContact, options: SolverOptions) -> Result<Self, RefError> {
        options.validate()?;
        let grid = Grid::new(contact.a(), options.grid)?;
        let n = options.grid as i64;
        let h = grid.h();
        let a = Kernel::new(h, contact.g(), contact.nu(), -(n - 1), n, n - 1, 0.0);
        let kernel = a.forward_difference(h);
        let pressure = grid.pressure(&contact);
        let bound = pressure.iter().map(|p| contact.mu() * p).collect();
        let order = gauss_seidel::leading_edge_first(&grid);
        let len = grid.len();
        Ok(SteadySolver {
            contact,
            options,
            grid,
            kernel,
            pressure,
            bound,
            order,
            tx: vec![0.0; len],
            ty: vec![0.0; len],
        })
    }

    /// The grid in use.
    pub fn grid(&self) -> &Grid {
        &self.grid
    }

    /// The contact in use.
    pub fn contact(&self) -> &CircularContact {
        &self.contact
    }

    /// Solves steady rolling at the given creepages (warm-started from the last solution).
    pub fn solve(&mut self, creepage: Creepage) -> Result<SteadyOutput, RefError> {
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
        let op = Operator {
            grid: &self.grid,
            kernel: &self.kernel,
        };
        let sweeps = gauss_seidel::solve(
            &op,
            &wx,
            &wy,
            &self.bound,
            &self.order,
            &self.options,
            &mut self.tx,
            &mut self.ty,
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
        Ok(SteadyOutput {
            fx,
            fy,
            mz,
            traction,
            sweeps,
        })
    }

    /// Forgets the last solution (the next solve starts from zero traction).
    pub fn reset(&mut self) {
        self.tx.iter_mut().for_each(|v| *v = 0.0);
        self.ty.iter_mut().for_each(|v| *v = 0.0);
    }
}

/// One steady-state rolling solve (builds a [`SteadySolver`] and solves once).
pub fn steady(input: &SteadyInput) -> Result<SteadyOutput, RefError> {
    SteadySolver::new(input.contact, input.options)?.solve(input.creepage)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn solver(nu: f64, n: usize) -> SteadySolver {
        SteadySolver::new(
            CircularContact::normalised(nu).unwrap(),
            SolverOptions::with_grid(n),
        )
        .unwrap()
    }

    #[test]
    fn force_follows_creepage_and_is_odd() {
        let mut s = solver(0.3, 12);
        let a = s.solve(Creepage::longitudinal(0.1)).unwrap();
        let b = s.solve(Creepage::longitudinal(-0.1)).unwrap();
        assert!(a.fx > 0.0, "Q . v_disp must be positive");
        assert!((a.fx + b.fx).abs() < 1e-9, "{} vs {}", a.fx, b.fx);
        assert!(a.fy.abs() < 1e-9 && a.mz.abs() < 1e-9);
    }

    #[test]
    fn full_slip_limit_is_mu_p() {
        // Creepage far above 3 / C11 (normalised) saturates: |Q| -> mu P, all elements slip.
        let mut s = solver(0.25, 12);
        let out = s.solve(Creepage::longitudinal(10.0)).unwrap();
        assert!((out.fx - 1.0).abs() < 1e-9, "{}", out.fx);
        assert!(out.traction.slip.iter().all(|&x| x));
    }

    #[test]
    fn small_creepage_sticks_at_leading_edge() {
        let mut s = solver(0.25, 16);
        let out = s.solve(Creepage::longitudinal(0.05)).unwrap();
        let t = &out.traction;
        // The leading-edge element of the middle row sticks; the trailing one slips.
        let row: Vec<usize> = (0..t.x.len()).filter(|&e| t.y[e].abs() < t.h).collect();
        let lead = *row.iter().max_by(|&&i, &&j| t.x[i].total_cmp(&t.x[j])).unwrap();
        let trail = *row.iter().min_by(|&&i, &&j| t.x[i].total_cmp(&t.x[j])).unwrap();
        assert!(!t.slip[lead] && t.slip[trail]);
    }

    #[test]
    fn rejects_bad_input() {
        let c = CircularContact::normalised(0.3).unwrap();
        assert!(SteadySolver::new(c, SolverOptions::with_grid(2)).is_err());
        let mut s = solver(0.3, 8);
        assert!(s.solve(Creepage::longitudinal(f64::NAN)).is_err());
    }
}
