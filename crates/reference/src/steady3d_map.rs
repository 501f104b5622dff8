//! The error map of creep-law's fast 3-D steady law (`creep_law::steady3d::Steady3d`) over the
//! whole normalised space of steady rolling: longitudinal, lateral and spin creepage each from
//! full slip in one sign to full slip in the other, every sign combination, Poisson ratios
//! [`MAP_POISSON`] and axis ratios [`MAP_RATIOS`] from `a/b = 0.2` to `5`.
//!
//! # The boundary-element table
//!
//! Each `(a/b, nu)` is solved by the elliptic boundary elements ([`crate::bem::elliptic`]) on two
//! grids, `N/2` and `N` elements across the shorter axis ([`crate::steady3d::default_grid`]:
//! `N = 32` for `min(a/b, b/a) >= 0.5`, `20` below), and extrapolated `2 f(N) - f(N/2)` (the
//! grid error of the steady boundary elements is `O(h)`). Only the quarter `xi_n >= 0`,
//! `eta_n >= 0` is solved: the exact theory (quasi-identical bodies, a contact symmetric about
//! the rolling direction) has the exact symmetries
//!
//! * oddness: `(xi, eta, phi) -> -(xi, eta, phi)` negates `(Fx, Fy, Mz)`;
//! * reflection `y -> -y`: `(xi, eta, phi) -> (xi, -eta, -phi)` gives `(Fx, -Fy, -Mz)`;
//!
//! and their composition `(xi, eta, phi) -> (-xi, eta, phi)` gives `(-Fx, Fy, Mz)`; so the
//! table's quarter determines every sign combination ([`expand`]), and the law is graded on all
//! of them (it need not share the symmetries: it is evaluated at every signed point).
//!
//! The creepage grid ([`MAP_XI`] for both `xi_n` and `eta_n`, [`MAP_PHI`] for `phi_n`) reaches
//! full slip of translation (`|xi_n| = 2`, about three times the onset of full slip,
//! `3 (4 - 3 nu)/16 / ...`) and a spin (`|phi_n| = 4`) where the spin moment is within a few per
//! cent of its full-slip value.
//!
//! # Fit and validation
//!
//! [`Set::Validation`] marks the points at axis ratios off the law's node rows
//! ([`FIT_RATIOS`]) or at `nu = 0.3` (off its columns); the rest is [`Set::Fit`]. A fit of the
//! law may use the fit set only; the test `steady3d_map` bounds the law's worst error on the
//! validation set.
//!
//! Written by `cargo run --release -p creep-reference --example steady3d_map -- bem`
//! to `data/steady3d_map.csv`, read by [`map_table`].

use crate::bem::{EllipticContact, EllipticSteadySolver, SolverOptions};
use crate::error::RefError;
use crate::steady3d::{default_grid, extrapolate, table_number, table_rows};

/// Axis ratios `a/b` of the map.
pub const MAP_RATIOS: [f64; 9] = [0.2, 0.35, 0.5, 0.7, 1.0, 1.4, 2.0, 3.0, 5.0];
/// The law's node rows (the map's fit set; the other ratios are validation).
pub const FIT_RATIOS: [f64; 5] = [0.2, 0.5, 1.0, 2.0, 5.0];
/// Poisson ratios of the map (`0.3` is validation).
pub const MAP_POISSON: [f64; 4] = [0.0, 0.25, 0.3, 0.5];
/// Non-negative normalised longitudinal and lateral creepages solved (the signs by symmetry).
pub const MAP_XI: [f64; 5] = [0.0, 0.15, 0.4, 0.8, 2.0];
/// Normalised spins solved (both signs).
pub const MAP_PHI: [f64; 9] = [-4.0, -1.5, -0.7, -0.25, 0.0, 0.25, 0.7, 1.5, 4.0];

/// Which set a point belongs to (module documentation).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Set {
    /// May be used to fit the law.
    Fit,
    /// Never used for fitting.
    Validation,
}

impl Set {
    /// The set of `(a/b, nu)`.
    pub fn of(ab: f64, nu: f64) -> Set {
        if nu == 0.3 || !FIT_RATIOS.contains(&ab) {
            Set::Validation
        } else {
            Set::Fit
        }
    }
}

