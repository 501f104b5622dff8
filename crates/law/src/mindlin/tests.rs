//! Tests of the Cattaneo-Mindlin algorithm against the closed forms of Mindlin (1949) and
//! Mindlin & Deresiewicz (1953) (as written in Johnson 1985, *Contact Mechanics*, §7.2).

use super::*;

const P: f64 = 100.0;

fn pair() -> PairMaterial {
    crate::material::steel_ball_on_plane()
}

/// Mindlin's slip displacement `delta_s = 3 mu P / (16 G* a)` \[m\].
fn delta_s(pair: &PairMaterial, p: f64) -> f64 {
    3.0 * pair.mu * p / (16.0 * pair.g_star * hertz::contact_radius(pair, p))
}

/// Mindlin (1949) virgin loading: `Q = mu P [1 - (1 - delta/delta_s)^(3/2)]`, `mu P` beyond.
fn q_load(mu_p: f64, ds: f64, d: f64) -> f64 {
    let t = (1.0 - d / ds).max(0.0);
    mu_p * (1.0 - t * t.sqrt())
}

/// Mindlin & Deresiewicz (1953) unloading from the turning point (d0, q0):
/// `Q = q0 - 2 Q_load((d0 - d)/2)`; reloading from (d0, q0) with `s = +1`: `q0 + 2 Q_load((d - d0)/2)`.
fn q_branch(mu_p: f64, ds: f64, d0: f64, q0: f64, d: f64) -> f64 {
    let s = (d - d0).signum();
    q0 + s * 2.0 * q_load(mu_p, ds, (d - d0).abs() / 2.0)
}

/// Drives a memory of capacity `N` collinearly along `dir` through `targets` in `steps` equal
/// steps per leg and checks every step against the closed-form curve.
fn check_path<const N: usize>(steps: usize, dir: Vec2) -> f64 {
    let pair = pair();
    let mu_p = pair.mu * P;
    let ds = delta_s(&pair, P);
    let mut st = MindlinMemory::<N>::new();
    st.update(&pair, P, Vec2::ZERO);
    let (d1, d2, d3) = (0.8 * ds, -0.6 * ds, 0.95 * ds);
    let q1 = q_load(mu_p, ds, d1);
    let q2 = q_branch(mu_p, ds, d1, q1, d2);
    let mut worst: f64 = 0.0;
    let mut d = 0.0;
    for (from, to) in [(0.0, d1), (d1, d2), (d2, d3)] {
        for i in 1..=steps {
            let next = from + (to - from) * i as f64 / steps as f64;
            let q = st.update(&pair, P, dir * (next - d)).q;
            d = next;
            let expect = if to == d1 {
                q_load(mu_p, ds, d)
            } else if to == d2 {
                q_branch(mu_p, ds, d1, q1, d)
            } else if d <= d1 {
                q_branch(mu_p, ds, d2, q2, d)
            } else {
                // Past the old turning point the memory is erased: back on the virgin curve.
                q_load(mu_p, ds, d)
            };
            let along = q.dot(dir);
            let across = (q - dir * along).length();
            worst = worst.max((along - expect).abs() / mu_p).max(across / mu_p);
        }
    }
    worst
}

#[test]
fn reproduces_mindlin_deresiewicz_with_1000_steps() {
    let err = check_path::<MAX_PIECES>(1000, Vec2::new(1.0, 0.0));
    println!("Mindlin-Deresiewicz, 1000 steps/branch: max |Q - closed form| = {err:.2e} mu P");
    assert!(err < 1e-12, "max error {err:e} of mu P");
    let err = check_path::<MAX_PIECES>(1000, Vec2::new(0.6, -0.8));
    println!("Mindlin-Deresiewicz, 1000 steps/branch, oblique axis: {err:.2e} mu P");
    assert!(err < 1e-12, "max error {err:e} of mu P");
}

#[test]
fn reproduces_mindlin_deresiewicz_with_10_steps() {
    let err = check_path::<MAX_PIECES>(10, Vec2::new(1.0, 0.0));
    println!("Mindlin-Deresiewicz, 10 steps/branch: max |Q - closed form| = {err:.2e} mu P");
    assert!(err < 1e-12, "max error {err:e} of mu P");
    let err = check_path::<MAX_PIECES>(10, Vec2::new(-0.28, 0.96));
    println!("Mindlin-Deresiewicz, 10 steps/branch, oblique axis: {err:.2e} mu P");
    assert!(err < 1e-12, "max error {err:e} of mu P");
}

#[test]
fn full_sliding_at_the_coulomb_limit() {
    let pair = pair();
    let ds = delta_s(&pair, P);
    let mut st = MindlinState::new();
    st.update(&pair, P, Vec2::ZERO);
    let q = st.update(&pair, P, Vec2::new(3.0 * ds, 0.0)).q;
    assert!((q.length() / (pair.mu * P) - 1.0).abs() < 1e-12, "{q:?}");
    // Reversing by 2 delta_s exactly reaches -mu P (Masing: twice the loading curve).
    let q = st.update(&pair, P, Vec2::new(-2.0 * ds, 0.0)).q;
    assert!((q.x / (pair.mu * P) + 1.0).abs() < 1e-12, "{q:?}");
}

#[test]
fn no_slip_limit_is_linear_with_8_g_star_a() {
    for mu in [f64::INFINITY, 1e9] {
        let pair = pair().with_friction(mu).unwrap();
        let a = hertz::contact_radius(&pair, P);
        let mut st = MindlinState::new();
        st.update(&pair, P, Vec2::ZERO);
        let mut u = Vec2::ZERO;
        let mut u_max: f64 = 0.0;
        for i in 0..200 {
            let du = Vec2::new((i as f64 * 0.37).sin(), (i as f64 * 0.11).cos()) * 1e-6;
            u += du;
            u_max = u_max.max(u.length());
            let step = st.update(&pair, P, du);
            let expect = u * (8.0 * pair.g_star * a);
            // mu = 1e9: the springs at the very edge (where the limit -> 0) still slip a little.
            let tol = if mu.is_infinite() { 1e-12 } else { 1e-6 };
            // Error relative to the largest force seen (the path crosses zero).
            let err = (step.q - expect).length() / (8.0 * pair.g_star * a * u_max);
            assert!(err <= tol, "mu={mu} step {i}: relative error {err:e}");
            assert!(step.q.is_finite());
            if mu.is_infinite() {
                assert_eq!(step.slip_dissipation, 0.0);
            }
        }
        let e = st.elastic_energy(&pair);
        let expect = 0.5 * 8.0 * pair.g_star * a * u.length_squared();
        let scale = 0.5 * 8.0 * pair.g_star * a * u_max * u_max;
        assert!(
            (e - expect).abs() < 1e-6 * scale,
            "mu={mu}: {e:e} vs {expect:e}"
        );
    }
}

