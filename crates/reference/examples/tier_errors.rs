//! Error tables of the creep-law tiers against the checked-in boundary-element tables
//! (`crates/reference/data`): steady (creepage for Q/(mu P) <= 0.98, force at any creepage)
//! and transient (held force, held creepage), as Markdown.
//! Usage: `cargo run --release -p creep-reference --example tier_errors`; `-- tune ORDER [rel]`
//! grid-searches the transient tier's `beta` and `l` (ORDER lags in series; `rel` minimises the
//! largest ratio to Kuhn's rule's error instead of the largest error); `-- show BETA L0 L1 ORDER`
//! prints model/BEM pairs along the nu = 0.25 curves.
use creep_law::{CreepModel, MindlinState, SteadyLaw, Vec2};
use creep_reference::fit::{TransientCase, TransientCurve};
use creep_reference::tiers;

fn main() {
    if std::env::args().nth(1).as_deref() == Some("show") {
        let a: Vec<f64> = std::env::args()
            .skip(2)
            .map(|s| s.parse().unwrap())
            .collect();
        let steady = tiers::steady_ext().unwrap();
        for c in tiers::transient("32")
            .unwrap()
            .iter()
            .filter(|c| c.nu == 0.25)
        {
            let r = match c.case {
                TransientCase::HoldForce(r) | TransientCase::HoldCreepage(r) => r,
            };
            let xi_ss = tiers::steady_creepage(&steady, c.nu, r).unwrap();
            let m = run(c, xi_ss, a[0], a[1], a[2], a[3] as usize);
            let mut line = String::new();
            for i in (1..64).step_by(4) {
                let (mv, bv) = match c.case {
                    TransientCase::HoldForce(_) => {
                        (m[i] / xi_ss, c.creepage[i] / c.steady_creepage)
                    }
                    TransientCase::HoldCreepage(_) => (m[i] / r, c.force[i] / r),
                };
                line += &format!(" {:.2}/{:.2}", mv, bv);
            }
            println!("{:?}{line}", c.case);
        }
        return;
    }
    if std::env::args().nth(1).as_deref() == Some("tune") {
        tune();
        return;
    }
    let steady = tiers::steady_ext().unwrap();
    println!("Steady, vs BEM (grid-extrapolated 2 N64 - N32):\n");
    println!("| nu | Kuhn creepage err (s<=0.98) | fitted | Kuhn Q err (any xi) | fitted |");
    println!("|---|---|---|---|---|");
    for c in &steady {
        let (kx, kq) = tiers::steady_errors(CreepModel::Kuhn, c);
        let (fx, fq) = tiers::steady_errors(CreepModel::Fitted, c);
        println!(
            "| {} | {:.2} % | {:.2} % | {:.2} % | {:.2} % |",
            c.nu,
            100.0 * kx,
            100.0 * fx,
            100.0 * kq,
            100.0 * fq
        );
    }
    for grid in ["32", "16"] {
        println!(
            "\nTransient, vs BEM N={grid} (max error, see creep_reference::tiers::transient_error):\n"
        );
        println!("| nu | case | Kuhn | fitted | fitted-transient |");
        println!("|---|---|---|---|---|");
        for c in tiers::transient(grid).unwrap() {
            let e: Vec<String> = CreepModel::ALL
                .iter()
                .map(|&m| {
                    format!(
                        "{:.1} %",
                        100.0 * tiers::transient_error(m, &c, &steady).unwrap()
                    )
                })
                .collect();
            println!(
                "| {} | {} | {} |",
                c.nu,
                tiers::case_label(c.case),
                e.join(" | ")
            );
        }
    }
}

