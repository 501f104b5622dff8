//! The kernel against closed forms, with no engine: a "solver" here is the fixed friction force
//! `Q` the engine would measure, fed back with the kernel's own last target until it settles.

use super::*;
use crate::kinematics::BodyMotion;
use crate::material::{Material, PairMaterial, Surface};
use crate::steady_law::CreepModel;
use crate::{kalker3d, vector::Vec3};

const G: f64 = 9.81;

/// A ball of radius `r` on the fixed plane `y = 0` (body p the plane, q the ball, `n = +y`),
/// rolling along +x at `v` with spin `w_spin` about the normal.
fn rolling_ball(r: f64, v: f64, w_spin: f64) -> (BodyMotion, BodyMotion) {
    let floor = BodyMotion {
        position: Vec3::new(0.0, -1.0, 0.0),
        velocity: Vec3::ZERO,
        angular_velocity: Vec3::ZERO,
        surface: Surface::Plane,
    };
    let ball = BodyMotion {
        position: Vec3::new(0.0, r, 0.0),
        velocity: Vec3::new(v, 0.0, 0.0),
        angular_velocity: Vec3::new(0.0, w_spin, -v / r),
        surface: Surface::Sphere(r),
    };
    (floor, ball)
}

struct BallCase {
    pair: PairMaterial,
    consts: RigidPair,
    contact: RigidContact,
    /// Mass of the ball \[kg\].
    m: f64,
    /// Inverse effective mass of the contact along a tangent (solid sphere on a fixed floor,
    /// `1/m + R^2/I = 7/(2 m)`) \[1/kg\].
    inv_m: f64,
}

/// A ball of `material`, radius `r`, under the normal force `p` \[N\], rolling at `v`.
fn ball_case(material: Material, r: f64, p: f64, v: f64, w_spin: f64, dt: f64) -> BallCase {
    let mu = material.friction();
    let consts = RigidPair::new(&material, &material, mu, CreepModel::Kuhn).unwrap();
    let pair = consts.pair_for(Surface::Plane, Surface::Sphere(r)).unwrap();
    let m = material.density() * 4.0 / 3.0 * std::f64::consts::PI * r.powi(3);
    let (floor, ball) = rolling_ball(r, v, w_spin);
    let contact = RigidContact {
        normal: Vec3::new(0.0, 1.0, 0.0),
        point: Vec3::ZERO,
        p: floor,
        q: ball,
        normal_impulse: p * dt,
        tangent_impulse: Vec3::ZERO,
        last_target: Vec3::ZERO,
        dt,
        auto_tolerance: None,
    };
    BallCase {
        pair,
        consts,
        contact,
        m,
        inv_m: 3.5 / m,
    }
}

/// The kernel's answer once the measured friction force `q` \[N\] (on p) and the target have
/// settled (the fixed point of the implicit solve).
fn settled(case: &BallCase, q: Vec3) -> RigidCreep {
    let mut c = case.contact;
    c.tangent_impulse = q * c.dt;
    let mut out = RigidCreep::coulomb(CoulombReason::NoLoad);
    for _ in 0..200 {
        out = ball_creep(&case.pair, &case.consts, &c, |_| case.inv_m);
        if (out.target - c.last_target).length() <= 1e-15 * out.target.length() {
            break;
        }
        c.last_target = out.target;
    }
    out
}

/// Hertz's contact radius `(3 P R*/(4 E*))^(1/3)` (Johnson 1985, §4.2) \[m\].
fn hertz_a(pair: &PairMaterial, p: f64) -> f64 {
    (3.0 * p * pair.r_star / (4.0 * pair.e_star)).cbrt()
}

/// Kalker's `F_ss(s) = 3 mu P/(G a^2 C11) (1 - (1 - s)^(1/3))` (Kalker 2000; Kuhn 2011).
fn kalker_f_ss(s: f64, mu_p: f64, g: f64, a: f64, c11: f64) -> f64 {
    3.0 * mu_p / (g * a * a * c11) * (1.0 - (1.0 - s).cbrt())
}

