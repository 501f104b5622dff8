//! Settled bodies sleep with the plugin as they do in plain Rapier, whatever the fidelity.

use creep_rapier::Fidelity;
use creep_scenes::pile::{asleep, sleeping_pile};

/// 512 steel balls poured into a box at 1/60 s with `CreepWorld::new`'s defaults and sleeping
/// on: after 900 steps (15 s) every ball sleeps with the plugin at every rigid fidelity, as in
/// plain Rapier (Creep's twisting moments, applied after each step, used to wake their bodies
/// every step: the settled pile with Creep never slept).
#[test]
fn a_settled_pile_sleeps_at_every_fidelity() {
    let n = 8;
    for fidelity in [
        None,
        Some(Fidelity::Coulomb),
        Some(Fidelity::Auto),
        Some(Fidelity::Creep),
    ] {
        let w = sleeping_pile(n, fidelity, 900).unwrap();
        let sleeping = asleep(&w.physics);
        eprintln!("{fidelity:?}: {sleeping} of {} asleep", n * n * n);
        assert_eq!(sleeping, n * n * n, "{fidelity:?}");
    }
}