/// The transient tier with parameters `(beta, l0, l1)` through a BEM case (same protocol as
/// `tiers::model_transient`, the creep step of `creep_law::transient_law` inlined).
fn run(c: &TransientCurve, xi_ss: f64, beta: f64, l0: f64, l1: f64, order: usize) -> Vec<f64> {
    let pair = tiers::pair(c.nu).unwrap();
    let p = 1.0;
    let a = creep_law::hertz::contact_radius(&pair, p);
    let scale = a * a;
    let law = SteadyLaw::new(CreepModel::Fitted, c.nu);
    let mut m = MindlinState::new();
    m.update_with_radius(&pair, a, Vec2::ZERO);
    let mut phis = vec![0.0f64; order.max(1)];
    let mut prev = 0.0;
    let mut out = Vec::new();
    for (i, &rolled) in c.rolled.iter().enumerate() {
        let dq = (rolled - prev) * a;
        prev = rolled;
        let q = m.force().x;
        let target = law.creepage_for_force(q, pair.mu * p, pair.g, a);
        let rate = beta * target + (1.0 - beta) * phis[phis.len() - 1];
        let len = a * (l0 + l1 * (1.0 - q / (pair.mu * p)).max(0.0).sqrt());
        if i > 0 || matches!(c.case, TransientCase::HoldCreepage(_)) {
            if order == 2 {
                // Two lags in series, exact for the held target (as `creep_law::transient_law`).
                let t = dq / len;
                let e = (-t).exp();
                let (d1, d2) = (phis[0] - target, phis[1] - target);
                phis[0] = target + d1 * e;
                phis[1] = target + (d2 + d1 * t) * e;
            } else {
                // Cascade of `order` lags, explicit in the stage inputs.
                let w = -(-dq / len).exp_m1();
                let mut input = target;
                for p in phis.iter_mut() {
                    let old = *p;
                    *p += (input - old) * w;
                    input = old;
                }
            }
        }
        let creep = rate * dq;
        match c.case {
            TransientCase::HoldForce(s) => {
                if i == 0 {
                    let ds = 3.0 * pair.mu * p / (16.0 * pair.g_star * a);
                    let d = ds * (1.0 - (1.0 - s).powf(2.0 / 3.0));
                    m.update_with_radius(&pair, a, Vec2::new(d, 0.0));
                    out.push(d / dq * scale);
                } else {
                    out.push(creep / dq * scale);
                }
            }
            TransientCase::HoldCreepage(_) => {
                let q = m
                    .update_with_radius(&pair, a, Vec2::new(xi_ss / scale * dq - creep, 0.0))
                    .q
                    .x;
                out.push(q / (pair.mu * p));
            }
        }
    }
    out
}

/// Grid search of `(beta, l0, l1)` minimising the largest transient error over the N=32 curves.
fn tune() {
    let steady = tiers::steady_ext().unwrap();
    let curves = tiers::transient("32").unwrap();
    let order: usize = std::env::args()
        .nth(2)
        .and_then(|s| s.parse().ok())
        .unwrap_or(1);
    let relative = std::env::args().nth(3).is_some();
    let kuhn: Vec<f64> = curves
        .iter()
        .map(|c| tiers::transient_error(CreepModel::Kuhn, c, &steady).unwrap())
        .collect();
    let err = |beta: f64, l0: f64, l1: f64| -> f64 {
        let mut worst: f64 = 0.0;
        for (ci, c) in curves.iter().enumerate() {
            let r = tiers::case_ratio(c.case);
            let xi_ss = tiers::steady_creepage(&steady, c.nu, r).unwrap();
            let m = run(c, xi_ss, beta, l0, l1, order);
            // Same measure as `tiers::transient_error`.
            let this = tiers::transient_stats(c, &m, xi_ss).max;
            worst = worst.max(if relative { this / kuhn[ci] } else { this });
        }
        worst
    };
    let mut best = (f64::INFINITY, 0.0, 0.0, 0.0);
    for ib in 0..=16 {
        let beta = 0.4 + 0.025 * ib as f64;
        for i0 in 0..=12 {
            let l0 = 0.05 * i0 as f64;
            for i1 in 0..=20 {
                let l1 = 0.05 * i1 as f64;
                if l0 + l1 <= 0.0 {
                    continue;
                }
                let e = err(beta, l0, l1);
                if e < best.0 {
                    best = (e, beta, l0, l1);
                }
            }
        }
    }
    println!(
        "best max error {:.4} at beta = {}, l0 = {}, l1 = {}",
        best.0, best.1, best.2, best.3
    );
}
