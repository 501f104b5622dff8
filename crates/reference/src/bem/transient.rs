//! Transient rolling and shift: start from no traction and advance step by step, each step rolling
//! a distance `dq` (possibly zero) with a rigid shift increment, holding either the creepage or
//! the tangential force (Kalker's exact theory, see [`crate::bem`]).
//!
//! Per step the slip distance of body q relative to body p at element `I` is
//! `S_I = dW_I - (u_I - u'_I)` with `dW_I` the rigid shift of the step, `u = A t` the displacement
//! difference `u_p - u_q` and `u'_I` the previous displacement difference at the material point's
//! previous position `x_I + dq` (the contact moves `dq` in `+x` over both surfaces). `u'` is
//! computed exactly from the previous tractions with influence coefficients at the shifted
//! offsets. With `dq = h` and the creepage held, the steps converge to the steady solution of
//! [`super::steady()`] (same discretisation); with `dq = 0` and the force increased, they are the
//! Cattaneo-Mindlin shift problem.

use super::{Creepage, SolverOptions, TractionField, convex_gs, root};
use crate::contact::CircularContact;
use crate::error::{RefError, check_finite, check_range};
use crate::grid::Grid;
use crate::influence::Kernel;

/// Largest number of steps accepted by the transient drivers.
pub const MAX_STEPS: usize = 1_000_000;

/// Input of a transient run.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TransientInput {
    /// The contact (radius, normal force, elastic constants, friction).
    pub contact: CircularContact,
    /// Grid and iteration parameters.
    pub options: SolverOptions,
    /// Rolling distance per step `dq` \[m\], finite and > 0 (any value: the previous
    /// displacements are evaluated exactly at the shifted positions; `dq` equal to the element
    /// side [`Grid::h`] reproduces the steady discretisation).
    pub step: f64,
    /// Number of steps, in `[1, MAX_STEPS]`.
    pub steps: usize,
}

/// State after one transient step.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TransientRecord {
    /// Step number, from 1.
    pub step: usize,
    /// Rolling distance since the start \[m\].
    pub rolled: f64,
    /// Longitudinal creepage of the step, `dW_x / dq` \[dimensionless\] (0 when `dq = 0`).
    pub creepage: f64,
    /// Accumulated rigid longitudinal shift `W_x` of q relative to p \[m\].
    pub shift: f64,
    /// Longitudinal force on body p \[N\].
    pub fx: f64,
    /// Lateral force on body p \[N\].
    pub fy: f64,
    /// `fx / (mu P)`.
    pub fx_over_mu_p: f64,
    /// Fraction of the contact area in slip.
    pub slip_fraction: f64,
}

/// A transient solver: the committed state is the traction of the last step.
#[derive(Debug, Clone)]
pub struct TransientSolver {
    contact: CircularContact,
    options: SolverOptions,
    grid: Grid,
    dq: f64,
    /// Cerruti kernel `A` at integer offsets.
    a: Kernel,
    /// Cerruti kernel at offsets shifted by `dq` (previous displacements).
    a_shift: Kernel,
    pressure: Vec<f64>,
    bound: Vec<f64>,
    tx: Vec<f64>,
    ty: Vec<f64>,
    step: usize,
    rolled: f64,
    shift: f64,
    /// Last `dFx/dWx` seen \[N/m\], for the force-held root finding.
    stiffness: f64,
    /// Last shift increment \[m\], the first guess of the next force-held step.
    last_dw: f64,
}

impl TransientSolver {
    /// A solver starting from zero traction, rolling `dq` \[m\] per step (`dq >= 0`, finite).
    pub fn new(
        contact: CircularContact,
        options: SolverOptions,
        dq: f64,
    ) -> Result<Self, RefError> {
        options.validate()?;
        check_range("step", dq, 0.0, f64::MAX, "finite and >= 0")?;
        let grid = Grid::new(contact.a(), options.grid)?;
        let n = options.grid as i64;
        let h = grid.h();
        // Shifted offsets reach (N - 1) h + dq; cap the shift kernel's extent to the grid.
        let a = Kernel::new(h, contact.g(), contact.nu(), -(n - 1), n - 1, n - 1, 0.0);
        let a_shift = if dq == 0.0 {
            a.clone()
        } else {
            Kernel::new(h, contact.g(), contact.nu(), -(n - 1), n - 1, n - 1, dq)
        };
        let pressure = grid.pressure(&contact);
        let bound = pressure.iter().map(|p| contact.mu() * p).collect();
        let len = grid.len();
        // Cattaneo-Mindlin initial stiffness 8 G* a with G* = G / (2 (2 - nu)) (Johnson 1985,
        // §7.2, for Kalker's combined constants).
        let stiffness = 4.0 * contact.g() * contact.a() / (2.0 - contact.nu());
        Ok(TransientSolver {
            contact,
            options,
            grid,
            dq,
            a,
            a_shift,
            pressure,
            bound,
            tx: vec![0.0; len],
            ty: vec![0.0; len],
            step: 0,
            rolled: 0.0,
            shift: 0.0,
            stiffness,
            last_dw: 0.0,
        })
    }

