//! The elliptic boundary elements against Kalker's table, and creep-law's fast 3-D steady law
//! (`creep_law::steady3d`) against the checked-in boundary-element table
//! `data/steady3d_bem.csv` (module `creep_reference::steady3d`; full error table:
//! `cargo run --release -p creep-reference --example steady3d_errors`).

use creep_law::kalker3d;
use creep_reference::bem::{
    EllipticContact, EllipticSteadySolver, SolverOptions, elliptic_creep_coefficients,
};
use creep_reference::steady3d::{Kind, POISSON, RATIOS, law_errors, read_csv, table};

#[test]
fn circular_c22_c23_c33_within_2_percent_of_kalkers_table() {
    // a/b = 1, grids 16 and 32 across the diameter, Richardson 2 C(32) - C(16) (the grid error
    // is O(h)). Measured: C22 within 0.05 %, C23 within 0.4 %, C33 within 1.0 %.
    for nu in POISSON {
        let a = elliptic_creep_coefficients(nu, 1.0, SolverOptions::with_grid(16)).unwrap();
        let b = elliptic_creep_coefficients(nu, 1.0, SolverOptions::with_grid(32)).unwrap();
        let k = kalker3d::coefficients(1.0, nu).unwrap();
        for (name, x16, x32, table) in [
            ("C11", a.c11, b.c11, k.c11),
            ("C22", a.c22, b.c22, k.c22),
            ("C23", a.c23, b.c23, k.c23),
            ("C33", a.c33, b.c33, k.c33),
        ] {
            let rich = 2.0 * x32 - x16;
            assert!(
                (rich / table - 1.0).abs() < 0.02,
                "nu={nu} {name}: {rich} vs {table}"
            );
            // Grid convergence: the finer grid is closer.
            assert!((x32 - table).abs() < (x16 - table).abs(), "nu={nu} {name}");
        }
        // Reciprocity C32 = -C23.
        assert!((b.c32 + b.c23).abs() < 1e-3 * b.c23);
    }
}

#[test]
#[ignore = "slow in debug builds: run with --release -- --ignored"]
fn elliptic_coefficients_within_2_percent_of_kalkers_table() {
    // a/b = 0.5 and 0.2 (grids 16 and 32 across the shorter axis), all four coefficients.
    for ab in [0.5, 0.2] {
        for nu in POISSON {
            let a = elliptic_creep_coefficients(nu, ab, SolverOptions::with_grid(16)).unwrap();
            let b = elliptic_creep_coefficients(nu, ab, SolverOptions::with_grid(32)).unwrap();
            let k = kalker3d::coefficients(ab, nu).unwrap();
            for (name, x16, x32, table) in [
                ("C11", a.c11, b.c11, k.c11),
                ("C22", a.c22, b.c22, k.c22),
                ("C23", a.c23, b.c23, k.c23),
                ("C33", a.c33, b.c33, k.c33),
            ] {
                let rich = 2.0 * x32 - x16;
                assert!(
                    (rich / table - 1.0).abs() < 0.02,
                    "a/b={ab} nu={nu} {name}: {rich} vs {table}"
                );
            }
        }
    }
}

#[test]
fn table_is_complete_and_reproducible() {
    let t = table().unwrap();
    assert_eq!(t.len(), RATIOS.len() * POISSON.len() * 39);
    // Live check of three points of the circular case at nu = 0.25 (grids 16 and 32, from zero
    // traction; the table was solved warm-started, to the same 1e-10 tolerance).
    let c = EllipticContact::normalised(0.25, 1.0).unwrap();
    let mut s16 = EllipticSteadySolver::new(c, SolverOptions::with_grid(16)).unwrap();
    let mut s32 = EllipticSteadySolver::new(c, SolverOptions::with_grid(32)).unwrap();
    for cr in [[0.2, 0.0, 0.0], [0.0, 0.0, 0.5], [0.2, 0.1, 0.5]] {
        s16.reset();
        s32.reset();
        let a = s16.solve_normalised(cr[0], cr[1], cr[2]).unwrap();
        let b = s32.solve_normalised(cr[0], cr[1], cr[2]).unwrap();
        let live = [2.0 * b.0 - a.0, 2.0 * b.1 - a.1, 2.0 * b.2 - a.2];
        let q = t
            .iter()
            .find(|q| q.ab == 1.0 && q.nu == 0.25 && q.creepage == cr)
            .unwrap();
        for i in 0..3 {
            assert!(
                (live[i] - q.load[i]).abs() < 2e-6,
                "{cr:?}: {live:?} vs {q:?}"
            );
        }
    }
}