#[test]
fn proportional_loading_below_mu_is_slip_free() {
    // Mindlin & Deresiewicz (1953): increasing P and Q together with dQ/dP = lambda < mu gives no
    // slip; the incremental stiffness is 8 G* a(P), so with a = A P^(1/3),
    // delta_t(P) = integral lambda dP / (8 G* A P^(1/3)) = 3 lambda P^(2/3) / (16 G* A).
    let pair = pair();
    let lambda = 0.2;
    let big_a = hertz::contact_radius(&pair, 1.0);
    let delta_t = |p: f64| 3.0 * lambda * p.powf(2.0 / 3.0) / (16.0 * pair.g_star * big_a);
    for (steps, tol) in [(10, 1e-12), (1000, 1e-12)] {
        let mut st = MindlinState::new();
        let mut prev = 0.0;
        let mut worst: f64 = 0.0;
        let mut dissipated = 0.0;
        for i in 1..=steps {
            let p = P * i as f64 / steps as f64;
            let d = delta_t(p);
            let step = st.update(&pair, p, Vec2::new(d - prev, 0.0));
            prev = d;
            dissipated += step.slip_dissipation;
            if i > steps / 10 {
                worst = worst.max((step.q.x / (lambda * p) - 1.0).abs());
            }
        }
        println!("proportional loading Q/P = 0.2, {steps} steps: max relative error {worst:.2e}");
        assert!(worst < tol, "steps={steps}: worst relative error {worst:e}");
        assert_eq!(dissipated, 0.0);
        assert_eq!(st.memory_depth(), 1);
    }
}

#[test]
fn decreasing_normal_force_keeps_q_within_coulomb() {
    let pair = pair();
    let ds = delta_s(&pair, P);
    let mut st = MindlinState::new();
    st.update(&pair, P, Vec2::ZERO);
    st.update(&pair, P, Vec2::new(0.5 * ds, 0.2 * ds));
    for i in 1..=100 {
        let p = P * (1.0 - i as f64 / 100.0);
        let q = st.update(&pair, p, Vec2::ZERO).q;
        assert!(
            q.length() <= pair.mu * p * (1.0 + 1e-12) + 1e-300,
            "p={p} q={q:?}"
        );
    }
    assert_eq!(st.force(), Vec2::ZERO);
    assert_eq!(st.memory_depth(), 0);
}

/// Energy of a closed Mindlin-Deresiewicz loop between +d_amp and -d_amp, by Simpson's rule on
/// the closed-form branches: integral (Q_upper - Q_lower) d delta.
fn closed_form_loop_energy(mu_p: f64, ds: f64, d_amp: f64) -> f64 {
    let q_amp = q_load(mu_p, ds, d_amp);
    let n = 20_000;
    let h = 2.0 * d_amp / n as f64;
    // The reloading branch (from -d_amp, travelled with d increasing) lies above the unloading one.
    let f = |d: f64| q_branch(mu_p, ds, -d_amp, -q_amp, d) - q_branch(mu_p, ds, d_amp, q_amp, d);
    let mut s = f(-d_amp) + f(d_amp);
    for i in 1..n {
        let d = -d_amp + i as f64 * h;
        s += if i % 2 == 1 { 4.0 } else { 2.0 } * f(d);
    }
    s * h / 3.0
}

#[test]
fn hysteresis_loop_dissipation_matches_closed_form() {
    let pair = pair();
    let mu_p = pair.mu * P;
    let ds = delta_s(&pair, P);
    for amp in [0.1, 0.5, 0.9] {
        let d_amp = amp * ds;
        let expect = closed_form_loop_energy(mu_p, ds, d_amp);
        for steps in [10, 500] {
            let mut st = MindlinState::new();
            st.update(&pair, P, Vec2::ZERO);
            for _ in 0..steps {
                st.update(&pair, P, Vec2::new(d_amp / steps as f64, 0.0));
            }
            // One full cycle +d_amp -> -d_amp -> +d_amp.
            let mut dissipated = 0.0;
            for leg in [-1.0, 1.0] {
                for _ in 0..steps {
                    dissipated += st
                        .update(&pair, P, Vec2::new(leg * 2.0 * d_amp / steps as f64, 0.0))
                        .slip_dissipation;
                }
            }
            println!(
                "loop energy amp={amp} steps={steps}: relative error {:.2e}",
                dissipated / expect - 1.0
            );
            assert!(
                (dissipated / expect - 1.0).abs() < 1e-10,
                "amp={amp} steps={steps}: {dissipated:e} vs {expect:e}"
            );
        }
    }
}

#[test]
fn energy_balance_on_virgin_loading() {
    // Work in = stored + dissipated; the work is integral Q d delta of the closed form.
    let pair = pair();
    let mu_p = pair.mu * P;
    let ds = delta_s(&pair, P);
    let d_end = 0.7 * ds;
    let n = 20_000;
    let h = d_end / n as f64;
    let mut work = q_load(mu_p, ds, 0.0) + q_load(mu_p, ds, d_end);
    for i in 1..n {
        work += if i % 2 == 1 { 4.0 } else { 2.0 } * q_load(mu_p, ds, i as f64 * h);
    }
    work *= h / 3.0;
    let mut st = MindlinState::new();
    st.update(&pair, P, Vec2::ZERO);
    let mut dissipated = 0.0;
    for _ in 0..7 {
        dissipated += st
            .update(&pair, P, Vec2::new(0.0, d_end / 7.0))
            .slip_dissipation;
    }
    let total = st.elastic_energy(&pair) + dissipated;
    println!(
        "virgin loading energy balance: relative error {:.2e}",
        total / work - 1.0
    );
    assert!((total / work - 1.0).abs() < 1e-8, "{total:e} vs {work:e}");
}

