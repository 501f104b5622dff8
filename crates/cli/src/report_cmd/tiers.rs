//! The tiers section: each model tier's speed (cost per contact update, timed in this process)
//! against its error (graded against the boundary-element solution of Kalker's exact theory,
//! `creep-reference`), the speed-against-error frontier and the steady-curve errors.

use super::{Config, ReportError, Section};
use crate::output::Csv;
use crate::plot::{Legend, LineChart, LineStyle, Series};
use creep_law::{
    CreepInput, CreepLaw, CreepModel, CreepState, Material, PairMaterial, SteadyLaw, Surface, Vec2,
    hertz,
};
use creep_reference::RefError;
use creep_reference::bem::{Creepage, SolverOptions, SteadySolver};
use creep_reference::contact::CircularContact;
use creep_reference::fastsim::fastsim;
use creep_reference::fit::{SteadyCurve, TransientCase, TransientCurve};
use creep_reference::tiers::{self, ErrorStats, Tier};
use indicatif::ProgressBar;
use std::fmt::Write as _;
use std::hint::black_box;
use std::path::Path;
use std::time::Instant;

// ------------------------------------------------------------------------------------------------
// Timing
// ------------------------------------------------------------------------------------------------

/// Median over `reps` timed loops of the cost of one call of `f` [ns]. Each loop runs `f(i)` for
/// `i = 0..n`, with `n` chosen from a first calibration call so that a loop lasts about
/// `loop_seconds`; callers pass inputs and consume outputs through [`black_box`].
fn median_ns(reps: usize, loop_seconds: f64, mut f: impl FnMut(usize)) -> f64 {
    let t0 = Instant::now();
    f(0);
    let once = t0.elapsed().as_secs_f64().max(1e-9);
    let n = ((loop_seconds / once) as usize).clamp(1, 50_000_000);
    // Warm-up loop, then the timed ones.
    for i in 0..n.min(1000) {
        f(i);
    }
    let mut per: Vec<f64> = (0..reps.max(1))
        .map(|_| {
            let t = Instant::now();
            for i in 0..n {
                f(i);
            }
            t.elapsed().as_secs_f64() * 1e9 / n as f64
        })
        .collect();
    creep_scenes::stats::median(&mut per).unwrap_or(f64::NAN) // never empty: reps >= 1
}

/// Glass beads of 1 mm radius at 1 N (a DEM-sized contact, as the criterion benches of
/// `creep-law`).
fn bench_pair() -> Result<PairMaterial, ReportError> {
    let m = Material::glass();
    PairMaterial::new(&m, &m, Surface::Sphere(1e-3), Surface::Sphere(1e-3)).map_err(|_| {
        ReportError::Reference(RefError::InvalidParameter {
            name: "pair",
            value: f64::NAN,
            expected: "the glass pair of the benches",
        })
    })
}