/// One point of the map: creepages and the extrapolated loads (this crate's signs; forces over
/// `mu P`, moment over `mu P c`, `c = sqrt(a b)`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MapPoint {
    /// Axis ratio `a/b`.
    pub ab: f64,
    /// Poisson ratio.
    pub nu: f64,
    /// Normalised creepages `(xi_n, eta_n, phi_n)`.
    pub creepage: [f64; 3],
    /// `(Fx, Fy, Mz)` extrapolated `2 f(N) - f(N/2)`.
    pub load: [f64; 3],
    /// The same on the grid `N` alone.
    pub fine: [f64; 3],
}

/// Solves the map's quarter for one `(a/b, nu)` on grids `grid/2` and `grid` (warm-started
/// along `phi_n` on each `(xi_n, eta_n)`; the zero creepage is included, with zero loads).
pub fn solve_map_case(ab: f64, nu: f64, grid: usize) -> Result<Vec<MapPoint>, RefError> {
    let contact = EllipticContact::normalised(nu, ab)?;
    let mut coarse = EllipticSteadySolver::new(contact, SolverOptions::with_grid(grid / 2))?;
    let mut fine = EllipticSteadySolver::new(contact, SolverOptions::with_grid(grid))?;
    let mut out = Vec::new();
    for &xi in &MAP_XI {
        for &eta in &MAP_XI {
            coarse.reset();
            fine.reset();
            for &phi in &MAP_PHI {
                let (p, q) = if xi == 0.0 && eta == 0.0 && phi == 0.0 {
                    ((0.0, 0.0, 0.0), (0.0, 0.0, 0.0))
                } else {
                    (
                        coarse.solve_normalised(xi, eta, phi)?,
                        fine.solve_normalised(xi, eta, phi)?,
                    )
                };
                out.push(MapPoint {
                    ab,
                    nu,
                    creepage: [xi, eta, phi],
                    load: extrapolate(q, p),
                    fine: [q.0, q.1, q.2],
                });
            }
        }
    }
    Ok(out)
}

/// Solves the whole map ([`MAP_RATIOS`] x [`MAP_POISSON`]), calling `progress` after each
/// `(a/b, nu)` with its points.
pub fn solve_map(mut progress: impl FnMut(&[MapPoint])) -> Result<Vec<MapPoint>, RefError> {
    let mut all = Vec::new();
    for &ab in &MAP_RATIOS {
        for &nu in &MAP_POISSON {
            let v = solve_map_case(ab, nu, default_grid(ab))?;
            progress(&v);
            all.extend(v);
        }
    }
    Ok(all)
}

/// Every sign combination of a quarter point (module documentation): the point, and where
/// `eta_n != 0` its reflection `(xi, -eta, -phi)`, and where `xi_n != 0` their mirrors in
/// `xi_n` (with `eta_n = 0` the reflection is a point of the quarter itself, the spins being
/// tabulated with both signs: each signed point appears once).
pub fn expand(p: &MapPoint) -> Vec<MapPoint> {
    let [x, y, z] = p.creepage;
    let [fx, fy, mz] = p.load;
    let [gx, gy, gz] = p.fine;
    let mut v = vec![*p];
    // (xi, -eta, -phi) -> (Fx, -Fy, -Mz).
    if y != 0.0 {
        v.push(MapPoint {
            creepage: [x, 0.0 - y, 0.0 - z],
            load: [fx, 0.0 - fy, 0.0 - mz],
            fine: [gx, 0.0 - gy, 0.0 - gz],
            ..*p
        });
    }
    if x != 0.0 {
        // (-xi, eta, phi) -> (-Fx, Fy, Mz) and (-xi, -eta, -phi) -> -(Fx, Fy, Mz).
        v.push(MapPoint {
            creepage: [0.0 - x, y, z],
            load: [0.0 - fx, fy, mz],
            fine: [0.0 - gx, gy, gz],
            ..*p
        });
        if y != 0.0 {
            v.push(MapPoint {
                creepage: [0.0 - x, 0.0 - y, 0.0 - z],
                load: [0.0 - fx, 0.0 - fy, 0.0 - mz],
                fine: [0.0 - gx, 0.0 - gy, 0.0 - gz],
                ..*p
            });
        }
    }
    v
}