#[test]
fn memory_stays_bounded_on_nested_cycles() {
    let pair = pair();
    let ds = delta_s(&pair, P);
    let mut st = MindlinState::new();
    st.update(&pair, P, Vec2::ZERO);
    // Decreasing nested cycles create ever more turning points.
    let mut d = 0.0;
    for k in 0..40 {
        let target = if k % 2 == 0 { 0.9 } else { -0.9 } * ds * 0.8f64.powi(k);
        let q = st.update(&pair, P, Vec2::new(target - d, 0.0)).q;
        d = target;
        assert!(q.length() <= pair.mu * P * (1.0 + 1e-12));
        assert!(st.memory_depth() <= MAX_PIECES);
    }
    assert!(st.memory_depth() >= 4, "depth {}", st.memory_depth());
}

#[test]
fn circular_path_stays_within_coulomb_and_saturates() {
    let pair = pair();
    let ds = delta_s(&pair, P);
    let mut st = MindlinState::new();
    st.update(&pair, P, Vec2::ZERO);
    let r = 2.0 * ds;
    let mut prev = Vec2::ZERO;
    let mut total_d = 0.0;
    for i in 1..=2000 {
        let th = i as f64 * 0.01;
        let pos = Vec2::new(r * (th.cos() - 1.0), r * th.sin());
        let step = st.update(&pair, P, pos - prev);
        prev = pos;
        total_d += step.slip_dissipation;
        assert!(step.q.length() <= pair.mu * P * (1.0 + 1e-12));
        assert!(step.slip_dissipation >= 0.0);
    }
    // Long circular sliding: the force is at the Coulomb limit and follows the path tangent
    // (within the lag a finite contact has: the force trails the slip direction).
    assert!(st.force().length() > 0.99 * pair.mu * P, "{:?}", st.force());
    assert!(total_d > 0.0);
}

#[test]
fn transform_rotates_force_and_state() {
    let pair = pair();
    let ds = delta_s(&pair, P);
    let mut st = MindlinState::new();
    st.update(&pair, P, Vec2::ZERO);
    st.update(&pair, P, Vec2::new(0.5 * ds, 0.0));
    let mut rotated = st;
    rotated.transform([[0.0, -1.0], [1.0, 0.0]]);
    assert!((rotated.force() - Vec2::new(0.0, st.force().x)).length() < 1e-12);
    // Continuing along the rotated axis behaves like continuing along the old one.
    let a = st.update(&pair, P, Vec2::new(0.1 * ds, 0.0)).q;
    let b = rotated.update(&pair, P, Vec2::new(0.0, 0.1 * ds)).q;
    assert!((a.x - b.y).abs() < 1e-12 * a.x.abs());
}

#[test]
fn opening_contact_and_bad_inputs() {
    let pair = pair();
    let mut st = MindlinState::new();
    st.update(&pair, P, Vec2::new(1e-7, 0.0));
    let step = st.update(&pair, 0.0, Vec2::new(1e-7, 0.0));
    assert_eq!(step.q, Vec2::ZERO);
    assert!(step.slip_dissipation > 0.0);
    for p in [f64::NAN, -1.0, f64::INFINITY] {
        let step = st.update(&pair, p, Vec2::new(1e-7, 0.0));
        assert!(step.q.is_finite() && step.slip_dissipation.is_finite());
    }
    st.update(&pair, P, Vec2::ZERO);
    let step = st.update(&pair, P, Vec2::new(f64::NAN, 1.0));
    assert_eq!(step.q, Vec2::ZERO);
    let step = st.update(&pair, P, Vec2::new(1e300, -1e300));
    assert!(step.q.is_finite());
    assert!(step.q.length() <= pair.mu * P * (1.0 + 1e-12));
}

// ---------------------------------------------------------------------------------------------
// Varying normal force: a contact radius that oscillates as a sine (a DEM contact under a
// vibrating load) while a tangential displacement is applied.

/// Relative amplitude of the radius oscillation `a(t) = a0 (1 + EPS sin(2 pi t))`, `t` in cycles.
const EPS: f64 = 0.3;
/// Number of radius cycles of every sine history.
const CYCLES: usize = 5;
/// Half-period (in radius cycles) of the back-and-forth displacement path: a multiple of the
/// step for every steps-per-cycle used, so that its turning points fall on step boundaries.
const HALF_PERIOD: f64 = 0.3;

/// A tangential displacement path `U(t) = dir * f(t)` \[m\], `t` in radius cycles.
#[derive(Clone, Copy)]
enum Path {
    /// `f = amp t / CYCLES`: monotone.
    Monotone,
    /// `f`: a triangle wave between 0 and `amp`, rising first, half-period [`HALF_PERIOD`].
    BackAndForth,
}

impl Path {
    fn f(self, amp: f64, t: f64) -> f64 {
        match self {
            Path::Monotone => amp * t / CYCLES as f64,
            Path::BackAndForth => {
                let k = (t / HALF_PERIOD).floor();
                let r = t / HALF_PERIOD - k;
                amp * if k as i64 % 2 == 0 { r } else { 1.0 - r }
            }
        }
    }
}

/// `a(t) = a0 (1 + EPS sin(2 pi t))` \[m\].
fn sine_radius(a0: f64, t: f64) -> f64 {
    a0 * (1.0 + EPS * (2.0 * std::f64::consts::PI * t).sin())
}