#[test]
fn incline_creepage_is_kalkers() {
    // A 0.1 m steel ball rolling down a 20 degree incline at 2 m/s: P = m g cos, Q = (2/7) m g
    // sin (the friction that makes it roll), at 1/240 s.
    let theta = 20f64.to_radians();
    let steel = Material::steel();
    let probe = ball_case(steel, 0.1, 1.0, 2.0, 0.0, 1.0 / 240.0);
    let (p, q) = (
        probe.m * G * theta.cos(),
        2.0 / 7.0 * probe.m * G * theta.sin(),
    );
    let case = ball_case(steel, 0.1, p, 2.0, 0.0, 1.0 / 240.0);
    for sign in [1.0, -1.0] {
        let out = settled(&case, Vec3::new(sign * q, 0.0, 0.0));
        assert!(out.creeps(), "{out:?}");
        let a = hertz_a(&case.pair, p);
        let mu_p = steel.friction() * p;
        let want = kalker_f_ss(q / mu_p, mu_p, case.pair.g, a, case.pair.c11);
        let got = out.target.x * sign / 2.0;
        assert!((got / want - 1.0).abs() < 1e-9, "{got} vs {want}");
        assert!(out.target.y.abs() < 1e-15 && out.target.z.abs() < 1e-15);
        // The force it was built for is the measured one; the booked power is Q . target.
        assert!((out.force.x - sign * q).abs() < 1e-9 * q, "{:?}", out.force);
        assert!((out.power - q * got * 2.0).abs() < 1e-9 * out.power);
        assert_eq!(out.moment, Vec3::ZERO);
    }
}

#[test]
fn follows_kalkers_curve_to_saturation() {
    let steel = Material::steel();
    let (p, v) = (40.0, 1.0);
    let case = ball_case(steel, 0.05, p, v, 0.0, 1.0 / 60.0);
    let mu_p = steel.friction() * p;
    let a = hertz_a(&case.pair, p);
    for s in [0.05, 0.2, 0.4, 0.6, 0.8, 0.9, 0.95] {
        let out = settled(&case, Vec3::new(s * mu_p, 0.0, 0.0));
        let want = kalker_f_ss(s, mu_p, case.pair.g, a, case.pair.c11);
        let got = out.target.length() / v;
        assert!((got / want - 1.0).abs() < 1e-8, "s = {s}: {got} vs {want}");
    }
    // Beyond the capacity the contact slides at mu P with the full-slip creepage.
    let out = ball_creep(
        &case.pair,
        &case.consts,
        &RigidContact {
            tangent_impulse: Vec3::new(2.0 * mu_p * case.contact.dt, 0.0, 0.0),
            ..case.contact
        },
        |_| case.inv_m,
    );
    assert!((out.force.length() / mu_p - 1.0).abs() < 1e-12);
    let full = kalker_f_ss(1.0, mu_p, case.pair.g, a, case.pair.c11);
    assert!((out.target.length() / v / full - 1.0).abs() < 1e-12);
}

#[test]
fn lateral_slope_is_kalkers_c22() {
    // A small lateral load: eta = Q_y/(G a^2 C22) (Kalker's linear theory, Kalker 1990,
    // Table E.3 at a/b = 1), to the law's curvature O(s) at s = 1e-3.
    for material in [Material::steel(), Material::rubber()] {
        let p = 20.0;
        let case = ball_case(material, 0.05, p, 1.0, 0.0, 1.0 / 120.0);
        let mu_p = material.friction() * p;
        let q = 1e-3 * mu_p;
        let out = settled(&case, Vec3::new(0.0, 0.0, q));
        let a = hertz_a(&case.pair, p);
        let c22 = kalker3d::coefficients(1.0, case.pair.nu).unwrap().c22;
        let want = q / (case.pair.g * a * a * c22);
        let got = out.target.z;
        assert!(out.creeps() && out.target.x.abs() < 1e-12 * got.abs());
        assert!((got / want - 1.0).abs() < 1e-3, "{got} vs {want}");
    }
}

