//! A steel ball rolls down a 20-degree incline in Avian, with creep-friction and as its Coulomb
//! twin; prints the creep slip, Kalker's steady creepage at the transmitted force and their
//! difference.
//!
//! `cargo run -p creep-avian --example incline --ignore-rust-version`

use creep_avian::scenes::{InclineParams, incline};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let p = InclineParams::default();
    let r = incline(&p)?;
    let (pn, q) = (r.creep.p, r.creep.q);
    println!(
        "Incline in Avian: steel ball R = {} m, theta = {:.1} deg, mu = {}, dt = {:.5} s, {} substeps, {} s",
        p.radius,
        p.theta.to_degrees(),
        p.material.friction(),
        p.dt,
        p.substeps,
        p.duration
    );
    println!(
        "  transmitted P = {pn:.3} N, Q = {q:.3} N, Q/(mu P) = {:.4}",
        r.q_over_mu_p
    );
    println!(
        "  acceleration: creep {:.4} m/s^2, Coulomb {:.4} m/s^2, (5/7) g sin(theta) = {:.4} m/s^2",
        r.creep.acceleration,
        r.coulomb.acceleration,
        5.0 / 7.0 * 9.81 * p.theta.sin()
    );
    println!(
        "  slip: creep run {:.4e}, Coulomb twin {:.4e}",
        r.creep.slip, r.coulomb.slip
    );
    println!(
        "  creep slip {:.4e}, Kalker F_ss {:.4e}, difference {:+.2} %",
        r.creepage_measured,
        r.creepage_expected,
        100.0 * (r.creepage_measured - r.creepage_expected) / r.creepage_expected
    );
    Ok(())
}