/// Largest force and moment errors of the law over the table, per family.
fn worst(kind: Kind) -> (f64, f64) {
    law_errors(&table().unwrap())
        .unwrap()
        .iter()
        .filter(|e| e.kind == kind)
        .fold((0.0f64, 0.0f64), |(f, m), e| {
            (f.max(e.force), m.max(e.moment))
        })
}

#[test]
fn fast_law_pure_cases_meet_the_issue_target() {
    // Issue target: pure cases within 2 % of mu P (forces; moments within 2 % of mu P c), at
    // a/b = 1, 0.5, 0.2 and nu = 0, 0.25, 0.5. Measured (docs/CREEP3D.md): longitudinal and
    // lateral forces at most 0.64 %, the lateral creepage's moment 0.68 %, the lateral force of
    // pure spin 1.68 %, the spin moment 0.76 % (before this law: 5.2 % and 2.07 %).
    let (fx, _) = worst(Kind::Longitudinal);
    let (fy, my) = worst(Kind::Lateral);
    let (fs, ms) = worst(Kind::Spin);
    for (name, got) in [
        ("longitudinal force", fx),
        ("lateral force", fy),
        ("lateral moment", my),
        ("spin force", fs),
        ("spin moment", ms),
    ] {
        assert!(got < 0.02, "{name}: {got}");
    }
}

#[test]
fn fast_law_combined_creepage_meets_the_issue_target() {
    // Issue target: combined creepages within 5 %. Measured: force 4.99 % (a/b = 1,
    // nu = 0.5; at most 3.51 % elsewhere), moment 3.69 % (before this law: 12.5 % and 11.5 %).
    let (fc, mc) = worst(Kind::Combined);
    assert!(fc < 0.05 && mc < 0.05, "{fc} {mc}");
}

#[test]
fn fast_law_off_the_fitted_nodes_measured_errors() {
    // The validation table (data/steady3d_bem_validation.csv: the same creepages, solved like
    // the fitted table, at a/b and nu the fit never saw). Between the nodes (a/b = 0.35,
    // nu = 0.125 and a/b = 0.7, nu = 0.375) the pure translation stays within 0.5 % and the
    // moments within 3.5 %, but the lateral force of pure spin is off by up to 13 % and the
    // combined force by up to 10.4 %: the issue's targets are NOT met between the nodes (three
    // rows in a/b are too few for the spin force's shape). Beyond them, a/b = 2 (a > b, never
    // fitted), translation is within 1.3 % (moment 2.1 %) but every spin load is wrong (force
    // up to 77 %). These are the measured errors, pinned so that any change is noticed.
    let v = read_csv(include_str!("../data/steady3d_bem_validation.csv")).unwrap();
    assert_eq!(v.len(), 4 * 39);
    for x in law_errors(&v).unwrap() {
        let between = x.ab < 1.0;
        let (f, m) = match (x.kind, between) {
            (Kind::Longitudinal | Kind::Lateral, true) => (0.005, 0.005),
            (Kind::Longitudinal | Kind::Lateral, false) => (0.013, 0.021),
            (Kind::Spin, true) => (0.130, 0.011),
            (Kind::Combined, true) => (0.105, 0.035),
            (Kind::Spin, false) => (0.770, 0.066),
            (Kind::Combined, false) => (0.468, 0.165),
        };
        assert!(
            x.force <= f && x.moment <= m,
            "a/b={} nu={} {:?}: {} {}",
            x.ab,
            x.nu,
            x.kind,
            x.force,
            x.moment
        );
    }
}