#[test]
fn spin_decay_rate_is_kalkers_linear_theory() {
    // A free rubber ball (0.05 m) rolling at 1 m/s and spinning at 0.15 rad/s about the normal on
    // a fixed floor. Kalker's linear theory (Kalker 1967; project signs, c = a):
    // Fy = G a^2 C22 eta + G a^3 C23 phi, Mz = -G a^3 C23 eta + G a^4 C33 phi, phi = w/V. A free
    // ball carries no lateral force (Fy = 0, so eta = -(C23/C22) a phi), which leaves
    // Mz = G a^4 (C33 + C23^2/C22) phi and the decay rate lambda = G a^4 (C33 + C23^2/C22)/(I V),
    // I = (2/5) m R^2 (creep-scenes' spinning ball), to the non-linear law's O(phi_n).
    let rubber = Material::rubber();
    let (r, v, w) = (0.05, 1.0, 0.15);
    let probe = ball_case(rubber, r, 1.0, v, w, 1.0 / 240.0);
    let p = probe.m * G;
    let case = ball_case(rubber, r, p, v, w, 1.0 / 240.0);
    // A small longitudinal load (above the solver's noise), none across.
    let out = settled(&case, Vec3::new(1e-3 * rubber.friction() * p, 0.0, 0.0));
    assert!(out.creeps());
    assert!(out.force.z.abs() < 1e-9 * out.force.x, "{:?}", out.force);
    let n = case.contact.normal;
    let mz_q = out.moment.dot(n);
    assert!(
        mz_q * w < 0.0,
        "the moment opposes the relative spin: {mz_q}"
    );
    let a = hertz_a(&case.pair, p);
    let k = kalker3d::coefficients(1.0, case.pair.nu).unwrap();
    let inertia = 0.4 * case.m * r * r;
    let rate = -mz_q / (inertia * w);
    let want = case.pair.g * a.powi(4) * (k.c33 + k.c23 * k.c23 / k.c22) / (v * inertia);
    let phi_n = w / v * case.pair.g * a.powi(3) / (rubber.friction() * p);
    assert!(
        (rate / want - 1.0).abs() < 2.0 * phi_n.max(1e-3),
        "{rate} vs {want} (phi_n {phi_n})"
    );
    // The spin's power is booked: Mz w_twist >= 0 on top of Q . target.
    assert!(out.power >= out.force.dot(out.target));
}

#[test]
fn implicit_solve_is_stable_at_loop_gains_above_one() {
    // A light rubber ball at a long step: the explicit loop would diverge (g > 1). The engine's
    // friction row is modelled as transmitting Q = Q_free - (m_t/dt) tau for a target tau
    // against a fixed demand Q_free: the kernel settles at once on q + K F(q) = |Q_free|.
    let rubber = Material::rubber();
    let (r, v, dt) = (0.1, 20.0, 1.0 / 30.0);
    let p = ball_case(rubber, r, 1.0, v, 0.0, dt).m * G;
    let case = ball_case(rubber, r, p, v, 0.0, dt);
    let m_t = 1.0 / case.inv_m;
    let q_free = 0.5 * rubber.friction() * p;
    let mut c = case.contact;
    let mut last = RigidCreep::coulomb(CoulombReason::NoLoad);
    for step in 0..6 {
        let q = q_free - m_t / dt * c.last_target.x;
        c.tangent_impulse = Vec3::new(q * dt, 0.0, 0.0);
        let out = ball_creep(&case.pair, &case.consts, &c, |_| case.inv_m);
        assert!(out.loop_gain > 1.0, "{}", out.loop_gain);
        if step > 1 {
            assert!((out.target.x - last.target.x).abs() <= 1e-12 * out.target.x);
        }
        c.last_target = out.target;
        last = out;
    }
    let q = last.force.x;
    let a = hertz_a(&case.pair, p);
    let mu_p = rubber.friction() * p;
    let f = kalker_f_ss(q / mu_p, mu_p, case.pair.g, a, case.pair.c11);
    assert!((q + m_t * v / dt * f - q_free).abs() < 1e-9 * q_free);
}

