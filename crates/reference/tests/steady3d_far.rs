//! creep-law's steady 3-D law beyond its box (`|xi_n|, |eta_n| <= 2`, `|phi_n| <= 4`), graded
//! on the checked-in boundary elements along rays (`data/steady3d_far.csv`, module
//! `creep_reference::steady3d_far`) and, far along every ray, against the rigid-slip
//! quadrature. Regenerate and grade: `cargo run --release -p creep-reference --example
//! steady3d_far -- bem | grade`.

use creep_law::steady3d::{Coverage, Steady3d};
use creep_reference::bem::{EllipticContact, EllipticSteadySolver, SolverOptions};
use creep_reference::steady3d_far::{CASES, DIRS, RAYS, ray_point};
use creep_reference::steady3d_map::{MapPoint, coverage_bounds, full_slip_loads, read_map_csv};

fn table() -> Vec<MapPoint> {
    read_map_csv(include_str!("../data/steady3d_far.csv")).unwrap()
}

/// The ray's `s` of a point of the table.
fn s_of(c: [f64; 3]) -> f64 {
    (c[0].abs().max(c[1].abs()) / 2.0).max(c[2].abs() / 4.0)
}

#[test]
fn far_table_is_complete_and_reproducible() {
    let t = table();
    assert_eq!(t.len(), CASES.len() * DIRS.len() * RAYS.len());
    for p in &t {
        assert!(p.fine[0].hypot(p.fine[1]) <= 1.0 + 2e-6, "{p:?}");
        assert!(RAYS.iter().any(|&s| (s_of(p.creepage) - s).abs() < 1e-9));
    }
    // Live: one ray point of the circle at nu = 0.3 (grids 16 and 32, from rest; the table was
    // warm-started along the ray to the same 1e-10 tolerance).
    let c = EllipticContact::normalised(0.3, 1.0).unwrap();
    let x = ray_point(DIRS[1], 2.0);
    let p = t
        .iter()
        .find(|p| p.ab == 1.0 && p.nu == 0.3 && p.creepage == x)
        .unwrap();
    let f = EllipticSteadySolver::new(c, SolverOptions::with_grid(32))
        .unwrap()
        .solve_normalised(x[0], x[1], x[2])
        .unwrap();
    let g = EllipticSteadySolver::new(c, SolverOptions::with_grid(16))
        .unwrap()
        .solve_normalised(x[0], x[1], x[2])
        .unwrap();
    let e = [2.0 * f.0 - g.0, 2.0 * f.1 - g.1, 2.0 * f.2 - g.2];
    for k in 0..3 {
        assert!((e[k] - p.load[k]).abs() < 2e-5, "{e:?} vs {p:?}");
    }
}

/// Where the boundary-element table covers the contact, beyond the box as within it: at every
/// ray point the bounds of the table's source (`steady3d_map::coverage_bounds`; at a computed
/// node 2 % of `mu P` in each force, 3 % of `mu P a` in the moment, `a` the semi-axis along the
/// rolling direction), where the exact loads are 3-19 % of `mu P` from full slip's.
#[test]
fn beyond_the_box_within_the_table_bounds() {
    let t = table();
    for &(ab, nu) in &CASES {
        let law = Steady3d::new(ab, nu).unwrap();
        let a = ab.sqrt();
        let mut worst = [0.0f64; 3];
        let mut gap = 0.0f64;
        for p in t.iter().filter(|p| p.ab == ab && p.nu == nu) {
            let c = p.creepage;
            let l = law.loads(c[0], c[1], c[2]);
            worst[0] = worst[0].max((l.fx - p.load[0]).abs());
            worst[1] = worst[1].max((l.fy - p.load[1]).abs());
            worst[2] = worst[2].max((l.mz - p.load[2]).abs() / a);
            let fs = full_slip_loads(ab, c, 60);
            gap = gap.max((p.load[1] - fs[1]).abs());
        }
        let Some([f, m]) = coverage_bounds(law.coverage()) else {
            continue;
        };
        assert!(
            gap > 0.15,
            "{ab} {nu}: the rays reach the sticking pole ({gap})"
        );
        assert!(
            worst[0] < f && worst[1] < f && worst[2] < m,
            "a/b {ab}, nu {nu} ({:?}): {worst:?}",
            law.coverage()
        );
    }
}

/// Where the fitted law answers, its error at the box's edge fades as `1/s` along the ray
/// (the full-slip limit is the law's whatever its source).
#[test]
fn beyond_the_box_the_fitted_law_fades_into_full_slip() {
    let t = table();
    for &(ab, nu) in &CASES {
        let law = Steady3d::new(ab, nu).unwrap();
        if law.coverage() != Coverage::Fitted {
            continue;
        }
        let worst = |s: f64| {
            t.iter()
                .filter(|p| p.ab == ab && p.nu == nu && (s_of(p.creepage) - s).abs() < 1e-9)
                .map(|p| {
                    let c = p.creepage;
                    let l = law.loads(c[0], c[1], c[2]);
                    (l.fx - p.load[0]).abs().max((l.fy - p.load[1]).abs())
                })
                .fold(0.0f64, f64::max)
        };
        let (e1, e8) = (worst(1.0), worst(8.0));
        assert!(
            e8 < e1 / 8.0 + 0.03,
            "a/b {ab}: {e1} at the edge, {e8} at s = 8"
        );
    }
}

/// Far along every ray (largest creepage 1e3) the law is full slip's (the rigid-slip
/// quadrature) within 1.1 % of `mu P` and `mu P c`, at every a/b and nu of Kalker's range.
#[test]
fn far_in_full_slip_at_every_axis_ratio_and_nu() {
    for ab in [0.1, 0.2, 0.35, 0.7, 1.0, 1.4, 3.0, 5.0, 10.0] {
        for nu in [0.0, 0.28, 0.5] {
            let law = Steady3d::new(ab, nu).unwrap();
            for d in DIRS
                .iter()
                .chain(&[[0.0, 0.0, 1.0], [1.0, 0.0, 0.0], [0.0, -1.0, 0.2]])
            {
                let m = d.iter().fold(0.0f64, |m, v| m.max(v.abs()));
                let c = d.map(|v| v * 1e3 / m);
                let (l, q) = (law.loads(c[0], c[1], c[2]), full_slip_loads(ab, *d, 100));
                let e = [l.fx - q[0], l.fy - q[1], l.mz - q[2]];
                assert!(
                    e.iter().all(|v| v.abs() < 0.011),
                    "a/b {ab}, nu {nu}, {d:?}: {l:?} vs {q:?}"
                );
            }
        }
    }
}