    /// The grid in use.
    pub fn grid(&self) -> &Grid {
        &self.grid
    }

    /// Rolling distance per step \[m\].
    pub fn dq(&self) -> f64 {
        self.dq
    }

    /// The committed traction field.
    pub fn traction(&self) -> TractionField {
        TractionField::new(
            &self.grid,
            &self.pressure,
            self.contact.mu(),
            &self.tx,
            &self.ty,
        )
    }

    /// `w = dW + u'` for a step with rigid shift increment `(dwx, dwy)` \[m\] and rotation
    /// increment `dphi` \[rad\] of q relative to p about the normal.
    fn rhs(&self, dwx: f64, dwy: f64, dphi: f64) -> (Vec<f64>, Vec<f64>) {
        let n = self.grid.len();
        let mut wx: Vec<f64> = (0..n).map(|e| dwx - dphi * self.grid.y()[e]).collect();
        let mut wy: Vec<f64> = (0..n).map(|e| dwy + dphi * self.grid.x()[e]).collect();
        // u'_I = sum_J A_shift(I - J) t_J: previous displacement at x_I + dq.
        for j in 0..n {
            if self.tx[j] != 0.0 || self.ty[j] != 0.0 {
                convex_gs::add_column(
                    &self.grid,
                    &self.a_shift,
                    j,
                    1.0,
                    self.tx[j],
                    self.ty[j],
                    &mut wx,
                    &mut wy,
                );
            }
        }
        (wx, wy)
    }

    /// Solves a step (without committing) into `(tx, ty)`, warm-started from their content.
    fn solve_into(
        &self,
        wx: &[f64],
        wy: &[f64],
        tx: &mut [f64],
        ty: &mut [f64],
    ) -> Result<(), RefError> {
        convex_gs::solve(
            &self.grid,
            &self.a,
            wx,
            wy,
            &self.bound,
            &self.options,
            tx,
            ty,
        )?;
        Ok(())
    }

    fn commit(&mut self, tx: Vec<f64>, ty: Vec<f64>, dwx: f64) -> TransientRecord {
        self.tx = tx;
        self.ty = ty;
        self.step += 1;
        self.rolled += self.dq;
        self.shift += dwx;
        let t = self.traction();
        let (fx, fy) = t.force();
        TransientRecord {
            step: self.step,
            rolled: self.rolled,
            creepage: if self.dq > 0.0 { dwx / self.dq } else { 0.0 },
            shift: self.shift,
            fx,
            fy,
            fx_over_mu_p: fx / self.contact.mu_p(),
            slip_fraction: t.slip_fraction(),
        }
    }

    /// Advances one step with the rigid shift increment `(dwx, dwy)` \[m\] and rotation increment
    /// `dphi` \[rad\] of q relative to p (all finite).
    pub fn advance(&mut self, dwx: f64, dwy: f64, dphi: f64) -> Result<TransientRecord, RefError> {
        check_finite("shift", dwx)?;
        check_finite("lateral shift", dwy)?;
        check_finite("rotation", dphi)?;
        let (wx, wy) = self.rhs(dwx, dwy, dphi);
        let (mut tx, mut ty) = (self.tx.clone(), self.ty.clone());
        self.solve_into(&wx, &wy, &mut tx, &mut ty)?;
        Ok(self.commit(tx, ty, dwx))
    }

    /// Advances one step holding the creepage: `dW = (xi dq, eta dq)`, `dphi = phi dq`.
    pub fn advance_creepage(&mut self, c: Creepage) -> Result<TransientRecord, RefError> {
        c.validate()?;
        self.advance(
            c.longitudinal * self.dq,
            c.lateral * self.dq,
            c.spin * self.dq,
        )
    }

    /// Advances one step with the longitudinal force brought to `fx` \[N\] (`|fx| < mu P`, lateral
    /// shift and spin zero): the rigid shift increment is found by a safeguarded secant iteration
    /// (regula falsi, Illinois variant) on the monotone map `dW_x -> Fx`.
    pub fn advance_force(&mut self, fx: f64) -> Result<TransientRecord, RefError> {
        let mu_p = self.contact.mu_p();
        check_range(
            "force",
            fx,
            -mu_p * (1.0 - 1e-9),
            mu_p * (1.0 - 1e-9),
            "|Fx| < mu P",
        )?;
        let (dw, tx, ty) = self.find_shift(fx)?;
        self.last_dw = dw;
        Ok(self.commit(tx, ty, dw))
    }

