//! The talk's figure "Effect of rolling upon tangential force" (`creep_scenes::rolling_effect`)
//! against closed forms and the steady boundary elements. Coarse grids keep these fast in the
//! debug profile; `creep figure rolling-effect --check-grid` measures the figure's own grid.

use creep_law::Material;
use creep_reference::bem::{Creepage, SolverOptions, SteadySolver};
use creep_reference::mindlin::Mindlin;
use creep_scenes::rolling_effect::{
    CreepEffect, Curve, RollingEffect, RollingEffectConfig, RollingEffectError, first_crossing,
    interpolate,
};

/// Mindlin's closed form for the figure's contact, from the material constants: two spheres of
/// one material, `1/G* = 2 (2 - nu)/G` (docs/ARCHITECTURE.md §4).
fn mindlin(fig: &RollingEffect) -> Mindlin {
    let m = fig.config().material;
    let g_star = m.shear_modulus() / (2.0 * (2.0 - m.poisson_ratio()));
    Mindlin::new(fig.mu_p(), g_star, fig.a()).unwrap()
}

/// `Q/(mu P)` by Mindlin's closed form at normalised displacement `delta_n`.
fn mindlin_ratio(fig: &RollingEffect, m: &Mindlin, delta_n: f64) -> f64 {
    m.loading_force(delta_n * fig.displacement_scale()).unwrap() / fig.mu_p()
}

fn config(grid: usize, steps: usize, end: f64, ratios: Vec<f64>) -> RollingEffectConfig {
    RollingEffectConfig {
        grid,
        steps,
        end,
        ratios,
        ..Default::default()
    }
}

#[test]
fn kuhn_without_rolling_is_mindlins_loading_curve() {
    // Cattaneo-Mindlin at constant P (Mindlin 1949): creep-law's memory is exact, so the only
    // error is rounding. The path runs past saturation (0.66).
    let fig = RollingEffect::new(config(16, 50, 1.0, vec![0.0])).unwrap();
    let m = mindlin(&fig);
    let q = fig.kuhn_path(0.0).unwrap();
    let worst = fig
        .deltas()
        .iter()
        .zip(&q)
        .map(|(d, q)| (q - mindlin_ratio(&fig, &m, *d)).abs())
        .fold(0.0f64, f64::max);
    eprintln!("r = 0, Kuhn against Mindlin: max |dQ|/(mu P) = {worst:.1e}");
    assert!(worst < 1e-9, "{worst}");
    assert!((q.last().unwrap() - 1.0).abs() < 1e-12);
}

#[test]
fn exact_without_rolling_is_mindlins_loading_curve() {
    // The boundary elements' Cattaneo-Mindlin curve converges at first order in the element
    // side (Kalker's exact theory; Mindlin's closed form also neglects the small non-parallel
    // slip at nu > 0). Measured max |dQ|/(mu P) over the path: 0.0073 (N = 12), 0.0063
    // (N = 16), 0.0018 (N = 32), 0.0007 (N = 64; `creep figure rolling-effect --check-grid`).
    // Asserted: below 0.01 at N = 16, and smaller than at N = 12.
    let mut worst = Vec::new();
    for grid in [12, 16] {
        let fig = RollingEffect::new(config(grid, 20, 1.0, vec![0.0])).unwrap();
        let m = mindlin(&fig);
        let q = fig.exact_path(0.0, grid, &mut || {}).unwrap();
        let e = fig
            .deltas()
            .iter()
            .zip(&q)
            .map(|(d, q)| (q - mindlin_ratio(&fig, &m, *d)).abs())
            .fold(0.0f64, f64::max);
        // Saturated at the end, like Mindlin.
        assert!((q.last().unwrap() - 1.0).abs() < 1e-4, "{q:?}");
        worst.push(e);
    }
    eprintln!("r = 0, BEM against Mindlin, max |dQ|/(mu P) at N = 12, 16: {worst:?}");
    assert!(worst[1] < 0.01, "{worst:?}");
    assert!(worst[1] < worst[0], "{worst:?}");
}

