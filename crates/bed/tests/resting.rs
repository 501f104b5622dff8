//! A rigid sphere resting on a settled bed: the bed carries its weight.

use creep_bed::scene::{BedSpec, RestingSphere, resting_sphere};
use creep_dem::Cheap;

fn spec(counts: [usize; 3], gravity: f64) -> RestingSphere {
    RestingSphere {
        bed: BedSpec {
            counts,
            gravity,
            ..BedSpec::default()
        },
        radius_factor: 3.0,
        density: 1500.0,
        substeps: 10,
        settle_steps: 20_000,
        rest_steps: 600,
        window: 300,
    }
}

fn check(s: &RestingSphere) {
    let r = resting_sphere::<Cheap>(s).unwrap();
    println!("{r:?}");
    assert!(r.contacts >= 3, "the sphere rests on grains: {r:?}");
    assert!(
        (r.ratio - 1.0).abs() < 0.01,
        "bed force / m g = {}",
        r.ratio
    );
    // It rests on the surface (no sinking through, no flying off).
    assert!(r.sinkage > -0.5 * s.bed.radius && r.sinkage < s.radius_factor * s.bed.radius);
}

/// Small, for CI: 256 grains under a centrifuge's gravity (settles in a few thousand steps).
#[test]
fn a_settled_bed_carries_a_resting_sphere() {
    check(&spec([8, 4, 8], 100.0));
}

/// A few thousand grains at 1 g (`cargo test --release -p creep-bed -- --ignored`).
#[test]
#[ignore = "a few thousand grains: run with --release"]
fn a_settled_bed_of_thousands_of_grains_carries_a_resting_sphere() {
    let mut s = spec([16, 10, 16], 9.81);
    s.settle_steps = 60_000;
    s.rest_steps = 1500;
    s.window = 500;
    check(&s);
}