#[test]
fn leaves_unloaded_resting_quiet_and_auto_contacts_to_coulomb() {
    let steel = Material::steel();
    let case = ball_case(steel, 0.05, 10.0, 1.0, 0.0, 1.0 / 60.0);
    let run = |c: RigidContact| ball_creep(&case.pair, &case.consts, &c, |_| case.inv_m);
    let loaded = RigidContact {
        tangent_impulse: Vec3::new(1.0 * case.contact.dt, 0.0, 0.0),
        ..case.contact
    };
    assert!(run(loaded).creeps());
    let new = RigidContact {
        normal_impulse: 0.0,
        ..loaded
    };
    assert_eq!(run(new), RigidCreep::coulomb(CoulombReason::NoLoad));
    let (floor, mut ball) = rolling_ball(0.05, 0.0, 0.0);
    ball.velocity = Vec3::ZERO;
    let resting = RigidContact {
        p: floor,
        q: ball,
        ..loaded
    };
    assert_eq!(run(resting), RigidCreep::coulomb(CoulombReason::NotRolling));
    let quiet = RigidContact {
        tangent_impulse: Vec3::ZERO,
        ..loaded
    };
    assert_eq!(run(quiet), RigidCreep::coulomb(CoulombReason::BelowNoise));
    let auto = RigidContact {
        auto_tolerance: Some(1.0),
        ..loaded
    };
    assert_eq!(
        run(auto),
        RigidCreep::coulomb(CoulombReason::BelowTolerance)
    );
    let auto = RigidContact {
        auto_tolerance: Some(1e-9),
        ..loaded
    };
    assert!(run(auto).creeps());
}

/// A wheel of radius `r` (axle along z) on the fixed plane `y = 0`, rolling along +x at `v`:
/// body p the wheel, q the floor, `n = -y` (from the wheel to the floor).
fn wheel_case(
    contact: WheelContact,
    r: f64,
    p: f64,
    v: f64,
    dt: f64,
) -> (WheelInput, RigidContact) {
    let floor = BodyMotion {
        position: Vec3::new(0.0, -1.0, 0.0),
        velocity: Vec3::ZERO,
        angular_velocity: Vec3::ZERO,
        surface: Surface::Plane,
    };
    let wheel = BodyMotion {
        position: Vec3::new(0.0, r, 0.0),
        velocity: Vec3::new(v, 0.0, 0.0),
        angular_velocity: Vec3::new(0.0, 0.0, -v / r),
        surface: Surface::Sphere(r),
    };
    let input = WheelInput {
        axle: Vec3::new(0.0, 0.0, 1.0),
        radius: r,
        contact,
        wheel_is_p: true,
        spin: true,
    };
    let c = RigidContact {
        normal: Vec3::new(0.0, -1.0, 0.0),
        point: Vec3::ZERO,
        p: wheel,
        q: floor,
        normal_impulse: p * dt,
        tangent_impulse: Vec3::ZERO,
        last_target: Vec3::ZERO,
        dt,
        auto_tolerance: None,
    };
    (input, c)
}

fn settled_wheel(pair: &PairMaterial, wheel: &WheelInput, c: RigidContact, q: Vec3) -> RigidCreep {
    let mut c = RigidContact {
        tangent_impulse: q * c.dt,
        ..c
    };
    let mut laws = LawCache::default();
    let mut out = RigidCreep::coulomb(CoulombReason::NoLoad);
    for _ in 0..200 {
        out = wheel_creep(pair, wheel, &c, &mut laws, || None, |_| 3.0);
        if (out.target - c.last_target).length() <= 1e-15 * out.target.length() {
            break;
        }
        c.last_target = out.target;
    }
    out
}

