//! The hard-case matrix of the rigid regime (`creep_scenes::hard_cases`, whose module docs
//! describe the scenes, the measurements and every check): each test runs one case and asserts
//! every one of its verdicts; the engine limits are ignored tests. `creep report` tabulates the
//! same runs with their margins.
//!
//! `cargo test -p creep-scenes --test hard_cases -- --include-ignored --nocapture` prints every
//! number.

use creep_scenes::hard_cases::HardCase;

/// Runs `case`, prints its numbers and asserts every verdict.
fn assert_case(case: HardCase) {
    let o = case.run().unwrap();
    for l in &o.lines {
        println!("{l}");
    }
    for v in &o.verdicts {
        println!("{}: {v}", case.label());
    }
    for v in &o.verdicts {
        assert!(v.passed(), "{}: {v}", case.label());
    }
}

#[test]
fn long_step_1_30_s() {
    assert_case(HardCase::LongStep);
}

#[test]
fn rubber_near_the_friction_limit() {
    assert_case(HardCase::Rubber240);
}

#[test]
#[ignore = "engine limit (HardCase::Rubber60::engine_limit): at 1/60 s Rapier's own Coulomb run already slips on this contact; run it to see the numbers"]
fn rubber_near_the_friction_limit_1_60_s() {
    assert_case(HardCase::Rubber60);
}

#[test]
fn mass_ratio_1000_to_1() {
    assert_case(HardCase::LightBallHeavySlab);
}

#[test]
#[ignore = "engine limit (HardCase::HeavyBallLightSlab::engine_limit): Rapier's Gauss-Seidel does not converge for a 32.9 kg ball on a 32.9 g slab on the floor; run it to see the numbers"]
fn mass_ratio_1000_to_1_heavy_ball_on_light_slab() {
    assert_case(HardCase::HeavyBallLightSlab);
}

#[test]
fn spin_100_rad_s() {
    assert_case(HardCase::Spin);
}

#[test]
fn column_of_ten_spheres() {
    assert_case(HardCase::Column);
}

#[test]
fn sphere_at_rest_does_not_creep_away() {
    assert_case(HardCase::AtRest);
}

#[test]
fn the_engine_limits_are_the_ignored_cases() {
    let limits: Vec<HardCase> = HardCase::ALL
        .into_iter()
        .filter(|c| c.engine_limit().is_some())
        .collect();
    assert_eq!(limits, [HardCase::Rubber60, HardCase::HeavyBallLightSlab]);
}

/// Runs fast-rolling cases at the matrix's substeps, prints the plugin's and plain Rapier's
/// figures and asserts the bounds on the plugin's.
fn assert_fast_rolling(cases: &[creep_scenes::hard_cases::fast_rolling::Case]) {
    use creep_scenes::hard_cases::fast_rolling::SUBSTEPS;
    let mut failed = Vec::new();
    for case in cases {
        let o = case.run(SUBSTEPS).unwrap();
        let (p, q) = (o.plugin, o.plain);
        println!(
            "{}: plugin gain {:.1e} loss {:.1e} rise {:.1e} m sink {:.1e} m | plain gain {:.1e} loss {:.1e} rise {:.1e} m sink {:.1e} m",
            case.label(),
            p.max_gain,
            p.loss,
            p.max_rise,
            p.max_sink,
            q.max_gain,
            q.loss,
            q.max_rise,
            q.max_sink
        );
        if !o.passed() {
            failed.push(case.label());
        }
    }
    assert!(failed.is_empty(), "outside the bounds: {failed:?}");
}

#[test]
fn fast_rolling_ci_subset() {
    assert_fast_rolling(&creep_scenes::hard_cases::fast_rolling::ci_subset());
}

#[test]
#[ignore = "the full fast-rolling matrix (108 cases; also in `creep report`)"]
fn fast_rolling_full_matrix() {
    assert_fast_rolling(&creep_scenes::hard_cases::fast_rolling::matrix());
}
