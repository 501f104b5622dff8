//! The coupling's cost against the bed alone (a measurement, not a pass/fail test):
//! `cargo test --release -p creep-bed --test cost -- --ignored --nocapture`
//! (the same as `creep run wheel-on-sand --cost`).

use creep_bed::cost::{CostReport, coupling_cost};

#[test]
#[ignore = "a timing: run in release"]
fn coupling_cost_against_the_bed_alone() {
    let nx: usize = std::env::var("BED_NX").map_or(20, |v| v.parse().unwrap());
    let rounds: usize = std::env::var("BED_ROUNDS").map_or(5, |v| v.parse().unwrap());
    let c = coupling_cost([nx, 5, 20], rounds).unwrap();
    println!("{}", CostReport::CSV_HEADER);
    println!("{}", c.csv_row());
    assert!(c.contacts > 0, "the wheel touches the bed");
}