/// Cost of one contact update of `tier` [ns] (see [`Section`] text for what each one times).
fn tier_cost(tier: Tier, cfg: &Config) -> Result<f64, ReportError> {
    let pair = bench_pair()?;
    let p = 1.0;
    let a = hertz::contact_radius(&pair, p);
    let mu_p = pair.mu * p;
    // A spread of force ratios, so that no branch predictor or constant folding helps.
    let q: Vec<f64> = (0..64).map(|i| mu_p * (i as f64 + 0.5) / 64.0).collect();
    let (reps, secs) = (cfg.reps, cfg.loop_seconds);
    Ok(match tier {
        Tier::Coulomb => {
            // Rapier's friction cone: the trial tangential force clamped to mu P.
            let trial: Vec<Vec2> = q.iter().map(|&v| Vec2::new(2.0 * v, 0.3 * v)).collect();
            median_ns(reps, secs, |i| {
                let t = black_box(trial[i & 63]);
                let n = t.length();
                let lim = black_box(mu_p);
                black_box(if n > lim { t * (lim / n) } else { t });
            })
        }
        Tier::RigidKuhn => {
            let law = SteadyLaw::Kuhn { c11: pair.c11 };
            median_ns(reps, secs, |i| {
                black_box(black_box(&law).creepage_for_force(
                    black_box(q[i & 63]),
                    black_box(mu_p),
                    pair.g,
                    a,
                ));
            })
        }
        Tier::RigidFitted => {
            let law = SteadyLaw::new(CreepModel::Fitted, pair.nu);
            median_ns(reps, secs, |i| {
                black_box(black_box(&law).creepage_for_force(
                    black_box(q[i & 63]),
                    black_box(mu_p),
                    pair.g,
                    a,
                ));
            })
        }
        Tier::CompliantKuhn | Tier::FittedTransient => {
            let model = tier.compliant_model().unwrap_or_default();
            // Steady rolling at 0.6 mu P is stationary, so updating one state repeatedly
            // measures the per-step cost (as the criterion bench `steady_law/creep_update_*`).
            let law = CreepLaw::new(pair, model);
            let xi = law.steady().creepage_for_force(0.6 * mu_p, mu_p, pair.g, a);
            let dr = a * 1e-3;
            let mut st = CreepState::new();
            st.update(
                &law,
                CreepInput::new(p, Vec2::ZERO, Vec2::ZERO).with_radius(a),
            );
            for _ in 0..20_000 {
                let du = Vec2::new(xi * dr, 0.0);
                st.update(
                    &law,
                    CreepInput::new(p, du, Vec2::new(dr, 0.0)).with_radius(a),
                );
            }
            median_ns(reps, secs, |_| {
                black_box(
                    st.update(
                        black_box(&law),
                        CreepInput::new(
                            black_box(p),
                            black_box(Vec2::new(xi * dr, 0.0)),
                            black_box(Vec2::new(dr, 0.0)),
                        )
                        .with_radius(black_box(a)),
                    ),
                );
            })
        }
        Tier::Fastsim => {
            let c = CircularContact::normalised(pair.nu)?;
            let xi = SteadyLaw::new(CreepModel::Fitted, pair.nu).creepage_n(0.6);
            let opts = cfg.grade.fastsim;
            fastsim(&c, Creepage::longitudinal(xi), &opts)?;
            median_ns(reps, secs, |_| {
                let _ = black_box(fastsim(
                    black_box(&c),
                    black_box(Creepage::longitudinal(xi)),
                    &opts,
                ));
            })
        }
        Tier::Bem => {
            // One steady solve from zero traction at 0.6 mu P's creepage, on the grid of the
            // tabulated curve the tier is graded by.
            let c = CircularContact::normalised(pair.nu)?;
            let xi = SteadyLaw::new(CreepModel::Fitted, pair.nu).creepage_n(0.6);
            let mut s = SteadySolver::new(c, SolverOptions::with_grid(cfg.bem_grid))?;
            s.solve(Creepage::longitudinal(xi))?;
            median_ns(if cfg.quick { 3 } else { 7 }, 0.0, |_| {
                s.reset();
                let _ = black_box(s.solve(black_box(Creepage::longitudinal(xi))));
            })
        }
    })
}

// ------------------------------------------------------------------------------------------------
// The tiers section
// ------------------------------------------------------------------------------------------------

/// Poisson ratios of the steady cases.
const STEADY_NUS: [f64; 4] = [0.0, 0.25, 0.3, 0.5];

/// Peak force ratio of the Cattaneo-Mindlin cycle, and its Poisson ratio.
const MINDLIN_PEAK: f64 = 0.8;
const MINDLIN_NU: f64 = 0.3;

/// The cases of the frontier, in table order.
const CASES: [&str; 8] = [
    "steady nu=0",
    "steady nu=0.25",
    "steady nu=0.3",
    "steady nu=0.5",
    "transient held creepage",
    "transient held force",
    "Mindlin load/unload/reload",
    "Carter line contact",
];