/// Tangential force of the MDR spring row at `mu = inf`, computed independently of the piece
/// machinery (Popov & Heß 2015, ch. 5: `Q = 8 G* integral_0^a u(x) dx`, a spring keeps the
/// displacement it accumulated since it last entered the contact, springs enter with zero
/// displacement): `u(x, t) = f(t) - f(t_e(x))`, with `t_e(x)` the last time before `t` at which
/// the radius grew through `x` (or 0 for springs in contact since the start; the contact starts
/// virgin at `a0`, `f(0) = 0`). For `x = a0 (1 + EPS sin phi)`, `phi` in `[-pi/2, pi/2]`, the
/// rising crossings are at `t = phi / (2 pi) + k`; springs with `x <= a0 (1 - EPS)` never left.
/// So `Q / (8 G*) = a_min f(t) + integral (f(t) - f(t_e)) a0 EPS cos(phi) dphi` over
/// `-pi/2 < phi <= asin((a(t)/a0 - 1)/EPS)`, by composite Simpson with `phi = 0` (where `t_e`
/// stops being clamped at 0) as a node. Returns `Q / (8 G* |dir|)` [m^2].
fn no_slip_force(a0: f64, path: Path, amp: f64, t: f64) -> f64 {
    use std::f64::consts::{FRAC_PI_2, PI};
    let a_min = a0 * (1.0 - EPS);
    let ft = path.f(amp, t);
    let y = ((sine_radius(a0, t) / a0 - 1.0) / EPS).clamp(-1.0, 1.0);
    let phi_hi = y.asin();
    let integrand = |phi: f64| {
        let tau = phi / (2.0 * PI);
        let k = (t - tau).floor();
        let te = (tau + k).max(0.0);
        (ft - path.f(amp, te)) * a0 * EPS * phi.cos()
    };
    let simpson = |lo: f64, hi: f64| {
        if hi <= lo {
            return 0.0;
        }
        let n = 20_000;
        let h = (hi - lo) / n as f64;
        let mut s = integrand(lo) + integrand(hi);
        for i in 1..n {
            s += if i % 2 == 1 { 4.0 } else { 2.0 } * integrand(lo + i as f64 * h);
        }
        s * h / 3.0
    };
    a_min * ft + simpson(-FRAC_PI_2, phi_hi.min(0.0)) + simpson(0.0, phi_hi)
}

/// Runs one sine history: returns (work by the trapezoidal rule, its scale sum |Q_mid| |du|,
/// stored energy at the end, summed slip dissipation, summed truncation energy, the largest
/// |Q - Q_ref| / max |Q_ref| against [`no_slip_force`]).
fn run_sine(mu: f64, spc: usize, path: Path) -> (f64, f64, f64, f64, f64, f64) {
    let pair = pair().with_friction(mu).unwrap();
    let a0 = hertz::contact_radius(&pair, P);
    // Half of Mindlin's slip distance at mu = 0.3: partial slip for the smallest mu.
    let amp = 0.5 * 3.0 * 0.3 * P / (16.0 * pair.g_star * a0);
    let dir = Vec2::new(0.6, 0.8);
    let mut st = MindlinState::new();
    st.update_with_radius(&pair, a0, Vec2::ZERO);
    let stored_0 = st.elastic_energy(&pair);
    let (mut work, mut scale, mut slip, mut trunc) = (0.0, 0.0, 0.0, 0.0);
    let (mut err, mut q_max): (f64, f64) = (0.0, 0.0);
    let n = spc * CYCLES;
    for i in 1..=n {
        let (t0, t1) = ((i - 1) as f64 / spc as f64, i as f64 / spc as f64);
        let du = dir * (path.f(amp, t1) - path.f(amp, t0));
        let q0 = st.force();
        let step = st.update_with_radius(&pair, sine_radius(a0, t1), du);
        let q_mid = (q0 + step.q) * 0.5;
        work += q_mid.dot(du);
        scale += q_mid.length() * du.length();
        slip += step.slip_dissipation;
        trunc += step.truncation_energy;
        if i % (spc / 10) == 0 {
            let q_ref = dir * (8.0 * pair.g_star * no_slip_force(a0, path, amp, t1));
            err = err.max((step.q - q_ref).length());
            q_max = q_max.max(q_ref.length());
        }
    }
    let stored = st.elastic_energy(&pair) - stored_0;
    (work, scale, stored, slip, trunc, err / q_max)
}

/// First-order bound on the energy-balance residual of a sine history, as a fraction of the
/// work scale `sum |Q_mid| |du|`, times the steps per radius cycle: the same bound as the
/// property test `closed_cycles_dissipate`. The trapezoidal work is second order; the first-order
/// terms are the slip of the springs that change from sticking to slipping within a step (booked
/// at an onset force known to within one step's displacement, see `Onset`) and of the springs
/// that meet the falling limit just before they leave. Measured: at most 0.072 / steps.
const BALANCE_PER_STEP: f64 = 0.2;

#[test]
fn sine_radius_history_energy_balance() {
    // A DEM contact under a vibrating load: a(t) = a0 (1 +- 0.3), 5 cycles, while the surfaces
    // are displaced monotonically or back and forth. Before the fix the balance failed by up to
    // 1e6 times the work at mu = 1000 (springs entering a full memory took the outer piece's
    // field, with its huge c after a small da2).
    for mu in [0.3, 3.0, 30.0, 1000.0, f64::INFINITY] {
        for spc in [50, 200, 500] {
            for (name, path) in [
                ("monotone", Path::Monotone),
                ("back-and-forth", Path::BackAndForth),
            ] {
                let (work, scale, stored, slip, trunc, _) = run_sine(mu, spc, path);
                let residual = (work - stored - slip + trunc) / scale;
                println!(
                    "sine a(t), mu={mu}, {spc} steps/cycle, {name}: work {work:.3e} J, slip \
                     {slip:.3e} J, stored {stored:.3e} J, truncation {trunc:.1e} J, residual \
                     {residual:.2e} of sum |Q||du|"
                );
                let tol = BALANCE_PER_STEP / spc as f64;
                assert!(
                    residual.abs() <= tol,
                    "mu={mu} spc={spc} {name}: residual {residual:e} > {tol:e}"
                );
                // The energy released by slip and by leaving springs was paid for by the work.
                assert!(
                    slip <= work + tol * scale,
                    "mu={mu} spc={spc} {name}: slip {slip:e} > work {work:e}"
                );
                assert!(
                    trunc <= tol * scale,
                    "mu={mu} spc={spc} {name}: truncation {trunc:e}"
                );
            }
        }
    }
}