    /// Force `Fx` \[N\] after a step with shift `dw`, solved into `(tx, ty)`.
    fn force_at(
        &self,
        u0x: &[f64],
        u0y: &[f64],
        dw: f64,
        tx: &mut [f64],
        ty: &mut [f64],
    ) -> Result<f64, RefError> {
        let wx: Vec<f64> = u0x.iter().map(|v| v + dw).collect();
        self.solve_into(&wx, u0y, tx, ty)?;
        Ok(tx.iter().sum::<f64>() * self.grid.area())
    }

    /// The shift increment that brings `Fx` to `fx`, and the tractions there.
    fn find_shift(&mut self, fx: f64) -> Result<(f64, Vec<f64>, Vec<f64>), RefError> {
        let tol = 1e-8 * self.contact.mu_p();
        let (u0x, u0y) = self.rhs(0.0, 0.0, 0.0);
        let (mut tx, mut ty) = (self.tx.clone(), self.ty.clone());
        let x0 = if self.dq > 0.0 { self.last_dw } else { 0.0 };
        let this = &*self;
        let (dw, slope) = root::illinois(
            |dw| Ok(this.force_at(&u0x, &u0y, dw, &mut tx, &mut ty)? - fx),
            x0,
            self.stiffness,
            tol,
            "force-held transient step",
        )?;
        self.stiffness = slope;
        Ok((dw, tx, ty))
    }
}

fn validate(input: &TransientInput) -> Result<(), RefError> {
    crate::error::check_positive("step", input.step)?;
    if !(1..=MAX_STEPS).contains(&input.steps) {
        return Err(RefError::InvalidGrid {
            name: "steps",
            value: input.steps,
            expected: "in [1, 1000000]",
        });
    }
    Ok(())
}

/// Transient rolling from zero traction with the creepages held: one record per step.
pub fn transient_hold_creepage(
    input: &TransientInput,
    creepage: Creepage,
) -> Result<Vec<TransientRecord>, RefError> {
    validate(input)?;
    creepage.validate()?;
    let mut s = TransientSolver::new(input.contact, input.options, input.step)?;
    (0..input.steps)
        .map(|_| s.advance_creepage(creepage))
        .collect()
}

/// Transient rolling from zero traction with the longitudinal force held at
/// `fx_over_mu_p * mu P` (`|fx_over_mu_p| < 1`): one record per step, the first of which also
/// applies the force (its creepage is the Cattaneo-Mindlin shift divided by `dq`).
pub fn transient_hold_force(
    input: &TransientInput,
    fx_over_mu_p: f64,
) -> Result<Vec<TransientRecord>, RefError> {
    validate(input)?;
    check_range(
        "force ratio",
        fx_over_mu_p,
        -0.999_999,
        0.999_999,
        "|Q/(mu P)| < 1",
    )?;
    let mut s = TransientSolver::new(input.contact, input.options, input.step)?;
    let fx = fx_over_mu_p * input.contact.mu_p();
    (0..input.steps).map(|_| s.advance_force(fx)).collect()
}

