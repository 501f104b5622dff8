//! The Cattaneo-Mindlin memory update (`MindlinState::update_with_radius`, which coalesces
//! neighbours at the slip limit eagerly) and the same memory without eager coalescing
//! (`MindlinUncoalesced`) against the frozen copy of the algorithm before its speed-up
//! (`crates/law/src/mindlin/reference.rs`, also the crate's test oracle), side by side: every
//! round times each load path with the three versions, interleaved (each version's fastest of
//! 4 alternating passes per round), and the medians over the rounds are printed (the machine
//! may be loaded; only ratios measured in one run mean anything).
//!
//! Load paths (1 mm glass beads at about 1 N, DEM-sized; one pass replays a precomputed input
//! sequence from a virgin contact, so both versions see the same inputs):
//! - `steady_rolling_creep`: constant load, Kuhn's creep term fed back from the force;
//! - `load_unload_cycles`: the normal force cycles 0.5-1.5 P with a collinear tangential cycle;
//! - `turning_reversals`: a 2-D path that turns and reverses, with a jittering contact radius
//!   (every step grows or shrinks `a`, as in a vibrating packing: the memory stays full);
//! - `dem_trace` (with `CREEP_MINDLIN_TRACE=FILE`): single updates sampled from a creep-dem
//!   packing (records of 59 little-endian f64: `r_star, e_star, g_star, g, nu, mu, c11, a,
//!   du.x, du.y` and the state's `to_array`), each replayed from its recorded state.
//!
//! Every pass also checks that the uncoalesced memory and the reference agree to the tolerances
//! of the crate's `reference_*` tests (a bench of a wrong answer is worthless) and prints the
//! largest relative difference; a larger one aborts. (The coalescing memory's bound against
//! the uncoalesced one is the crate's test `coalescing_keeps_its_bound_against_the_uncoalesced_memory`.)
//! On `dem_trace` the coalescing memory replays single updates from states the uncoalesced
//! memory left (the trace's), so it shows only what coalescing saves within one update, not
//! the shorter memories it keeps in a packing (for those: the engine, `examples/packing`).
//!
//! Run: `cargo bench -p creep-law --bench mindlin [-- ROUNDS]`
//!
//! Instructions: `CREEP_MINDLIN_TRACE=FILE valgrind --tool=callgrind <bench binary> count`
//! replays the trace once with the optimised memory only (no timing, no reference; `count
//! uncoalesced`: with `MindlinUncoalesced`);
//! `update_with_radius`'s inclusive count over the number of records is the instructions per
//! update. With `CREEP_MINDLIN_OUT=FILE` that mode also writes every update's result and
//! state (`q.x, q.y, slip_dissipation, truncation_energy` and `to_array`, little-endian f64),
//! to compare two builds bit for bit.

use std::hint::black_box;
use std::time::Instant;

// The frozen reference refers to `crate::hertz`, `crate::material::PairMaterial`, ...: give it
// those paths here.
pub use creep_law::{LawError, hertz, material, vector};

#[path = "../src/mindlin/reference.rs"]
mod reference;

use creep_law::mindlin::{MAX_PIECES, MindlinMemory, MindlinUncoalesced};
use creep_law::{Material, PairMaterial, Surface, Vec2, kalker};

/// Glass beads of 1 mm radius: a DEM-sized contact.
fn pair() -> PairMaterial {
    let m = Material::glass();
    PairMaterial::new(&m, &m, Surface::Sphere(1e-3), Surface::Sphere(1e-3)).expect("valid pair")
}

/// A small deterministic generator (xorshift64*), so the paths are the same in every run.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> f64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        (self.0.wrapping_mul(0x2545_f491_4f6c_dd1d) >> 11) as f64 / (1u64 << 53) as f64
    }
    /// Uniform in `[-1, 1)`.
    fn sym(&mut self) -> f64 {
        2.0 * self.next() - 1.0
    }
}

