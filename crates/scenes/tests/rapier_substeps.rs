//! The fast-rolling matrix at Rapier's default four substeps, for the patched Rapier
//! (`upstream/rapier/check.sh` builds the workspace against it and runs these with
//! `--ignored`; against crates.io's Rapier they fail, which is what the patches fix).
//!
//! `CREEP_MATRIX=full` runs the full matrix (plane and triangle mesh: the heightfield is an
//! engine limit at any substep count, `hard_cases::fast_rolling`), otherwise the CI subset.
//! Bounds: those of the matrix (loss <= 1e-3 of E0, centre within 0.1 mm of rest, gain <= 1e-6
//! of E0); a case that misses only the gain bound is held to plain Rapier's own drift
//! ([`ENGINE_DRIFT`]) and, for the plugin, to plain Rapier's gain in the same case.
//!
//! Measured (`CREEP_MATRIX=full`, the 72 half-space and mesh cases, 10 s each): plain Rapier and
//! the plugin both meet the loss and height bounds in 72 of 72 (worst loss 2.3e-4 of E0, rise
//! 9.4 um, sink 23 um; crates.io's Rapier: 0 of 108, loss up to 0.99, sinking 8.6 mm), the 1e-6
//! gain bound in 23 (plain) and 23 (plugin), worst gain 1.5e-4 (plain) and 1.6e-4 (plugin). On
//! the mesh the plugin gains up to 1.0e-5 of E0 more than plain Rapier (steel at 5 m/s and
//! 1/120 s), more than 1e-6 above it in 9 of the 36 mesh cases, which the full matrix therefore
//! does not hold (the CI subset does).

use creep_scenes::hard_cases::fast_rolling::{
    Case, DEFAULT_SUBSTEPS, DURATION, MAX_GAIN, MAX_HEIGHT_ERROR, MAX_LOSS, bounds_met, ci_subset,
    material, matrix,
};
use creep_scenes::rolling_ball::{FidelityChoice, Ground, RollingBall, Stepper, Summary};

fn cases() -> Vec<Case> {
    if std::env::var("CREEP_MATRIX").is_ok_and(|m| m == "full") {
        matrix()
            .into_iter()
            .filter(|c| c.ground != Ground::Heightfield)
            .collect()
    } else {
        ci_subset()
    }
}

fn run(case: &Case, stepper: Stepper) -> Summary {
    RollingBall {
        material: material(case.material).unwrap(),
        speed: case.speed,
        dt: case.dt,
        ground: case.ground,
        stepper,
        steps: (DURATION / case.dt).round() as usize,
        substeps: DEFAULT_SUBSTEPS,
    }
    .run(|_| {})
    .unwrap()
}

/// Plain Rapier's own f32 energy drift in free rolling over [`DURATION`], as a bound: a slow
/// ball gains up to 1.0e-3 of E0 in 60 s (`hard_cases`' `plain_rapier_gains_energy_in_slow_free_rolling`),
/// i.e. up to 1.7e-4 in 10 s; the estimate [`Case::engine_drift`] (a slower ball, scaled) is
/// printed beside but undershoots at some speeds (steel 2 m/s 1/120 s: 3.4e-5 against 7.8e-5).
const ENGINE_DRIFT: f64 = 2e-4;

/// Runs every case with `stepper` and with plain Rapier at four substeps, prints the figures and
/// asserts the bounds: loss and height strictly; the gain within Rapier's own drift
/// ([`ENGINE_DRIFT`]), and for the plugin within plain Rapier's gain plus 1e-6 of E0 (the
/// plugin does no work in free rolling).
fn assert_matrix(stepper: Stepper) {
    let mut failed = Vec::new();
    let mut worst = [0.0f64; 4];
    for case in cases() {
        let s = run(&case, stepper);
        let plain = run(&case, Stepper::Plain);
        println!(
            "{} ({} substeps, {}): gain {:.1e} loss {:.1e} rise {:.1e} m sink {:.1e} m",
            case.label(),
            DEFAULT_SUBSTEPS,
            stepper.label(),
            s.max_gain,
            s.loss,
            s.max_rise,
            s.max_sink
        );
        for (w, x) in worst
            .iter_mut()
            .zip([s.max_gain, s.loss, s.max_rise, s.max_sink])
        {
            *w = w.max(x);
        }
        if bounds_met(&s) {
            continue;
        }
        let loss_and_height =
            s.loss <= MAX_LOSS && s.max_rise <= MAX_HEIGHT_ERROR && s.max_sink <= MAX_HEIGHT_ERROR;
        if loss_and_height {
            let estimate = case
                .engine_drift(DEFAULT_SUBSTEPS)
                .map_or(f64::NAN, |d| d.gain_at(case.speed));
            println!(
                "  gain above {MAX_GAIN:.0e}: plain Rapier gains {:.1e} here (drift estimate {estimate:.1e})",
                plain.max_gain
            );
            if s.max_gain <= ENGINE_DRIFT && s.max_gain <= plain.max_gain + MAX_GAIN {
                continue;
            }
        }
        failed.push(case.label());
    }
    println!(
        "worst ({}): gain {:.1e} loss {:.1e} rise {:.1e} m sink {:.1e} m",
        stepper.label(),
        worst[0],
        worst[1],
        worst[2],
        worst[3]
    );
    assert!(failed.is_empty(), "outside the bounds: {failed:?}");
}

#[test]
#[ignore = "needs the patched Rapier (upstream/rapier/check.sh)"]
fn plain_rapier_rolls_within_the_bounds_at_four_substeps() {
    assert_matrix(Stepper::Plain);
}

#[test]
#[ignore = "needs the patched Rapier and creep-rapier's `rapier-patched` feature (upstream/rapier/check.sh)"]
fn plugin_rolls_within_the_bounds_at_four_substeps() {
    assert_matrix(Stepper::Plugin(FidelityChoice::Creep));
}
