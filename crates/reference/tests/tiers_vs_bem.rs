//! The creep-law tiers (`creep_law::CreepModel`: Kuhn's rule, the fitted steady law, the fitted
//! law with the transient extension) graded against the checked-in boundary-element tables of
//! `crates/reference/data` (written by `creep ref fit steady` / `creep ref fit transient`), with
//! the error bounds asserted as measured (the closing note and the data README quote the full
//! tables: `cargo run --release -p creep-reference --example tier_errors`). One small live
//! boundary-element check keeps the tables honest.

use creep_law::{CreepModel, SteadyLaw, kalker};
use creep_reference::bem::{SolverOptions, SteadySolver};
use creep_reference::contact::CircularContact;
use creep_reference::fit::{STEADY_RATIOS, TransientCase};
use creep_reference::tiers;

#[test]
fn steady_fitted_law_meets_the_issue_bounds_and_kuhn_does_not() {
    let curves = tiers::steady_ext().unwrap();
    assert_eq!(curves.len(), 8, "5 node and 3 check Poisson ratios");
    for c in &curves {
        let (fx, fq) = tiers::steady_errors(CreepModel::Fitted, c);
        let (kx, kq) = tiers::steady_errors(CreepModel::Kuhn, c);
        // Issue bounds: 1 % in creepage for Q/(mu P) <= 0.98, 0.5 % of mu P in force at any
        // creepage; measured 0.25-0.45 % and 0.10-0.42 % (the force error peaks at full slip
        // for nu = 0.5, where the exact force is 0.9958 mu P).
        assert!(fx < 0.005, "nu={}: fitted creepage error {fx}", c.nu);
        assert!(fq < 0.0045, "nu={}: fitted force error {fq}", c.nu);
        // Kuhn's F_ss: 8.9-10.3 % in creepage, 2.0-2.7 % in force (the issue: ~10 %, 2-3 %).
        assert!(
            kx > 0.085 && kx < 0.105,
            "nu={}: Kuhn creepage error {kx}",
            c.nu
        );
        assert!(
            kq > 0.019 && kq < 0.028,
            "nu={}: Kuhn force error {kq}",
            c.nu
        );
        assert!(kx > 15.0 * fx && kq > 4.0 * fq);
    }
}

#[test]
fn issue_figures_for_kuhns_steady_law() {
    for c in &tiers::steady_ext().unwrap() {
        let kuhn = SteadyLaw::new(CreepModel::Kuhn, c.nu);
        // F_ss over-estimates the creepage at every force but the smallest (where it is Kalker's
        // C11, within 0.4 % of the boundary elements), the most near full slip.
        let e: Vec<f64> = STEADY_RATIOS
            .iter()
            .zip(&c.creepage)
            .map(|(s, x)| kuhn.creepage_n(*s) / x - 1.0)
            .collect();
        assert!(e.iter().all(|&e| e > -0.005), "nu={}: {e:?}", c.nu);
        assert!(e.iter().skip(4).all(|&e| e > 0.0), "nu={}: {e:?}", c.nu);
        let at_098 = e[STEADY_RATIOS.iter().position(|&s| s == 0.98).unwrap()];
        assert!(at_098 > 0.085, "nu={}: {at_098}", c.nu);
        // ... so it under-estimates the force at a given creepage, by 2-3 % of mu P, the most
        // between Q/(mu P) = 0.8 and 0.95.
        let (mut worst, mut at) = (0.0f64, 0.0);
        for (s, x) in STEADY_RATIOS.iter().zip(&c.creepage) {
            let d = kuhn.force_ratio(*x) - s;
            assert!(d <= 5e-4, "nu={} s={s}: {d}", c.nu);
            if -d > worst {
                worst = -d;
                at = *s;
            }
        }
        assert!((0.8..=0.95).contains(&at), "nu={}: worst at {at}", c.nu);
        // It saturates at 3/C11, 17-24 % above the exact saturation creepage (issue: ~20 %).
        let ratio = kuhn.saturation_creepage_n() / c.x_sat;
        assert!(ratio > 1.15 && ratio < 1.25, "nu={}: {ratio}", c.nu);
        // The fitted law has the exact slope and saturation by construction (node values).
        let fitted = SteadyLaw::new(CreepModel::Fitted, c.nu);
        assert!((fitted.c11() / c.c11 - 1.0).abs() < 2e-4, "nu={}", c.nu);
        assert!(
            (fitted.saturation_creepage_n() / c.x_sat - 1.0).abs() < 2e-3,
            "nu={}",
            c.nu
        );
        // Kalker's table (quadratic in nu between its three entries) agrees with the
        // extrapolated boundary-element C11 to 0.4 % (0.15 % at the table's own nu).
        let d = kalker::c11(c.nu) / c.c11 - 1.0;
        assert!(d.abs() < 0.004, "nu={}: {d}", c.nu);
        if [0.0, 0.25, 0.5].contains(&c.nu) {
            assert!(d.abs() < 0.0015, "nu={}: {d}", c.nu);
        }
    }
}