/// One graded comparison: a tier on one case (`detail`: the curve within the case).
#[derive(Debug, Clone)]
struct Row {
    tier: Tier,
    case: &'static str,
    detail: String,
    err: Option<ErrorStats>,
    /// Per force ratio `(Q/(mu P), relative creepage error)` of a steady case (else empty).
    curve: Vec<(f64, f64)>,
}

/// Max of the maxima and quadratic mean of the RMS values of the rows of (tier, case); `None`
/// when the tier has no version of the case.
fn aggregate(rows: &[Row], tier: Tier, case: &str) -> Option<ErrorStats> {
    let v: Vec<ErrorStats> = rows
        .iter()
        .filter(|r| r.tier == tier && r.case == case)
        .filter_map(|r| r.err)
        .collect();
    if v.is_empty() {
        return None;
    }
    Some(ErrorStats {
        max: v.iter().map(|e| e.max).fold(0.0, f64::max),
        rms: (v.iter().map(|e| e.rms * e.rms).sum::<f64>() / v.len() as f64).sqrt(),
    })
}

/// Largest error of `tier` over the point-contact cases (all but Carter's), if it has a version
/// of every one of them.
fn worst_point_contact(rows: &[Row], tier: Tier) -> Option<f64> {
    CASES[..7]
        .iter()
        .map(|c| aggregate(rows, tier, c).map(|e| e.max))
        .try_fold(0.0f64, |w, e| e.map(|e| w.max(e)))
}

/// Grades every tier on every case.
fn grade(cfg: &Config, pb: &ProgressBar) -> Result<Vec<Row>, ReportError> {
    let ext = tiers::steady_ext()?;
    let n32 = tiers::steady("32")?;
    let t32 = tiers::transient("32")?;
    let t16 = tiers::transient("16")?;
    let curve = |set: &[SteadyCurve], nu: f64| -> Result<SteadyCurve, ReportError> {
        set.iter()
            .find(|c| c.nu == nu)
            .cloned()
            .ok_or(ReportError::Reference(RefError::InvalidParameter {
                name: "nu",
                value: nu,
                expected: "a Poisson ratio of the steady table",
            }))
    };
    let mut rows = Vec::new();
    for tier in Tier::ALL {
        pb.set_message(format!("errors: {}", tier.name()));
        for (k, &nu) in STEADY_NUS.iter().enumerate() {
            let (e, b) = (curve(&ext, nu)?, curve(&n32, nu)?);
            let points = tiers::steady_case_errors(tier, &e, &b, &cfg.grade)?;
            rows.push(Row {
                tier,
                case: CASES[k],
                detail: format!("nu={nu}"),
                err: Some(ErrorStats::of(points.iter().map(|p| p.1))),
                curve: points,
            });
        }
        for c in &t32 {
            let coarse = t16
                .iter()
                .find(|k| k.nu == c.nu && k.case == c.case)
                .filter(|_| tier == Tier::Bem);
            let case = match c.case {
                TransientCase::HoldCreepage(_) => CASES[4],
                TransientCase::HoldForce(_) => CASES[5],
            };
            rows.push(Row {
                tier,
                case,
                detail: transient_detail(c),
                err: tiers::transient_case(tier, c, coarse, &ext)?,
                curve: Vec::new(),
            });
        }
        rows.push(Row {
            tier,
            case: CASES[6],
            detail: format!("nu={MINDLIN_NU} peak={MINDLIN_PEAK}"),
            err: tiers::mindlin_case(
                tier,
                MINDLIN_NU,
                MINDLIN_PEAK,
                cfg.mindlin_steps,
                &cfg.grade,
            )?,
            curve: Vec::new(),
        });
        rows.push(Row {
            tier,
            case: CASES[7],
            detail: "Q/(mu P) 0.02..0.98".into(),
            err: tiers::carter_case(tier)?,
            curve: Vec::new(),
        });
        pb.inc(1);
    }
    Ok(rows)
}

