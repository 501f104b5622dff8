//! Grading of the model tiers against the references: the creep-law tiers (crate `creep-law`:
//! Kuhn's rule, the fitted steady law, the fitted transient law), Coulomb friction, FASTSIM
//! ([`crate::fastsim`]) and the boundary elements ([`crate::bem`]), on the cases of the
//! speed-against-error report (`creep report`): steady creep curves, transient build-up at held
//! force and held creepage, a Cattaneo-Mindlin load/unload/reload cycle and Carter's line contact.
//!
//! The exact theory is read from the checked-in boundary-element tables of `crates/reference/data`
//! (written by `creep ref fit steady|transient`, provenance in `data/README.md`), so grading is
//! fast. Used by the test `tiers_vs_bem`, the example `tier_errors` and the CLI's report.
//!
//! All quantities are in the normalised units of the tables (`a = G = mu P = 1` for the boundary
//! elements; the creep-law tiers run on [`pair`], a unit sphere on a plane with `G = mu = 1` at
//! `P = 1 N`, with creepages scaled by `mu P/(G a^2)` and distances by `a`).

use crate::bem::{Creepage, SolverOptions};
use crate::carter::Carter;
use crate::contact::CircularContact;
use crate::error::RefError;
use crate::fastsim::{FastsimOptions, fastsim};
use crate::fit::{
    BEYOND_SATURATION, STEADY_RATIOS, SteadyCurve, TransientCase, TransientCurve, read_steady_csv,
    read_transient_csv,
};
use crate::mindlin::Mindlin;
use creep_law::{
    CreepInput, CreepLaw, CreepModel, CreepState, Material, PairMaterial, SteadyLaw, Surface, Vec2,
};

/// The steady table (grids `"32"`, `"64"` and their extrapolation `"ext"`).
pub const STEADY_CSV: &str = include_str!("../data/steady_bem.csv");
/// The transient table (grids `"16"` and `"32"`).
pub const TRANSIENT_CSV: &str = include_str!("../data/transient_bem.csv");

/// Smallest force ratio `Q/(mu P)` of the report's steady creepage errors.
pub const S_MIN: f64 = 0.02;
/// Largest force ratio of the creepage-error bound (and of the report's steady errors).
pub const S_MAX: f64 = 0.98;

/// Steady curves of one grid label (`"32"`, `"64"` or `"ext"`).
pub fn steady(grid: &str) -> Result<Vec<SteadyCurve>, RefError> {
    Ok(read_steady_csv(STEADY_CSV)?
        .into_iter()
        .filter(|c| c.grid == grid)
        .collect())
}

/// Grid-extrapolated steady curves (`2 f(64) - f(32)`).
pub fn steady_ext() -> Result<Vec<SteadyCurve>, RefError> {
    steady("ext")
}

/// Transient curves of one grid label (`"16"` or `"32"`).
pub fn transient(grid: &str) -> Result<Vec<TransientCurve>, RefError> {
    Ok(read_transient_csv(TRANSIENT_CSV)?
        .into_iter()
        .filter(|c| c.grid == grid)
        .collect())
}

/// Steady errors of `model` on one curve: (max |relative creepage error| for s <= S_MAX,
/// max |force error| / (mu P) over every tabulated creepage, including saturation and beyond).
pub fn steady_errors(model: CreepModel, c: &SteadyCurve) -> (f64, f64) {
    let law = SteadyLaw::new(model, c.nu);
    let mut ex: f64 = 0.0;
    let mut eq: f64 = 0.0;
    for (&s, &x) in STEADY_RATIOS.iter().zip(&c.creepage) {
        if s <= S_MAX {
            ex = ex.max((law.creepage_n(s) / x - 1.0).abs());
        }
        eq = eq.max((law.force_ratio(x) - s).abs());
    }
    eq = eq.max((law.force_ratio(c.x_sat) - c.s_sat).abs());
    for (k, &s) in BEYOND_SATURATION.iter().zip(&c.beyond) {
        eq = eq.max((law.force_ratio(k * c.x_sat) - s).abs());
    }
    (ex, eq)
}

fn missing(name: &'static str, value: f64) -> RefError {
    RefError::InvalidParameter {
        name,
        value,
        expected: "a value of the boundary-element tables",
    }
}