/// The Cattaneo-Mindlin loading curve by the boundary elements: no rolling, the longitudinal force
/// raised through `ratios` (values of `Q/(mu P)`, each in `[0, 1)`, increasing); returns the
/// rigid shift `delta` \[m\] of q relative to p at each. Compare [`crate::mindlin::Mindlin::loading_shift`].
pub fn mindlin_loading(
    contact: CircularContact,
    options: SolverOptions,
    ratios: &[f64],
) -> Result<Vec<f64>, RefError> {
    let mut s = TransientSolver::new(contact, options, 0.0)?;
    let mut prev = 0.0;
    let mut out = Vec::with_capacity(ratios.len());
    for &r in ratios {
        check_range("force ratio", r, 0.0, 0.999_999, "in [0, 1)")?;
        if r < prev {
            return Err(RefError::InvalidParameter {
                name: "force ratio",
                value: r,
                expected: "non-decreasing (monotonic loading)",
            });
        }
        prev = r;
        out.push(s.advance_force(r * contact.mu_p())?.shift);
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bem::SteadySolver;
    use crate::mindlin::Mindlin;

    fn closed_form(c: &CircularContact) -> Mindlin {
        // Quasi-identical pair in Kalker's constants: G* = G / (2 (2 - nu)).
        Mindlin::new(c.mu_p(), c.g() / (2.0 * (2.0 - c.nu())), c.a()).unwrap()
    }

    #[test]
    fn no_rolling_reproduces_mindlins_loading_curve() {
        // Cattaneo-Mindlin (Johnson 1985 §7.2): exact in the uncoupled theory at nu = 0; at
        // nu > 0 Mindlin neglects the non-parallel slip in the annulus, which is small. The grid
        // error is O(h): within 1.5 % at N = 16, smaller at N = 24.
        for nu in [0.0, 0.3] {
            let c = CircularContact::normalised(nu).unwrap();
            let m = closed_form(&c);
            let ratios = [0.1, 0.3, 0.5, 0.7, 0.9, 0.97];
            let mut worst = [0.0f64; 2];
            for (k, n) in [16, 24].into_iter().enumerate() {
                let d = mindlin_loading(c, SolverOptions::with_grid(n), &ratios).unwrap();
                for (r, d) in ratios.iter().zip(&d) {
                    let e = d / m.loading_shift(*r).unwrap() - 1.0;
                    worst[k] = worst[k].max(e.abs());
                }
            }
            assert!(worst[0] < 0.015, "nu={nu}: {worst:?}");
            assert!(worst[1] < worst[0], "nu={nu}: {worst:?}");
        }
    }

    #[test]
    fn unloading_follows_mindlin_deresiewicz() {
        let c = CircularContact::normalised(0.0).unwrap();
        let m = closed_form(&c);
        let mut s = TransientSolver::new(c, SolverOptions::with_grid(16), 0.0).unwrap();
        let qs = 0.8;
        for r in [0.4, qs] {
            s.advance_force(r).unwrap();
        }
        for q in [0.5, 0.0, -0.4, -0.8] {
            let d = s.advance_force(q).unwrap().shift;
            let expect = m.unloading_shift(qs, q).unwrap();
            let scale = m.loading_shift(qs).unwrap();
            assert!((d - expect).abs() < 0.015 * scale, "Q={q}: {d} vs {expect}");
        }
        // Reloading back to Q* closes the loop.
        let d = s.advance_force(qs).unwrap().shift;
        let expect = m.reloading_shift(qs, qs).unwrap();
        assert!((d - expect).abs() < 0.015 * expect.abs(), "{d} vs {expect}");
    }

    #[test]
    fn long_rolling_with_creepage_held_reaches_the_steady_solution() {
        // Rolling one element per step is the steady discretisation; after rolling 8 diameters
        // the transient force equals the steady one.
        let c = CircularContact::normalised(0.25).unwrap();
        let opts = SolverOptions::with_grid(10);
        let mut st = SteadySolver::new(c, opts).unwrap();
        let xi = 0.2;
        let steady = st.solve(Creepage::longitudinal(xi)).unwrap();
        let h = st.grid().h();
        let input = TransientInput {
            contact: c,
            options: opts,
            step: h,
            steps: 80,
        };
        let rec = transient_hold_creepage(&input, Creepage::longitudinal(xi)).unwrap();
        // Starts from zero and grows monotonically to the steady force.
        assert!(rec[0].fx_over_mu_p < 0.25 * steady.fx);
        assert!(rec.windows(2).all(|w| w[1].fx >= w[0].fx - 1e-9));
        let last = rec.last().unwrap();
        assert!(
            (last.fx / steady.fx - 1.0).abs() < 1e-4,
            "{} vs {}",
            last.fx,
            steady.fx
        );
        assert!((last.rolled - 80.0 * h).abs() < 1e-12);
    }

    #[test]
    fn long_rolling_with_force_held_reaches_the_steady_creepage() {
        let c = CircularContact::normalised(0.25).unwrap();
        let opts = SolverOptions::with_grid(10);
        let mut st = SteadySolver::new(c, opts).unwrap();
        let steady = st.solve(Creepage::longitudinal(0.2)).unwrap();
        let input = TransientInput {
            contact: c,
            options: opts,
            step: st.grid().h(),
            steps: 60,
        };
        let rec = transient_hold_force(&input, steady.fx).unwrap();
        // The first step carries the Cattaneo-Mindlin shift: a large apparent creepage.
        assert!(rec[0].creepage > 5.0 * 0.2, "{}", rec[0].creepage);
        assert!(
            rec.iter()
                .all(|r| (r.fx_over_mu_p - steady.fx).abs() < 1e-7)
        );
        let last = rec.last().unwrap();
        assert!(
            (last.creepage / 0.2 - 1.0).abs() < 1e-3,
            "{}",
            last.creepage
        );
    }

    #[test]
    fn rejects_bad_input() {
        let c = CircularContact::normalised(0.25).unwrap();
        let opts = SolverOptions::with_grid(8);
        let mut input = TransientInput {
            contact: c,
            options: opts,
            step: 0.0,
            steps: 3,
        };
        assert!(transient_hold_force(&input, 0.5).is_err());
        input.step = 0.1;
        assert!(transient_hold_force(&input, 1.0).is_err());
        input.steps = 0;
        assert!(transient_hold_creepage(&input, Creepage::longitudinal(0.1)).is_err());
        assert!(mindlin_loading(c, opts, &[0.5, 0.2]).is_err());
        assert!(TransientSolver::new(c, opts, f64::NAN).is_err());
    }
}
