use super::kernel::{carry_tangent, rates_and_approach, sphere_rates_and_approach};
use super::*;
use crate::hertz;
use crate::kalker;
use crate::material::{Material, PairMaterial, Surface};
use crate::steady_law::CreepModel;
use crate::vector::Vec3;

fn glass() -> Material {
    Material::glass()
}

fn constants(mu: f64, e: f64, creep: Option<CreepModel>) -> PairConstants {
    PairConstants::new(&glass(), &glass(), mu, e, creep, None).unwrap()
}

fn sphere(x: Vec3, v: Vec3, w: Vec3, r: f64) -> PairBody {
    let m = 4.0 / 3.0 * std::f64::consts::PI * r * r * r * glass().density();
    PairBody {
        position: x,
        velocity: v,
        angular_velocity: w,
        surface: Surface::Sphere(r),
        mass: m,
    }
}

fn wall() -> PairBody {
    PairBody {
        position: Vec3::ZERO,
        velocity: Vec3::ZERO,
        angular_velocity: Vec3::ZERO,
        surface: Surface::Plane,
        mass: f64::INFINITY,
    }
}

/// A sphere of radius `r` pressed `delta` into the plane z = 0 (p = plane, q = sphere), moving
/// with `v` and spinning with `w`.
fn on_plane(r: f64, delta: f64, v: Vec3, w: Vec3) -> (PairBody, PairBody, ContactGeometry) {
    let q = sphere(Vec3::new(0.0, 0.0, r - delta), v, w, r);
    let g = ContactGeometry::plane_sphere(Vec3::ZERO, Vec3::Z, q.position, r);
    (wall(), q, g)
}

#[test]
fn static_normal_force_is_hertz() {
    let c = constants(0.5, 0.5, None);
    let (r, delta) = (1e-3, 2e-6);
    let (p, q, g) = on_plane(r, delta, Vec3::ZERO, Vec3::ZERO);
    let mut h = ContactHistory::<Exact>::default();
    let f = pair_force(&c, &p, &q, &g, &mut h, 1e-8);
    let pm = PairMaterial::new(&glass(), &glass(), Surface::Plane, Surface::Sphere(r)).unwrap();
    // Johnson (1985, §4.2) written out.
    let expect = 4.0 / 3.0 * pm.e_star * r.sqrt() * delta.powf(1.5);
    assert!(f.touching);
    assert!((f.normal_force / expect - 1.0).abs() < 1e-12, "{f:?}");
    // Force on p (the plane) points away from q: -n P.
    assert!((f.force_p + Vec3::Z * expect).length() < 1e-9 * expect);
    let (wn, wt) = h.elastic_energy(&c, p.surface, q.surface);
    assert!((wn / (0.4 * expect * delta) - 1.0).abs() < 1e-12 && wt == 0.0);
    // Open: no force, history reset.
    let (p, q, g) = on_plane(r, -1e-9, Vec3::ZERO, Vec3::ZERO);
    let f = pair_force(&c, &p, &q, &g, &mut h, 1e-8);
    assert!(!f.touching && f.force_p == Vec3::ZERO && h.is_virgin());
}

/// Head-on impact of two equal spheres, integrated with the kernel (symplectic Euler);
/// returns (rebound ratio, contact duration \[s\]).
fn impact<T: TangentialLaw>(e: f64, v0: f64, steps_per_contact: f64) -> (f64, f64) {
    let c = constants(0.5, e, Some(CreepModel::Kuhn));
    let r = 1e-3;
    let mut xp = Vec3::ZERO;
    let mut xq = Vec3::new(2.0 * r + 1e-9, 0.0, 0.0);
    let mut vp = Vec3::new(v0, 0.0, 0.0);
    let mut vq = -vp;
    let m = sphere(xp, vp, Vec3::ZERO, r).mass;
    let pm = c.pair_material(Surface::Sphere(r), Surface::Sphere(r));
    let m_star = m / 2.0;
    let vrel = 2.0 * v0;
    // Johnson (1985, §11.4): t_c = 2.9432 delta_max / V, delta_max = (15 m* V^2 / (16 E* sqrt(R*)))^(2/5).
    let dmax = (15.0 * m_star * vrel * vrel / (16.0 * pm.e_star * pm.r_star.sqrt())).powf(0.4);
    let tc = 2.9432 * dmax / vrel;
    let dt = tc / steps_per_contact;
    let mut h = ContactHistory::<T>::default();
    let (mut t, mut t_in, mut t_out) = (0.0, None, None);
    for _ in 0..(10.0 * steps_per_contact) as usize {
        let bp = sphere(xp, vp, Vec3::ZERO, r);
        let bq = sphere(xq, vq, Vec3::ZERO, r);
        let g = ContactGeometry::sphere_sphere(xp, r, xq, r).unwrap();
        let f = pair_force(&c, &bp, &bq, &g, &mut h, dt);
        if f.touching && t_in.is_none() {
            t_in = Some(t);
        }
        if !f.touching && t_in.is_some() && t_out.is_none() && g.overlap <= 0.0 {
            t_out = Some(t);
        }
        vp += f.force_p * (dt / m);
        vq -= f.force_p * (dt / m);
        xp += vp * dt;
        xq += vq * dt;
        t += dt;
    }
    let dur = t_out.unwrap() - t_in.unwrap();
    ((vq.x - vp.x) / vrel, dur / tc)
}