/// Steady creepage (normalised) of the curves at Poisson ratio `nu` and force ratio `r` (one of
/// [`STEADY_RATIOS`]).
pub fn steady_creepage(curves: &[SteadyCurve], nu: f64, r: f64) -> Result<f64, RefError> {
    let c = curves
        .iter()
        .find(|c| c.nu == nu)
        .ok_or(missing("nu", nu))?;
    let i = STEADY_RATIOS
        .iter()
        .position(|&s| s == r)
        .ok_or(missing("force ratio", r))?;
    Ok(c.creepage[i])
}

/// The normalised pair (G = 1 Pa, mu = 1, a unit sphere on a plane; the law is run at P = 1 N
/// with Hertz's `a`, creepages scaled by `mu P/(G a^2)` and distances by `a`).
pub fn pair(nu: f64) -> Result<PairMaterial, RefError> {
    let bad = |_| RefError::InvalidParameter {
        name: "nu",
        value: nu,
        expected: "a Poisson ratio in [0, 0.5]",
    };
    let m = Material::new(1.0, nu, 1.0, 1.0).map_err(bad)?;
    PairMaterial::new(&m, &m, Surface::Sphere(1.0), Surface::Plane).map_err(bad)
}

/// `model` run through a BEM transient case with the same steps: returns, per step, the
/// normalised creepage (held force) or the force ratio (held creepage). `xi_ss` is the steady
/// creepage held in the held-creepage case.
pub fn model_transient(
    model: CreepModel,
    c: &TransientCurve,
    xi_ss: f64,
) -> Result<Vec<f64>, RefError> {
    let pair = pair(c.nu)?;
    let p = 1.0;
    let a = creep_law::hertz::contact_radius(&pair, p);
    // Normalised creepage xi_n = xi G a^2/(mu P) = xi a^2 here.
    let scale = a * a;
    let mut st = CreepState::new();
    st.update(
        &CreepLaw::new(pair, model),
        CreepInput::new(p, Vec2::ZERO, Vec2::ZERO).with_radius(a),
    );
    let mut prev = 0.0;
    let mut out = Vec::with_capacity(c.rolled.len());
    for (i, &rolled) in c.rolled.iter().enumerate() {
        let dq = (rolled - prev) * a;
        prev = rolled;
        let roll = Vec2::new(dq, 0.0);
        match c.case {
            TransientCase::HoldForce(s) => {
                if i == 0 {
                    // Mindlin's shift to s mu P (Cattaneo-Mindlin, exact in MindlinState).
                    let d = mindlin_shift(&pair, p, a, s);
                    let step = st.update(
                        &CreepLaw::new(pair, model),
                        CreepInput::new(p, Vec2::new(d, 0.0), roll).with_radius(a),
                    );
                    out.push((d + step.creep_displacement.x) / dq * scale);
                } else {
                    out.push(hold_force_step(&mut st, &pair, model, p, a, dq) * scale);
                }
            }
            TransientCase::HoldCreepage(_) => {
                let step = st.update(
                    &CreepLaw::new(pair, model),
                    CreepInput::new(p, Vec2::new(xi_ss / scale * dq, 0.0), roll).with_radius(a),
                );
                out.push(step.q.x / (pair.mu * p));
            }
        }
    }
    Ok(out)
}

/// Cattaneo-Mindlin shift \[m\] of loading from rest to `s mu P` (Mindlin 1949;
/// `3 mu P/(16 G* a) [1 - (1 - s)^(2/3)]`).
fn mindlin_shift(pair: &PairMaterial, p: f64, a: f64, s: f64) -> f64 {
    let ds = 3.0 * pair.mu * p / (16.0 * pair.g_star * a);
    ds * (1.0 - (1.0 - s).powf(2.0 / 3.0))
}

/// One step rolling `dq` \[m\] with the force held: the contact slides by exactly the step's creep
/// displacement. Returns the creepage of the step (creep displacement over `dq`, dimensional).
fn hold_force_step(
    st: &mut CreepState,
    pair: &PairMaterial,
    model: CreepModel,
    p: f64,
    a: f64,
    dq: f64,
) -> f64 {
    let roll = Vec2::new(dq, 0.0);
    let mut probe = *st;
    let c = probe
        .update(
            &CreepLaw::new(*pair, model),
            CreepInput::new(p, Vec2::ZERO, roll).with_radius(a),
        )
        .creep_displacement;
    st.update(
        &CreepLaw::new(*pair, model),
        CreepInput::new(p, c, roll).with_radius(a),
    );
    c.x / dq
}