#[test]
fn transient_tier_is_at_least_twice_as_good_as_kuhns_rule() {
    let steady = tiers::steady_ext().unwrap();
    let curves = tiers::transient("32").unwrap();
    assert_eq!(curves.len(), 18);
    for c in &curves {
        let kuhn = tiers::transient_error(CreepModel::Kuhn, c, &steady).unwrap();
        let tr = tiers::transient_error(CreepModel::FittedTransient, c, &steady).unwrap();
        // Measured: held force Kuhn 44-46 %, transient tier 10-16 %; held creepage Kuhn
        // 7-10 %, transient tier 1-4 %. The worst ratio is 2.6.
        assert!(
            tr < 0.4 * kuhn,
            "nu={} {:?}: {tr} vs Kuhn {kuhn}",
            c.nu,
            c.case
        );
        let bound = match c.case {
            TransientCase::HoldForce(_) => 0.17,
            TransientCase::HoldCreepage(_) => 0.04,
        };
        assert!(tr < bound, "nu={} {:?}: {tr}", c.nu, c.case);
    }
}

#[test]
fn issue_figures_for_the_transients() {
    // At held force the exact creep rate starts near 60 % of the steady one and reaches it
    // within one and a half contact radii (sooner at higher force).
    for c in tiers::transient("32").unwrap() {
        if let TransientCase::HoldForce(r) = c.case {
            let shape: Vec<f64> = c.creepage.iter().map(|x| x / c.steady_creepage).collect();
            assert!(shape[1] > 0.55 && shape[1] < 0.65, "{r}: {}", shape[1]);
            let reach = c.rolled[shape.iter().skip(1).position(|&v| v >= 0.98).unwrap() + 1];
            assert!(reach > 0.3 && reach < 1.5, "nu={} {r}: {reach}", c.nu);
            assert!((shape.last().unwrap() - 1.0).abs() < 0.01);
        }
    }
}

#[test]
fn transient_tier_has_the_steady_limit_and_kuhns_start() {
    let steady = tiers::steady_ext().unwrap();
    for c in tiers::transient("32").unwrap() {
        let r = match c.case {
            TransientCase::HoldForce(r) | TransientCase::HoldCreepage(r) => r,
        };
        let xi = tiers::steady_creepage(&steady, c.nu, r).unwrap();
        let m = tiers::model_transient(CreepModel::FittedTransient, &c, xi).unwrap();
        let f = tiers::model_transient(CreepModel::Fitted, &c, xi).unwrap();
        let law = SteadyLaw::new(CreepModel::Fitted, c.nu);
        match c.case {
            TransientCase::HoldForce(_) => {
                // After 4 a the creep rate is the fitted steady law's; the first step (the
                // Mindlin shift, no creep yet) is the same as the steady tier's.
                assert!((m.last().unwrap() / law.creepage_n(r) - 1.0).abs() < 1e-3);
                assert_eq!(m[0], f[0]);
            }
            TransientCase::HoldCreepage(_) => {
                // Rolling on at the held creepage converges to the fitted law's force.
                assert!((m.last().unwrap() - law.force_ratio(xi)).abs() < 0.05);
                assert!(m.windows(2).all(|w| w[1] >= w[0] - 1e-12));
            }
        }
    }
}

#[test]
fn live_small_grid_check_of_the_tables() {
    // Boundary elements at N = 12 now (fast in debug): the fitted law is closer to them than
    // Kalker's F_ss at every force ratio tried, although N = 12 itself under-estimates the
    // creepage by up to 9 % (grid error of O(h)).
    let nu = 0.25;
    let mut s = SteadySolver::new(
        CircularContact::normalised(nu).unwrap(),
        SolverOptions::with_grid(12),
    )
    .unwrap();
    let fitted = SteadyLaw::new(CreepModel::Fitted, nu);
    let kuhn = SteadyLaw::new(CreepModel::Kuhn, nu);
    for r in [0.5, 0.9] {
        let (xi, _) = s.solve_force(r).unwrap();
        let ef = fitted.creepage_n(r) / xi - 1.0;
        let ek = kuhn.creepage_n(r) / xi - 1.0;
        assert!(ef.abs() < ek.abs(), "s={r}: fitted {ef}, Kuhn {ek}");
        assert!(ef > 0.0 && ef < 0.1, "s={r}: {ef}");
    }
}