#[test]
fn impact_restitution_and_hertz_duration() {
    for e in [1.0, 0.9, 0.5, 0.2] {
        let (rebound, _) = impact::<Exact>(e, 0.5, 2000.0);
        assert!((rebound / e - 1.0).abs() < 2e-3, "e = {e}: {rebound}");
        let (rebound_cheap, _) = impact::<Cheap>(e, 0.5, 2000.0);
        assert_eq!(rebound, rebound_cheap, "head-on: no tangential force");
    }
    let (_, dur) = impact::<Exact>(1.0, 0.5, 2000.0);
    assert!((dur - 1.0).abs() < 2e-3, "duration / Hertz = {dur}");
}

/// Tangential displacement at constant overlap: returns (Q.x per step, mu P, 16 G* a / 3).
fn tangential_loading<T: TangentialLaw>(steps: usize, total: f64) -> (Vec<f64>, f64, f64) {
    let c = constants(0.5, 0.5, None);
    let (r, delta) = (1e-3, 2e-6);
    let dt = 1e-7;
    let v = Vec3::new(total / (steps as f64 * dt), 0.0, 0.0);
    let (p, q, g) = on_plane(r, delta, v, Vec3::ZERO);
    let mut h = ContactHistory::<T>::default();
    let mut qs = Vec::new();
    let mut p_el = 0.0;
    let mut a = 0.0;
    // Close the contact at rest first (Mindlin's curve is for a contact formed before the
    // tangential load).
    let (p0, q0, g0) = on_plane(r, delta, Vec3::ZERO, Vec3::ZERO);
    pair_force(&c, &p0, &q0, &g0, &mut h, dt);
    for _ in 0..steps {
        let f = pair_force(&c, &p, &q, &g, &mut h, dt);
        // Q on p from q: q moves +x relative to p, so Q on p is +x.
        qs.push(f.tangential_force.x);
        p_el = f.elastic_normal_force;
        a = f.contact_radius;
    }
    let pm = c.pair_material(p.surface, q.surface);
    (qs, pm.mu * p_el, 16.0 * pm.g_star * a / 3.0)
}

#[test]
fn exact_tier_follows_mindlins_loading_curve() {
    // Mindlin (1949), Johnson (1985, eq. 7.43): Q = mu P [1 - (1 - 16 G* a d / (3 mu P))^(3/2)]
    // for d below the full-slip displacement 3 mu P / (16 G* a).
    let (qs, mu_p, k) = tangential_loading::<Exact>(200, 0.0);
    assert!(qs.iter().all(|&q| q == 0.0));
    let d_full = mu_p / k;
    let n = 400;
    let (qs, mu_p, k) = tangential_loading::<Exact>(n, 0.9 * d_full);
    for (i, &q) in qs.iter().enumerate() {
        let d = 0.9 * d_full * (i + 1) as f64 / n as f64;
        let expect = mu_p * (1.0 - (1.0 - k * d / mu_p).powf(1.5));
        assert!(
            (q - expect).abs() < 1e-9 * mu_p,
            "step {i}: {q} vs {expect}"
        );
    }
    // Beyond full slip: Q = mu P.
    let (qs, mu_p, _) = tangential_loading::<Exact>(n, 1.5 * d_full);
    assert!((qs[n - 1] / mu_p - 1.0).abs() < 1e-12);
}

#[test]
fn cheap_tier_is_a_linear_spring_capped_at_coulomb() {
    let (qs, mu_p, k3) = tangential_loading::<Cheap>(400, 0.0);
    assert!(qs.iter().all(|&q| q == 0.0));
    // k_t = 8 G* a = (3/2) (16 G* a / 3).
    let k_t = 1.5 * k3;
    let total = 1.5 * mu_p / k_t;
    let (qs, mu_p, _) = tangential_loading::<Cheap>(400, total);
    for (i, &q) in qs.iter().enumerate() {
        let d = total * (i + 1) as f64 / 400.0;
        let expect = (k_t * d).min(mu_p);
        assert!(
            (q - expect).abs() < 1e-9 * mu_p,
            "step {i}: {q} vs {expect}"
        );
    }
}

/// Rolls a sphere on the plane at a held ratio `xi = |du_disp| / |du_roll|`; returns `|Q| / mu P`.
fn steady_rolling<T: TangentialLaw>(xi: f64, steps: usize) -> f64 {
    let c = constants(0.5, 0.5, Some(CreepModel::Kuhn));
    let (r, delta) = (1e-3, 2e-6);
    let pm = c.pair_material(Surface::Plane, Surface::Sphere(r));
    let a = (pm.r_star * delta).sqrt();
    let dt = 1e-7;
    let roll = a / 50.0 / dt; // |v_roll|
    // uq = v + w x (c - x_q) = xi roll along x; v_roll = uq / 2 - v = -roll.
    let uq = xi * roll;
    let v = uq / 2.0 + roll;
    let rho = r - delta / 2.0;
    let w = (v - uq) / rho;
    let (p, q, g) = on_plane(r, delta, Vec3::new(v, 0.0, 0.0), Vec3::new(0.0, w, 0.0));
    let mut h = ContactHistory::<T>::default();
    let mut f = PairForces::default();
    for _ in 0..steps {
        f = pair_force(&c, &p, &q, &g, &mut h, dt);
    }
    assert!((f.v_roll.length() / roll - 1.0).abs() < 1e-9);
    assert!((f.v_disp.length() / uq - 1.0).abs() < 1e-9);
    f.tangential_force.length() / (pm.mu * f.elastic_normal_force)
}

