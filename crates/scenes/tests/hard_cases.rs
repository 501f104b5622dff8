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

/// Substeps of the full fast-rolling matrix: `CREEP_SUBSTEPS` if set (e.g. 4, Rapier's
/// default), else the matrix's own ([`SUBSTEPS`](creep_scenes::hard_cases::fast_rolling::SUBSTEPS)).
fn matrix_substeps() -> usize {
    use creep_scenes::hard_cases::fast_rolling::SUBSTEPS;
    std::env::var("CREEP_SUBSTEPS")
        .ok()
        .map(|s| s.parse().expect("CREEP_SUBSTEPS: a positive integer"))
        .unwrap_or(SUBSTEPS)
}

/// Whether a run meets every bound but the energy-gain one.
fn bounds_met_but_gain(s: &creep_scenes::rolling_ball::Summary) -> bool {
    use creep_scenes::hard_cases::fast_rolling::{MAX_HEIGHT_ERROR, MAX_LOSS};
    s.loss <= MAX_LOSS && s.max_rise <= MAX_HEIGHT_ERROR && s.max_sink <= MAX_HEIGHT_ERROR
}

/// Runs fast-rolling cases at `substeps`, prints the plugin's and plain Rapier's figures and
/// asserts the bounds on the plugin's.
fn assert_fast_rolling(cases: &[creep_scenes::hard_cases::fast_rolling::Case], substeps: usize) {
    let mut failed = Vec::new();
    for case in cases {
        let o = case.run(substeps).unwrap();
        let (p, q) = (o.plugin, o.plain);
        println!(
            "{} ({substeps} substeps): plugin gain {:.1e} loss {:.1e} rise {:.1e} m sink {:.1e} m | plain gain {:.1e} loss {:.1e} rise {:.1e} m sink {:.1e} m",
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
            if bounds_met_but_gain(&p) {
                match case.engine_drift(substeps) {
                    Ok(d) => println!(
                        "  only the gain bound: plain Rapier's own drift here {:.2e} m/s over the run (measured at {:.3} m/s), {:.2e} of E0 at {} m/s",
                        d.velocity_drift(),
                        d.speed,
                        d.gain_at(case.speed),
                        case.speed
                    ),
                    Err(e) => println!("  only the gain bound; engine drift not measured: {e}"),
                }
            }
            failed.push(case.label());
        }
    }
    assert!(
        failed.is_empty(),
        "outside the bounds ({} of {}): {failed:?}",
        failed.len(),
        cases.len()
    );
}

/// The CI subset of the fast-rolling matrix against every bound of issue 14, strictly, on the
/// plugin's own run (creep fidelity, the matrix's substeps): energy never above its start by
/// more than 1e-6 of it, loss <= 1e-3 of it, centre within 0.1 mm of rest. Fast steel, which
/// gains 2e-6..2e-5 of E0 through Rapier's own f32 drift, is in the full matrix, where that
/// drift is measured apart and printed beside it.
#[test]
fn fast_rolling_ci_subset() {
    use creep_scenes::hard_cases::fast_rolling::{SUBSTEPS, ci_subset};
    assert_fast_rolling(&ci_subset(), SUBSTEPS);
}

#[test]
#[ignore = "the full fast-rolling matrix (108 cases; also in `creep report`); CREEP_SUBSTEPS=4 runs it at Rapier's default"]
fn fast_rolling_full_matrix() {
    assert_fast_rolling(
        &creep_scenes::hard_cases::fast_rolling::matrix(),
        matrix_substeps(),
    );
}

/// Creep-friction in free rolling adds no work: for the fast rubber balls where a creep target
/// built on the solver's rounding once did work (20 m/s at 1/30 s: +1.5e-4 of E0, 10 m/s at
/// 1/60 s: +1.1e-4, the ball sinking 3-22 um), the creep run's energy never exceeds its start by
/// more than the Coulomb run's own f32 excursion plus 1e-6 of E0, and its centre never sinks
/// more than 1 um below rest. Fails if any slip target does work in free rolling.
#[test]
fn creep_adds_no_work_in_free_rolling() {
    use creep_scenes::hard_cases::fast_rolling::{DURATION, SUBSTEPS, material};
    use creep_scenes::rolling_ball::{FidelityChoice, Ground, RollingBall, Stepper};
    for (speed, dt) in [(20.0, 1.0 / 30.0), (10.0, 1.0 / 60.0), (20.0, 1.0 / 120.0)] {
        let run = |f| {
            RollingBall {
                material: material("rubber").unwrap(),
                speed,
                dt,
                ground: Ground::Plane,
                stepper: Stepper::Plugin(f),
                steps: (DURATION / dt).round() as usize,
                substeps: SUBSTEPS,
            }
            .run(|_| {})
            .unwrap()
        };
        let (creep, coulomb) = (run(FidelityChoice::Creep), run(FidelityChoice::Coulomb));
        println!(
            "rubber {speed} m/s 1/{:.0} s: gain creep {:.2e} coulomb {:.2e}; sink creep {:.2e} m",
            1.0 / dt,
            creep.max_gain,
            coulomb.max_gain,
            creep.max_sink
        );
        assert!(
            creep.max_gain <= coulomb.max_gain + 1e-6,
            "creep gains {:.3e} of E0, Coulomb {:.3e}",
            creep.max_gain,
            coulomb.max_gain
        );
        assert!(creep.max_sink <= 1e-6, "sinks {:.3e} m", creep.max_sink);
    }
}

/// Rapier's own energy drift in free rolling, without the plugin: a ball rolling so slowly that
/// the rotation gap stays inside the contact's overlap (the correction then changes nothing the
/// solver reads), for 60 s. Plain Rapier gains energy there (measured 1.8e-4..1.0e-3 of E0:
/// a steady forward drift of v and w of about 3e-6 m/s^2, a third of an f32 ulp per step),
/// and the plugin's Coulomb run is the same run bit for bit: the gain the fast-rolling matrix
/// shows beyond 1e-6 is the engine's, not the plugin's.
#[test]
#[ignore = "measures Rapier's own drift (60 s runs); run it to see the numbers"]
fn plain_rapier_gains_energy_in_slow_free_rolling() {
    use creep_scenes::hard_cases::fast_rolling::material;
    use creep_scenes::rolling_ball::{FidelityChoice, Ground, RollingBall, Stepper};
    for m in ["steel", "glass", "rubber"] {
        for (speed, hz) in [(0.15, 60.0), (0.3, 120.0), (0.3, 240.0)] {
            let run = |stepper| {
                RollingBall {
                    material: material(m).unwrap(),
                    speed,
                    dt: 1.0 / hz,
                    ground: Ground::Plane,
                    stepper,
                    steps: (60.0 * hz) as usize,
                    substeps: 1,
                }
                .run(|_| {})
                .unwrap()
            };
            let plain = run(Stepper::Plain);
            let coulomb = run(Stepper::Plugin(FidelityChoice::Coulomb));
            println!(
                "{m} {speed} m/s 1/{hz} s, 60 s: plain gain {:.2e} loss {:.2e}; plugin (Coulomb) gain {:.2e} loss {:.2e}",
                plain.max_gain, plain.loss, coulomb.max_gain, coulomb.loss
            );
            assert_eq!(plain.max_gain, coulomb.max_gain);
            assert_eq!(plain.loss, coulomb.loss);
        }
    }
}
