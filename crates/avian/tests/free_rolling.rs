//! Free rolling in Avian: a ball rolling on a flat ground carries no tangential load, so the
//! plugin must add no energy: at every step the creep run's energy is at most its Coulomb
//! twin's (plus f32 rounding of the energy itself).

use creep_avian::Fidelity;
use creep_avian::scenes::{DEFAULT_SUBSTEPS, Ground, RollingBall, Run};
use creep_law::Material;

fn energies(ball: &RollingBall, run: Run) -> (Vec<f64>, f64) {
    let mut e = Vec::new();
    let s = ball.run(run, |energy, _| e.push(energy));
    (e, s.e0)
}

#[test]
fn free_rolling_gains_no_energy_from_the_plugin() {
    for (material, speed, ground) in [
        (Material::steel(), 2.0, Ground::Plane),
        (Material::glass(), 5.0, Ground::Trimesh),
    ] {
        let ball = RollingBall {
            material,
            speed,
            dt: 1.0 / 60.0,
            duration: 2.0,
            ground,
            substeps: DEFAULT_SUBSTEPS,
        };
        let (creep, e0) = energies(&ball, Run::Plugin(Fidelity::Creep));
        let (twin, _) = energies(&ball, Run::Plugin(Fidelity::Coulomb));
        let worst = creep
            .iter()
            .zip(&twin)
            .map(|(c, t)| (c - t) / e0)
            .fold(f64::NEG_INFINITY, f64::max);
        let gain = creep.iter().map(|e| (e - e0) / e0).fold(f64::NEG_INFINITY, f64::max);
        println!("{ground:?} {speed} m/s: creep - twin at most {worst:.2e} E0; gain {gain:.2e} E0");
        assert!(worst <= 1e-6, "{worst}");
    }
}