fn transient_detail(c: &TransientCurve) -> String {
    format!("nu={} {}", c.nu, tiers::case_label(c.case))
}

/// Percent with a sensible number of digits (`n/a` for none).
fn pct(v: Option<f64>) -> String {
    match v {
        None => "n/a".into(),
        Some(v) if v < 1e-6 => format!("{:.0e} %", 100.0 * v),
        Some(v) if v < 0.01 => format!("{:.2} %", 100.0 * v),
        Some(v) => format!("{:.1} %", 100.0 * v),
    }
}

/// A cost with its unit.
fn cost_text(ns: f64) -> String {
    if ns < 1e3 {
        format!("{ns:.1} ns")
    } else if ns < 1e6 {
        format!("{:.1} µs", ns / 1e3)
    } else {
        format!("{:.1} ms", ns / 1e6)
    }
}

/// Errors below this are drawn at it on the log-log frontier.
const PLOT_FLOOR: f64 = 1e-4;

/// The tiers section: cost per update and errors of every tier; `tiers_cost.csv`,
/// `tiers_errors.csv`, `frontier.csv`, `frontier.svg`/`.png`.
pub fn section(cfg: &Config, dir: &Path, pb: &ProgressBar) -> Result<Section, ReportError> {
    pb.set_length(2 * Tier::ALL.len() as u64 + 1);
    let mut cost = Vec::with_capacity(Tier::ALL.len());
    for tier in Tier::ALL {
        pb.set_message(format!("cost: {}", tier.name()));
        cost.push(tier_cost(tier, cfg)?);
        pb.inc(1);
    }
    let cost_of = |t: Tier| {
        Tier::ALL
            .iter()
            .position(|&x| x == t)
            .map_or(f64::NAN, |i| cost[i])
    };
    let rows = grade(cfg, pb)?;
    pb.set_message("writing");

    // CSVs.
    let mut csv = Csv::new(&["tier", "cost_ns_per_update"]);
    for (t, c) in Tier::ALL.iter().zip(&cost) {
        csv.row(&[&t.name(), &format_args!("{c:.3}")]);
    }
    csv.write(&dir.join("tiers_cost.csv"))?;
    let mut csv = Csv::new(&["tier", "case", "detail", "max_error", "rms_error"]);
    for r in &rows {
        // A tier without a version of the case: empty fields.
        let (m, s) = r.err.map_or((String::new(), String::new()), |e| {
            (format!("{:.6e}", e.max), format!("{:.6e}", e.rms))
        });
        csv.row(&[&r.tier.name(), &r.case, &r.detail, &m, &s]);
    }
    csv.write(&dir.join("tiers_errors.csv"))?;
    let mut csv = Csv::new(&[
        "tier",
        "cost_ns_per_update",
        "case",
        "max_error",
        "rms_error",
    ]);
    let mut series = Vec::new();
    for (k, tier) in Tier::ALL.into_iter().enumerate() {
        let mut pts = Vec::new();
        for case in CASES {
            if let Some(e) = aggregate(&rows, tier, case) {
                csv.row(&[
                    &tier.name(),
                    &format_args!("{:.3}", cost_of(tier)),
                    &case,
                    &format_args!("{:.6e}", e.max),
                    &format_args!("{:.6e}", e.rms),
                ]);
                pts.push((cost_of(tier), e.max.max(PLOT_FLOOR)));
            }
        }
        series.push(
            Series::line(tier.label(), pts)
                .color(k + 1)
                .markers()
                .style(LineStyle::None),
        );
    }
    // The frontier: the tiers that no cheaper tier beats on the worst point-contact error.
    let mut front = Vec::new();
    let mut by_cost: Vec<(f64, f64)> = Tier::ALL
        .into_iter()
        .filter_map(|t| worst_point_contact(&rows, t).map(|e| (cost_of(t), e)))
        .collect();
    by_cost.sort_by(|a, b| a.0.total_cmp(&b.0));
    for (c, e) in by_cost {
        if front.last().is_none_or(|&(_, best): &(f64, f64)| e < best) {
            front.push((c, e));
        }
    }
    series.push(Series::line("frontier: worst point-contact error", front).dashed());
    csv.write(&dir.join("frontier.csv"))?;
    let mut chart = LineChart::new(
        "Speed against error: one point per tier per case",
        "cost per contact update [ns]",
        "largest error (relative, or of mu P)",
    )
    .legend(Legend::UpperRight)
    .y_range(PLOT_FLOOR / 10.0, 10.0);
    chart.size = (1000, 650);
    for s in series {
        chart = chart.series(s);
    }
    chart.write_log_log(&dir.join("frontier"))?;
    steady_curves(&rows, dir)?;
    pb.inc(1);

    let markdown = tiers_markdown(cfg, &rows, &cost_of);
    Ok(Section {
        markdown,
        files: [
            "tiers_cost.csv",
            "tiers_errors.csv",
            "frontier.csv",
            "frontier.svg",
            "frontier.png",
            "steady_errors.csv",
            "steady_errors.svg",
            "steady_errors.png",
        ]
        .map(String::from)
        .to_vec(),
    })
}