#[test]
fn line_wheel_follows_carter() {
    // Carter (1926; Johnson 1985, eq. 8.38): xi = (mu a/R)(1 - sqrt(1 - Q/(mu P))), with the
    // half-width a = sqrt(4 (P/L) R/(pi E*)) (Johnson 1985, eq. 4.43).
    let rubber = Material::rubber();
    let consts = RigidPair::new(&rubber, &rubber, rubber.friction(), CreepModel::Kuhn).unwrap();
    let (r, width, p, v) = (0.05, 0.04, 5.0, 0.1);
    let pair = consts.pair_for(Surface::Sphere(r), Surface::Plane).unwrap();
    let (wheel, c) = wheel_case(WheelContact::Line { width }, r, p, v, 1.0 / 60.0);
    let mu_p = rubber.friction() * p;
    let a = (4.0 * (p / width) * r / (std::f64::consts::PI * pair.e_star)).sqrt();
    for s in [0.1, 0.5, 0.9] {
        let out = settled_wheel(&pair, &wheel, c, Vec3::new(s * mu_p, 0.0, 0.0));
        let want = rubber.friction() * a / r * (1.0 - (1.0 - s).sqrt());
        let got = out.target.length() / v;
        assert!((got / want - 1.0).abs() < 1e-8, "s = {s}: {got} vs {want}");
        assert_eq!(out.moment, Vec3::ZERO);
    }
}

#[test]
fn crowned_wheel_lateral_slope_is_kalkers_c22() {
    // Hertz's ellipse of a crowned wheel, eta = Q_y/(G c^2 C22(a/b)), c^2 = a b.
    let rubber = Material::rubber();
    let consts = RigidPair::new(&rubber, &rubber, rubber.friction(), CreepModel::Kuhn).unwrap();
    let (r, crown, p, v) = (0.05, 0.2, 5.0, 0.1);
    let pair = consts.pair_for(Surface::Sphere(r), Surface::Plane).unwrap();
    let contact = WheelContact::crowned(r, crown, pair.e_star).unwrap();
    let (wheel, c) = wheel_case(contact, r, p, v, 1.0 / 60.0);
    let h = crate::elliptic::elliptic_hertz(1.0 / r, 1.0 / crown, p, pair.e_star).unwrap();
    let c22 = kalker3d::coefficients(h.a / h.b, pair.nu.clamp(0.0, 0.5))
        .unwrap()
        .c22;
    let q = 1e-3 * rubber.friction() * p;
    let out = settled_wheel(&pair, &wheel, c, Vec3::new(0.0, 0.0, q));
    let want = q / (pair.g * h.a * h.b * c22);
    let got = out.target.z.abs() / v;
    assert!((got / want - 1.0).abs() < 2e-3, "{got} vs {want}");
}

#[test]
fn solver_noise_force_scales_with_the_surface_speed_and_the_effective_mass() {
    let ball = |v: f64, w: f64| BodyMotion {
        position: Vec3::new(0.0, 0.1, 0.0),
        velocity: Vec3::new(v, 0.0, 0.0),
        angular_velocity: Vec3::new(0.0, 0.0, w),
        surface: Surface::Sphere(0.1),
    };
    let ground = BodyMotion {
        position: Vec3::ZERO,
        velocity: Vec3::ZERO,
        angular_velocity: Vec3::ZERO,
        surface: Surface::Plane,
    };
    let c = Vec3::ZERO;
    // u = |v| + |w| |c - x| = 2 + 20 * 0.1 = 4 m/s; m_t = 1 / 0.5 kg; dt = 1/60 s.
    let f = solver_noise_force(&ball(2.0, -20.0), &ground, c, 0.5, 1.0 / 60.0);
    let expected = NOISE_ULPS * f64::from(f32::EPSILON) * 4.0 * 2.0 * 60.0;
    assert!(
        (f - expected).abs() <= 1e-12 * expected,
        "{f} vs {expected}"
    );
    // Twice the speed, twice the floor; a fixed pair (no dynamic body) has none.
    let f2 = solver_noise_force(&ball(4.0, -40.0), &ground, c, 0.5, 1.0 / 60.0);
    assert!((f2 / f - 2.0).abs() < 1e-12);
    assert_eq!(
        solver_noise_force(&ball(2.0, -20.0), &ground, c, 0.0, 1.0 / 60.0),
        0.0
    );
    // At rest: no floor, so a real load on a resting contact always creeps.
    assert_eq!(
        solver_noise_force(&ball(0.0, 0.0), &ground, c, 0.5, 1.0 / 60.0),
        0.0
    );
}

