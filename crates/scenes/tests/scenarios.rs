//! The scenarios against their closed forms (headless Rapier stepping).

use creep_law::Material;
use creep_scenes::{cue_ball, free_rolling, friction_drive, incline};

#[test]
fn incline_rolls_at_five_sevenths_and_creeps_by_kalker() {
    let r = incline::run(&incline::InclineParams::default()).unwrap();
    let acc_err = r.creep.acceleration / r.acceleration_expected - 1.0;
    let creep_err = r.creepage_measured / r.creepage_expected - 1.0;
    println!(
        "incline: acceleration error {acc_err:+.2e}, creep {:.4e} vs {:.4e} ({creep_err:+.2e})",
        r.creepage_measured, r.creepage_expected
    );
    assert!(acc_err.abs() < 1e-3, "{acc_err}");
    assert!(creep_err.abs() < 0.01, "{creep_err}");
    let counts = r.creep.counts;
    assert_eq!(counts.creep, 1);
    assert!(counts.creep_power > 0.0);
    assert!(counts.max_loop_gain < 1.0);
}

#[test]
fn the_fitted_law_is_one_setting_away() {
    // The same incline with `creep_model = Fitted`: the plugin follows creep-law's BEM-fitted
    // steady law, which differs from Kuhn's F_ss at this load by more than the tolerance.
    let kuhn = incline::run(&incline::InclineParams::default()).unwrap();
    let p = incline::InclineParams {
        creep_model: creep_law::CreepModel::Fitted,
        ..Default::default()
    };
    let r = incline::run(&p).unwrap();
    let err = r.creepage_measured / r.creepage_expected - 1.0;
    println!(
        "fitted: creep {:.4e} vs fitted law {:.4e} (Kuhn's F_ss {:.4e})",
        r.creepage_measured, r.creepage_expected, kuhn.creepage_expected
    );
    assert!(err.abs() < 0.01, "{err}");
    assert!((r.creepage_expected / kuhn.creepage_expected - 1.0).abs() > 0.005);
}

#[test]
fn friction_drive_creep_curve_matches_kalker_below_095() {
    let p = friction_drive::DriveParams::default();
    let m = p.material.density() * 4.0 / 3.0 * std::f64::consts::PI * p.radius.powi(3);
    let mu_p = p.material.friction() * m * incline::G;
    let torques: Vec<f64> = [0.1, 0.5, 0.9, 0.94]
        .iter()
        .map(|s| s * mu_p * p.radius)
        .collect();
    for row in friction_drive::run(&p, &torques).unwrap() {
        let err = row.creepage_measured / row.creepage_expected - 1.0;
        println!(
            "drive Q/(mu P) = {:.2}: creepage {:.4e} vs F_ss {:.4e} ({err:+.2e})",
            row.q_over_mu_p, row.creepage_measured, row.creepage_expected
        );
        assert!(err.abs() < 0.01, "Q/(mu P) = {}: {err}", row.q_over_mu_p);
    }
    assert!(friction_drive::run(&p, &[2.0 * mu_p * p.radius]).is_err());
}

#[test]
fn free_rolling_has_no_creep_resistance() {
    let r = free_rolling::run(Material::steel(), 2.0, 1.0 / 60.0, 10.0).unwrap();
    let rel = r.creep_speed / r.coulomb_speed - 1.0;
    println!(
        "free rolling 10 s: creep {} vs coulomb {} ({rel:+.1e})",
        r.creep_speed, r.coulomb_speed
    );
    assert!(rel.abs() < 1e-4, "{rel}");
    assert!((r.coulomb_speed - r.v0).abs() < 1e-2, "{}", r.coulomb_speed);
}

#[test]
fn cue_ball_slides_then_rolls_as_coulomb() {
    let r = cue_ball::run(Material::steel(), 2.0, 1.0 / 240.0).unwrap();
    for run in [r.coulomb, r.creep] {
        assert!(
            (run.final_speed / r.final_speed_expected - 1.0).abs() < 0.01,
            "{run:?}"
        );
        assert!(
            (run.slip_time / r.slip_time_expected - 1.0).abs() < 0.01,
            "{run:?} vs {}",
            r.slip_time_expected
        );
    }
    assert!((r.creep.final_speed / r.coulomb.final_speed - 1.0).abs() < 1e-4);
}

#[test]
fn soft_rubber_creeps_by_kalker_up_to_large_creepage() {
    // G = 1 MPa: creepage up to 4e-2 of the rolled distance. With creep the rotation lags, so
    // the transmitted force is below (2/7) m g sin(theta); F_ss is taken at the measured force.
    for (theta_deg, tol) in [(40.0f64, 0.02), (68.4, 0.03)] {
        let p = incline::InclineParams {
            theta: theta_deg.to_radians(),
            material: Material::rubber(),
            ..Default::default()
        };
        let r = incline::run(&p).unwrap();
        let err = r.creepage_measured / r.creepage_expected - 1.0;
        println!(
            "rubber {theta_deg} deg: Q/(mu P) = {:.3}, creep {:.4e} vs F_ss {:.4e} ({err:+.2e})",
            r.q_over_mu_p, r.creepage_measured, r.creepage_expected
        );
        assert!(err.abs() < tol, "{theta_deg} deg: {err}");
    }
}

#[test]
fn compliant_impact_matches_hertz_and_converges_at_second_order() {
    use creep_scenes::impact::{ImpactParams, run};
    let at = |f: f64, e: f64| {
        run(&ImpactParams {
            dt_over_rayleigh: f,
            restitution: e,
            ..Default::default()
        })
        .unwrap()
    };
    let (coarse, fine) = (at(0.2, 1.0), at(0.1, 1.0));
    println!(
        "impact at 0.2 / 0.1 T_R: duration {:+.3e} / {:+.3e}, peak {:+.3e} / {:+.3e}, rebound {:+.3e} / {:+.3e}",
        coarse.duration_error(),
        fine.duration_error(),
        coarse.peak_force_error(),
        fine.peak_force_error(),
        coarse.rebound - 1.0,
        fine.rebound - 1.0
    );
    assert!(fine.duration_error().abs() < 1e-3 && fine.peak_force_error().abs() < 1e-3);
    assert!((fine.rebound - 1.0).abs() < 1e-4);
    // Halving the step quarters the duration error (symplectic Euler, leap-frog in positions).
    let order = (coarse.duration_error() / fine.duration_error()).log2();
    assert!((order - 2.0).abs() < 0.3, "order {order}");
    let damped = at(0.1, 0.5);
    assert!(
        (damped.rebound / 0.5 - 1.0).abs() < 0.01,
        "{}",
        damped.rebound
    );
    for bad in [
        ImpactParams {
            dt_over_rayleigh: 1.5,
            ..Default::default()
        },
        ImpactParams {
            restitution: 0.0,
            ..Default::default()
        },
        ImpactParams {
            speed: f64::NAN,
            ..Default::default()
        },
    ] {
        assert!(run(&bad).is_err());
    }
}