/// One update's inputs.
#[derive(Clone, Copy)]
struct Input {
    a: f64,
    du: Vec2,
}

/// A load path: its name and inputs, replayed from a virgin contact.
struct Path {
    name: &'static str,
    inputs: Vec<Input>,
}

fn paths(pair: &PairMaterial) -> Vec<Path> {
    let p0 = 1.0;
    let a0 = hertz::contact_radius(pair, p0);
    let ds = 3.0 * pair.mu * p0 / (16.0 * pair.g_star * a0);
    let n = 4000;
    let mut out = Vec::new();

    // Steady rolling with creep at 0.6 mu P: du_eff = xi dr - F_ss(|Q|/(mu P)) dr along x, the
    // creep computed from the reference state's own force (Kuhn 2011, eq. 1).
    let dr = a0 * 2e-3;
    let xi = kalker::steady_creepage(0.6, pair.mu * p0, pair.g, a0, pair.c11);
    let mut st = reference::MindlinState::new();
    let mut inputs = Vec::with_capacity(n);
    for _ in 0..n {
        let q = st.force().x.abs();
        let f = if q > 0.0 {
            kalker::steady_creepage(
                (q / (pair.mu * p0)).min(1.0),
                pair.mu * p0,
                pair.g,
                a0,
                pair.c11,
            )
        } else {
            0.0
        };
        let du = Vec2::new((xi - f) * dr, 0.0);
        st.update_with_radius(pair, a0, du);
        inputs.push(Input { a: a0, du });
    }
    out.push(Path {
        name: "steady_rolling_creep",
        inputs,
    });

    // Loading / unloading cycles: P from 0.5 to 1.5 P0 and back, Q cycling at 0.8 of the slip
    // displacement, out of phase.
    let inputs = (0..n)
        .map(|i| {
            let t = i as f64 / 200.0 * std::f64::consts::TAU;
            let p = p0 * (1.0 + 0.5 * t.sin());
            let dd = 0.8 * ds * (t.cos() - (t - std::f64::consts::TAU / 200.0).cos());
            Input {
                a: hertz::contact_radius(pair, p),
                du: Vec2::new(dd, 0.0),
            }
        })
        .collect();
    out.push(Path {
        name: "load_unload_cycles",
        inputs,
    });

    // Turning path with reversals and a jittering radius.
    let mut rng = Rng(0x9e37_79b9_7f4a_7c15);
    let mut dir: f64 = 0.0;
    let mut a = a0;
    let inputs = (0..n)
        .map(|i| {
            dir += 0.05 * rng.sym();
            if i % 700 == 350 {
                dir += std::f64::consts::PI;
            }
            a = (a * (1.0 + 2e-4 * rng.sym())).clamp(0.9 * a0, 1.1 * a0);
            let len = ds * 2e-3 * (1.0 + rng.sym());
            Input {
                a,
                du: Vec2::new(dir.cos(), dir.sin()) * len
                    + Vec2::new(rng.sym(), rng.sym()) * (2e-4 * ds),
            }
        })
        .collect();
    out.push(Path {
        name: "turning_reversals",
        inputs,
    });
    out
}

/// Records of a creep-dem trace (see the module doc).
fn trace() -> Option<Vec<(PairMaterial, Input, [f64; 49])>> {
    let file = std::env::var("CREEP_MINDLIN_TRACE").ok()?;
    let bytes = std::fs::read(&file).expect("CREEP_MINDLIN_TRACE: unreadable");
    let vals: Vec<f64> = bytes
        .chunks_exact(8)
        .map(|c| f64::from_le_bytes(c.try_into().expect("8 bytes")))
        .collect();
    let base = pair();
    Some(
        vals.chunks_exact(59)
            .map(|r| {
                let pm = PairMaterial {
                    r_star: r[0],
                    e_star: r[1],
                    g_star: r[2],
                    g: r[3],
                    nu: r[4],
                    mu: r[5],
                    c11: r[6],
                    ..base
                };
                let mut s = [0.0; 49];
                s.copy_from_slice(&r[10..59]);
                (
                    pm,
                    Input {
                        a: r[7],
                        du: Vec2::new(r[8], r[9]),
                    },
                    s,
                )
            })
            .collect(),
    )
}

