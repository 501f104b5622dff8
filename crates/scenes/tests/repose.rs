//! The angle of repose scene (creep-scenes' `repose`, on creep-dem): a small collapsed column,
//! Coulomb only against creep + EPSD rolling torque, and the latter against Zhou et al.'s
//! (2002) correlation.

use creep_scenes::repose::{self, ReposeParams};

/// The CI pile: a 5 x 5 x 4 column (100 grains) on a 22 x 4 fixed base, mu = 0.5.
fn small() -> ReposeParams {
    ReposeParams {
        columns: 5,
        layers: 5,
        max_time: 1.0,
        ..ReposeParams::default()
    }
}

/// Margin by which the rolling torque (EPSD, mu_r = 0.3) must steepen the pile over Coulomb
/// only \[degrees\] (measured at the time of writing: 9.2).
const STEEPER_BY: f64 = 4.0;

/// Band around Zhou et al.'s correlation the rolling-torque pile must fall in, relative
/// (measured at the time of writing: +23 %; the small pile's profile is 5 grains high, so
/// its fitted slope is noisy).
const BAND: f64 = 0.3;

#[test]
fn rolling_torque_steepens_the_pile() {
    let coulomb = repose::run(
        &ReposeParams {
            creep: false,
            rolling: None,
            ..small()
        },
        &mut |_| {},
    )
    .unwrap();
    let rolling = repose::run(
        &ReposeParams {
            creep: true,
            rolling: Some(0.3),
            ..small()
        },
        &mut |_| {},
    )
    .unwrap();
    eprintln!(
        "Coulomb only {:.2} deg (settled {} after {:.3} s), creep + rolling 0.3: {:.2} deg (settled {} after {:.3} s), correlation {:?} deg",
        coulomb.angle_deg,
        coulomb.settled,
        coulomb.time,
        rolling.angle_deg,
        rolling.settled,
        rolling.time,
        rolling.correlation_deg
    );
    assert!(coulomb.settled && rolling.settled);
    assert_eq!(coulomb.grains, 100);
    assert_eq!(coulomb.base_grains, 22 * 4);
    // On the rough base, monodisperse spheres without rolling resistance still form a pile.
    assert!(coulomb.angle_deg > 10.0, "{}", coulomb.angle_deg);
    assert!(coulomb.correlation_deg.is_none());
    assert!(
        rolling.angle_deg > coulomb.angle_deg + STEEPER_BY,
        "rolling {} vs Coulomb {}",
        rolling.angle_deg,
        coulomb.angle_deg
    );
    let corr = rolling.correlation_deg.unwrap();
    assert!(
        (rolling.angle_deg - corr).abs() < BAND * corr,
        "rolling {} vs correlation {corr}",
        rolling.angle_deg
    );
}

#[test]
fn bad_parameters_are_refused_before_running() {
    let e = repose::run(
        &ReposeParams {
            mu: f64::NAN,
            ..small()
        },
        &mut |_| {},
    );
    assert!(e.is_err());
    assert!(
        repose::build(&ReposeParams {
            restitution: 0.0,
            ..small()
        })
        .is_err()
    );
}