/// Per force ratio steady creepage errors of every tier (`steady_errors.csv`), and their plot at
/// nu = 0.25 for the tiers with creep (`steady_errors.svg`/`.png`; the compliant tiers' steady
/// limits are the rigid tiers' laws).
fn steady_curves(rows: &[Row], dir: &Path) -> Result<(), ReportError> {
    let mut csv = Csv::new(&["tier", "case", "q_over_mu_p", "relative_creepage_error"]);
    for r in rows.iter().filter(|r| !r.curve.is_empty()) {
        for (q, e) in &r.curve {
            csv.row(&[&r.tier.name(), &r.case, q, &format_args!("{e:.6e}")]);
        }
    }
    csv.write(&dir.join("steady_errors.csv"))?;
    let mut chart = LineChart::new(
        "Steady creepage error against the exact theory, nu = 0.25",
        "Q/(mu P)",
        "creepage error [%]",
    )
    .legend(Legend::UpperLeft);
    for (k, tier) in Tier::ALL.into_iter().enumerate() {
        if matches!(
            tier,
            Tier::Coulomb | Tier::CompliantKuhn | Tier::FittedTransient
        ) {
            continue;
        }
        if let Some(r) = rows.iter().find(|r| r.tier == tier && r.case == CASES[1]) {
            let pts = r.curve.iter().map(|&(q, e)| (q, 100.0 * e)).collect();
            chart = chart.series(Series::line(tier.label(), pts).color(k + 1).markers());
        }
    }
    chart.write(&dir.join("steady_errors"))?;
    Ok(())
}

