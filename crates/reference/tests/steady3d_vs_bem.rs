//! The elliptic boundary elements against Kalker's table, and creep-law's fast 3-D steady law
//! (`creep_law::steady3d`) against the checked-in boundary-element table
//! `data/steady3d_bem.csv` (module `creep_reference::steady3d`; full error table:
//! `cargo run --release -p creep-reference --example steady3d_errors`).

use creep_law::kalker3d;
use creep_reference::bem::{
    EllipticContact, EllipticSteadySolver, SolverOptions, elliptic_creep_coefficients,
};
use creep_reference::steady3d::{
    Kind, POISSON, RATIOS, law_errors_of, low_spin_table, read_csv, table,
};

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
        let live = creep_reference::steady3d::extrapolate(b, a);
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

/// Largest force and moment errors of the fitted law over the table's rows `a/b = 1, 0.5, 0.2` (the
/// issue's stated cases), per family.
fn worst(kind: Kind) -> (f64, f64) {
    law_errors_of(&table().unwrap(), fitted)
        .unwrap()
        .iter()
        .filter(|e| e.kind == kind && e.ab <= 1.0)
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

/// Asserts every `(a/b, nu, kind)` of `errors` against `limits` (force, moment over `mu P`,
/// `mu P c`; measured values rounded up), and that `limits` covers every row of `errors`.
fn check_pinned(errors: &[creep_reference::steady3d::LawError3d], limits: &[(f64, f64, [f64; 8])]) {
    for x in errors {
        let (_, _, l) = limits
            .iter()
            .find(|(ab, nu, _)| *ab == x.ab && *nu == x.nu)
            .unwrap_or_else(|| panic!("no limits for a/b={} nu={}", x.ab, x.nu));
        let k = match x.kind {
            Kind::Longitudinal => 0,
            Kind::Lateral => 1,
            Kind::Spin => 2,
            Kind::Combined => 3,
        };
        let (f, m) = (l[2 * k], l[2 * k + 1]);
        assert!(
            x.force <= f && x.moment <= m,
            "a/b={} nu={} {:?}: {} {} (limits {f} {m})",
            x.ab,
            x.nu,
            x.kind,
            x.force,
            x.moment
        );
    }
}

#[test]
fn fast_law_a_greater_than_b_rows_measured_errors() {
    // The rows a/b = 2 and 5 (a > b: wheels, whose contact is long along the rolling
    // direction). The law's form, fitted there like the other rows, does NOT meet the issue's
    // targets with spin: the translation is within 0.5 %, but the lateral force of pure spin
    // is off by up to 2.8 % at a/b = 2 and 8.9 % at a/b = 5, the combined force by up to
    // 9.1 % (a/b = 2) and 24 % (a/b = 5), the moments by up to 15 %. Before the refit with the
    // low-spin points (a/b = 2, 5 at nu = 0.5): spin 12.0 / 11.3 %, combined 34.9 / 31.3 %;
    // before these rows (a/b > 1 used the constants of b/a) the spin force was off by up to
    // 84 % and the combined force by up to 93 %.
    // Pinned (measured, rounded up; per family: force, moment for long., lat., spin, combined).
    // The fitted law (`without_table`): where the boundary-element table covers a case
    // (`Steady3d::coverage`), the error map's tests grade it.
    let e = law_errors_of(&table().unwrap(), fitted).unwrap();
    let rows: Vec<_> = e.into_iter().filter(|x| x.ab > 1.0).collect();
    assert_eq!(rows.len(), 2 * 3 * 4);
    check_pinned(&rows, ROWS_A_GT_B_LIMITS);
}

#[test]
fn fast_law_off_the_fitted_nodes_measured_errors() {
    // The validation table (data/steady3d_bem_validation.csv: the same creepages, solved like
    // the fitted table, at a/b and nu the fit never saw: between the rows and between the
    // columns). Pure translation stays within 0.8 %; between
    // the rows a/b = 0.2, 0.5, 1 the lateral force of pure spin within 4.7 % (13 % before the
    // row blend) and combined creepage within 4.7 % (force) / 3.7 % (moment): the issue's
    // 2 % (pure) is NOT met there, its 5 % (combined) is. Between a/b = 1 and 5 (a/b = 1.4,
    // 3) the spin loads are off by up to 19 % (force; 24 % before the refit of the a > b
    // rows with the low-spin points) and the combined force by up to 18 % (25 %; 46-80 %
    // before the rows a/b = 2, 5).
    // Between rows the law evaluates one translation on the two rows' blended spin terms
    // (tabulated per contact in phi_n) with a pure-spin correction (issue #17's cost): the
    // translation is the two-row blend's (the previous law's), spin and moments within the
    // table's interpolation of it (here equal or better by up to 0.05 points), and the
    // combined force moved from 5.39, 4.91, 3.30, 3.81, 14.46, 22.39 % to 4.64, 4.15, 2.73,
    // 3.66, 14.84, 17.68 % (a/b = 0.35, 0.7, 0.27, 0.85, 1.4, 3): better everywhere but
    // a/b = 1.4 (+0.38 points, where the law is 14 % off anyway).
    // Pinned (measured, rounded up), so that a regression fails.
    let v = read_csv(include_str!("../data/steady3d_bem_validation.csv")).unwrap();
    assert_eq!(v.len(), 6 * 39);
    check_pinned(&law_errors_of(&v, fitted).unwrap(), VALIDATION_LIMITS);
}

/// The fitted law at `(a/b, nu)`, without the boundary-element table.
fn fitted(ab: f64, nu: f64) -> Result<creep_law::steady3d::Steady3d, creep_law::LawError> {
    creep_law::steady3d::Steady3d::new(ab, nu).map(|l| l.without_table())
}

/// Limits of [`fast_law_a_greater_than_b_rows_measured_errors`]: `(a/b, nu, [long. F, long. M,
/// lat. F, lat. M, spin F, spin M, comb. F, comb. M])` over `mu P` (`mu P c`), the measured
/// errors rounded up (`steady3d_errors`).
const ROWS_A_GT_B_LIMITS: &[(f64, f64, [f64; 8])] = &[
    (
        2.0,
        0.0,
        [0.004, 0.001, 0.004, 0.004, 0.018, 0.015, 0.058, 0.059],
    ),
    (
        2.0,
        0.25,
        [0.004, 0.001, 0.004, 0.003, 0.023, 0.020, 0.073, 0.073],
    ),
    (
        2.0,
        0.5,
        [0.004, 0.001, 0.005, 0.006, 0.029, 0.024, 0.092, 0.082],
    ),
    (
        5.0,
        0.0,
        [0.005, 0.001, 0.005, 0.005, 0.072, 0.034, 0.196, 0.138],
    ),
    (
        5.0,
        0.25,
        [0.004, 0.001, 0.004, 0.004, 0.089, 0.042, 0.244, 0.152],
    ),
    (
        5.0,
        0.5,
        [0.004, 0.001, 0.005, 0.004, 0.051, 0.052, 0.185, 0.147],
    ),
];

/// Limits of [`fast_law_off_the_fitted_nodes_measured_errors`], as [`ROWS_A_GT_B_LIMITS`]
/// (`steady3d_errors -- --table crates/reference/data/steady3d_bem_validation.csv`).
const VALIDATION_LIMITS: &[(f64, f64, [f64; 8])] = &[
    (
        0.35,
        0.125,
        [0.005, 0.001, 0.005, 0.005, 0.047, 0.009, 0.047, 0.020],
    ),
    (
        0.7,
        0.375,
        [0.004, 0.001, 0.003, 0.005, 0.045, 0.012, 0.042, 0.038],
    ),
    (
        0.27,
        0.375,
        [0.007, 0.001, 0.003, 0.007, 0.034, 0.014, 0.028, 0.017],
    ),
    (
        0.85,
        0.125,
        [0.006, 0.001, 0.008, 0.005, 0.026, 0.017, 0.037, 0.035],
    ),
    (
        1.4,
        0.125,
        [0.005, 0.001, 0.005, 0.006, 0.091, 0.020, 0.149, 0.048],
    ),
    (
        3.0,
        0.375,
        [0.005, 0.001, 0.006, 0.010, 0.196, 0.094, 0.177, 0.125],
    ),
];

#[test]
fn low_spin_points_follow_kalkers_slope_and_the_law_follows_them() {
    // data/steady3d_bem_lowspin.csv: pure spin phi_n = 0.025, 0.05, 0.075 for a/b = 2, 5 (below
    // the table's 0.1; steady3d_fit uses them). The boundary elements' lateral force there is
    // Kalker's linear C23 phi_n to within 1.5 % (measured at most 1.45 %, where the force
    // starts to saturate). The fast law against them (measured, rounded up): a/b = 2 within
    // 1.27 % of mu P (force) and 0.69 % of mu P c (moment); a/b = 5 within 3.1 % / 3.6 %
    // (before the refit with these points: 18.2 % at a/b = 5, nu = 0.5, a bump below the
    // table).
    let pts = low_spin_table().unwrap();
    assert_eq!(pts.len(), 2 * 3 * 3);
    for p in &pts {
        let c23 = kalker3d::coefficients(p.ab, p.nu).unwrap().c23;
        let r = p.load[1] / (c23 * p.creepage[2]);
        assert!((r - 1.0).abs() < 0.015, "{p:?}: {r}");
    }
    // The fitted law (`without_table`): where the table or its extrapolation in nu covers a
    // point (a/b = 2), the error map's tests grade it.
    for x in law_errors_of(&pts, fitted).unwrap() {
        let (f, m) = match (x.ab, x.nu) {
            (2.0, _) => (0.013, 0.007),
            (5.0, nu) if nu < 0.5 => (0.031, 0.028),
            _ => (0.031, 0.036),
        };
        assert!(x.force <= f && x.moment <= m, "{x:?}");
    }
}