#[test]
fn both_tiers_roll_to_kalkers_steady_creepage() {
    let c = constants(0.5, 0.5, Some(CreepModel::Kuhn));
    let (r, delta) = (1e-3, 2e-6);
    let pm = c.pair_material(Surface::Plane, Surface::Sphere(r));
    let a = (pm.r_star * delta).sqrt();
    let p = hertz::normal_force(&pm, delta);
    for s in [0.2, 0.6, 0.9] {
        let xi = kalker::steady_creepage(s, pm.mu * p, pm.g, a, pm.c11);
        let exact = steady_rolling::<Exact>(xi, 5000);
        let cheap = steady_rolling::<Cheap>(xi, 5000);
        assert!((exact - s).abs() < 1e-6, "exact {s}: {exact}");
        assert!((cheap - s).abs() < 1e-6, "cheap {s}: {cheap}");
    }
}

/// Work of the tangential force over a displacement cycle with varying overlap against
/// stored + dissipated energy.
fn tangential_balance<T: TangentialLaw>() -> (f64, f64) {
    let c = constants(0.4, 0.5, Some(CreepModel::Kuhn));
    let r = 1e-3;
    let dt = 1e-7;
    let mut h = ContactHistory::<T>::default();
    let (mut work, mut diss) = (0.0, 0.0);
    let mut q_prev = Vec3::ZERO;
    let n = 20_000;
    for i in 0..n {
        let t = i as f64 / n as f64;
        let delta = 2e-6 * (1.0 + 0.3 * (6.0 * t).sin());
        let v = Vec3::new(0.02 * (20.0 * t).cos(), 0.015 * (13.0 * t).sin(), 0.0);
        let w = Vec3::new(3.0 * (7.0 * t).sin(), 5.0, 0.0);
        let (p, q, g) = on_plane(r, delta, v, w);
        let f = pair_force(&c, &p, &q, &g, &mut h, dt);
        // Work done on the contact's tangential springs: Q (on p from q) . du_disp, at the
        // mid-step force.
        let q_mid = (q_prev + f.tangential_force) * 0.5;
        work += q_mid.dot(f.v_disp * dt);
        q_prev = f.tangential_force;
        let d = f.dissipation;
        diss += d.slip + d.creep - d.truncation;
    }
    let (_, stored) = h.elastic_energy(&c, Surface::Plane, Surface::Sphere(r));
    (work, stored + diss)
}

#[test]
fn tangential_energy_balance_closes() {
    let (w, e) = tangential_balance::<Exact>();
    assert!(
        w > 0.0 && ((e - w) / w).abs() < 1e-2,
        "exact: work {w}, stored + dissipated {e}"
    );
    let (w, e) = tangential_balance::<Cheap>();
    assert!(
        w > 0.0 && ((e - w) / w).abs() < 1e-2,
        "cheap: work {w}, stored + dissipated {e}"
    );
}

#[test]
fn forces_are_equal_and_opposite_when_p_and_q_swap() {
    let c = constants(0.5, 0.5, Some(CreepModel::Kuhn));
    let r = 1e-3;
    let a = sphere(
        Vec3::new(0.0, 0.0, 0.0),
        Vec3::new(0.01, -0.02, 0.0),
        Vec3::new(1.0, 2.0, -3.0),
        r,
    );
    let b = sphere(
        Vec3::new(1.899e-3, 1e-5, 0.0),
        Vec3::new(-0.01, 0.0, 0.03),
        Vec3::new(0.0, -1.0, 2.0),
        0.9 * r,
    );
    let (mut h1, mut h2) = (
        ContactHistory::<Cheap>::default(),
        ContactHistory::<Cheap>::default(),
    );
    for _ in 0..3 {
        let g1 = ContactGeometry::sphere_sphere(a.position, r, b.position, 0.9 * r).unwrap();
        let g2 = ContactGeometry::sphere_sphere(b.position, 0.9 * r, a.position, r).unwrap();
        let f1 = pair_force(&c, &a, &b, &g1, &mut h1, 1e-7);
        let f2 = pair_force(&c, &b, &a, &g2, &mut h2, 1e-7);
        assert!(f1.touching && f1.tangential_force.length() > 0.0);
        let scale = f1.force_p.length();
        assert!((f1.force_p + f2.force_p).length() < 1e-9 * scale);
        assert!((f1.torque_p - f2.torque_q).length() < 1e-9 * scale * r);
    }
}

#[test]
fn flat_history_round_trips() {
    let c = constants(0.5, 0.5, Some(CreepModel::Kuhn));
    let (p, q, g) = on_plane(
        1e-3,
        2e-6,
        Vec3::new(0.05, 0.01, 0.0),
        Vec3::new(1.0, 3.0, 0.0),
    );
    let mut he = ContactHistory::<Exact>::default();
    let mut hc = ContactHistory::<Cheap>::default();
    for _ in 0..50 {
        pair_force(&c, &p, &q, &g, &mut he, 1e-7);
        pair_force(&c, &p, &q, &g, &mut hc, 1e-7);
    }
    let mut buf = vec![0.0; ContactHistory::<Exact>::LEN];
    he.write(&mut buf).unwrap();
    assert_eq!(ContactHistory::<Exact>::read(&buf).unwrap(), he);
    let mut buf = vec![0.0; ContactHistory::<Cheap>::LEN];
    hc.write(&mut buf).unwrap();
    assert_eq!(ContactHistory::<Cheap>::read(&buf).unwrap(), hc);
    assert_eq!(ContactHistory::<Cheap>::LEN, 13);
    assert!(hc.write(&mut [0.0; 3]).is_err());
    buf[0] = f64::NAN;
    assert!(ContactHistory::<Cheap>::read(&buf).is_err());
}

