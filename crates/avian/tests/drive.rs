//! The friction drive in Avian: the output ball turns slower than the driver by Kalker's
//! steady creepage at the transmitted force, from 0.2 to 0.9 mu P, against the Coulomb twin.

use creep_avian::scenes::{DriveParams, drive};

#[test]
fn drive_creepage_is_kalkers_within_two_percent_from_02_to_09_mu_p() {
    let p = DriveParams::default();
    let rows = drive(&p, &[0.2, 0.4, 0.6, 0.8, 0.9]).unwrap();
    for r in &rows {
        let err = (r.creepage_measured - r.creepage_expected) / r.creepage_expected;
        println!(
            "Q/(mu P) {:.3}: creepage {:.4e}, Kalker {:.4e}, error {:+.2} %; Coulomb twin {:.2e}",
            r.q_over_mu_p,
            r.creepage_measured,
            r.creepage_expected,
            100.0 * err,
            r.coulomb.creepage
        );
        assert!(err.abs() < 0.02, "{r:?}");
        // The twin transmits the torque without losing speed (beyond a small fraction).
        assert!(r.coulomb.creepage.abs() < 0.05 * r.creepage_expected, "{r:?}");
    }
    // The force ratios span the range asked for.
    assert!((rows[0].q_over_mu_p - 0.2).abs() < 0.01 && (rows[4].q_over_mu_p - 0.9).abs() < 0.02);
}