/// Max error of `model` on a transient BEM curve: held force, `max |xi_model/xi_ss - shape|`
/// from the second step on (the first carries the Mindlin shift), with `shape` the BEM creepage
/// over that grid's own steady creepage and `xi_ss` the extrapolated steady creepage; held
/// creepage, `max |s_model/s - f_bem/s|` over all steps (the model held at `xi_ss`).
pub fn transient_error(
    model: CreepModel,
    c: &TransientCurve,
    steady: &[SteadyCurve],
) -> Result<f64, RefError> {
    let xi_ss = steady_creepage(steady, c.nu, case_ratio(c.case))?;
    let m = model_transient(model, c, xi_ss)?;
    Ok(transient_stats(c, &m, xi_ss).max)
}

/// The force ratio of a transient case.
pub fn case_ratio(c: TransientCase) -> f64 {
    match c {
        TransientCase::HoldForce(r) | TransientCase::HoldCreepage(r) => r,
    }
}

/// Short label of a case.
pub fn case_label(c: TransientCase) -> String {
    match c {
        TransientCase::HoldForce(r) => format!("held force {r}"),
        TransientCase::HoldCreepage(r) => format!("held creepage xi_ss({r})"),
    }
}

/// Largest and root-mean-square error of a comparison.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ErrorStats {
    /// Largest absolute error.
    pub max: f64,
    /// Root mean square of the errors.
    pub rms: f64,
}

impl ErrorStats {
    /// Statistics of the errors `e` (NaN for an empty list).
    pub fn of(e: impl IntoIterator<Item = f64>) -> Self {
        let (mut max, mut sum2, mut n) = (0.0f64, 0.0, 0usize);
        for v in e {
            max = max.max(v.abs());
            sum2 += v * v;
            n += 1;
        }
        if n == 0 {
            return ErrorStats {
                max: f64::NAN,
                rms: f64::NAN,
            };
        }
        ErrorStats {
            max,
            rms: (sum2 / n as f64).sqrt(),
        }
    }
}

/// The transient measure of [`transient_error`] applied to any model output `m` (one value per
/// step of `c`, as [`model_transient`] returns), with max and RMS over the steps.
pub fn transient_stats(c: &TransientCurve, m: &[f64], xi_ss: f64) -> ErrorStats {
    let r = case_ratio(c.case);
    ErrorStats::of(m.iter().enumerate().filter_map(|(i, &v)| match c.case {
        TransientCase::HoldForce(_) if i == 0 => None,
        TransientCase::HoldForce(_) => Some(v / xi_ss - c.creepage[i] / c.steady_creepage),
        TransientCase::HoldCreepage(_) => Some((v - c.force[i]) / r),
    }))
}

/// A model tier of the speed-against-error report, from the cheapest to the exact.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Tier {
    /// Rapier's own Coulomb friction: rigid, no creep (its error is the whole creep).
    Coulomb,
    /// Rigid regime with Kalker's closed-form steady creepage `F_ss` (Kuhn's rule, applied at
    /// once, no tangential compliance).
    RigidKuhn,
    /// Rigid regime with the fitted steady law ([`CreepModel::Fitted`]).
    RigidFitted,
    /// Compliant regime: Kuhn's transient update on the exact Cattaneo-Mindlin memory
    /// ([`CreepState`] with [`CreepModel::Kuhn`]).
    CompliantKuhn,
    /// Compliant regime with the fitted transient law ([`CreepModel::FittedTransient`]).
    FittedTransient,
    /// Kalker's simplified theory ([`crate::fastsim`]): steady rolling only.
    Fastsim,
    /// The boundary elements of Kalker's exact theory ([`crate::bem`]).
    Bem,
}

impl Tier {
    /// Every tier, cheapest first.
    pub const ALL: [Tier; 7] = [
        Tier::Coulomb,
        Tier::RigidKuhn,
        Tier::RigidFitted,
        Tier::CompliantKuhn,
        Tier::FittedTransient,
        Tier::Fastsim,
        Tier::Bem,
    ];