/// Largest relative differences the bench accepts between the two versions, as the crate's
/// `reference_*` tests (crates/law/src/mindlin/tests.rs, which say why): after a whole path
/// (force over the path's largest force, summed dissipation over the work scale), and after one
/// update from the same state (force over the force or `mu P`; energy over the step's work
/// scale).
const TOL_PATH: f64 = 1e-2;
const TOL_STEP_FORCE: f64 = 1e-4;
const TOL_STEP_ENERGY: f64 = 1e-9;

/// `|x - y| / scale`, with `0 / 0 = 0`.
fn rel(x: f64, y: f64, scale: f64) -> f64 {
    let d = (x - y).abs();
    if d == 0.0 { 0.0 } else { d / scale }
}

/// Seconds per update of `reps` passes over `path` with `MindlinMemory<MAX_PIECES, C>`.
fn time_memory<const C: u32>(pair: &PairMaterial, path: &Path, reps: usize) -> f64 {
    let t = Instant::now();
    for _ in 0..reps {
        let mut new = MindlinMemory::<MAX_PIECES, C>::new();
        for x in &path.inputs {
            black_box(new.update_with_radius(black_box(pair), x.a, x.du));
        }
    }
    t.elapsed().as_secs_f64() / (reps * path.inputs.len()) as f64
}

/// Seconds per update of one pass over `path`: (coalescing, uncoalesced, reference). Checks
/// that the uncoalesced memory's and the reference's forces after every update agree to
/// [`TOL_PATH`] of the largest force on the path, and their summed slip dissipation to
/// [`TOL_PATH`] of the summed `|Q| |du|`; returns the largest relative differences too.
fn time_path(pair: &PairMaterial, path: &Path, reps: usize) -> (f64, f64, f64, f64) {
    let t_coal = time_memory::<{ creep_law::mindlin::COALESCE_URAD }>(pair, path, reps);
    let t_new = time_memory::<0>(pair, path, reps);
    let t = Instant::now();
    for _ in 0..reps {
        let mut old = reference::MindlinState::new();
        for x in &path.inputs {
            black_box(old.update_with_radius(black_box(pair), x.a, x.du));
        }
    }
    let t_old = t.elapsed().as_secs_f64() / (reps * path.inputs.len()) as f64;
    let (mut new, mut old) = (MindlinUncoalesced::new(), reference::MindlinState::new());
    let (mut q_max, mut work, mut d_new, mut d_old) = (0.0f64, 0.0, 0.0, 0.0);
    let mut diffs = Vec::with_capacity(path.inputs.len());
    for x in &path.inputs {
        let sn = new.update_with_radius(pair, x.a, x.du);
        let so = old.update_with_radius(pair, x.a, x.du);
        q_max = q_max.max(so.q.length());
        work += so.q.length() * x.du.length();
        d_new += sn.slip_dissipation;
        d_old += so.slip_dissipation;
        diffs.push((sn.q - so.q).length());
    }
    let dq = diffs.iter().fold(0.0f64, |m, d| m.max(*d)) / q_max;
    let de = rel(d_new, d_old, work);
    assert!(
        dq <= TOL_PATH && de <= TOL_PATH,
        "{}: results differ (force {dq:.1e}, dissipation {de:.1e})",
        path.name
    );
    (t_coal, t_new, t_old, dq.max(de))
}