#[test]
fn bad_constants_are_errors() {
    let m = glass();
    assert!(PairConstants::new(&m, &m, 0.5, 0.0, None, None).is_err());
    assert!(PairConstants::new(&m, &m, 0.5, 1.5, None, None).is_err());
    assert!(PairConstants::new(&m, &m, -0.5, 0.5, None, None).is_err());
    assert!(PairConstants::new(&m, &m, f64::NAN, 0.5, None, None).is_err());
    let pm = PairMaterial::new(&m, &m, Surface::Plane, Surface::Sphere(1.0)).unwrap();
    assert!(PairConstants::from_parts(&pm, f64::NAN, None, None).is_err());
    assert!(!Cheap::supports(Some(CreepModel::FittedTransient)));
    assert!(Exact::supports(Some(CreepModel::FittedTransient)));
}

#[test]
fn inlined_rates_equal_kinematics_contact_rates_bit_for_bit() {
    use crate::kinematics::{BodyMotion, contact_rates};
    let motion = |b: &PairBody| BodyMotion {
        position: b.position,
        velocity: b.velocity,
        angular_velocity: b.angular_velocity,
        surface: b.surface,
    };
    let p = sphere(
        Vec3::new(0.001, -0.002, 0.0005),
        Vec3::new(0.3, -0.1, 0.2),
        Vec3::new(5.0, -3.0, 7.0),
        0.004,
    );
    let q = sphere(
        Vec3::new(0.0085, 0.001, -0.0003),
        Vec3::new(-0.2, 0.4, 0.1),
        Vec3::new(-2.0, 6.0, 1.0),
        0.005,
    );
    let g = ContactGeometry::sphere_sphere(p.position, 0.004, q.position, 0.005).unwrap();
    let (pl, b, gw) = on_plane(
        0.003,
        1e-6,
        Vec3::new(0.1, 0.2, -0.05),
        Vec3::new(3.0, -1.0, 2.0),
    );
    for (p, q, g) in [
        (p, q, g),
        (pl, b, gw),
        (
            b,
            pl,
            ContactGeometry {
                normal: -gw.normal,
                ..gw
            },
        ),
    ] {
        let (r, dd) = rates_and_approach(&p, &q, g.point, g.normal);
        let (mp, mq) = (motion(&p), motion(&q));
        let k = contact_rates(&mp, &mq, g.point, g.normal);
        assert_eq!(r, k);
        let dd0 = -(mq.velocity_at(g.point) - mp.velocity_at(g.point)).dot(g.normal);
        assert_eq!(dd.to_bits(), dd0.to_bits());
    }
}

#[test]
fn inlined_kuhn_creepage_equals_the_steady_law() {
    // The cheap tier's inlined F_ss against SteadyLaw::creepage_for_force, bit for bit, over the
    // force ratio (0 .. past the Coulomb limit), the edge cases (|Q| = 0, mu P = inf, a = 0, NaN)
    // and the fitted law (which takes the general path).
    use crate::steady_law::SteadyLaw;
    let laws = [
        SteadyLaw::with_c11(CreepModel::Kuhn, 0.25, kalker::c11(0.25)),
        SteadyLaw::with_c11(CreepModel::Fitted, 0.25, kalker::c11(0.25)),
    ];
    let (g, a, mu_p) = (2.9e7, 3.1e-5, 0.7);
    let mut cases = vec![
        (0.0, mu_p, g, a),
        (mu_p, mu_p, g, a),
        (2.0 * mu_p, mu_p, g, a),
        (0.3, f64::INFINITY, g, a),
        (0.3, 0.0, g, a),
        (0.3, mu_p, g, 0.0),
        (f64::NAN, mu_p, g, a),
        (0.3, f64::NAN, g, a),
        (f64::INFINITY, mu_p, g, a),
    ];
    for k in 0..=1000 {
        let s = f64::from(k) / 900.0;
        cases.push((s * mu_p, mu_p, g, a * (1.0 + f64::from(k % 7))));
    }
    for law in &laws {
        for &(q, m, g, a) in &cases {
            let want = law.creepage_for_force(q, m, g, a);
            let got = tiers::kuhn_creepage(law, q, m, g, a);
            assert!(
                got.to_bits() == want.to_bits() || (got.is_nan() && want.is_nan()),
                "{law:?} q {q} mu P {m} a {a}: {got} against {want}"
            );
        }
    }
}