    /// Short machine name (CSV).
    pub fn name(self) -> &'static str {
        match self {
            Tier::Coulomb => "coulomb",
            Tier::RigidKuhn => "rigid-kuhn",
            Tier::RigidFitted => "rigid-fitted",
            Tier::CompliantKuhn => "compliant-kuhn",
            Tier::FittedTransient => "fitted-transient",
            Tier::Fastsim => "fastsim",
            Tier::Bem => "bem",
        }
    }

    /// Human label (tables, plots).
    pub fn label(self) -> &'static str {
        match self {
            Tier::Coulomb => "Coulomb (Rapier)",
            Tier::RigidKuhn => "rigid creep, F_ss (Kuhn)",
            Tier::RigidFitted => "rigid creep, fitted steady",
            Tier::CompliantKuhn => "compliant Kuhn (transient)",
            Tier::FittedTransient => "compliant, FittedTransient",
            Tier::Fastsim => "FASTSIM",
            Tier::Bem => "BEM (exact; its grid error)",
        }
    }

    /// The steady law of a rigid tier.
    fn rigid_law(self, nu: f64) -> Option<SteadyLaw> {
        match self {
            Tier::RigidKuhn => Some(SteadyLaw::new(CreepModel::Kuhn, nu)),
            Tier::RigidFitted => Some(SteadyLaw::new(CreepModel::Fitted, nu)),
            _ => None,
        }
    }

    /// The creep model of a compliant tier.
    pub fn compliant_model(self) -> Option<CreepModel> {
        match self {
            Tier::CompliantKuhn => Some(CreepModel::Kuhn),
            Tier::FittedTransient => Some(CreepModel::FittedTransient),
            _ => None,
        }
    }
}

/// Discretisation of the live references used while grading.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GradeOptions {
    /// FASTSIM's strips and elements per strip.
    pub fastsim: FastsimOptions,
    /// Grid `N` of the live boundary-element Cattaneo-Mindlin loading.
    pub bem_grid: usize,
    /// Steps of `a/16` rolled at held force before a compliant tier's steady creepage is read.
    pub steady_roll_steps: usize,
}

/// Force ratios of the steady grading: [`STEADY_RATIOS`] within `[S_MIN, S_MAX]`.
pub fn steady_ratios() -> Vec<f64> {
    STEADY_RATIOS
        .iter()
        .copied()
        .filter(|s| (S_MIN..=S_MAX).contains(s))
        .collect()
}

/// Normalised steady creepage of a compliant tier at force ratio `s`: the force applied by a
/// Mindlin shift, then held while rolling `steps` steps of `a/16`; the creep rate of the last step.
pub fn compliant_steady_creepage_n(
    model: CreepModel,
    nu: f64,
    s: f64,
    steps: usize,
) -> Result<f64, RefError> {
    let pair = pair(nu)?;
    let p = 1.0;
    let a = creep_law::hertz::contact_radius(&pair, p);
    let mut st = CreepState::new();
    st.update(
        &CreepLaw::new(pair, model),
        CreepInput::new(p, Vec2::ZERO, Vec2::ZERO).with_radius(a),
    );
    let d = mindlin_shift(&pair, p, a, s);
    st.update(
        &CreepLaw::new(pair, model),
        CreepInput::new(p, Vec2::new(d, 0.0), Vec2::ZERO).with_radius(a),
    );
    let mut xi = 0.0;
    for _ in 0..steps.max(1) {
        xi = hold_force_step(&mut st, &pair, model, p, a, a / 16.0);
    }
    Ok(xi * a * a)
}