#[test]
fn long_rolling_tends_to_steady_rolling_at_creepage_one_over_r() {
    // The figure's glass contact at r = 50 ends near full slip (steady 0.996 mu P), where
    // steady rolling and Cattaneo-Mindlin saturation are hard to tell apart; r = 200 (steady
    // creepage 1/200, Q near 0.5 mu P) rolls 15 contact radii by the end of the path and
    // discriminates. The exact end is compared with the steady boundary elements on the same
    // grid, within 0.015 mu P: the transient rolls dq < h per step, the steady solver takes the
    // upwind difference over h, two first-order discretisations of the same limit (measured
    // differences 0.012 at N = 12, 0.0004 at N = 16, 0.007 at N = 32). Kuhn's end is compared
    // with Kalker's closed form (Kalker 2000, `s = 1 - (1 - C11 xi G a^2/(3 mu P))^3`) within
    // 1e-3.
    let r = 200.0;
    let grid = 16;
    let fig = RollingEffect::new(config(grid, 40, 2.0, vec![0.0, r])).unwrap();
    let exact = fig.exact_path(r, grid, &mut || {}).unwrap();
    let kuhn = fig.kuhn_path(r).unwrap();

    let mut steady = SteadySolver::new(*fig.contact(), SolverOptions::with_grid(grid)).unwrap();
    let ss = steady.solve(Creepage::longitudinal(1.0 / r)).unwrap().fx / fig.mu_p();
    assert!(ss > 0.3 && ss < 0.8, "steady {ss}");
    let end = *exact.last().unwrap();
    eprintln!("r = {r}, N = {grid}: exact end {end:.4}, steady BEM {ss:.4}");
    assert!((end - ss).abs() < 0.015, "exact end {end} vs steady {ss}");

    let m = fig.config().material;
    let c11 = creep_law::kalker::c11(m.poisson_ratio());
    let xi_n = 1.0 / (r * fig.epsilon());
    let kalker = 1.0 - (1.0 - c11 * xi_n / 3.0).powi(3);
    let end = *kuhn.last().unwrap();
    assert!(
        (end - kalker).abs() < 1e-3,
        "Kuhn end {end} vs Kalker {kalker}"
    );

    // Rolling lowers the force at every displacement against no rolling (Mindlin).
    let mm = mindlin(&fig);
    for (d, (e, k)) in fig.deltas().iter().zip(exact.iter().zip(&kuhn)).skip(1) {
        let q0 = mindlin_ratio(&fig, &mm, *d);
        assert!(*k < q0 + 1e-12, "Kuhn at {d}: {k} vs {q0}");
        assert!(*e < q0 + 0.015, "exact at {d}: {e} vs {q0}");
    }
}

#[test]
fn creep_effect_and_thresholds_on_known_curves() {
    // Three straight lines Q = k delta (k = 1, 0.9, 0.5) and the r = 0 line reaching 0.5 at
    // delta = 0.5: the reductions are 0, 10 % and 50 %.
    let delta: Vec<f64> = (0..=10).map(|k| 0.1 * k as f64).collect();
    let curve = |r: f64, k: f64| Curve {
        r,
        delta: delta.clone(),
        exact: delta.iter().map(|d| k * d).collect(),
        kuhn: delta.iter().map(|d| k * d).collect(),
    };
    let curves = [curve(0.0, 1.0), curve(10.0, 0.9), curve(20.0, 0.5)];
    let e = CreepEffect::measure(&curves, |c| &c.exact, 0.5).unwrap();
    assert!((e.delta - 0.5).abs() < 1e-12);
    let expect = [0.0, 0.1, 0.5];
    for ((_, c), x) in e.change.iter().zip(expect) {
        assert!((c - x).abs() < 1e-12, "{c} vs {x}");
    }
    // 5 % is halfway between r = 0 and r = 10; 30 % halfway between 10 and 20.
    assert!((e.threshold_ratio(0.05).unwrap() - 5.0).abs() < 1e-9);
    assert!((e.threshold_ratio(0.3).unwrap() - 15.0).abs() < 1e-9);
    assert!(e.threshold_ratio(0.6).is_none());
    assert!(CreepEffect::measure(&curves, |c| &c.kuhn, 1.5).is_none());
    assert_eq!(interpolate(&[0.0, 1.0], &[2.0, 4.0], 0.25), Some(2.5));
    assert_eq!(interpolate(&[0.0, 1.0], &[2.0, 4.0], 1.5), None);
    assert_eq!(first_crossing(&[0.0, 2.0], &[0.0, 1.0], 0.25), Some(0.5));
}

#[test]
fn bad_input_is_a_typed_error() {
    let bad = |c: RollingEffectConfig| {
        matches!(
            RollingEffect::new(c),
            Err(RollingEffectError::Parameter { .. }) | Err(RollingEffectError::Law(_))
        )
    };
    let d = RollingEffectConfig::default;
    assert!(bad(RollingEffectConfig {
        normal_force: 0.0,
        ..d()
    }));
    assert!(bad(RollingEffectConfig {
        radius: f64::NAN,
        ..d()
    }));
    assert!(bad(RollingEffectConfig {
        ratios: vec![1.0, -1.0],
        ..d()
    }));
    assert!(bad(RollingEffectConfig { grid: 2, ..d() }));
    assert!(bad(RollingEffectConfig { steps: 0, ..d() }));
    assert!(bad(RollingEffectConfig {
        end: f64::INFINITY,
        ..d()
    }));
    assert!(bad(RollingEffectConfig {
        material: Material::glass().with_friction(0.0).unwrap(),
        ..d()
    }));
    let fig = RollingEffect::new(d()).unwrap();
    assert!(fig.kuhn_path(f64::NAN).is_err());
    assert!(fig.kuhn_path_at(1.0, 0.0).is_err());
    assert!(matches!(
        fig.compliant_path(-1.0),
        Err(RollingEffectError::Parameter { .. })
    ));
    assert!(fig.steady(0.0, 8).is_err());
}