#[test]
fn creep_per_force_equals_the_steady_law() {
    // The cheap tier's creep displacement per unit force, `min(F_ss |du_roll|, |Q|/k) / |Q|`,
    // against the same evaluated from SteadyLaw::creepage_for_force: Kalker's law through the
    // identity `1 - c = s/(1 + c + c^2)` (rounding apart: the steady law's `1 - c` loses
    // `log10(3/s)` digits to cancellation, and `1 - s` near s = 1 is ill-conditioned for
    // both, so the bound is `4e-16 (1 + 3/s + 1/(1 - s))` relative), and
    // against the binomial series of `1 - (1 - s)^(1/3)` at small `s`, where `1 - c` is
    // inaccurate; the fitted law and the edge cases (mu P = inf, 0, NaN, a = 0) take the general
    // path, bit for bit.
    use crate::steady_law::SteadyLaw;
    let c11 = kalker::c11(0.25);
    let kuhn = SteadyLaw::with_c11(CreepModel::Kuhn, 0.25, c11);
    let fitted = SteadyLaw::with_c11(CreepModel::Fitted, 0.25, c11);
    let (g, a, mu_p) = (2.9e7, 3.1e-5, 0.7);
    let reference = |law: &SteadyLaw, q: f64, roll: f64, m: f64, a: f64, k: f64| {
        (law.creepage_for_force(q, m, g, a) * roll).min(q / k) / q
    };
    let mut checked = 0;
    for i in 1..=1200 {
        let s = f64::from(i) / 1000.0; // past the Coulomb limit too (s > 1)
        let q = s * mu_p;
        let a = a * (1.0 + f64::from(i % 7));
        for (roll, k) in [(1e-12, 1e5), (1e-9, 1e5), (1e-7, 1e9), (3e-5, 1e9)] {
            let got = tiers::creep_per_force(&kuhn, q * q, roll, mu_p, g, a, k);
            let want = reference(&kuhn, q, roll, mu_p, a, k);
            // Near s = 1, `1 - s` turns an ulp of `s` (here `|Q| (1/(mu P))` against the
            // steady law's `|Q|/(mu P)`) into a relative error `eps s/(1 - s)` of `1 - s`, a third
            // of it in `c`: the condition number of the closed form there, for both.
            let cond = if s < 1.0 { 1.0 / (1.0 - s) } else { 0.0 };
            let tol = 4e-16 * (1.0 + 3.0 / s.min(1.0) + cond) * want;
            assert!(
                got > 0.0 && (got - want).abs() <= tol,
                "s {s} roll {roll} k {k}: {got:e} against {want:e}"
            );
            checked += 1;
            // The general path, bit for bit.
            let got = tiers::creep_per_force(&fitted, q * q, roll, mu_p, g, a, k);
            let want = reference(&fitted, q, roll, mu_p, a, k);
            assert_eq!(got.to_bits(), want.to_bits(), "fitted s {s}");
        }
    }
    assert_eq!(checked, 4800);
    // Both the creep and the cap |Q|/k occur above (the cap for the large increments).
    let creeping = tiers::creep_per_force(&kuhn, 0.25, 1e-12, 1.0, g, a, 1e5);
    let capped = tiers::creep_per_force(&kuhn, 0.25, 3e-5, 1.0, g, a, 1e9);
    assert!(
        creeping > 0.0 && creeping < 1e-5 && capped == 1e-9,
        "{creeping} {capped}"
    );
    // Small force ratios: Kalker's series `1 - (1 - s)^(1/3) = s/3 + s^2/9 + 5 s^3/81 +
    // 10 s^4/243 + 22 s^5/729 + 154 s^6/6561 + ...` (binomial series), so `F_ss/|Q| = 3 (1/3 +
    // s/9 + 5 s^2/81 + ...)/(G a^2 C11)` (truncated: < 1e-19 relative at s = 1e-3), down to
    // s = 1e-20, where the `1 - c` form gives 0; the cap 1/k far away (k = 1e-30 N/m).
    for s in [1e-20, 1e-16, 1e-12, 1e-8, 1e-4, 1e-3] {
        let q = s * mu_p;
        let series = 3.0
            * (1.0 / 3.0
                + s / 9.0
                + 5.0 * s * s / 81.0
                + 10.0 * s.powi(3) / 243.0
                + 22.0 * s.powi(4) / 729.0
                + 154.0 * s.powi(5) / 6561.0)
            / (g * a * a * c11);
        let got = tiers::creep_per_force(&kuhn, q * q, 1.0, mu_p, g, a, 1e-30);
        assert!(
            (got / series - 1.0).abs() < 1e-15,
            "s {s}: {got:e} against {series:e}"
        );
    }
    // The general path's edge cases, bit for bit with the reference.
    for (q, m, a) in [
        (0.3, f64::INFINITY, a),
        (0.3, 0.0, a),
        (0.3, mu_p, 0.0),
        (0.3, f64::NAN, a),
    ] {
        let got = tiers::creep_per_force(&kuhn, q * q, 1e-9, m, g, a, 1e5);
        let want = reference(&kuhn, q, 1e-9, m, a, 1e5);
        assert!(
            got.to_bits() == want.to_bits() || (got.is_nan() && want.is_nan()),
            "q {q} mu P {m} a {a}: {got} against {want}"
        );
    }
}

/// A small deterministic generator (xorshift64) of numbers uniform in `[-0.5, 0.5)`, for the
/// random cases of the tests below.
fn uniform(mut seed: u64) -> impl FnMut() -> f64 {
    move || {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        (seed >> 11) as f64 / (1u64 << 53) as f64 - 0.5
    }
}

