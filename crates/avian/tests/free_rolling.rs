//! Free rolling in Avian: a ball rolling on a flat ground carries no tangential load, so the
//! plugin must add no energy: the creep run's energy never exceeds its start by more than
//! 1e-6 of it, nor its Coulomb twin's largest gain by more than that.

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
        let gain = |e: &[f64]| {
            e.iter()
                .map(|e| (e - e0) / e0)
                .fold(f64::NEG_INFINITY, f64::max)
        };
        let loss = |e: &[f64]| (e0 - e.last().copied().unwrap_or(e0)) / e0;
        let (g_creep, g_twin) = (gain(&creep), gain(&twin));
        println!(
            "{ground:?} {speed} m/s: largest gain creep {g_creep:.2e}, twin {g_twin:.2e} of E0; loss creep {:.2e}, twin {:.2e}",
            loss(&creep),
            loss(&twin)
        );
        assert!(g_creep <= 1e-6, "{g_creep}");
        assert!(g_creep <= g_twin.max(0.0) + 1e-6, "{g_creep} {g_twin}");
    }
}

/// With the plugin's rotation-gap removal a ball rolling freely neither sinks nor loses
/// energy to Avian's rotation gap: the fast-rolling bounds (height within 0.1 mm, loss below
/// 1e-3) hold at 1/30 s, where plain Avian sinks the ball 8 mm at 2 m/s and 40 mm at 10 m/s.
#[test]
fn rotation_gap_removal_keeps_a_rolling_ball_at_its_height() {
    use creep_avian::scenes::{MAX_HEIGHT_ERROR, MAX_LOSS};
    for speed in [2.0, 10.0] {
        let ball = RollingBall {
            material: Material::steel(),
            speed,
            dt: 1.0 / 30.0,
            duration: 2.0,
            ground: Ground::Plane,
            substeps: DEFAULT_SUBSTEPS,
        };
        let removed = ball.run(Run::GapRemoved(Fidelity::Creep), |_, _| {});
        let plain = ball.run(Run::Plain, |_, _| {});
        println!(
            "{speed} m/s: sink {:.2e} m, rise {:.2e} m, loss {:.2e} (plain Avian: sink {:.2e} m, loss {:.2e})",
            removed.max_sink, removed.max_rise, removed.loss, plain.max_sink, plain.loss
        );
        assert!(removed.max_sink <= MAX_HEIGHT_ERROR, "{removed:?}");
        assert!(removed.max_rise <= MAX_HEIGHT_ERROR, "{removed:?}");
        assert!(removed.loss <= MAX_LOSS, "{removed:?}");
    }
}