#[test]
fn sine_radius_history_matches_no_slip_closed_form() {
    // mu = inf: no spring slips, each keeps what it accumulated since it entered, which
    // `no_slip_force` integrates independently. The tolerance covers the MAX_PIECES memory: the
    // exact field f(t) - f(t_e(x)) is not piecewise linear in the depth, so the least-squares
    // merges approximate it (measured <= 8.2e-4 of max |Q|, 3e-5 for the monotone path at 200
    // steps and more). mu = 1000 only slips in a band at the edge that vanishes as mu grows and
    // must stay as close (before the fix: 2 % off in an impact).
    for mu in [1000.0, f64::INFINITY] {
        for spc in [50, 200, 500] {
            for (name, path) in [
                ("monotone", Path::Monotone),
                ("back-and-forth", Path::BackAndForth),
            ] {
                let err = run_sine(mu, spc, path).5;
                println!(
                    "sine a(t), mu={mu}, {spc} steps/cycle, {name}: max |Q - Q_no_slip| = \
                     {err:.2e} max |Q_no_slip|"
                );
                assert!(err <= 2e-3, "mu={mu} spc={spc} {name}: {err:e}");
            }
        }
    }
}

#[test]
fn springs_entering_a_full_memory_enter_unstrained() {
    // Growing the contact without tangential motion adds springs with zero displacement
    // (Popov & Heß 2015, ch. 5): Q and the stored energy cannot change (a merge may only move
    // energy into the dissipation), however deep the memory.
    let pair = pair();
    let ds = delta_s(&pair, P);
    let mut st = MindlinState::new();
    st.update(&pair, P, Vec2::ZERO);
    let dir = Vec2::new(0.6, -0.8);
    let mut d = 0.0;
    for k in 0..12 {
        // Nested cycles at a slowly varying load fill the memory.
        let target = if k % 2 == 0 { 0.9 } else { -0.9 } * ds * 0.7f64.powi(k);
        st.update(&pair, P * (1.0 - 0.01 * k as f64), dir * (target - d));
        d = target;
    }
    assert_eq!(st.memory_depth(), MAX_PIECES);
    let p0 = P * (1.0 - 0.01 * 11.0);
    for i in 1..=20 {
        let q0 = st.force();
        let e0 = st.elastic_energy(&pair);
        let step = st.update(&pair, p0 * (1.0 + 0.05 * i as f64), Vec2::ZERO);
        let e1 = st.elastic_energy(&pair);
        assert!(
            (step.q - q0).length() <= 1e-12 * q0.length(),
            "step {i}: Q {:?} -> {:?}",
            q0,
            step.q
        );
        assert!(
            (e1 + step.slip_dissipation - step.truncation_energy - e0).abs() <= 1e-12 * e0,
            "step {i}: energy {e0:e} -> {e1:e} + slip {:e}",
            step.slip_dissipation
        );
        assert!(st.memory_depth() <= MAX_PIECES);
    }
}

/// A small deterministic generator (xorshift64*), uniform in `[-1, 1)`.
struct Rng(u64);

impl Rng {
    fn sym(&mut self) -> f64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        let u = (self.0.wrapping_mul(0x2545_f491_4f6c_dd1d) >> 11) as f64 / (1u64 << 53) as f64;
        2.0 * u - 1.0
    }
}

/// Largest differences accepted between one update of the optimised memory and one of the
/// frozen reference from the same state (the flat layouts are the same): force relative to the
/// path's largest force, energies relative to the step's work scale `|Q| |du|` plus its
/// dissipation and the energy stored before the step. The optimised memory classifies sticking and slipping springs and tests merges
/// in other forms (rounding-level differences), and snaps a stick-slip cut within `1e-12 a` of
/// a piece's end to that end, where the reference splits off a sliver of springs that then
/// takes a slot of a full memory and makes `merge` join other neighbours: one such update
/// differs by up to 2.6e-5 of the largest force (measured on these paths; otherwise the force
/// differs by at most 6.7e-15 and the energies by at most 4.7e-14 of their scale).
const STEP_TOL_FORCE: f64 = 1e-4;
const STEP_TOL_ENERGY: f64 = 1e-12;

/// Largest difference accepted after free-running both versions along a whole path (force
/// relative to the largest force on the path; summed energies relative to the work scale
/// `sum |Q| |du|`). Different slivers and merges (see [`STEP_TOL_FORCE`]) make two valid
/// memories that are not the same list of annuli, so long paths with a full memory drift apart
/// by more than rounding; every physical test holds for each. Measured on these paths: up to
/// 3.4e-3 of the largest force and 8.5e-5 of the work (printed with `--nocapture`).
const PATH_TOL: f64 = 1e-2;