#[test]
fn sphere_forms_equal_the_general_ones() {
    // Two spheres: the kernel's short forms of Kuhn & Bagi's rates and of the torques (arms
    // along the normal) against the general ones (kinematics::contact_rates; `(c - x) x f`)
    // on random pairs, to rounding: relative to the size of the terms, 1e-14.
    use crate::kinematics::{BodyMotion, contact_rates};
    let mut rnd = uniform(0x1234_5678_9abc_def1u64);
    let c = constants(0.5, 0.6, Some(CreepModel::Kuhn));
    let mut checked = 0;
    for _ in 0..2000 {
        let (rp, rq) = (0.004 * (1.0 + rnd()), 0.004 * (1.0 + rnd()));
        let dir = Vec3::new(rnd(), rnd(), rnd()).try_normalize().unwrap();
        let xp = Vec3::new(rnd(), rnd(), rnd()) * 0.01;
        let xq = xp + dir * ((rp + rq) * (1.0 - 0.01 * (rnd() + 0.5)));
        let mut v = |s: f64| Vec3::new(rnd(), rnd(), rnd()) * s;
        let p = sphere(xp, v(0.5), v(50.0), rp);
        let q = sphere(xq, v(0.5), v(50.0), rq);
        let g = ContactGeometry::sphere_sphere(p.position, rp, q.position, rq).unwrap();
        let (n, cp) = (g.normal, g.point);
        // The kernel's arms, the radii less half the overlap, are the projections of
        // `c - x_p` and `x_q - c` on the normal, to rounding.
        let (rho_p, rho_q) = (rp - 0.5 * g.overlap, rq - 0.5 * g.overlap);
        for (got, want) in [
            (rho_p, (cp - p.position).dot(n)),
            (rho_q, (q.position - cp).dot(n)),
        ] {
            assert!(
                (got - want).abs() <= 1e-14 * (rp + rq),
                "{got} against {want}"
            );
        }
        let (r, dd) = sphere_rates_and_approach(&p, &q, rho_p, rho_q, n);
        let motion = |b: &PairBody| BodyMotion {
            position: b.position,
            velocity: b.velocity,
            angular_velocity: b.angular_velocity,
            surface: b.surface,
        };
        let (mp, mq) = (motion(&p), motion(&q));
        let k = contact_rates(&mp, &mq, cp, n);
        let dd0 = -(mq.velocity_at(cp) - mp.velocity_at(cp)).dot(n);
        // The size of the terms: the speeds and the spins times the radii.
        let scale = (p.velocity.length() + q.velocity.length())
            + (p.angular_velocity.length() * rp + q.angular_velocity.length() * rq);
        let tol = 1e-14 * scale;
        for (got, want) in [
            (r.v_disp, k.v_disp),
            (r.v_roll, k.v_roll),
            (r.w_roll * rp, k.w_roll * rp),
        ] {
            assert!((got - want).length() <= tol, "{got:?} against {want:?}");
        }
        assert!((r.w_twist - k.w_twist).abs() * rp <= tol);
        assert!((dd - dd0).abs() <= tol, "{dd} against {dd0}");
        // The kernel's torques against the arms' cross products, over a few steps.
        let mut h = ContactHistory::<Cheap>::default();
        for _ in 0..3 {
            let f = pair_force(&c, &p, &q, &g, &mut h, 1e-6);
            assert!(f.touching);
            let tp = (f.point - p.position).cross(f.force_p);
            let tq = (f.point - q.position).cross(-f.force_p);
            let tol = 1e-14 * (rp + rq) * f.force_p.length();
            assert!(
                (f.torque_p - tp).length() <= tol,
                "{:?} against {tp:?}",
                f.torque_p
            );
            assert!(
                (f.torque_q - tq).length() <= tol,
                "{:?} against {tq:?}",
                f.torque_q
            );
            checked += 1;
        }
        // Some tangential force (else the torques would be zero on both sides).
        assert!(h.tangential.q.length() > 0.0);
    }
    assert_eq!(checked, 6000);
}

#[test]
fn carried_tangent_is_the_rotation_to_second_order() {
    // The basis carried by projection against the smallest rotation (Rodrigues, `rotate_to`)
    // and the spin turn: within (theta^2/4) |sin(2 phi)| + rounding for small turns theta of
    // the normal, exact (to rounding) for a tangent in the plane of the turn or along its
    // axis, and the rotation itself for large turns (a half turn reverses the tangent).
    let from = Vec3::new(0.3, -0.5, 0.8).try_normalize().unwrap();
    let (e1, e2) = from.tangent_basis();
    let mut worst_ratio: f64 = 0.0;
    for &theta in &[1e-7, 1e-5, 1e-3, 0.05] {
        for k in 0..24 {
            let psi = f64::from(k) * std::f64::consts::PI / 12.0; // direction of the turn
            let axis = e1 * psi.cos() + e2 * psi.sin();
            let to = rotate_about(from, axis, theta);
            for j in 0..12 {
                let phi = f64::from(j) * std::f64::consts::PI / 12.0; // tangent from the axis
                let t1 = axis * phi.cos() + from.cross(axis) * phi.sin();
                for spin in [0.0, 2e-6, 0.2] {
                    let got = carry_tangent(t1, from, to, spin).unwrap();
                    let want = rotate_about(rotate_to(t1, from, to), to, spin);
                    assert!((got.length() - 1.0).abs() < 1e-15);
                    assert!(got.dot(to).abs() < 1e-15);
                    let dev = (got - want).length();
                    let bound = theta * theta / 4.0 * (2.0 * phi).sin().abs();
                    assert!(
                        dev <= 1.01 * bound + 1e-15,
                        "theta {theta} phi {phi}: {dev:e} > {bound:e}"
                    );
                    if bound > 1e-12 {
                        worst_ratio = worst_ratio.max(dev / bound);
                    }
                }
            }
        }
    }
    // The bound is the actual size of the difference (not a loose one).
    assert!(worst_ratio > 0.9, "{worst_ratio}");
    // Large turns: the rotation. 60 degrees with the tangent along the turn's direction, and
    // a half turn of the normal.
    let axis = e1;
    let to = rotate_about(from, axis, 1.05);
    let t1 = from.cross(axis);
    let got = carry_tangent(t1, from, to, 0.0).unwrap();
    assert!((got - rotate_to(t1, from, to)).length() < 1e-15);
    let got = carry_tangent(e1, from, -from, 0.0).unwrap();
    assert!((got + e1).length() < 1e-15, "{got:?}");
}

#[test]
fn block_equals_the_one_contact_kernel() {
    block_equals_one_contact::<Cheap>();
    block_equals_one_contact::<Exact>();
}

