//! The incline in Avian: a steel ball rolling down 20 degrees creeps by Kalker's steady
//! creepage at the force it transmits, against the Coulomb twin of the same scene.

use creep_avian::scenes::{InclineParams, incline};

#[test]
fn incline_creep_slip_is_kalkers_within_two_percent() {
    let p = InclineParams::default();
    let r = incline(&p).unwrap();
    let err = (r.creepage_measured - r.creepage_expected) / r.creepage_expected;
    println!(
        "creep slip {:.4e}, Kalker {:.4e} at Q/(mu P) = {:.3}, error {:+.2} %; Coulomb twin's slip {:.2e}",
        r.creepage_measured,
        r.creepage_expected,
        r.q_over_mu_p,
        100.0 * err,
        r.coulomb.slip
    );
    assert!(err.abs() < 0.02, "{err}");
    // The creep run gave its contact a target every step; the twin none.
    assert_eq!(r.creep.counts.creep, 1, "{:?}", r.creep.counts);
    assert_eq!(r.coulomb.counts.creep, 0, "{:?}", r.coulomb.counts);
    assert_eq!(
        r.coulomb.counts.coulomb_requested, 1,
        "{:?}",
        r.coulomb.counts
    );
    // The transmitted loads are rolling's, (m g cos(theta), (2/7) m g sin(theta)): P within
    // 0.3 % (the ball bobs with Avian's rotation gap), Q within 1 %.
    let (pn, q) = p.rolling_loads();
    assert!(
        (r.creep.p - pn).abs() < 3e-3 * pn,
        "P {} vs {pn}",
        r.creep.p
    );
    assert!((r.creep.q - q).abs() < 1e-2 * q, "Q {} vs {q}", r.creep.q);
    // Both accelerate at (5/7) g sin(theta) within 1 %.
    let a = 5.0 / 7.0 * 9.81 * p.theta.sin();
    for run in [r.creep, r.coulomb] {
        assert!(
            (run.acceleration - a).abs() < 1e-2 * a,
            "{} vs {a}",
            run.acceleration
        );
    }
}