/// CSV header of the map table.
pub const MAP_HEADER: &str = "ab,nu,xi_n,eta_n,phi_n,fx_n,fy_n,mz_n,fx_fine,fy_fine,mz_fine";

/// One CSV line of the map table (no newline).
pub fn map_csv_line(p: &MapPoint) -> String {
    format!(
        "{},{},{},{},{},{:.6},{:.6},{:.6},{:.6},{:.6},{:.6}",
        p.ab,
        p.nu,
        p.creepage[0],
        p.creepage[1],
        p.creepage[2],
        p.load[0],
        p.load[1],
        p.load[2],
        p.fine[0],
        p.fine[1],
        p.fine[2]
    )
}

/// Parses a map table (lines starting with `#` and the header skipped).
pub fn read_map_csv(text: &str) -> Result<Vec<MapPoint>, RefError> {
    let mut v = Vec::new();
    for f in table_rows(text, "steady3d map columns", 11)? {
        let n = |i: usize| table_number(f[i], "steady3d map table");
        v.push(MapPoint {
            ab: n(0)?,
            nu: n(1)?,
            creepage: [n(2)?, n(3)?, n(4)?],
            load: [n(5)?, n(6)?, n(7)?],
            fine: [n(8)?, n(9)?, n(10)?],
        });
    }
    Ok(v)
}

/// The checked-in map table (`data/steady3d_map.csv`, the quarter `xi_n, eta_n >= 0`).
pub fn map_table() -> Result<Vec<MapPoint>, RefError> {
    read_map_csv(include_str!("../data/steady3d_map.csv"))
}

/// The error of the law at one signed point: `|dFx|, |dFy|` over `mu P`, `|dMz|` over `mu P c`
/// and over `mu P a` (`a = c sqrt(a/b)`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MapError {
    /// The point (signed creepages, reference loads).
    pub point: MapPoint,
    /// The law's loads.
    pub law: [f64; 3],
    /// `|Fx_law - Fx_bem|` over `mu P`.
    pub fx: f64,
    /// `|Fy_law - Fy_bem|` over `mu P`.
    pub fy: f64,
    /// `|Mz_law - Mz_bem|` over `mu P c`.
    pub mz_c: f64,
    /// `|Mz_law - Mz_bem|` over `mu P a`.
    pub mz_a: f64,
}

/// Grades `law(a/b, nu)` (built once per `(a/b, nu)`, evaluated by `eval`) on every signed
/// point of the quarter table `points`.
pub fn grade<L>(
    points: &[MapPoint],
    make: impl Fn(f64, f64) -> Result<L, RefError>,
    eval: impl Fn(&L, [f64; 3]) -> [f64; 3],
) -> Result<Vec<MapError>, RefError> {
    let mut out = Vec::new();
    let mut built: Option<(f64, f64, L)> = None;
    for q in points {
        if !matches!(&built, Some((ab, nu, _)) if *ab == q.ab && *nu == q.nu) {
            built = Some((q.ab, q.nu, make(q.ab, q.nu)?));
        }
        let law = &built.as_ref().expect("built above").2;
        for p in expand(q) {
            let l = eval(law, p.creepage);
            let dm = (l[2] - p.load[2]).abs();
            out.push(MapError {
                point: p,
                law: l,
                fx: (l[0] - p.load[0]).abs(),
                fy: (l[1] - p.load[1]).abs(),
                mz_c: dm,
                mz_a: dm / p.ab.sqrt(),
            });
        }
    }
    Ok(out)
}

/// Grades creep-law's `Steady3d::new` (module documentation).
pub fn grade_steady3d(points: &[MapPoint]) -> Result<Vec<MapError>, RefError> {
    grade(
        points,
        |ab, nu| {
            creep_law::steady3d::Steady3d::new(ab, nu).map_err(|_| RefError::InvalidParameter {
                name: "a/b or nu",
                value: ab,
                expected: "in Kalker's table range",
            })
        },
        |law, c| {
            let l = law.loads(c[0], c[1], c[2]);
            [l.fx, l.fy, l.mz]
        },
    )
}