#[test]
fn rapier_compliant_regime_reproduces_kuhns_rule() {
    // The compliant regime runs Kuhn's rule (creep-law `CreepState`) from the engine's poses and
    // velocities, on the same increments as the Kuhn path (one engine step per sub-step), so
    // the two differ only by the coupling. Expected error, in units of mu P:
    // * the overlap: f32 centres at about R put the Hertz overlap (0.93 um, 8000 f32 spacings
    //   at 1 mm) within half a spacing, 5.8e-11 m, so |P_engine/P - 1| <= 1.5 * 6.3e-5 = 9.4e-5
    //   (measured -4.9e-5). At r = 0 the Cattaneo-Mindlin curve Q/(mu P) = (P'/P) f(x) with
    //   x = delta/K, K ~ P'^(2/3), changes by (P'/P - 1) (f - 2/3 x f') <= |P'/P - 1| (the
    //   bracket rises from 0 to 1 at saturation, where the engine's Q is exactly mu P');
    // * f32 angular velocities: each surface speed to 6e-8, so the increments to 6e-8 (1 + r);
    // * the step: none, the increments are those of the Kuhn path by construction.
    // So against Kuhn's rule at the engine's own P' the error is the f32 velocities' alone:
    // asserted below 2e-7 (1 + r) (measured 2.0e-8 at r = 0, 4.1e-7 at r = 20).
    // Asserted: r = 0 within |P'/P - 1| + 1e-9 and at saturation exactly P'/P; r = 20 within
    // 1e-3 (20 times the measured 4.9e-5: the bound for the "engine reproduces the law"
    // with room for a coarser overlap on another configuration).
    let fig = RollingEffect::new(RollingEffectConfig {
        kuhn_substeps: 10,
        ..config(16, 20, 1.0, vec![0.0, 20.0])
    })
    .unwrap();
    for r in [0.0, 20.0] {
        let kuhn = fig.kuhn_path(r).unwrap();
        let eng = fig.compliant_path(r).unwrap();
        let e = eng.error_against(&kuhn);
        let p_err = eng.normal_force / fig.config().normal_force - 1.0;
        eprintln!(
            "r = {r}: engine - Kuhn max {:.2e}, RMS {:.2e}, end {:+.2e}; P'/P - 1 = {p_err:+.2e}, \
             overlap {:.6e} m, dt {:.3e} s",
            e.max, e.rms, e.end, eng.overlap, eng.dt
        );
        assert!(p_err.abs() < 9.5e-5, "{p_err}");
        // Sign conventions: Q on the lower ball follows v_disp, from 0 and rising.
        assert_eq!(eng.q[0], 0.0);
        assert!(
            eng.q.windows(2).all(|w| w[1] >= w[0] - 1e-12),
            "{:?}",
            eng.q
        );
        assert!(eng.q[1] > 0.05, "{:?}", eng.q);
        // Kinematics: the regime's own v_disp dt and |v_roll| dt are the path's.
        for (d, nominal) in eng.delta.iter().zip(fig.deltas()) {
            assert!((d - nominal).abs() < 1e-5, "{d} vs {nominal}");
        }
        let end = fig.config().end;
        assert!(
            (eng.rolled - r * end).abs() < 1e-5 * (1.0 + r),
            "{}",
            eng.rolled
        );
        // The same law at the engine's P' on the same increments: what is left is f32 velocities.
        let at_p = fig.kuhn_path_at(r, eng.normal_force).unwrap();
        let coupling = eng.error_against(&at_p).max;
        eprintln!("r = {r}: engine - Kuhn at the engine's P': max {coupling:.2e}");
        assert!(coupling < 2e-7 * (1.0 + r), "{coupling}");
        if r == 0.0 {
            assert!(e.max <= p_err.abs() + 1e-9, "{e:?}");
            let sat = eng.q.last().unwrap();
            assert!(
                (sat - (1.0 + p_err)).abs() < 1e-9,
                "{sat} vs {}",
                1.0 + p_err
            );
        } else {
            assert!(e.max < 1e-3, "{e:?}");
        }
    }
}