/// The section's Markdown: the frontier table, the figure, the tier-choice paragraph, the
/// definitions.
fn tiers_markdown(cfg: &Config, rows: &[Row], cost_of: &dyn Fn(Tier) -> f64) -> String {
    let agg = |t: Tier, case: &str| aggregate(rows, t, case);
    // Worst steady error of a tier over the four Poisson ratios.
    let steady = |t: Tier| {
        CASES[..4]
            .iter()
            .filter_map(|c| agg(t, c).map(|e| e.max))
            .fold(None, |a: Option<f64>, v| Some(a.map_or(v, |a| a.max(v))))
    };
    let mut md = String::from("## Tiers: speed against error\n\n");
    md += "Cost per contact update measured in this process (median of repeated timed loops, \
           `std::hint::black_box`); the criterion benches (`cargo bench -p creep-law --bench \
           law`, `cargo bench -p creep-reference --bench bem`) hold the authoritative numbers. \
           Errors: largest / RMS over each case (definitions below).\n\n";
    md += "| tier | cost per update | worst, point contact |";
    for c in CASES {
        let _ = write!(md, " {c} |");
    }
    md += "\n|---|---|---|";
    md += &"---|".repeat(CASES.len());
    md.push('\n');
    for tier in Tier::ALL {
        let _ = write!(
            md,
            "| {} | {} | {} |",
            tier.label(),
            cost_text(cost_of(tier)),
            pct(worst_point_contact(rows, tier))
        );
        for c in CASES {
            match agg(tier, c) {
                Some(e) => {
                    let _ = write!(md, " {} / {} |", pct(Some(e.max)), pct(Some(e.rms)));
                }
                None => md += " n/a |",
            }
        }
        md.push('\n');
    }
    let _ = write!(
        md,
        "\n![speed against error](frontier.png)\n\n(`frontier.svg`; errors below {} are drawn \
         at {}; the dashed line joins the tiers that no cheaper tier beats on the worst \
         point-contact error, i.e. over every case but Carter's, counting only tiers that have \
         a version of each; data in `frontier.csv`, per curve in `tiers_errors.csv`.)\n\n\
         ![steady creepage error](steady_errors.png)\n\n(`steady_errors.csv`: every tier, \
         nu and force ratio.)\n\n",
        PLOT_FLOOR, PLOT_FLOOR
    );
    md += "### Which tier for which scene\n\n";
    md += &advice(cost_of, &steady, &agg);
    md += "\n\n### What is measured\n\n";
    let _ = writeln!(
        md,
        "* **Cost.** Coulomb: the friction-cone clamp of a trial force (Rapier's own work, which \
         every tier also pays: the tier's extra cost is its own entry). Rigid tiers: one steady \
         creepage evaluation `F(|Q|/(mu P))` (Kalker's `F_ss` with a cube root, or the fitted \
         law). Compliant tiers: one `CreepState` update in steady rolling (Cattaneo-Mindlin memory \
         + creep term; glass beads of 1 mm at 1 N, as the criterion benches). FASTSIM: one \
         evaluation on {}x{} elements. BEM: one steady solve from zero traction on the N = {} grid \
         ({} elements across the diameter).",
        cfg.grade.fastsim.strips, cfg.grade.fastsim.elements, cfg.bem_grid, cfg.bem_grid
    );
    md += "* **Steady** (nu = 0, 0.25, 0.3, 0.5): relative creepage error at `Q/(mu P)` in \
           0.02 ... 0.98 (18 force ratios) against the grid-extrapolated boundary elements \
           (`data/steady_bem.csv`). Coulomb predicts no creep (error 100 %). Compliant tiers: the \
           force applied by a Mindlin shift, then held while rolling, the creep rate read at the \
           end. FASTSIM: creepage by bisection on its force. BEM: its N = 32 curve against the \
           extrapolation (its grid error).\n";
    md += "* **Transient** (nu = 0, 0.25, 0.5; `Q/(mu P)` = 0.3, 0.6, 0.9; rolled 4 a in steps \
           of a/16; `data/transient_bem.csv`, N = 32): held force, error of the creep rate over \
           the steady creep rate from the second step on; held creepage, error of the force over \
           the held steady force. Rigid tiers act at once (the steady law from the first step; \
           Coulomb: no creep at held force, gross sliding at `mu P` at held creepage). BEM: the \
           N = 16 curves against N = 32 (grid sensitivity). FASTSIM: n/a (steady only).\n";
    let _ = writeln!(
        md,
        "* **Mindlin** (nu = {MINDLIN_NU}): load to {MINDLIN_PEAK} mu P, unload to -{MINDLIN_PEAK} \
         mu P, reload, {} force steps per branch, no rolling: each tier is driven by the \
         closed-form shifts (Mindlin & Deresiewicz 1953, `creep_reference::mindlin`) and its force \
         compared, in units of `mu P`. Rigid tiers have no tangential compliance: an imposed shift \
         is gross sliding. BEM: loading branch only, N = {}.",
        cfg.mindlin_steps, cfg.grade.bem_grid
    );
    md += "* **Carter** (line contact, Carter 1926): relative creepage error at 0.02 ... 0.98. The \
           creep-law tiers, FASTSIM and the BEM here are for the circular (Hertz point) contact: \
           n/a.\n";
    md
}