fn block_equals_one_contact<T: TangentialLaw>() {
    // Random sphere pairs in contact, stepped a few times from a loaded history (sticking,
    // sliding and creeping contacts, small and large spins, normals that turn far): every lane
    // the block takes has the one-contact kernel's outputs and history, bit for bit, and the
    // lanes it leaves are untouched; most lanes are taken.
    let mut rnd = uniform(0x2545_f491_4f6c_dd1du64);
    let dt = 2e-6;
    let (mut taken, mut lanes) = (0, 0);
    for (case, creep) in [Some(CreepModel::Kuhn), None]
        .into_iter()
        .cycle()
        .take(1200)
        .enumerate()
    {
        let mu = [0.5, 0.05, 0.0, 1.0][case % 4];
        let c = constants(mu, 0.6, creep);
        assert!(block_supports(&c));
        let mut pairs = SphereLanes::default();
        let mut hist = [ContactHistory::<T>::default(); LANES];
        let mut bodies = Vec::new();
        for l in 0..LANES {
            let (rp, rq) = (0.001 * (1.0 + 0.4 * rnd()), 0.001 * (1.0 + 0.4 * rnd()));
            let dir = Vec3::new(rnd(), rnd(), rnd()).try_normalize().unwrap();
            let xp = Vec3::new(rnd(), rnd(), rnd()) * 0.01;
            let xq = xp + dir * ((rp + rq) * (1.0 - 0.002 * (rnd() + 0.5)));
            let speed = [1e-3, 0.1, 3.0][(case + l) % 3];
            let spin = [1.0, 100.0, 1e3][(case / 3 + l) % 3];
            let mut v = |s: f64| Vec3::new(rnd(), rnd(), rnd()) * s;
            let p = sphere(xp, v(speed), v(spin), rp);
            let q = sphere(xq, v(speed), v(spin), rq);
            // Load the history with a few steps of the kernel (from a virgin contact).
            let g = ContactGeometry::sphere_sphere(p.position, rp, q.position, rq).unwrap();
            for _ in 0..1 + (case + l) % 4 {
                pair_force(&c, &p, &q, &g, &mut hist[l], dt);
            }
            if (case + l) % 7 == 0 {
                // A normal that turned far since the last step: the block leaves it.
                hist[l].normal = hist[l].t1;
            }
            // The next step with the bodies moved on.
            let p = PairBody {
                position: p.position + p.velocity * dt,
                ..p
            };
            let q = PairBody {
                position: q.position + q.velocity * dt,
                ..q
            };
            pairs.set(
                l,
                &SpherePair {
                    xp: p.position,
                    xq: q.position,
                    rp,
                    rq,
                    vp: p.velocity,
                    vq: q.velocity,
                    wp: p.angular_velocity,
                    wq: q.angular_velocity,
                    mp: p.mass,
                    mq: q.mass,
                },
            );
            bodies.push((p, q, rp, rq));
        }
        let before = hist;
        let mut out = [SphereForces::default(); LANES];
        let idx = std::array::from_fn(|l| l);
        let mask = T::sphere_block(&c, &pairs, &mut hist, &mut out, idx, LANES, dt);
        for l in 0..LANES {
            lanes += 1;
            if mask >> l & 1 == 0 {
                assert_eq!(
                    hist[l], before[l],
                    "case {case} lane {l}: a left lane changed"
                );
                continue;
            }
            taken += 1;
            let (p, q, rp, rq) = bodies[l];
            let mut h = before[l];
            let g = ContactGeometry::sphere_sphere(p.position, rp, q.position, rq).unwrap();
            let f = pair_force(&c, &p, &q, &g, &mut h, dt);
            assert!(f.touching);
            let bits3 = |v: Vec3| [v.x.to_bits(), v.y.to_bits(), v.z.to_bits()];
            let o = out[l];
            assert_eq!(
                bits3(o.force_p),
                bits3(f.force_p),
                "case {case} lane {l}: force"
            );
            assert_eq!(bits3(o.torque_p), bits3(f.torque_p), "case {case} lane {l}");
            assert_eq!(bits3(o.torque_q), bits3(f.torque_q), "case {case} lane {l}");
            assert_eq!(o.sliding, f.sliding, "case {case} lane {l}");
            assert_eq!(
                [
                    o.creep_displacement.x.to_bits(),
                    o.creep_displacement.y.to_bits()
                ],
                [
                    f.creep_displacement.x.to_bits(),
                    f.creep_displacement.y.to_bits()
                ],
                "case {case} lane {l}"
            );
            let d = |x: PairDissipation| {
                [x.damping, x.slip, x.creep, x.rolling, x.truncation].map(f64::to_bits)
            };
            assert_eq!(d(o.dissipation), d(f.dissipation), "case {case} lane {l}");
            let hb = |h: &ContactHistory<T>| {
                let mut v = vec![0.0; ContactHistory::<T>::LEN];
                h.write(&mut v).unwrap();
                v.into_iter().map(f64::to_bits).collect::<Vec<_>>()
            };
            assert_eq!(hb(&hist[l]), hb(&h), "case {case} lane {l}: history");
        }
    }
    println!("block ({}) took {taken} of {lanes} lanes", T::NAME);
    assert!(
        taken * 10 > lanes * 6,
        "block took {taken} of {lanes} lanes"
    );
}

#[test]
fn wall_block_equals_the_one_contact_kernel() {
    wall_block_equals_one_contact::<Cheap>();
    wall_block_equals_one_contact::<Exact>();
}

