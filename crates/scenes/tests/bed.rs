//! The bed scenes through creep-scenes (one scenario code for tests, the CLI and benches): a
//! small wheel sweep, both contact models from one settled bed.

use creep_dem::Cheap;
use creep_law::CreepModel;
use creep_scenes::bed::{Progress, WheelOnSand, sweep};

#[test]
fn a_small_wheel_sweep_runs_both_contact_models_from_one_bed() {
    let mut s = WheelOnSand::with_grains(640).unwrap();
    s.bed.counts = [10, 5, 6];
    s.radius_factor = 5.0;
    s.settle_steps = 4000;
    s.sink_steps = 40;
    s.drive_steps = 60;
    s.spin = 10.0;
    let slips = [0.0, 0.6];
    let models = [Some(CreepModel::Kuhn), None];
    let settled = std::sync::atomic::AtomicUsize::new(0);
    let drives = sweep::<Cheap>(&s, &slips, &models, 2, |p| {
        if let Progress::Settled(n, _, _) = p {
            settled.store(n, std::sync::atomic::Ordering::Relaxed);
        }
    })
    .unwrap();
    assert_eq!(settled.into_inner(), 300, "settled once, 300 grains");
    assert_eq!(drives.len(), 4);
    // Results in the order models x slips.
    for (k, d) in drives.iter().enumerate() {
        assert_eq!(d.steady.creep, k < 2);
        assert_eq!(d.steady.slip, slips[k % 2]);
        assert_eq!(d.rows.len(), s.drive_steps);
        println!("{:?}", d.steady);
    }
    // Same bed, same landing: the two models start from the same grains, and each one's
    // drawbar pull rises with slip.
    for m in 0..2 {
        let (a, b) = (&drives[2 * m].steady, &drives[2 * m + 1].steady);
        assert!(
            b.drawbar_pull > a.drawbar_pull,
            "model {m}: pull {} at slip 0.6 vs {} at 0",
            b.drawbar_pull,
            a.drawbar_pull
        );
        assert!(a.sinkage > 0.0 && a.sinkage < a.radius);
    }
}