/// Normalised steady creepage by FASTSIM at force ratio `s` (in `(0, 1)`) and Poisson ratio `nu`:
/// bisection on the monotone map `xi -> Fx` to `1e-10 mu P`.
pub fn fastsim_creepage_n(nu: f64, s: f64, options: &FastsimOptions) -> Result<f64, RefError> {
    let c = CircularContact::normalised(nu)?;
    let f = |xi: f64| -> Result<f64, RefError> {
        Ok(fastsim(&c, Creepage::longitudinal(xi), options)?.fx / c.mu_p())
    };
    let (mut lo, mut hi) = (0.0f64, 1.0f64);
    while f(hi)? < s {
        hi *= 2.0;
        if hi > 1e3 {
            return Err(RefError::NoConvergence {
                solver: "FASTSIM force bracket",
                iterations: 10,
                residual: s,
            });
        }
    }
    for _ in 0..100 {
        let mid = 0.5 * (lo + hi);
        let v = f(mid)?;
        if (v - s).abs() <= 1e-10 {
            return Ok(mid / c.creepage_scale());
        }
        if v < s {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    Ok(0.5 * (lo + hi) / c.creepage_scale())
}

/// Relative steady creepage errors `(s, xi_model/xi_exact - 1)` of `tier` at every force ratio `s`
/// of [`steady_ratios`], against the extrapolated curve `ext`. `bem` is the table curve (same
/// `nu`) the boundary elements are graded with (its grid error: e.g. grid `"32"` against
/// `"ext"`). Coulomb predicts no creep (error -1).
pub fn steady_case_errors(
    tier: Tier,
    ext: &SteadyCurve,
    bem: &SteadyCurve,
    opts: &GradeOptions,
) -> Result<Vec<(f64, f64)>, RefError> {
    let mut e = Vec::new();
    for s in steady_ratios() {
        let exact = steady_creepage(std::slice::from_ref(ext), ext.nu, s)?;
        let model = match (tier.rigid_law(ext.nu), tier.compliant_model()) {
            (Some(law), _) => law.creepage_n(s),
            (_, Some(m)) => compliant_steady_creepage_n(m, ext.nu, s, opts.steady_roll_steps)?,
            _ => match tier {
                Tier::Fastsim => fastsim_creepage_n(ext.nu, s, &opts.fastsim)?,
                Tier::Bem => steady_creepage(std::slice::from_ref(bem), bem.nu, s)?,
                _ => 0.0,
            },
        };
        e.push((s, model / exact - 1.0));
    }
    Ok(e)
}

/// Max and RMS of [`steady_case_errors`]. Every tier has a steady version (`Some`).
pub fn steady_case(
    tier: Tier,
    ext: &SteadyCurve,
    bem: &SteadyCurve,
    opts: &GradeOptions,
) -> Result<Option<ErrorStats>, RefError> {
    let e = steady_case_errors(tier, ext, bem, opts)?;
    Ok(Some(ErrorStats::of(e.into_iter().map(|(_, v)| v))))
}

/// Transient errors of `tier` on the boundary-element curve `c` (grid 32) with the measure of
/// [`transient_stats`]. Rigid tiers have no build-up: at held force their creep rate is the
/// steady one from the first roll, at held creepage their force is the steady force at once
/// (Coulomb: no creep, so the creepage is gross sliding at `mu P`). The boundary elements are
/// graded by their grid sensitivity: the curve `coarse` (grid 16) against `c`. FASTSIM: `None`.
pub fn transient_case(
    tier: Tier,
    c: &TransientCurve,
    coarse: Option<&TransientCurve>,
    steady: &[SteadyCurve],
) -> Result<Option<ErrorStats>, RefError> {
    let r = case_ratio(c.case);
    let xi_ss = steady_creepage(steady, c.nu, r)?;
    let hold_force = matches!(c.case, TransientCase::HoldForce(_));
    let m: Vec<f64> = match tier {
        Tier::Coulomb => vec![if hold_force { 0.0 } else { 1.0 }; c.rolled.len()],
        Tier::RigidKuhn | Tier::RigidFitted => match tier.rigid_law(c.nu) {
            Some(law) if hold_force => vec![law.creepage_n(r); c.rolled.len()],
            Some(law) => vec![law.force_ratio(xi_ss); c.rolled.len()],
            None => return Ok(None),
        },
        Tier::CompliantKuhn | Tier::FittedTransient => match tier.compliant_model() {
            Some(model) => model_transient(model, c, xi_ss)?,
            None => return Ok(None),
        },
        Tier::Fastsim => return Ok(None),
        Tier::Bem => {
            let Some(k) = coarse else { return Ok(None) };
            if k.rolled.len() != c.rolled.len() {
                return Ok(None);
            }
            // Same measure, with the coarse grid's shape in place of the model.
            let e = (0..c.rolled.len()).filter_map(|i| {
                if hold_force {
                    (i > 0).then(|| {
                        k.creepage[i] / k.steady_creepage - c.creepage[i] / c.steady_creepage
                    })
                } else {
                    Some((k.force[i] - c.force[i]) / r)
                }
            });
            return Ok(Some(ErrorStats::of(e)));
        }
    };
    Ok(Some(transient_stats(c, &m, xi_ss)))
}

/// Force levels `Q/(mu P)` of the Cattaneo-Mindlin cycle: loading `0 -> peak`, unloading
/// `peak -> -peak`, reloading `-peak -> peak`, `steps` increments per branch (`steps >= 1`).
/// Returns `(branch, s)` with branch 0, 1, 2.
pub fn mindlin_cycle(peak: f64, steps: usize) -> Vec<(usize, f64)> {
    let n = steps.max(1);
    let mut out = Vec::with_capacity(3 * n);
    for i in 1..=n {
        out.push((0, peak * i as f64 / n as f64));
    }
    for i in 1..=n {
        out.push((1, peak - 2.0 * peak * i as f64 / n as f64));
    }
    for i in 1..=n {
        out.push((2, -peak + 2.0 * peak * i as f64 / n as f64));
    }
    out
}

/// Cattaneo-Mindlin load/unload/reload cycle to `peak mu P` at constant `P` (no rolling): each
/// tier is driven by the closed-form shift increments (Mindlin & Deresiewicz 1953, [`Mindlin`]) and
/// its force is compared with the closed form's, error in units of `mu P`. Compliant tiers run
/// [`CreepState`] with `du_roll = 0`; rigid tiers have no tangential compliance, so any imposed
/// shift is gross sliding at `mu P` in its direction. The boundary elements
/// ([`crate::bem::mindlin_loading`], grid `opts.bem_grid`) are graded on the loading branch only:
/// their shift at each force, mapped through the closed-form loading curve to a force. FASTSIM:
/// `None`.
pub fn mindlin_case(
    tier: Tier,
    nu: f64,
    peak: f64,
    steps: usize,
    opts: &GradeOptions,
) -> Result<Option<ErrorStats>, RefError> {
    let pair = pair(nu)?;
    let p = 1.0;
    let a = creep_law::hertz::contact_radius(&pair, p);
    let closed = Mindlin::new(pair.mu * p, pair.g_star, a)?;
    let path = mindlin_cycle(peak, steps);
    let shift = |branch: usize, s: f64| -> Result<f64, RefError> {
        let q = s * closed.mu_p();
        match branch {
            0 => closed.loading_shift(q),
            1 => closed.unloading_shift(peak * closed.mu_p(), q),
            _ => closed.reloading_shift(peak * closed.mu_p(), q),
        }
    };
    match tier {
        Tier::Fastsim => Ok(None),
        Tier::Bem => {
            let c = CircularContact::normalised(nu)?;
            let loading: Vec<f64> = path
                .iter()
                .filter(|(b, _)| *b == 0)
                .map(|(_, s)| *s)
                .collect();
            let shifts =
                crate::bem::mindlin_loading(c, SolverOptions::with_grid(opts.bem_grid), &loading)?;
            // Closed form of the normalised contact (quasi-identical: G* = G / (2 (2 - nu))).
            let m = Mindlin::new(c.mu_p(), c.g() / (2.0 * (2.0 - nu)), c.a())?;
            let mut e = Vec::with_capacity(loading.len());
            for (d, s) in shifts.iter().zip(&loading) {
                e.push(m.loading_force(*d)? / m.mu_p() - s);
            }
            Ok(Some(ErrorStats::of(e)))
        }
        Tier::Coulomb | Tier::RigidKuhn | Tier::RigidFitted => {
            let mut prev = 0.0;
            let mut e = Vec::with_capacity(path.len());
            for &(b, s) in &path {
                let d = shift(b, s)?;
                e.push((d - prev).signum() - s);
                prev = d;
            }
            Ok(Some(ErrorStats::of(e)))
        }
        Tier::CompliantKuhn | Tier::FittedTransient => {
            let Some(model) = tier.compliant_model() else {
                return Ok(None);
            };
            let mut st = CreepState::new();
            st.update(
                &CreepLaw::new(pair, model),
                CreepInput::new(p, Vec2::ZERO, Vec2::ZERO).with_radius(a),
            );
            let mut prev = 0.0;
            let mut e = Vec::with_capacity(path.len());
            for &(b, s) in &path {
                let d = shift(b, s)?;
                let q = st
                    .update(
                        &CreepLaw::new(pair, model),
                        CreepInput::new(p, Vec2::new(d - prev, 0.0), Vec2::ZERO).with_radius(a),
                    )
                    .q
                    .x;
                prev = d;
                e.push(q / closed.mu_p() - s);
            }
            Ok(Some(ErrorStats::of(e)))
        }
    }
}

/// Carter's line contact (Carter 1926, [`Carter`]): relative creepage error at the force ratios of
/// [`steady_ratios`]. Only Coulomb has a line-contact version among the tiers (it predicts no
/// creep: error 1); the creep-law tiers, FASTSIM and the boundary elements here are for the
/// circular contact: `None`.
pub fn carter_case(tier: Tier) -> Result<Option<ErrorStats>, RefError> {
    if tier != Tier::Coulomb {
        return Ok(None);
    }
    // Normalised: a = R = mu = 1 (the creepage scale cancels in the relative error).
    let c = Carter::new(1.0, 1.0, 1.0)?;
    let mut e = Vec::new();
    for s in steady_ratios() {
        let exact = c.creepage(s)?;
        e.push(0.0 / exact - 1.0);
    }
    Ok(Some(ErrorStats::of(e)))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn compliant_steady_limit_is_the_steady_law() {
        // Rolling on at held force, Kuhn's rule creeps at F_ss exactly, the transient tier at
        // the fitted law once its lag has filled.
        for (model, tier) in [
            (CreepModel::Kuhn, CreepModel::Kuhn),
            (CreepModel::FittedTransient, CreepModel::Fitted),
        ] {
            let law = SteadyLaw::new(tier, 0.25);
            for s in [0.1, 0.6, 0.95] {
                let x = compliant_steady_creepage_n(model, 0.25, s, 400).unwrap();
                assert!(
                    (x / law.creepage_n(s) - 1.0).abs() < 1e-6,
                    "{model} {s}: {x}"
                );
            }
        }
    }

    #[test]
    fn fastsim_inverse_matches_kalkers_linear_theory_at_small_force() {
        // FASTSIM's flexibility reproduces Kalker's C11 in the linear limit (Kalker 1982).
        let opts = FastsimOptions::default();
        let s = 1e-3;
        let x = fastsim_creepage_n(0.25, s, &opts).unwrap();
        let linear = s / crate::kalker_linear::c11(0.25).unwrap();
        assert!((x / linear - 1.0).abs() < 0.02, "{x} vs {linear}");
    }

    #[test]
    fn compliant_tiers_reproduce_the_mindlin_cycle() {
        let opts = GradeOptions {
            fastsim: FastsimOptions::default(),
            bem_grid: 8,
            steady_roll_steps: 10,
        };
        for tier in [Tier::CompliantKuhn, Tier::FittedTransient] {
            let e = mindlin_case(tier, 0.3, 0.8, 20, &opts).unwrap().unwrap();
            assert!(e.max < 1e-9, "{tier:?}: {e:?}");
        }
        let e = mindlin_case(Tier::Coulomb, 0.3, 0.8, 20, &opts)
            .unwrap()
            .unwrap();
        assert!(e.max > 1.0);
        assert!(
            mindlin_case(Tier::Fastsim, 0.3, 0.8, 20, &opts)
                .unwrap()
                .is_none()
        );
    }

    #[test]
    fn coulomb_misses_the_whole_creep() {
        let ext = steady_ext().unwrap();
        let opts = GradeOptions {
            fastsim: FastsimOptions::default(),
            bem_grid: 8,
            steady_roll_steps: 10,
        };
        let e = steady_case(Tier::Coulomb, &ext[0], &ext[0], &opts)
            .unwrap()
            .unwrap();
        assert_eq!((e.max, e.rms), (1.0, 1.0));
        assert_eq!(carter_case(Tier::Coulomb).unwrap().unwrap().max, 1.0);
        assert!(carter_case(Tier::Bem).unwrap().is_none());
    }
}