/// Seconds per update of `reps` replays of the trace's single updates with
/// `MindlinMemory<MAX_PIECES, C>`.
fn time_trace_memory<const C: u32>(recs: &[(PairMaterial, Input, [f64; 49])], reps: usize) -> f64 {
    let states: Vec<MindlinMemory<MAX_PIECES, C>> = recs
        .iter()
        .map(|r| MindlinMemory::from_array(&r.2).expect("valid state"))
        .collect();
    let t = Instant::now();
    for _ in 0..reps {
        for (r, s) in recs.iter().zip(&states) {
            let mut s = *s;
            black_box(s.update_with_radius(black_box(&r.0), r.1.a, r.1.du));
        }
    }
    t.elapsed().as_secs_f64() / (reps * recs.len()) as f64
}

fn time_trace(recs: &[(PairMaterial, Input, [f64; 49])], reps: usize) -> (f64, f64, f64, f64) {
    let t_coal = time_trace_memory::<{ creep_law::mindlin::COALESCE_URAD }>(recs, reps);
    let t_new = time_trace_memory::<0>(recs, reps);
    let news: Vec<MindlinUncoalesced> = recs
        .iter()
        .map(|r| MindlinUncoalesced::from_array(&r.2).expect("valid state"))
        .collect();
    let olds: Vec<reference::MindlinState> = recs
        .iter()
        .map(|r| reference::MindlinState::from_array(&r.2).expect("valid state"))
        .collect();
    let t = Instant::now();
    for _ in 0..reps {
        for (r, s) in recs.iter().zip(&olds) {
            let mut s = *s;
            black_box(s.update_with_radius(black_box(&r.0), r.1.a, r.1.du));
        }
    }
    let t_old = t.elapsed().as_secs_f64() / (reps * recs.len()) as f64;
    let mut worst = 0.0f64;
    for ((r, n), o) in recs.iter().zip(&news).zip(&olds) {
        let (mut n, mut o) = (*n, *o);
        let sn = n.update_with_radius(&r.0, r.1.a, r.1.du);
        let so = o.update_with_radius(&r.0, r.1.a, r.1.du);
        // Scale: the force, or the Coulomb force of the contact (mu P from Hertz' a).
        let mu_p = r.0.mu * 4.0 * r.0.e_star * r.1.a.powi(3) / (3.0 * r.0.r_star);
        let scale = so.q.length().max(mu_p.min(f64::MAX)).max(f64::MIN_POSITIVE);
        let e_scale = scale * r.1.du.length() + so.slip_dissipation;
        let dq = (sn.q - so.q).length() / scale;
        let de = rel(
            sn.slip_dissipation,
            so.slip_dissipation,
            e_scale.max(f64::MIN_POSITIVE),
        );
        assert!(
            dq <= TOL_STEP_FORCE && de <= TOL_STEP_ENERGY,
            "dem_trace: results differ (force {dq:.1e}, energy {de:.1e})"
        );
        worst = worst.max(dq).max(de);
    }
    (t_coal, t_new, t_old, worst)
}

/// A load path's timings over the rounds: name, coalescing, uncoalesced, reference, per-round
/// ratios uncoalesced / coalescing and reference / uncoalesced, the largest difference.
struct Row {
    name: &'static str,
    coal: Vec<f64>,
    new: Vec<f64>,
    old: Vec<f64>,
    gain: Vec<f64>,
    ratio: Vec<f64>,
    diff: f64,
}

impl Row {
    fn push(&mut self, (c, n, o, d): (f64, f64, f64, f64)) {
        self.coal.push(c);
        self.new.push(n);
        self.old.push(o);
        self.gain.push(n / c);
        self.ratio.push(o / n);
        self.diff = self.diff.max(d);
    }
}