/// Drives the optimised memory without eager coalescing ([`MindlinUncoalesced`], whose results
/// are the memory's before coalescing, bit for bit) and the frozen reference (`mindlin/reference.rs`, the algorithm
/// before its speed-up) through the same inputs: after every step, one update of the optimised
/// memory from the reference's state must agree with the reference's to [`STEP_TOL_FORCE`] and
/// [`STEP_TOL_ENERGY`], and the
/// free-running optimised memory must stay within [`PATH_TOL`]. Returns the memory-depth
/// histogram of the free-running optimised memory.
fn run_against_reference(pair: &PairMaterial, inputs: &[(f64, Vec2)]) -> [usize; MAX_PIECES + 1] {
    let mut new = MindlinUncoalesced::new();
    let mut old = reference::MindlinState::new();
    let mut depth = [0; MAX_PIECES + 1];
    let mut q_max = 0.0f64;
    let mut work = 0.0;
    let (mut dn, mut d_old, mut tn, mut t_old) = (0.0f64, 0.0f64, 0.0f64, 0.0f64);
    let (mut dq_path, mut de_path) = (0.0f64, 0.0f64);
    let (mut dq_step, mut de_step) = (0.0f64, 0.0f64);
    for &(a, du) in inputs {
        let mut one = MindlinUncoalesced::from_array(&old.to_array()).expect("valid state");
        let stored = old.elastic_energy(pair);
        let s1 = one.update_with_radius(pair, a, du);
        let s = new.update_with_radius(pair, a, du);
        let r = old.update_with_radius(pair, a, du);
        assert_eq!(s.a.to_bits(), r.a.to_bits(), "contact radius differs");
        assert_eq!(s1.a.to_bits(), r.a.to_bits(), "contact radius differs");
        q_max = q_max.max(r.q.length());
        let step_work = r.q.length() * du.length();
        work += step_work;
        // The step's energies are differences of integrals of the field's square, so their
        // rounding scales with the stored energy, not with the (possibly tiny) step.
        let scale = step_work + r.slip_dissipation + r.truncation_energy + stored;
        if scale > 0.0 {
            de_step = de_step.max(
                (s1.slip_dissipation - r.slip_dissipation)
                    .abs()
                    .max((s1.truncation_energy - r.truncation_energy).abs())
                    / scale,
            );
        }
        if q_max > 0.0 {
            dq_step = dq_step.max((s1.q - r.q).length() / q_max);
            dq_path = dq_path.max((s.q - r.q).length() / q_max);
        }
        dn += s.slip_dissipation;
        d_old += r.slip_dissipation;
        tn += s.truncation_energy;
        t_old += r.truncation_energy;
        if work > 0.0 {
            de_path = de_path.max((dn - d_old).abs().max((tn - t_old).abs()) / work);
        }
        assert_eq!(
            new.memory_depth() == 0,
            old.memory_depth() == 0,
            "open/closed differs"
        );
        depth[new.memory_depth()] += 1;
    }
    println!(
        "against the reference: one step {dq_step:.2e} (force) {de_step:.2e} (energies); \
         free-running path {dq_path:.2e} (force) {de_path:.2e} (energies)"
    );
    assert!(
        dq_step <= STEP_TOL_FORCE && de_step <= STEP_TOL_ENERGY,
        "one update differs: {dq_step:.2e} {de_step:.2e}"
    );
    assert!(
        dq_path <= PATH_TOL && de_path <= PATH_TOL,
        "path differs: {dq_path:.2e} {de_path:.2e}"
    );
    depth
}

/// The inputs `(a, du)` of a contact in a vibrating packing (6,000 steps from a seed): the
/// radius grows or shrinks every step, the displacement turns by up to 0.2 rad per step,
/// reverses every 500 steps, and moves by 1e-6 to 0.3 slip distances (those of `base` at
/// `P`); the contact opens (and a bad radius comes) every 997 steps.
fn jittering_dem_path(seed: u64, base: &PairMaterial) -> Vec<(f64, Vec2)> {
    let a0 = hertz::contact_radius(base, P);
    let ds = delta_s(&base.with_friction(0.5).unwrap(), P);
    let mut rng = Rng(0x9e37_79b9_7f4a_7c15 ^ seed.wrapping_mul(0xbf58_476d_1ce4_e5b9));
    let (mut a, mut dir) = (a0, 0.0f64);
    let mut inputs = Vec::new();
    for i in 0..6000 {
        a = (a * (1.0 + 3e-3 * rng.sym())).clamp(0.5 * a0, 1.5 * a0);
        dir += 0.2 * rng.sym();
        if i % 500 == 250 {
            dir += std::f64::consts::PI;
        }
        // Step lengths from 1e-6 to 0.3 slip distances.
        let len = ds * 10f64.powf(-3.5 + 3.0 * rng.sym());
        let du = Vec2::new(dir.cos(), dir.sin()) * len;
        let a_in = match i % 997 {
            500 => 0.0,                // opens
            501 => f64::NAN,           // bad input: open
            502 => a0 * (1.0 + 1e-15), // closes again
            _ => a,
        };
        inputs.push((a_in, du));
    }
    inputs
}

#[test]
fn reference_to_rounding_on_jittering_dem_paths() {
    // A contact in a vibrating packing: the radius grows or shrinks every step (the memory is
    // full and merges every step), the displacement turns, reverses, creeps and slides grossly;
    // sometimes the contact opens. Friction from 0 (walls) to +inf.
    let base = pair();
    let mut full = 0;
    for (seed, mu) in [
        (1u64, 0.5),
        (2, 0.3),
        (3, 0.0),
        (4, f64::INFINITY),
        (5, 1e3),
        (6, 0.5),
    ] {
        let pair = base.with_friction(mu).unwrap();
        let inputs = jittering_dem_path(seed, &base);
        let depth = run_against_reference(&pair, &inputs);
        full += depth[MAX_PIECES];
    }
    // The paths exercised the full memory (the merges) most of the time.
    assert!(full > 10_000, "full memory in only {full} steps");
}

#[test]
fn reference_to_rounding_on_cycles_and_rolling() {
    let pair = pair();
    let mu_p = pair.mu * P;
    let ds = delta_s(&pair, P);
    let a0 = hertz::contact_radius(&pair, P);
    // Loading/unloading cycles of P with out-of-phase tangential cycles (collinear, then 2-D).
    let cycles: Vec<(f64, Vec2)> = (1..3000)
        .map(|i| {
            let t = i as f64 * std::f64::consts::TAU / 150.0;
            let p = P * (1.0 + 0.6 * t.sin());
            let dd = 0.9 * ds * (t.cos() - (t - std::f64::consts::TAU / 150.0).cos());
            let dir = if i < 1500 {
                Vec2::new(1.0, 0.0)
            } else {
                Vec2::new(t.cos(), (0.7 * t).sin())
            };
            (hertz::contact_radius(&pair, p), dir * dd)
        })
        .collect();
    run_against_reference(&pair, &cycles);
    // Steady rolling with Kuhn's creep fed back from the force (constant P), then at a slowly
    // falling load; the creep from the reference state's force.
    let mut st = reference::MindlinState::new();
    let dr = a0 * 1e-3;
    let xi = crate::kalker::steady_creepage(0.6, mu_p, pair.g, a0, pair.c11);
    let rolling: Vec<(f64, Vec2)> = (0..3000)
        .map(|i| {
            let p = if i < 2000 {
                P
            } else {
                P * (1.0 - 1e-4 * (i - 2000) as f64)
            };
            let a = hertz::contact_radius(&pair, p);
            let q = st.force().length();
            let f = if q > 0.0 {
                crate::kalker::steady_creepage(
                    (q / (pair.mu * p)).min(1.0),
                    pair.mu * p,
                    pair.g,
                    a,
                    pair.c11,
                )
            } else {
                0.0
            };
            let du = Vec2::new((xi - f) * dr, 0.1 * xi * dr);
            st.update_with_radius(&pair, a, du);
            (a, du)
        })
        .collect();
    run_against_reference(&pair, &rolling);
}