fn wall_block_equals_one_contact<T: TangentialLaw>() {
    // Random spheres pressed onto walls (axis-aligned normals of either sign, as a box's, and
    // oblique ones; walls at rest and moving; frictionless, sticking, sliding and creeping
    // contacts; small and large spins; normals that turned far), stepped a few times from a
    // virgin history by the one-contact kernel, then once more by the block and by the kernel:
    // every lane the block takes has the kernel's outputs and history, bit for bit (the signs
    // of zeros included), the lanes it leaves are untouched, and most lanes are taken.
    let mut rnd = uniform(0x9e37_79b9_7f4a_7c15u64);
    let dt = 2e-6;
    let (mut taken, mut lanes) = (0, 0);
    let axes = [
        Vec3::new(1.0, 0.0, 0.0),
        Vec3::new(-1.0, 0.0, 0.0),
        Vec3::new(0.0, 1.0, 0.0),
        Vec3::new(0.0, -1.0, 0.0),
        Vec3::new(0.0, 0.0, 1.0),
        Vec3::new(0.0, 0.0, -1.0),
    ];
    for (case, creep) in [Some(CreepModel::Kuhn), None]
        .into_iter()
        .cycle()
        .take(1200)
        .enumerate()
    {
        let mu = [0.0, 0.5, 0.05, 1.0][case % 4];
        let c = constants(mu, 0.6, creep);
        assert!(block_supports(&c));
        let mut walls = WallLanes::default();
        let mut hist = [ContactHistory::<T>::default(); LANES];
        let mut bodies = Vec::new();
        for l in 0..LANES {
            let rq = 0.001 * (1.0 + 0.4 * rnd());
            let normal = if (case + l) % 3 == 0 {
                Vec3::new(rnd(), rnd(), rnd()).try_normalize().unwrap()
            } else {
                axes[(case + 2 * l) % 6]
            };
            let point = Vec3::new(rnd(), rnd(), rnd()) * 0.01;
            let along = Vec3::new(rnd(), rnd(), rnd()) * 0.01;
            let xq = point + along.reject(normal) + normal * (rq * (1.0 - 0.002 * (rnd() + 0.5)));
            let speed = [1e-3, 0.1, 3.0][(case + l) % 3];
            let spin = [0.0, 1.0, 100.0, 1e3][(case / 3 + l) % 4];
            let mut v = |s: f64| Vec3::new(rnd(), rnd(), rnd()) * s;
            let velocity = if (case + l) % 2 == 0 {
                Vec3::ZERO
            } else {
                v(speed)
            };
            let q = sphere(xq, v(speed), v(spin), rq);
            let wall = |g: &ContactGeometry| PairBody {
                position: g.point,
                velocity,
                angular_velocity: Vec3::ZERO,
                surface: Surface::Plane,
                mass: f64::INFINITY,
            };
            let g = ContactGeometry::plane_sphere(point, normal, q.position, rq);
            for _ in 0..1 + (case + l) % 4 {
                pair_force(&c, &wall(&g), &q, &g, &mut hist[l], dt);
            }
            if (case + l) % 7 == 0 {
                hist[l].normal = hist[l].t1;
            }
            let point = point + velocity * dt;
            let q = PairBody {
                position: q.position + q.velocity * dt,
                ..q
            };
            walls.set(
                l,
                &WallSphere {
                    point,
                    normal,
                    velocity,
                    xq: q.position,
                    vq: q.velocity,
                    wq: q.angular_velocity,
                    rq,
                    mq: q.mass,
                },
            );
            bodies.push((point, normal, velocity, q, rq));
        }
        let before = hist;
        let mut out = WallForceLanes::default();
        let idx = std::array::from_fn(|l| l);
        let mask = wall_block_lanes(&c, &walls, &mut hist, idx, LANES, dt, &mut out);
        for l in 0..LANES {
            lanes += 1;
            if mask >> l & 1 == 0 {
                assert_eq!(
                    hist[l], before[l],
                    "case {case} lane {l}: a left lane changed"
                );
                continue;
            }
            taken += 1;
            let (point, normal, velocity, q, rq) = bodies[l];
            let mut h = before[l];
            let g = ContactGeometry::plane_sphere(point, normal, q.position, rq);
            let p = PairBody {
                position: g.point,
                velocity,
                angular_velocity: Vec3::ZERO,
                surface: Surface::Plane,
                mass: f64::INFINITY,
            };
            let f = pair_force(&c, &p, &q, &g, &mut h, dt);
            assert!(f.touching);
            let bits3 = |v: Vec3| [v.x.to_bits(), v.y.to_bits(), v.z.to_bits()];
            let lane3 = |a: &[[f64; LANES]; 3]| Vec3::new(a[0][l], a[1][l], a[2][l]);
            assert_eq!(
                bits3(lane3(&out.force_p)),
                bits3(f.force_p),
                "case {case} lane {l}: force"
            );
            assert_eq!(
                bits3(lane3(&out.torque_q)),
                bits3(f.torque_q),
                "case {case} lane {l}: torque"
            );
            assert_eq!(out.sliding[l], f.sliding, "case {case} lane {l}");
            assert_eq!(
                out.creeping[l],
                f.creep_displacement != crate::vector::Vec2::ZERO,
                "case {case} lane {l}"
            );
            let d = |x: PairDissipation| {
                [x.damping, x.slip, x.creep, x.rolling, x.truncation].map(f64::to_bits)
            };
            assert_eq!(
                d(out.dissipation(l)),
                d(f.dissipation),
                "case {case} lane {l}"
            );
            let hb = |h: &ContactHistory<T>| {
                let mut v = vec![0.0; ContactHistory::<T>::LEN];
                h.write(&mut v).unwrap();
                v.into_iter().map(f64::to_bits).collect::<Vec<_>>()
            };
            assert_eq!(hb(&hist[l]), hb(&h), "case {case} lane {l}: history");
        }
    }
    println!("wall block ({}) took {taken} of {lanes} lanes", T::NAME);
    assert!(
        taken * 10 > lanes * 6,
        "wall block took {taken} of {lanes} lanes"
    );
}