#[test]
fn carter_matches_its_closed_form() {
    let (mu_p, p, a, r) = (0.9, 1.0, 1e-3, 0.05);
    for s in [0.0f64, 0.1, 0.5, 0.9, 1.0] {
        let want = (0.9 * a / r) * (1.0 - (1.0 - s).sqrt());
        let got = wheel::carter_creepage(s * mu_p, mu_p, p, a, r);
        assert!(
            (got - want).abs() <= 1e-15 + 1e-12 * want,
            "{s}: {got} {want}"
        );
    }
    // Linear slope: xi = a q/(2 R P).
    let q = 1e-9;
    assert!(
        (wheel::carter_creepage(q, mu_p, p, a, r) / (a * q / (2.0 * r * p)) - 1.0).abs() < 1e-8
    );
    assert_eq!(wheel::carter_creepage(0.5, 0.0, p, a, r), 0.0);
}

#[test]
fn combined_solve_meets_the_law_and_its_implicit_relation() {
    // L(z, phi_n) + kappa z = q*, and the loads returned are the law's at z.
    for ab in [0.5, 1.0] {
        for nu in [0.25, 0.5] {
            let law = crate::steady3d::Steady3d::new(ab, nu).unwrap();
            assert!(law.tabulated(), "a/b {ab}, nu {nu}");
            for (q_star, kappa, phi_n) in [
                ((0.3, -0.2), 2.0, 0.0),
                ((-0.5, 0.4), 0.5, 0.3),
                ((0.05, -0.3), 10.0, 0.8),
                ((0.2, 0.6), 0.2, -0.5),
                ((-0.1, -0.05), 40.0, 0.1),
            ] {
                let c = solve_combined(&law, q_star, kappa, phi_n, (0.0, 0.0));
                let (x, y) = c.creepage;
                let l = law.loads(x, y, phi_n);
                assert_eq!((l.fx, l.fy, l.mz), (c.loads.fx, c.loads.fy, c.loads.mz));
                let (ex, ey) = (l.fx + kappa * x - q_star.0, l.fy + kappa * y - q_star.1);
                assert!(
                    ex.abs().max(ey.abs()) < 1e-9,
                    "a/b {ab}, nu {nu}, {q_star:?}, {kappa}, {phi_n}: {ex} {ey}"
                );
                assert!(c.residual < 1e-9);
            }
        }
    }
}