/// The paragraph "which tier for which scene", from the numbers.
fn advice(
    cost_of: &dyn Fn(Tier) -> f64,
    steady: &dyn Fn(Tier) -> Option<f64>,
    agg: &dyn Fn(Tier, &str) -> Option<ErrorStats>,
) -> String {
    let c = |t: Tier| cost_text(cost_of(t));
    let s = |t: Tier| pct(steady(t));
    let held = |t: Tier, case: usize| pct(agg(t, CASES[case]).map(|e| e.max));
    let mut p = String::new();
    let _ = write!(
        p,
        "*Model only what a scene needs.* **Coulomb** ({}) misses the creep entirely (steady error \
         {}): keep it where bodies do not roll under a tangential load, or where rolling \
         resistance does not matter. ",
        c(Tier::Coulomb),
        s(Tier::Coulomb)
    );
    let (k, f) = (steady(Tier::RigidKuhn), steady(Tier::RigidFitted));
    let better = matches!((k, f), (Some(k), Some(f)) if f < k);
    let cheaper = cost_of(Tier::RigidFitted) <= cost_of(Tier::RigidKuhn);
    let _ = write!(
        p,
        "For the **rigid regime** (games, robotics, 30-120 Hz) choose the {} law: steady error {} \
         against Kalker's `F_ss` {}, at {} against {} per evaluation{}. ",
        if better {
            "fitted steady"
        } else {
            "Kalker F_ss"
        },
        s(Tier::RigidFitted),
        s(Tier::RigidKuhn),
        c(Tier::RigidFitted),
        c(Tier::RigidKuhn),
        if better && cheaper {
            " (more accurate and cheaper)"
        } else {
            ""
        }
    );
    let _ = write!(
        p,
        "It has no build-up: at held creepage the rigid tiers err by {} (held force: {}), because \
         the force appears at once. ",
        held(Tier::RigidFitted, 4),
        held(Tier::RigidFitted, 5)
    );
    let ratio = cost_of(Tier::FittedTransient) / cost_of(Tier::CompliantKuhn);
    let _ = write!(
        p,
        "For the **compliant regime** (DEM, start of rolling, oscillating loads, micro-slip) the \
         Cattaneo-Mindlin memory is exact in both compliant tiers (Mindlin cycle {} / {}); \
         **FittedTransient** cuts the held-force error from {} (Kuhn's rule) to {} and the \
         held-creepage error from {} to {}, and its steady error from {} to {}, at {} against {} \
         per update ({:.2}x). ",
        held(Tier::CompliantKuhn, 6),
        held(Tier::FittedTransient, 6),
        held(Tier::CompliantKuhn, 5),
        held(Tier::FittedTransient, 5),
        held(Tier::CompliantKuhn, 4),
        held(Tier::FittedTransient, 4),
        s(Tier::CompliantKuhn),
        s(Tier::FittedTransient),
        c(Tier::FittedTransient),
        c(Tier::CompliantKuhn),
        ratio
    );
    let fs = steady(Tier::Fastsim);
    let fast_vs_fit = cost_of(Tier::Fastsim) / cost_of(Tier::RigidFitted);
    let _ = write!(
        p,
        "**FASTSIM** ({}, {:.0}x the fitted law) errs by {} in steady creepage{}: use it only \
         where lateral and spin creepage matter, which the tiers above do not model. The \
         **boundary elements** ({} per solve) are the reference, for tables and checks, never \
         per contact.",
        c(Tier::Fastsim),
        fast_vs_fit,
        s(Tier::Fastsim),
        match (fs, f) {
            (Some(a), Some(b)) if a > b => ", worse than the fitted law",
            _ => "",
        },
        c(Tier::Bem)
    );
    p
}