/// Drives the uncoalesced memory ([`MindlinUncoalesced`]) along `inputs` and, before every
/// step, copies its state into the coalescing memory `MindlinMemory<MAX_PIECES, C>`; both make
/// the step. Where the uncoalesced update needed no capacity merge (it ends below the
/// capacity), the two differ only by the coalescing, whose bound (module docs, "Coalescing") is
/// asserted: the same slip dissipation and truncation energy (coalescing comes after the slip),
/// the same stored energy to rounding, and a force within `k (1 - cos(theta / 2)) mu P` of the
/// uncoalesced one, `k` the number of coalescings (the difference of the two depths), `theta`
/// the coalescing angle; with `k = 0` the two updates are the same bits. Both memories keep
/// `|Q| <= mu P`. Returns the number of steps checked and of steps that coalesced.
fn coalesced_against_uncoalesced<const C: u32>(
    pair: &PairMaterial,
    inputs: &[(f64, Vec2)],
) -> (usize, usize) {
    let theta = f64::from(C) * 1e-6;
    let per = 1.0 - (0.5 * theta.min(std::f64::consts::PI)).cos();
    let kappa = kappa(pair);
    let mut old = MindlinUncoalesced::new();
    let (mut checked, mut coalesced) = (0, 0);
    let mut worst = 0.0f64;
    for &(a, du) in inputs {
        let mut one = MindlinMemory::<MAX_PIECES, C>::from_array(&old.to_array()).unwrap();
        let stored = old.elastic_energy(pair);
        let s = one.update_with_radius(pair, a, du);
        let r = old.update_with_radius(pair, a, du);
        // mu P at the step's radius: 8 G* kappa integral_0^a s dx = 8 G* kappa (2/3) a^3.
        let mu_p = 8.0 * pair.g_star * kappa * (2.0 / 3.0) * r.a.powi(3);
        if mu_p.is_finite() {
            for q in [s.q, r.q] {
                assert!(
                    q.length() <= mu_p * (1.0 + 1e-12),
                    "|Q| {} > mu P {mu_p}",
                    q.length()
                );
            }
        }
        if old.memory_depth() >= MAX_PIECES {
            continue;
        }
        checked += 1;
        assert!(one.memory_depth() <= old.memory_depth());
        let k = old.memory_depth() - one.memory_depth();
        if k == 0 {
            assert_eq!(
                one.to_array(),
                old.to_array(),
                "no coalescing, yet another state"
            );
            assert_eq!(s, r, "no coalescing, yet another step");
            continue;
        }
        coalesced += 1;
        let dq = (s.q - r.q).length();
        worst = worst.max(dq / (k as f64 * per * mu_p));
        assert!(
            dq <= k as f64 * per * mu_p * (1.0 + 1e-9) + 1e-12 * mu_p,
            "force moved by {dq:e}, bound {:e} (k = {k})",
            k as f64 * per * mu_p
        );
        let scale = stored + s.slip_dissipation + r.q.length() * du.length();
        assert!((s.slip_dissipation - r.slip_dissipation).abs() <= 1e-12 * scale);
        assert_eq!(s.truncation_energy, r.truncation_energy);
        let (w1, w2) = (one.elastic_energy(pair), old.elastic_energy(pair));
        assert!(
            (w1 - w2).abs() <= 1e-8 * (w1 + w2) + 1e-12 * scale,
            "stored energy {w1:e} against {w2:e}"
        );
    }
    println!(
        "coalesced ({C} urad) against uncoalesced: {checked} steps checked, {coalesced} coalesced, \
         largest force change {worst:.3} of the bound"
    );
    (checked, coalesced)
}

/// Eager coalescing against the uncoalesced memory, one update from the same state, on 2-D
/// paths (the jittering DEM paths of the reference tests and a rolling contact whose
/// tangential direction turns), at the default angle ([`COALESCE_URAD`]) and at a small and a
/// large one; the bound of [`coalesced_against_uncoalesced`] holds and the paths do coalesce.
#[test]
fn coalescing_keeps_its_bound_against_the_uncoalesced_memory() {
    let base = pair();
    let mut paths: Vec<(PairMaterial, Vec<(f64, Vec2)>)> = [(1u64, 0.5), (2, 0.3), (5, 1e3)]
        .iter()
        .map(|&(seed, mu)| {
            (
                base.with_friction(mu).unwrap(),
                jittering_dem_path(seed, &base),
            )
        })
        .collect();
    // Rolling under a slowly turning creepage with a jittering radius.
    let a0 = hertz::contact_radius(&base, P);
    let ds = delta_s(&base, P);
    let mut rng = Rng(77);
    let turning = (0..4000)
        .map(|i| {
            let t = i as f64 * 2e-3;
            let a = a0 * (1.0 + 2e-3 * rng.sym());
            (
                a,
                Vec2::new(t.cos(), t.sin()) * (0.05 * ds * (1.0 + 0.5 * rng.sym())),
            )
        })
        .collect();
    paths.push((base, turning));
    let (mut checked, mut coalesced) = ([0; 3], [0; 3]);
    for (pair, inputs) in &paths {
        for (k, (c, n)) in [
            coalesced_against_uncoalesced::<COALESCE_URAD>(pair, inputs),
            coalesced_against_uncoalesced::<10_000>(pair, inputs),
            coalesced_against_uncoalesced::<3_200_000>(pair, inputs),
        ]
        .into_iter()
        .enumerate()
        {
            checked[k] += c;
            coalesced[k] += n;
        }
    }
    for k in 0..3 {
        assert!(
            checked[k] > 1000 && coalesced[k] > 100,
            "{checked:?} {coalesced:?}"
        );
    }
}

