//! The friction drive in Avian: a kinematic ball driven at 10 rad/s turns a ball resting on
//! it against a brake torque `s mu P R`, `s` from 0.2 to 0.9 (1/240 s, 6 substeps), with the
//! plugin's rotation-gap removal in the creep run and its Coulomb twin alike. The contact
//! transmits `Q = s mu P` at `P = m g`, and the output turns slower than the driver by
//! Kalker's creepage at that force, against the twin (whose own slip is below 2e-5).
//!
//! Two things the scene needs from the plugin: the friction frame and warm start it repairs
//! (Avian builds the frame from the centres' relative velocity, here along the normal, so the
//! frame turned at random from step to step and the warm start landed elsewhere: the contact
//! chattered and slipped outright from 0.6 mu P), and the rotation-gap removal (two balls
//! spinning in place open Avian's rotation gap on both sides: the contact went slack in the
//! last two substeps of each step and the output lagged by 1 %, five times Kalker's creepage).

use creep_avian::scenes::{DriveParams, drive};

const RATIOS: [f64; 5] = [0.2, 0.4, 0.6, 0.8, 0.9];

#[test]
fn drive_transmits_the_brake_torque_from_02_to_09_mu_p() {
    let p = DriveParams::default();
    let rows = drive(&p, &RATIOS).unwrap();
    for (r, s) in rows.iter().zip(RATIOS) {
        println!(
            "s {s}: Q/(mu P) {:.4}, P {:.3} N (m g {:.3} N)",
            r.q_over_mu_p,
            r.creep.p,
            p.normal_force()
        );
        assert!((r.q_over_mu_p - s).abs() < 0.02 * s, "{r:?}");
        assert!(
            (r.creep.p - p.normal_force()).abs() < 0.02 * p.normal_force(),
            "{r:?}"
        );
    }
}

#[test]
fn drive_creepage_against_kalker() {
    let p = DriveParams::default();
    let rows = drive(&p, &RATIOS).unwrap();
    let mut worst: f64 = 0.0;
    for r in &rows {
        let err = (r.creepage_measured - r.creepage_expected) / r.creepage_expected;
        worst = worst.max(err.abs());
        println!(
            "Q/(mu P) {:.3}: creepage {:.4e} (creep run {:.4e} less twin {:.4e}), Kalker {:.4e}, error {:+.1} %",
            r.q_over_mu_p,
            r.creepage_measured,
            r.creep.creepage,
            r.coulomb.creepage,
            r.creepage_expected,
            100.0 * err,
        );
    }
    assert!(worst < 0.02, "{worst}");
}