/// The worst errors of a set of graded points: `(max |dFx|, max |dFy|, max |dMz|/(mu P c),
/// max |dMz|/(mu P a))`.
pub fn worst<'a>(errors: impl IntoIterator<Item = &'a MapError>) -> [f64; 4] {
    errors.into_iter().fold([0.0; 4], |w, e| {
        [
            w[0].max(e.fx),
            w[1].max(e.fy),
            w[2].max(e.mz_c),
            w[3].max(e.mz_a),
        ]
    })
}

/// The loads of full slip for the creepage direction `(xi_n, eta_n, phi_n)` (not all zero) on
/// the contact `a/b = ab` (normalised: `c = sqrt(a b) = 1`, `mu P = 1`): the traction `mu p`
/// along the rigid slip `w = (xi - phi y, eta + phi x)` everywhere, `F = integral mu p w/|w| dA`,
/// `Mz = integral mu p (x w_y - y w_x)/|w| dA`, with Hertz's pressure `p = 3 P/(2 pi a b)
/// sqrt(1 - x^2/a^2 - y^2/b^2)` (Johnson 1985, eq. 4.37). It is the limit of the exact theory
/// as the creepage grows along a fixed direction (the elastic part of the slip, `du/dx`, stays
/// bounded while `w` grows). Midpoint quadrature on `x = a sin(al) cos(th)`, `y = b sin(al)
/// sin(th)`, `n` points in `al` and `4 n` in `th` (`dA = a b sin(al) cos(al) dal dth`; the
/// pressure's square root is `cos(al)`): the integrand is bounded, discontinuous only at the
/// pole of the slip field; `n = 200` is within 1e-4.
pub fn full_slip_loads(ab: f64, dir: [f64; 3], n: usize) -> [f64; 3] {
    creep_law::steady3d::full_slip::rigid_slip_loads(ab, dir, n)
}

/// `(a/b, nu)` of the off-grid validation table ([`solve_validation`]): off the law's node rows
/// and columns and off the map's ratios.
pub const VALIDATION_CASES: [(f64, f64); 6] = [
    (0.27, 0.3),
    (0.6, 0.1),
    (0.85, 0.4),
    (1.2, 0.3),
    (2.5, 0.15),
    (4.0, 0.45),
];
/// Points per case of the off-grid validation table.
pub const VALIDATION_POINTS: usize = 30;

/// The creepages of the off-grid validation table for case `k` of [`VALIDATION_CASES`]: each
/// of `xi_n`, `eta_n` drawn as `sign * 2 u^2` and `phi_n` as `sign * 4 u^2` (`u` uniform in
/// `[0, 1]`, a fixed linear congruential sequence; the square puts more points at small
/// creepage, where the loads change fastest), with every sign combination equally likely.
pub fn validation_creepages(k: usize) -> Vec<[f64; 3]> {
    // Knuth's MMIX LCG, the top 53 bits.
    let mut state: u64 = 0x9E37_79B9_7F4A_7C15 ^ (k as u64 + 1).wrapping_mul(0xD1B5_4A32_D192_ED03);
    let mut u = move || {
        state = state
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        (state >> 11) as f64 / (1u64 << 53) as f64
    };
    (0..VALIDATION_POINTS)
        .map(|_| {
            let mut c = [0.0; 3];
            for (i, v) in c.iter_mut().enumerate() {
                let m = u();
                let s = if u() < 0.5 { -1.0 } else { 1.0 };
                let scale = if i == 2 { 4.0 } else { 2.0 };
                // Rounded to 4 decimals so the CSV reproduces the creepage exactly.
                *v = s * (scale * m * m * 1e4).round() / 1e4;
            }
            c
        })
        .collect()
}