/// The trace's single updates from their recorded states with `MindlinMemory<MAX_PIECES, C>`:
/// the sum of the forces, and every update's result and state.
fn count<const C: u32>(recs: &[(PairMaterial, Input, [f64; 49])]) -> (Vec2, Vec<f64>) {
    let mut q = Vec2::ZERO;
    let mut out = Vec::new();
    for r in recs {
        let mut s = MindlinMemory::<MAX_PIECES, C>::from_array(&r.2).expect("valid state");
        let step = black_box(s.update_with_radius(black_box(&r.0), r.1.a, r.1.du));
        q += step.q;
        out.extend([
            step.q.x,
            step.q.y,
            step.slip_dissipation,
            step.truncation_energy,
        ]);
        out.extend(s.to_array());
    }
    (q, out)
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    let n = v.len();
    if n % 2 == 1 {
        v[n / 2]
    } else {
        0.5 * (v[n / 2 - 1] + v[n / 2])
    }
}

fn main() {
    // `-- count`: only the new memory's updates on the DEM trace, once, no timing and no
    // reference (for `valgrind --tool=callgrind`: instructions per update = the total of
    // `update_with_radius` over the number of records).
    if std::env::args().any(|a| a == "count") {
        let recs = trace().expect("count needs CREEP_MINDLIN_TRACE");
        let (q, out) = if std::env::args().any(|a| a == "uncoalesced") {
            count::<0>(&recs)
        } else {
            count::<{ creep_law::mindlin::COALESCE_URAD }>(&recs)
        };
        // `CREEP_MINDLIN_OUT=FILE`: every update's result and state, for comparing two builds.
        if let Ok(file) = std::env::var("CREEP_MINDLIN_OUT") {
            let bytes: Vec<u8> = out.iter().flat_map(|x| x.to_le_bytes()).collect();
            std::fs::write(file, bytes).expect("CREEP_MINDLIN_OUT: unwritable");
        }
        println!("{} updates, sum of forces {q:?}", recs.len());
        return;
    }
    let rounds: usize = std::env::args()
        .skip(1)
        .find_map(|a| a.parse().ok())
        .unwrap_or(7);
    let pair = pair();
    let paths = paths(&pair);
    let trace = trace();
    let row = |name| Row {
        name,
        coal: Vec::new(),
        new: Vec::new(),
        old: Vec::new(),
        gain: Vec::new(),
        ratio: Vec::new(),
        diff: 0.0,
    };
    let mut rows: Vec<Row> = paths.iter().map(|p| row(p.name)).collect();
    if trace.is_some() {
        rows.push(row("dem_trace"));
    }
    // Within a round each version runs ALTERNATIONS times, alternating, and keeps its fastest
    // pass: on a loaded machine the minimum is the pass least disturbed by other jobs.
    const ALTERNATIONS: usize = 4;
    let fastest = |f: &mut dyn FnMut() -> (f64, f64, f64, f64)| {
        let (mut c, mut n, mut o, mut d) = (f64::INFINITY, f64::INFINITY, f64::INFINITY, 0.0f64);
        for _ in 0..ALTERNATIONS {
            let (w, x, y, z) = f();
            c = c.min(w);
            n = n.min(x);
            o = o.min(y);
            d = d.max(z);
        }
        (c, n, o, d)
    };
    for _ in 0..rounds {
        for (i, p) in paths.iter().enumerate() {
            rows[i].push(fastest(&mut || time_path(&pair, p, 6)));
        }
        if let Some(t) = &trace {
            let r = rows.last_mut().expect("a row");
            r.push(fastest(&mut || time_trace(t, 5)));
        }
    }
    println!("{rounds} rounds, interleaved; medians");
    println!(
        "| load path | coalescing ns/update | uncoalesced ns/update | reference ns/update | coalescing speed-up (per-round ratios) | uncoalesced over reference | largest relative difference, uncoalesced vs reference |"
    );
    println!("|---|---|---|---|---|---|---|");
    for r in rows {
        println!(
            "| {} | {:.1} | {:.1} | {:.1} | {:.2} | {:.2} | {:.1e} |",
            r.name,
            median(r.coal) * 1e9,
            median(r.new) * 1e9,
            median(r.old) * 1e9,
            median(r.gain),
            median(r.ratio),
            r.diff
        );
    }
}