/// The coalescing bound's squared chord is `2 (1 - cos theta)` (the `const fn` series against
/// `cos`), 0 for no coalescing and 4 (every direction) from `pi` on.
#[test]
fn coalescing_chord_is_two_minus_two_cos() {
    for urad in [1u32, 1_000, 10_000, 100_000, 300_000, 1_000_000, 3_000_000] {
        let t = f64::from(urad) * 1e-6;
        let exact = 4.0 * (0.5 * t).sin().powi(2);
        assert!(
            (chord2(urad) - exact).abs() <= 1e-15 * exact,
            "{urad}: {}",
            chord2(urad)
        );
    }
    assert_eq!(chord2(0), 0.0);
    assert_eq!(chord2(3_141_593), 4.0);
    assert_eq!(MindlinUncoalesced::CHORD2, 0.0);
}

/// A smaller memory (`MindlinMemory<N>`, N < MAX_PIECES) is the same law until it is full: the
/// collinear Mindlin-Deresiewicz paths (which never need more than a few pieces) are reproduced
/// to rounding at N = 4 and 6 as at 8.
#[test]
fn smaller_capacities_reproduce_mindlin_deresiewicz() {
    for (n, err) in [
        (4, check_path::<4>(10, Vec2::new(0.6, -0.8))),
        (4, check_path::<4>(1000, Vec2::new(1.0, 0.0))),
        (6, check_path::<6>(10, Vec2::new(-0.28, 0.96))),
        (6, check_path::<6>(1000, Vec2::new(1.0, 0.0))),
    ] {
        println!("capacity {n}: max |Q - closed form| = {err:.2e} mu P");
        assert!(err < 1e-12, "capacity {n}: {err:e}");
    }
}

/// A smaller memory keeps its bound and the law's invariants on a jittering, turning DEM-like
/// path that keeps it full: at most `N` pieces, `|Q| <= mu P`, non-negative slip and truncation
/// energies; and the flat form of a deeper memory is refused, not truncated.
#[test]
fn smaller_capacities_keep_their_bound_and_coulomb() {
    fn run<const N: usize, const C: u32>() -> usize {
        let pair = pair();
        let ds = delta_s(&pair, P);
        let mut rng = Rng(0x1234_5678_9abc_def1);
        let mut st = MindlinMemory::<N, C>::new();
        let (mut p, mut dir) = (P, 0.0f64);
        let mut full = 0;
        for i in 0..4000 {
            p = (p * (1.0 + 1e-2 * rng.sym())).clamp(0.5 * P, 1.5 * P);
            dir += 0.3 * rng.sym();
            if i % 400 == 200 {
                dir += std::f64::consts::PI;
            }
            let len = ds * 10f64.powf(-3.0 + 2.0 * rng.sym());
            let step = st.update(&pair, p, Vec2::new(dir.cos(), dir.sin()) * len);
            assert!(st.memory_depth() <= N, "depth {} > {N}", st.memory_depth());
            assert!(
                step.q.length() <= pair.mu * p * (1.0 + 1e-12),
                "step {i}: |Q| {} > mu P {}",
                step.q.length(),
                pair.mu * p
            );
            assert!(step.slip_dissipation >= 0.0 && step.truncation_energy >= 0.0);
            full += usize::from(st.memory_depth() == N);
        }
        full
    }
    // Without coalescing the path keeps every capacity full most of the time; with it (the
    // default) the bound and Coulomb's law hold as well.
    for (n, full) in [(4, run::<4, 0>()), (6, run::<6, 0>()), (8, run::<8, 0>())] {
        println!("capacity {n}: full in {full} of 4000 steps");
        assert!(full > 1000, "capacity {n} full in only {full} steps");
    }
    for (n, full) in [
        (4, run::<4, COALESCE_URAD>()),
        (8, run::<8, COALESCE_URAD>()),
    ] {
        println!("capacity {n}, coalescing: full in {full} of 4000 steps");
    }
    // An 8-piece memory's flat form does not fit a 4-piece memory.
    let pair = pair();
    let mut st = MindlinState::new();
    st.update(&pair, P, Vec2::ZERO);
    let ds = delta_s(&pair, P);
    let mut d = 0.0;
    for k in 0..12 {
        let target = if k % 2 == 0 { 0.9 } else { -0.9 } * ds * 0.7f64.powi(k);
        st.update(
            &pair,
            P * (1.0 - 0.01 * k as f64),
            Vec2::new(0.6, -0.8) * (target - d),
        );
        d = target;
    }
    assert!(st.memory_depth() > 4);
    assert!(MindlinMemory::<4>::from_array(&st.to_array()).is_err());
    assert!(MindlinMemory::<8>::from_array(&st.to_array()).is_ok());
}

/// `from_array` accepts only pieces inner to outer (the update relies on non-empty,
/// increasing annuli): a swapped pair, an empty piece or a first piece at radius 0 is an
/// error; the state an update leaves reads back exactly.
#[test]
fn from_array_refuses_pieces_out_of_order() {
    let pair = pair();
    let mut st = MindlinState::new();
    let ds = delta_s(&pair, P);
    st.update(&pair, P, Vec2::new(0.5 * ds, 0.0));
    st.update(&pair, P, Vec2::new(-0.3 * ds, 0.0));
    st.update(&pair, 1.1 * P, Vec2::new(0.0, 0.1 * ds));
    assert!(st.memory_depth() >= 3, "depth {}", st.memory_depth());
    let good = st.to_array();
    assert_eq!(MindlinState::from_array(&good).unwrap(), st);
    // Piece k's outer radius sits at index 4 + 5 k.
    let mut swapped = good;
    swapped.swap(4, 9);
    assert!(MindlinState::from_array(&swapped).is_err());
    let mut empty = good;
    empty[9] = empty[4];
    assert!(MindlinState::from_array(&empty).is_err());
    let mut at_zero = good;
    at_zero[4] = 0.0;
    assert!(MindlinState::from_array(&at_zero).is_err());
}