/// Solves the off-grid validation table for case `k` of [`VALIDATION_CASES`] (grids as
/// [`solve_map_case`], each point from zero traction). These points are signed as drawn: they
/// are graded as they are, not expanded by symmetry.
pub fn solve_validation(k: usize) -> Result<Vec<MapPoint>, RefError> {
    let (ab, nu) = VALIDATION_CASES[k];
    let grid = default_grid(ab);
    let contact = EllipticContact::normalised(nu, ab)?;
    let mut coarse = EllipticSteadySolver::new(contact, SolverOptions::with_grid(grid / 2))?;
    let mut fine = EllipticSteadySolver::new(contact, SolverOptions::with_grid(grid))?;
    let mut out = Vec::new();
    for c in validation_creepages(k) {
        coarse.reset();
        fine.reset();
        let p = coarse.solve_normalised(c[0], c[1], c[2])?;
        let q = fine.solve_normalised(c[0], c[1], c[2])?;
        out.push(MapPoint {
            ab,
            nu,
            creepage: c,
            load: extrapolate(q, p),
            fine: [q.0, q.1, q.2],
        });
    }
    Ok(out)
}

/// The checked-in off-grid validation table (`data/steady3d_map_validation.csv`).
pub fn validation_table() -> Result<Vec<MapPoint>, RefError> {
    read_map_csv(include_str!("../data/steady3d_map_validation.csv"))
}

/// Grades `Steady3d::new` on points taken as they are (no expansion by symmetry).
pub fn grade_steady3d_as_is(points: &[MapPoint]) -> Result<Vec<MapError>, RefError> {
    let mut out = Vec::new();
    for p in points {
        let law = creep_law::steady3d::Steady3d::new(p.ab, p.nu).map_err(|_| {
            RefError::InvalidParameter {
                name: "a/b or nu",
                value: p.ab,
                expected: "in Kalker's table range",
            }
        })?;
        let l = law.loads(p.creepage[0], p.creepage[1], p.creepage[2]);
        let dm = (l.mz - p.load[2]).abs();
        out.push(MapError {
            point: *p,
            law: [l.fx, l.fy, l.mz],
            fx: (l.fx - p.load[0]).abs(),
            fy: (l.fy - p.load[1]).abs(),
            mz_c: dm,
            mz_a: dm / p.ab.sqrt(),
        });
    }
    Ok(out)
}

/// The bounds the law is held to by the source that answers a contact
/// ([`creep_law::steady3d::Steady3d::coverage`]): `[force over mu P, moment over mu P a]`, or
/// `None` for the fitted law (no bound: docs/CREEP3D.md lists its errors).
///
/// * At a computed node and between two computed `nu` of one `a/b`: the target's 2 % and 3 %
///   (measured: Fy 1.78 % at `(0, -0.15, 0.25)`, `a/b = 5`, `nu = 0`, where the spin's lateral
///   force of the elongated contact bends fastest at small spin; Mz 2.09 % at `a/b = 0.2`).
/// * Between two computed `a/b` (Lagrange's cubic in `ln(a/b)`, the moment in units of each
///   row's full-slip spin moment), the target's 2 % and 3 %: measured on the map Fx 1.33 %, Fy
///   1.46 %, Mz 1.56 % at `a/b = 0.7`; on the off-grid cases Fy 1.57 % and Mz 1.34 % at `a/b =
///   0.85`, `nu = 0.4`, and at `a/b = 0.27`, `nu = 0.3` (between the rows `0.2` and `0.3`) Fx
///   0.86 %, Mz 1.28 % of `mu P a`.
/// * A `nu` outside the computed ones (the nearest computed `nu`, creepages scaled by Kalker's
///   coefficients), 9 % and 9 % (the measured worst in docs/CREEP3D.md, "Beyond the computed
///   nu").
pub fn coverage_bounds(coverage: creep_law::steady3d::Coverage) -> Option<[f64; 2]> {
    use creep_law::steady3d::Coverage;
    match coverage {
        Coverage::Table => Some([0.02, 0.03]),
        Coverage::BetweenRatios => Some([0.02, 0.03]),
        Coverage::ExtrapolatedNu => Some([0.09, 0.09]),
        Coverage::Fitted => None,
    }
}