/// A crowned wheel at a/b = `ab` (semi-axes at 1 N set directly) spinning at `phi_n`: its force
/// is the 3-D law's at the creepages of its target, and the implicit relation holds.
fn crowned_wheel_is_the_combined_law(ab: f64, phi_n: f64, q_n: (f64, f64)) {
    let rubber = Material::rubber();
    let consts = RigidPair::new(&rubber, &rubber, rubber.friction(), CreepModel::Kuhn).unwrap();
    let (r, p, v, dt) = (0.05, 5.0, 0.1, 1.0 / 60.0);
    let pair = consts.pair_for(Surface::Sphere(r), Surface::Plane).unwrap();
    let a1 = match WheelContact::crowned(r, r, pair.e_star).unwrap() {
        WheelContact::Crowned { a1, .. } => a1,
        WheelContact::Line { .. } => unreachable!(),
    };
    let contact = WheelContact::Crowned { a1, b1: a1 / ab };
    let (wheel, mut c) = wheel_case(contact, r, p, v, dt);
    let mu_p = rubber.friction() * p;
    let (a, b) = (a1 * p.cbrt(), a1 / ab * p.cbrt());
    let c2 = a * b;
    // The frame is (x, z) (n = -y); the wheel is p: w_twist = -w_p . n = w_p.y.
    let w = phi_n * mu_p * v / (pair.g * c2 * c2.sqrt());
    c.p.angular_velocity.y = w;
    let law = crate::steady3d::Steady3d::new(ab, pair.nu.clamp(0.0, 0.5)).unwrap();
    assert!(law.tabulated());
    let q = Vec3::new(q_n.0 * mu_p, 0.0, q_n.1 * mu_p);
    let scale = pair.g * c2 / mu_p;
    let check = |out: &RigidCreep, what: &str| {
        assert!(out.creeps(), "{what}");
        let (cx, cy) = (out.target.x / v, out.target.z / v);
        let l = law.loads(cx * scale, cy * scale, phi_n);
        let (ex, ey) = (out.force.x / mu_p - l.fx, out.force.z / mu_p - l.fy);
        assert!(
            ex.abs().max(ey.abs()) < 1e-6,
            "{what} a/b {ab}, phi_n {phi_n}, {q_n:?}: force {:?} vs the law's {l:?}",
            out.force * (1.0 / mu_p)
        );
    };
    // Settled: the force is the measured one.
    let out = settled_wheel(&pair, &wheel, c, q);
    check(&out, "settled");
    let e = (out.force - q).length() / mu_p;
    assert!(e < 1e-6, "settled force off by {e} mu P");
    // One step from another target: Q + (m_t/dt) tau = Q_measured + (m_t/dt) tau_prev.
    let c = RigidContact {
        tangent_impulse: q * dt,
        last_target: out.target * 0.5 + Vec3::new(1e-4, 0.0, -2e-4),
        ..c
    };
    let mut laws = LawCache::default();
    let one = wheel_creep(&pair, &wheel, &c, &mut laws, || None, |_| 3.0);
    check(&one, "one step");
    let m_dt = 1.0 / (3.0 * dt);
    let e = (one.force + one.target * m_dt - q - c.last_target * m_dt).length() / mu_p;
    assert!(e < 1e-6, "implicit relation off by {e} mu P");
}

#[test]
fn crowned_wheel_force_is_the_combined_law_at_its_creepages() {
    for ab in [0.5, 1.0] {
        for (phi_n, q_n) in [
            (0.0, (0.3, 0.2)),
            (0.3, (0.1, 0.2)),
            (0.3, (-0.05, -0.4)),
            (-0.6, (0.4, 0.1)),
            (0.1, (-0.2, 0.05)),
        ] {
            crowned_wheel_is_the_combined_law(ab, phi_n, q_n);
        }
    }
}

/// The implicit solve's residual stop (`solve_translation`) assumes `F(q)/q` never falls with
/// `q`: checked for every creep model at `nu` over `[0, 0.5]`.
#[test]
fn creepage_over_force_never_falls() {
    use crate::steady_law::SteadyLaw;
    for model in [
        crate::CreepModel::Kuhn,
        crate::CreepModel::Fitted,
        crate::CreepModel::FittedTransient,
    ] {
        for k in 0..=10 {
            let law = SteadyLaw::new(model, 0.05 * k as f64);
            let mut last = 0.0;
            for i in 1..=2000 {
                let q = i as f64 / 2000.0;
                let r = law.creepage_for_force(q, 1.0, 1.0, 1.0) / q;
                assert!(
                    r >= last * (1.0 - 1e-12),
                    "{model:?} nu {} q {q}: {r} < {last}",
                    0.05 * k as f64
                );
                last = r;
            }
        }
    }
}
