//! Particle-level checks of the compliant (soft-sphere DEM) regime, after Chung & Ooi (2011,
//! "Benchmark tests for verifying discrete element modelling codes at particle impact level",
//! Granular Matter 13, 643-656), against closed forms:
//! 1. elastic normal impact of two identical spheres and of a sphere on a wall: contact duration
//!    and peak force vs Hertz (Johnson 1985, *Contact Mechanics*, §11.4);
//! 2. restitution sweep: the rebound/approach speed ratio vs the requested `e`;
//! 3. oblique impact on a wall at constant normal speed: gross sliding vs Coulomb's impulse
//!    closed forms; sticking (`mu` -> large) vs an independent quadrature of Mindlin's no-slip
//!    law (the problem of Maw, Barber & Fawcett 1976);
//! 4. energy: kinetic + elastic + dissipated constant within 0.1 %;
//! 5. the Rayleigh time-step check.
//!
//! Also: Kuhn's creep term in a driven rolling contact against Kalker's steady creepage, the
//! exact restoration of the user's forces, and f32 resolution against the step size.
//!
//! Materials (Chung & Ooi's tables were not at hand; ours, in their spirit): glass spheres
//! (creep-law `Material::glass`, G = 29 GPa, nu = 0.23, rho = 2500 kg/m^3) of radius 10 mm at
//! 1 m/s relative speed; an aluminium-alloy sphere (E = 70 GPa, nu = 0.33, rho = 2700 kg/m^3) of
//! radius 0.1 m at 0.2 m/s on a wall of the same alloy; an alumina sphere (E = 380 GPa,
//! nu = 0.23, rho = 4000 kg/m^3, mu = 0.092, radius 2.5 mm: Kharaz, Gorham & Salman's 2001
//! experiment, which Chung & Ooi's oblique tests follow) at 3.9 m/s normal speed. Gravity off.
//! `cargo test -p creep-rapier --test compliant -- --nocapture` prints the numbers.

use creep_law::Material;
use creep_rapier::{
    CompliantSettings, CreepMaterial, CreepSettings, CreepWorld, Fidelity, PluginError,
    RayleighCheck,
};
use rapier3d::prelude::*;

/// Friction of the sticking runs: high enough that micro-slip is small up to v_t / v_n = 0.2
/// (at mu = 3 the edge slip put v_t / v_n = 0.2 1.4 % off the no-slip law; creep-law's memory
/// now books the slip of large-mu contacts correctly under varying P).
const MU_STICK: f64 = 30.0;

fn alloy() -> Material {
    let (e, nu) = (70e9, 0.33);
    Material::new(e / (2.0 * (1.0 + nu)), nu, 0.3, 2700.0).unwrap()
}

fn alumina() -> Material {
    let (e, nu) = (380e9, 0.23);
    Material::new(e / (2.0 * (1.0 + nu)), nu, 0.092, 4000.0).unwrap()
}

fn compliant(m: Material) -> Option<CreepMaterial> {
    Some(CreepMaterial::compliant(m))
}

/// A zero-gravity world with one solver iteration (symplectic Euler for the contact forces).
fn world(dt: f64) -> CreepWorld {
    let mut w = CreepWorld::new(dt as f32, CreepSettings::default()).unwrap();
    w.physics.gravity = Vector::ZERO;
    w.physics.integration_parameters.num_solver_iterations = 1;
    w
}

fn ball(r: f64, m: &Material, e: f64, mu: f64) -> Collider {
    ColliderBuilder::ball(r as f32)
        .density(m.density() as f32)
        .restitution(e as f32)
        .friction(mu as f32)
        .build()
}

/// A fixed cuboid wall whose top face is the plane y = `top` [m].
fn add_wall(w: &mut CreepWorld, m: &Material, e: f64, mu: f64, top: f64) {
    let wall = ColliderBuilder::cuboid(1.0, 0.05, 1.0)
        .restitution(e as f32)
        .friction(mu as f32);
    w.insert(
        RigidBodyBuilder::fixed().translation(Vector::new(0.0, (top - 0.05) as f32, 0.0)),
        wall,
        compliant(*m),
    );
}

fn e_star(p: &Material, q: &Material) -> f64 {
    1.0 / ((1.0 - p.poisson_ratio().powi(2)) / p.young_modulus()
        + (1.0 - q.poisson_ratio().powi(2)) / q.young_modulus())
}

fn g_star(p: &Material, q: &Material) -> f64 {
    1.0 / ((2.0 - p.poisson_ratio()) / p.shear_modulus()
        + (2.0 - q.poisson_ratio()) / q.shear_modulus())
}

/// Hertz impact (Johnson 1985, §11.4): contact duration `2.87 (m*^2/(R* E*^2 v))^(1/5)` and
/// peak force from the energy balance, `delta_max = (15 m* v^2 / (16 E* R*^(1/2)))^(2/5)`,
/// `P_max = (4/3) E* R*^(1/2) delta_max^(3/2)`.
fn hertz_impact(m_star: f64, r_star: f64, e_star: f64, v: f64) -> (f64, f64) {
    let t_c = 2.87 * (m_star * m_star / (r_star * e_star * e_star * v)).powf(0.2);
    let d = (15.0 * m_star * v * v / (16.0 * e_star * r_star.sqrt())).powf(0.4);
    (t_c, 4.0 / 3.0 * e_star * r_star.sqrt() * d.powf(1.5))
}

/// What one impact run measured.
#[derive(Debug, Default)]
struct Impact {
    duration: f64,
    peak_force: f64,
    /// Largest |E(t) - E(0)| / E(0), E = kinetic + elastic + dissipated.
    energy_error: f64,
    steps: usize,
}

/// Linear and angular velocities of the dynamic bodies.
fn velocities(w: &CreepWorld) -> Vec<(f64, Vector, Vector, Vector)> {
    w.physics
        .bodies
        .iter()
        .filter(|(_, rb)| rb.is_dynamic())
        .map(|(_, rb)| {
            let i = rb.mass_properties().local_mprops.principal_inertia();
            (f64::from(rb.mass()), rb.linvel(), rb.angvel(), i)
        })
        .collect()
}

/// Kinetic energy `(1/2) m v_a . v_b + (1/2) w_a . I w_b` of two velocity states [J] (spheres:
/// isotropic inertia). With `a = b` the plain kinetic energy; with the velocities before and
/// after a step, the kinetic part of the energy that the symplectic Euler (leapfrog) update
/// conserves exactly for a quadratic potential (Hairer, Lubich & Wanner 2006, *Geometric
/// Numerical Integration*, §I.1.4, Störmer-Verlet with staggered velocities): `x_n` sits between
/// `v_n` and `v_(n+1)`.
fn kinetic_between(
    a: &[(f64, Vector, Vector, Vector)],
    b: &[(f64, Vector, Vector, Vector)],
) -> f64 {
    a.iter()
        .zip(b)
        .map(|((m, v, w, i), (_, v2, w2, _))| {
            0.5 * m * f64::from(v.dot(*v2))
                + 0.5
                    * (f64::from(i.x * w.x * w2.x)
                        + f64::from(i.y * w.y * w2.y)
                        + f64::from(i.z * w.z * w2.z))
        })
        .sum()
}

fn kinetic(w: &CreepWorld) -> f64 {
    let v = velocities(w);
    kinetic_between(&v, &v)
}

#[test]
fn elastic_normal_impact_of_two_spheres() {
    let glass = Material::glass();
    let (r, v) = (0.01, 1.0);
    let m = glass.density() * 4.0 / 3.0 * std::f64::consts::PI * r.powi(3);
    let (t_c, p_max) = hertz_impact(0.5 * m, 0.5 * r, e_star(&glass, &glass), v);
    let mut w = world(t_c / 300.0);
    let gap = 5e-7;
    let (a, _) = w.insert(
        RigidBodyBuilder::dynamic()
            .translation(Vector::new(-(r + gap) as f32, 0.0, 0.0))
            .linvel(Vector::new((v / 2.0) as f32, 0.0, 0.0)),
        ball(r, &glass, 1.0, 0.5),
        compliant(glass),
    );
    let (b, _) = w.insert(
        RigidBodyBuilder::dynamic()
            .translation(Vector::new((r + gap) as f32, 0.0, 0.0))
            .linvel(Vector::new((-v / 2.0) as f32, 0.0, 0.0)),
        ball(r, &glass, 1.0, 0.5),
        compliant(glass),
    );
    let imp = run(&mut w, 20_000);
    // No contact can start unseen: the step's largest displacement is far below the
    // prediction distance that the broad phase adds.
    let prediction = f64::from(w.physics.integration_parameters.prediction_distance());
    assert!(2.0 * w.compliant().counts().max_step_displacement < prediction);
    let va = f64::from(w.physics.bodies[a].linvel().x);
    let vb = f64::from(w.physics.bodies[b].linvel().x);
    println!(
        "two glass spheres R = {r} m, v = {v} m/s: t_c = {:.5e} s (Hertz {t_c:.5e}, {:+.3} %), \
         P_max = {:.4} N (Hertz {p_max:.4}, {:+.3} %), rebound {:.6}, energy error {:.2e}, {} steps",
        imp.duration,
        (imp.duration / t_c - 1.0) * 100.0,
        imp.peak_force,
        (imp.peak_force / p_max - 1.0) * 100.0,
        (vb - va) / v,
        imp.energy_error,
        imp.steps
    );
    assert!((imp.duration / t_c - 1.0).abs() < 0.01);
    assert!((imp.peak_force / p_max - 1.0).abs() < 0.01);
    assert!(((vb - va) / v - 1.0).abs() < 1e-3);
    assert!(imp.energy_error < 1e-3, "energy error {}", imp.energy_error);
}

/// Steps until the contact has opened again; returns the measurements. The energy
/// `E_n = K(v_n, v_(n+1)) + elastic(x_n) + dissipated before step n` ([`kinetic_between`]).
fn run(w: &mut CreepWorld, max_steps: usize) -> Impact {
    let dt = f64::from(w.physics.integration_parameters.dt);
    let mut out = Impact::default();
    let e0 = kinetic(w);
    let mut touched = false;
    let mut diss_before = 0.0;
    for _ in 0..max_steps {
        let before = velocities(w);
        w.step().expect("step");
        out.steps += 1;
        let en = w.compliant().energy();
        let total = kinetic_between(&before, &velocities(w)) + en.elastic() + diss_before;
        diss_before = en.dissipated();
        out.energy_error = out.energy_error.max((total - e0).abs() / e0);
        if w.compliant().counts().contacts > 0 {
            touched = true;
            out.duration += dt;
            for (_, k) in w.compliant().contacts() {
                out.peak_force = out.peak_force.max(k.normal_force);
            }
        } else if touched {
            return out;
        }
    }
    panic!("impact did not end in {max_steps} steps");
}

/// A sphere launched (no gravity) onto the wall with normal speed `v_n` [m/s] and tangential
/// speed `v_t` [m/s], the wall's face at y = -r so that the centre meets it near the origin,
/// where f32 positions are finest; returns the world, the sphere's handle and Hertz's t_c.
fn sphere_on_wall(
    m: &Material,
    r: f64,
    v_n: f64,
    v_t: f64,
    e: f64,
    mu: f64,
    steps_per_contact: f64,
) -> (CreepWorld, RigidBodyHandle, f64) {
    sphere_on_wall_at(m, r, v_n, v_t, e, mu, steps_per_contact, -r)
}

/// [`sphere_on_wall`] with the wall's face at y = `top` [m].
#[allow(clippy::too_many_arguments)]
fn sphere_on_wall_at(
    m: &Material,
    r: f64,
    v_n: f64,
    v_t: f64,
    e: f64,
    mu: f64,
    steps_per_contact: f64,
    top: f64,
) -> (CreepWorld, RigidBodyHandle, f64) {
    let mass = m.density() * 4.0 / 3.0 * std::f64::consts::PI * r.powi(3);
    let (t_c, _) = hertz_impact(mass, r, e_star(m, m), v_n);
    let dt = t_c / steps_per_contact;
    let mut w = world(dt);
    add_wall(&mut w, m, e, mu, top);
    let gap = 3.0 * v_n * dt;
    let (h, _) = w.insert(
        RigidBodyBuilder::dynamic()
            .translation(Vector::new(0.0, (top + r + gap) as f32, 0.0))
            .linvel(Vector::new(v_t as f32, -v_n as f32, 0.0)),
        ball(r, m, e, mu),
        compliant(*m),
    );
    (w, h, t_c)
}

#[test]
fn elastic_normal_impact_on_a_wall() {
    let al = alloy();
    let (r, v) = (0.1, 0.2);
    let (mut w, h, t_c) = sphere_on_wall(&al, r, v, 0.0, 1.0, 0.3, 300.0);
    let mass = f64::from(w.physics.bodies[h].mass());
    let (_, p_max) = hertz_impact(mass, r, e_star(&al, &al), v);
    let imp = run(&mut w, 20_000);
    let vy = f64::from(w.physics.bodies[h].linvel().y);
    println!(
        "alloy sphere R = {r} m on alloy wall, v = {v} m/s: t_c = {:.5e} s (Hertz {t_c:.5e}, \
         {:+.3} %), P_max = {:.2} N (Hertz {p_max:.2}, {:+.3} %), rebound {:.6}, energy error \
         {:.2e}",
        imp.duration,
        (imp.duration / t_c - 1.0) * 100.0,
        imp.peak_force,
        (imp.peak_force / p_max - 1.0) * 100.0,
        vy / v,
        imp.energy_error
    );
    assert!((imp.duration / t_c - 1.0).abs() < 0.01);
    assert!((imp.peak_force / p_max - 1.0).abs() < 0.01);
    assert!((vy / v - 1.0).abs() < 1e-3);
    assert!(imp.energy_error < 1e-3, "energy error {}", imp.energy_error);
}

#[test]
fn restitution_sweep() {
    let al = alloy();
    let (r, v) = (0.1, 0.2);
    for e in [0.1, 0.3, 0.5, 0.7, 0.9] {
        let (mut w, h, _) = sphere_on_wall(&al, r, v, 0.0, e, 0.3, 500.0);
        let imp = run(&mut w, 20_000);
        let got = f64::from(w.physics.bodies[h].linvel().y) / v;
        let en = w.compliant().energy();
        let ke0 = 0.5 * f64::from(w.physics.bodies[h].mass()) * v * v;
        let balance = (kinetic(&w) + en.dissipated()) / ke0 - 1.0;
        println!(
            "restitution: requested {e}, got {got:.5} ({:+.3} %); damping dissipated {:.4e} J, \
             energy balance {balance:+.2e}, {} steps",
            (got / e - 1.0) * 100.0,
            en.damping,
            imp.steps
        );
        assert!((got / e - 1.0).abs() < 0.01, "e = {e}: {got}");
        // The damping work is booked as F_d(x_n) delta_dot(v_n) dt: first order in dt.
        assert!(balance.abs() < 1e-2);
    }
}

/// Mindlin's no-slip law (mu -> infinity) for a sphere of mass `m`, radius `r` meeting a fixed
/// wall with normal speed `v_n` and tangential speed `v_t`, integrated here independently of
/// the plugin: Hertz normal motion, and the tangential force of the springs that entered the
/// contact while it grew, `Q = 8 G* (a U - integral_0^a U_in(x) dx)` (U: tangential displacement
/// of the contact point since first touch; `U_in(x)`: its value when the contact radius passed
/// x; Mindlin & Deresiewicz 1953 as mapped by Popov & Hess 2015, ch. 5). The force acts at the
/// middle of the overlap, `R - delta/2` below the centre. Returns the final tangential velocity
/// of the centre and the spin about z.
fn no_slip_reference(
    m: f64,
    r: f64,
    e_star: f64,
    g_star: f64,
    v_n: f64,
    v_t: f64,
    t_c: f64,
) -> (f64, f64) {
    let inertia = 0.4 * m * r * r;
    let k_h = 4.0 / 3.0 * e_star * r.sqrt();
    let h = t_c / 200_000.0;
    let (mut delta, mut dd) = (0.0f64, v_n);
    let (mut v, mut w) = (v_t, 0.0f64);
    let (mut u, mut integral, mut a_prev) = (0.0f64, 0.0f64, 0.0f64);
    let mut table: Vec<(f64, f64)> = vec![(0.0, 0.0)];
    let mut loading = true;
    for _ in 0..2_000_000 {
        let a = (r * delta.max(0.0)).sqrt();
        if loading && a >= a_prev {
            integral += u * (a - a_prev);
            table.push((a, integral));
        } else {
            loading = false;
            // Interpolate the loading table at a (the springs still attached).
            let i = table
                .partition_point(|&(x, _)| x < a)
                .clamp(1, table.len() - 1);
            let (x0, i0) = table[i - 1];
            let (x1, i1) = table[i];
            integral = if x1 > x0 {
                i0 + (i1 - i0) * (a - x0) / (x1 - x0)
            } else {
                i0
            };
        }
        a_prev = a;
        let q = -8.0 * g_star * (a * u - integral);
        let p = k_h * delta.max(0.0).powf(1.5);
        let arm = r - 0.5 * delta;
        // Symplectic Euler, forces at the start of the step.
        dd -= p / m * h;
        v += q / m * h;
        w += arm * q / inertia * h;
        delta += dd * h;
        u += (v + w * arm) * h;
        if delta <= 0.0 && dd < 0.0 {
            return (v, w);
        }
    }
    panic!("reference impact did not end");
}

#[test]
fn oblique_impact_gross_sliding_and_sticking() {
    let ox = alumina();
    let (r, v_n, mu) = (2.5e-3, 3.9, 0.092);
    // Gross sliding throughout when v_t / v_n > (7/2) mu (1 + e) (Coulomb impulse; 2/5 m R^2).
    for ratio in [1.0, 2.0, 4.0] {
        let v_t = ratio * v_n;
        let (mut w, h, _) = sphere_on_wall(&ox, r, v_n, v_t, 1.0, mu, 1000.0);
        let imp = run(&mut w, 20_000);
        let rb = &w.physics.bodies[h];
        let m = f64::from(rb.mass());
        let (vt, om) = (f64::from(rb.linvel().x), f64::from(rb.angvel().z));
        // Coulomb: tangential impulse mu (1 + e) m v_n opposite to the slip.
        let jt = mu * 2.0 * m * v_n;
        let vt_expect = v_t - jt / m;
        let om_expect = -jt * r / (0.4 * m * r * r);
        let en = w.compliant().energy();
        println!(
            "oblique, sliding: v_t/v_n = {ratio}: v_t' = {vt:.5} (Coulomb {vt_expect:.5}, {:+.3} %), \
             w' = {om:.3} rad/s (Coulomb {om_expect:.3}, {:+.3} %), tangential restitution \
             {:.4}, slip dissipation {:.4e} J, energy error {:.2e}",
            (vt / vt_expect - 1.0) * 100.0,
            (om / om_expect - 1.0) * 100.0,
            (vt + om * r) / v_t,
            en.slip,
            imp.energy_error
        );
        assert!((vt / vt_expect - 1.0).abs() < 0.01);
        assert!((om / om_expect - 1.0).abs() < 0.01);
        assert!(imp.energy_error < 1e-3, "energy error {}", imp.energy_error);
    }
    // Sticking: mu = 30 and a small tangential speed (v_t / v_n far below 7 mu): Mindlin's
    // no-slip law, integrated independently above (`no_slip_reference`). The edge of a Hertz
    // contact always micro-slips, more so as v_t / v_n grows: measured within 0.47 % up to
    // v_t / v_n = 0.2, asserted within 1 %.
    for ratio in [0.02, 0.05, 0.1, 0.2] {
        let v_t = ratio * v_n;
        let (mut w, h, t_c) = sphere_on_wall(&ox, r, v_n, v_t, 1.0, MU_STICK, 1000.0);
        let imp = run(&mut w, 20_000);
        let rb = &w.physics.bodies[h];
        let m = f64::from(rb.mass());
        let (vt, om) = (f64::from(rb.linvel().x), f64::from(rb.angvel().z));
        let (vt_ref, om_ref) =
            no_slip_reference(m, r, e_star(&ox, &ox), g_star(&ox, &ox), v_n, v_t, t_c);
        let dv = vt - v_t;
        let dv_ref = vt_ref - v_t;
        println!(
            "oblique, sticking (mu = {MU_STICK}): v_t/v_n = {ratio}: tangential impulse / m = \
             {dv:.6} m/s (no-slip reference {dv_ref:.6}, {:+.3} %), w' = {om:.4} rad/s \
             (reference {om_ref:.4}, {:+.3} %), contact-point tangential restitution {:.4} \
             (reference {:.4}), energy error {:.2e}",
            (dv / dv_ref - 1.0) * 100.0,
            (om / om_ref - 1.0) * 100.0,
            (vt + om * r) / v_t,
            (vt_ref + om_ref * r) / v_t,
            imp.energy_error
        );
        // The impulse and its moment come from one force at the contact: m R dv = I dw
        // (to the arm's R - delta/2, below 0.2 %).
        assert!((m * r * dv / (0.4 * m * r * r * om) - 1.0).abs() < 2e-3);
        assert!(imp.energy_error < 1e-3, "energy error {}", imp.energy_error);
        assert!((dv / dv_ref - 1.0).abs() < 0.01, "dv {dv} vs {dv_ref}");
        assert!((om / om_ref - 1.0).abs() < 0.01);
    }
}

#[test]
fn rayleigh_time_step_is_checked() {
    let glass = Material::glass();
    let r = 1e-3;
    let t_r = creep_law::hertz::rayleigh_time_step(&glass, r);
    for (fraction, ok) in [(0.1, true), (0.3, false)] {
        let mut w = world(fraction * t_r);
        w.insert(
            RigidBodyBuilder::dynamic(),
            ball(r, &glass, 0.5, 0.5),
            compliant(glass),
        );
        let res = w.step();
        match res {
            Ok(_) => assert!(ok, "dt = {fraction} T_R accepted"),
            Err(PluginError::RayleighTimeStep { rayleigh, .. }) => {
                assert!(!ok, "dt = {fraction} T_R refused");
                assert!((rayleigh / t_r - 1.0).abs() < 1e-6); // radius rounded to f32
            }
            Err(e) => panic!("unexpected error {e}"),
        }
        // As a warning instead.
        w.compliant_mut()
            .set_settings(CompliantSettings {
                rayleigh_check: RayleighCheck::Warn,
                ..CompliantSettings::default()
            })
            .unwrap();
        w.step().unwrap();
        assert_eq!(w.compliant().counts().rayleigh_exceeded, !ok);
    }
}

#[test]
fn substeps_other_than_one_are_refused() {
    let glass = Material::glass();
    let r = 1e-3;
    let mut w = world(0.1 * creep_law::hertz::rayleigh_time_step(&glass, r));
    w.physics.integration_parameters.num_solver_iterations = 4;
    w.insert(
        RigidBodyBuilder::dynamic(),
        ball(r, &glass, 0.5, 0.5),
        compliant(glass),
    );
    assert!(matches!(w.step(), Err(PluginError::CompliantSubsteps(4))));
    w.physics.integration_parameters.num_solver_iterations = 1;
    assert!(w.step().is_ok());
}

#[test]
fn user_forces_are_restored_exactly() {
    let glass = Material::glass();
    let (r, v) = (0.01, 1.0);
    let (mut w, h, _) = sphere_on_wall(&glass, r, v, 0.3, 0.5, 0.5, 200.0);
    let f = Vector::new(0.123_456_7, -1.5e-3, 7.0);
    let tq = Vector::new(-2.5e-4, 3.25, 1e-3);
    w.physics.bodies[h].add_force(f, true);
    w.physics.bodies[h].add_torque(tq, true);
    let mut touched = false;
    for _ in 0..2000 {
        w.step().unwrap();
        touched |= w.compliant().counts().contacts > 0;
        assert_eq!(w.physics.bodies[h].user_force(), f);
        assert_eq!(w.physics.bodies[h].user_torque(), tq);
    }
    assert!(touched);
}

#[test]
fn zero_restitution_is_a_typed_error() {
    let glass = Material::glass();
    let (mut w, _, _) = sphere_on_wall(&glass, 0.01, 1.0, 0.0, 0.0, 0.5, 100.0);
    let mut err = None;
    let mut steps = 0;
    for _ in 0..400 {
        steps += 1;
        if let Err(e) = w.step() {
            err = Some(e);
            break;
        }
    }
    assert!(matches!(err, Some(PluginError::Restitution(_))), "{err:?}");
    // Refused at the first step, before any contact state moved.
    assert_eq!(steps, 1);
    assert_eq!(w.compliant().contacts().count(), 0);
}

/// f32 positions: the per-step displacement `v dt` against the f32 spacing (ulp) of the
/// position, for the alloy sphere of radius 0.1 m (overlap 49 um) at 0.2 m/s with 100 to 4000
/// steps per contact, its centre meeting the wall at y = 0.1 m (ulp 7.5e-9 m) and at y = 0.
/// Printed, not asserted beyond the rebound speed: the energy error grows as `v dt` approaches
/// the ulp (rounding of `x + v dt`), while the time-discretisation error falls with dt.
#[test]
fn f32_resolution_against_step_size() {
    let al = alloy();
    let (r, v) = (0.1, 0.2);
    for (top, steps) in [
        (0.0, 100.0),
        (0.0, 300.0),
        (0.0, 1000.0),
        (0.0, 4000.0),
        (-r, 300.0),
        (-r, 4000.0),
    ] {
        let y = (top + r) as f32;
        let ulp = f64::from(y.next_up() - y).max(f64::from(f32::MIN_POSITIVE));
        let (mut w, h, t_c) = sphere_on_wall_at(&al, r, v, 0.0, 1.0, 0.3, steps, top);
        let imp = run(&mut w, 200_000);
        let dt = f64::from(w.physics.integration_parameters.dt);
        let rebound = f64::from(w.physics.bodies[h].linvel().y) / v;
        println!(
            "f32: centre at y = {y} m, {steps} steps per contact: v dt = {:.3e} ulp, energy \
             error {:.2e}, rebound {rebound:.6}, duration {:+.2} %",
            v * dt / ulp,
            imp.energy_error,
            (imp.duration / t_c - 1.0) * 100.0
        );
        assert!((rebound - 1.0).abs() < 1e-3);
    }
}

/// Kuhn's creep term in the compliant regime: a glass sphere (R = 10 mm) rolling on a glass
/// wall under gravity, driven by a constant horizontal force at its centre so that the wall's
/// friction on it is `Q = (2/7) F = s mu P`. After a few contact radii of rolling, its creepage
/// `|u'| / |v_roll|` (u': slip velocity of its surface at the contact; v_roll: Kuhn & Bagi's
/// rolling velocity) must be Kalker's steady creepage for circular contact (Kalker 2000;
/// Kuhn 2011, eq. 1), `F_ss = 3 mu P / (G a^2 C11) [1 - (1 - s)^(1/3)]`, with P = m g, a from
/// Hertz and C11 from Kalker's table (creep-law `kalker::c11`); with the creep term off
/// (plain Coulomb-Mindlin) the steady creepage must vanish. Plain Cattaneo-Mindlin leaves an
/// undamped tangential oscillation, so the creepage is the ratio of the means of the signed
/// slip and rolling velocities over the last 6,000 steps (some 20 oscillation periods).
#[test]
fn driven_rolling_creeps_at_kalkers_rate() {
    let glass = Material::glass();
    let (r, mu, v0) = (0.01, 0.5, 0.05);
    let t_r = creep_law::hertz::rayleigh_time_step(&glass, r);
    for (s, creep) in [(0.3, true), (0.7, true), (0.7, false)] {
        let mut w = world(0.1 * t_r);
        w.physics.gravity = Vector::new(0.0, -9.81, 0.0);
        w.compliant_mut()
            .set_settings(CompliantSettings {
                creep,
                ..CompliantSettings::default()
            })
            .unwrap();
        add_wall(&mut w, &glass, 0.5, mu, -r);
        let m = glass.density() * 4.0 / 3.0 * std::f64::consts::PI * r.powi(3);
        let p = m * 9.81;
        let es = e_star(&glass, &glass);
        let a = (0.75 * p * r / es).cbrt();
        let delta = a * a / r;
        let (h, _) = w.insert(
            RigidBodyBuilder::dynamic()
                .translation(Vector::new(0.0, -delta as f32, 0.0))
                .linvel(Vector::new(v0 as f32, 0.0, 0.0))
                .angvel(Vector::new(0.0, 0.0, (-v0 / r) as f32)),
            ball(r, &glass, 0.5, mu),
            compliant(glass),
        );
        let mass = f64::from(w.physics.bodies[h].mass());
        let force = 3.5 * s * mu * mass * 9.81;
        w.physics.bodies[h].add_force(Vector::new(force as f32, 0.0, 0.0), true);
        let (mut slip, mut roll) = (0.0, 0.0);
        for i in 0..12_000 {
            w.step().unwrap();
            if i >= 6000 {
                let rb = &w.physics.bodies[h];
                let (vx, wz) = (f64::from(rb.linvel().x), f64::from(rb.angvel().z));
                let c = w
                    .compliant()
                    .contacts()
                    .next()
                    .map(|(_, c)| c.overlap)
                    .unwrap();
                let u = vx + wz * (r - 0.5 * c);
                slip += u;
                roll += (0.5 * u - vx).abs();
            }
        }
        // The wall pushes back against the drive: the sphere's surface slips forwards.
        let xi_mean = slip / roll;
        let c11 = creep_law::kalker::c11(glass.poisson_ratio());
        let expect = if creep {
            3.0 * mu * p / (glass.shear_modulus() * a * a * c11) * (1.0 - (1.0 - s).cbrt())
        } else {
            0.0
        };
        println!(
            "driven rolling, s = {s}, creep {creep}: creepage {xi_mean:.5e} (Kalker F_ss \
             {expect:.5e}{})",
            if creep {
                format!(", {:+.2} %", (xi_mean / expect - 1.0) * 100.0)
            } else {
                String::new()
            }
        );
        if creep {
            assert!((xi_mean / expect - 1.0).abs() < 0.02);
        } else {
            // Against Kalker's creepage at the same s: no creep at all.
            let kalker =
                3.0 * mu * p / (glass.shear_modulus() * a * a * c11) * (1.0 - (1.0 - s).cbrt());
            assert!(xi_mean.abs() < 0.02 * kalker, "{xi_mean}");
        }
    }
}

/// The compliant regime's forces are creep-law's pure pair kernel (`creep_law::pair`): on the
/// same configuration (poses, velocities, contact history) a direct kernel call gives the same
/// normal force, tangential force and contact history to rounding.
#[test]
fn forces_equal_a_direct_kernel_call() {
    use creep_law::pair::{
        ContactGeometry, ContactHistory, Exact, PairBody, PairConstants, pair_force,
    };
    use creep_law::{CreepModel, Surface, Vec3};
    let glass = Material::glass();
    let r = 0.01;
    let t_r = creep_law::hertz::rayleigh_time_step(&glass, r);
    let dt = 0.1 * t_r;
    let mut w = world(dt);
    // Three spheres squeezed in a bent chain, moving and spinning: sliding, rolling, creep.
    let specs = [
        (
            Vector::new(0.0, 0.0, 0.0),
            Vector::new(0.2, 0.05, 0.0),
            Vector::new(0.0, 0.0, 3.0),
        ),
        (
            Vector::new(0.0199, 0.001, 0.0),
            Vector::new(-0.1, 0.0, 0.02),
            Vector::new(1.0, -2.0, 0.0),
        ),
        (
            Vector::new(0.0398, -0.001, 0.0005),
            Vector::new(-0.2, 0.0, 0.0),
            Vector::new(0.0, 4.0, 1.0),
        ),
    ];
    for (x, v, om) in specs {
        w.insert(
            RigidBodyBuilder::dynamic()
                .translation(x)
                .linvel(v)
                .angvel(om),
            ball(r, &glass, 0.5, 0.5),
            compliant(glass),
        );
    }
    for _ in 0..20 {
        w.step().unwrap();
    }
    let before: Vec<_> = w.compliant().contacts().map(|(k, c)| (*k, *c)).collect();
    assert_eq!(before.len(), 2, "both contacts closed");
    let body = |w: &CreepWorld, c: ColliderHandle| {
        let co = &w.physics.colliders[c];
        let rb = &w.physics.bodies[co.parent().unwrap()];
        let v3 = |v: Vector| Vec3::new(f64::from(v.x), f64::from(v.y), f64::from(v.z));
        let centre = v3(co.position().translation);
        let b = PairBody {
            position: v3(rb.center_of_mass()),
            velocity: v3(rb.linvel()),
            angular_velocity: v3(rb.angvel()),
            surface: Surface::Sphere(f64::from(co.shape().as_ball().unwrap().radius)),
            mass: f64::from(rb.mass()),
        };
        (centre, b)
    };
    let constants = PairConstants::new(
        &glass,
        &glass,
        f64::from(0.5f32),
        f64::from(0.5f32),
        Some(CreepModel::Kuhn),
        None,
    )
    .unwrap();
    let direct: Vec<_> = before
        .iter()
        .map(|((c1, c2), rec)| {
            let (x1, p) = body(&w, *c1);
            let (x2, q) = body(&w, *c2);
            let g = ContactGeometry::sphere_sphere(x1, p.surface.radius(), x2, q.surface.radius())
                .unwrap();
            let mut h = ContactHistory::<Exact> {
                tangential: rec.state,
                t1: rec.t1,
                normal: rec.normal,
                rolling: rec.rolling,
                overlap: rec.overlap,
            };
            let f = pair_force(&constants, &p, &q, &g, &mut h, f64::from(dt as f32));
            ((*c1, *c2), f, h)
        })
        .collect();
    // The regime's next step from the same state (its forces come from the poses and
    // velocities at the start of the step, as the direct calls above).
    w.step().unwrap();
    let after: std::collections::HashMap<_, _> =
        w.compliant().contacts().map(|(k, c)| (*k, *c)).collect();
    for (key, f, h) in direct {
        let rec = after[&key];
        let close = |a: f64, b: f64, scale: f64| (a - b).abs() <= 1e-12 * scale;
        let scale = f.normal_force;
        assert!(f.touching && f.tangential_force.length() > 0.0);
        assert!(
            close(rec.normal_force, f.normal_force, scale),
            "{} vs {}",
            rec.normal_force,
            f.normal_force
        );
        assert!((rec.tangential_force - f.tangential_force).length() <= 1e-12 * scale);
        assert_eq!(rec.state, h.tangential);
        assert!((rec.t1 - h.t1).length() < 1e-15);
        println!(
            "kernel vs compliant regime: P = {:.6e} N (diff {:.1e}), |Q| = {:.6e} N (diff {:.1e})",
            f.normal_force,
            rec.normal_force - f.normal_force,
            f.tangential_force.length(),
            (rec.tangential_force - f.tangential_force).length()
        );
    }
}

/// A compliant ball settled on a compliant floor sleeps (a steady contact force does not wake
/// it), and a compliant ball dropped on it wakes it.
#[test]
fn a_settled_compliant_ball_sleeps_and_is_woken_by_a_moving_one() {
    let soft = Material::new(1.0e6, 0.4, 0.5, 1100.0).unwrap();
    let mut w = CreepWorld::new(1.0e-3, CreepSettings::default()).unwrap();
    let mat = compliant(soft);
    w.insert(
        RigidBodyBuilder::fixed().translation(Vector::new(0.0, -0.5, 0.0)),
        ColliderBuilder::cuboid(5.0, 0.5, 5.0).restitution(0.3),
        mat,
    );
    let r = 0.05f32;
    let (low, _) = w.insert(
        RigidBodyBuilder::dynamic().translation(Vector::new(0.0, r + 1e-3, 0.0)),
        ColliderBuilder::ball(r).restitution(0.3),
        mat,
    );
    for _ in 0..3000 {
        w.step().unwrap();
    }
    assert!(
        w.physics.bodies[low].is_sleeping(),
        "the settled ball sleeps"
    );
    let y = w.physics.bodies[low].translation().y;
    w.insert(
        RigidBodyBuilder::dynamic().translation(Vector::new(0.0, y + 2.0 * r + 0.02, 0.0)),
        ColliderBuilder::ball(r).restitution(0.3),
        mat,
    );
    let mut woke = false;
    for _ in 0..300 {
        w.step().unwrap();
        woke |= !w.physics.bodies[low].is_sleeping();
    }
    assert!(woke, "the ball dropped on it wakes it");
    assert!(
        w.physics.bodies[low].translation().y < y,
        "and presses it into the floor"
    );
}

/// Contacts the rigid hook handled in one step, on any of its paths.
fn rigid_contacts(c: &creep_rapier::StepCounts) -> usize {
    c.coulomb_unregistered
        + c.coulomb_unsupported
        + c.coulomb_no_sphere
        + c.coulomb_requested
        + c.coulomb_auto
        + c.creep
        + c.quiet
}

/// A pair of one compliant and one rigid-regime collider is compliant (`Regime::pair`): a
/// compliant sphere on a wall registered in the rigid regime (`Fidelity::Creep`) rebounds as on a
/// compliant wall of the same material, Hertz's contact duration and an elastic rebound, with no
/// solver contact from the rigid hook.
#[test]
fn a_compliant_ball_meets_a_rigid_regime_wall_through_the_compliant_forces() {
    let al = alloy();
    let (r, v) = (0.1, 0.2);
    let mass = al.density() * 4.0 / 3.0 * std::f64::consts::PI * r.powi(3);
    let (t_c, p_max) = hertz_impact(mass, r, e_star(&al, &al), v);
    let dt = t_c / 300.0;
    let mut w = world(dt);
    let wall = ColliderBuilder::cuboid(1.0, 0.05, 1.0)
        .restitution(1.0)
        .friction(0.3);
    let (_, wall) = w.insert(
        RigidBodyBuilder::fixed().translation(Vector::new(0.0, (-r - 0.05) as f32, 0.0)),
        wall,
        Some(CreepMaterial::rigid(al, Fidelity::Creep)),
    );
    let (h, _) = w.insert(
        RigidBodyBuilder::dynamic()
            .translation(Vector::new(0.0, (3.0 * v * dt) as f32, 0.0))
            .linvel(Vector::new(0.0, -v as f32, 0.0)),
        ball(r, &al, 1.0, 0.3),
        compliant(al),
    );
    assert!(!w.registry().get(wall).unwrap().is_compliant());
    let (mut duration, mut peak, mut touched) = (0.0, 0.0f64, false);
    for _ in 0..20_000 {
        let counts = w.step().expect("step");
        assert_eq!(
            rigid_contacts(&counts),
            0,
            "the rigid hook solved a compliant pair"
        );
        let c = w.compliant().counts();
        assert_eq!(c.unsupported, 0);
        if c.contacts > 0 {
            touched = true;
            duration += dt;
            for (_, k) in w.compliant().contacts() {
                peak = peak.max(k.normal_force);
            }
        } else if touched {
            break;
        }
    }
    let vy = f64::from(w.physics.bodies[h].linvel().y);
    println!(
        "compliant alloy sphere on a rigid-regime wall: t_c {duration:.5e} s (Hertz {t_c:.5e}), \
         P_max {peak:.2} N (Hertz {p_max:.2}), rebound {:.6}",
        vy / v
    );
    assert!(touched);
    assert!((duration / t_c - 1.0).abs() < 0.01);
    assert!((peak / p_max - 1.0).abs() < 0.01);
    assert!((vy / v - 1.0).abs() < 1e-3);
}

/// A compliant ball and a rigid-regime shape the compliant regime does not model (a capsule):
/// the pair is compliant, so Rapier gives it no contact, and the compliant regime passes it
/// through, counted in `CompliantCounts::unsupported`; the ball flies on untouched.
#[test]
fn a_compliant_ball_passes_through_a_shape_the_compliant_regime_does_not_model() {
    let glass = Material::glass();
    let r = 0.01;
    let dt = 0.1 * creep_law::hertz::rayleigh_time_step(&glass, r);
    let mut w = world(dt);
    let v0 = Vector::new(10.0, 0.0, 0.0);
    w.insert(
        RigidBodyBuilder::fixed(),
        ColliderBuilder::capsule_y(0.01, 0.005).restitution(0.5),
        Some(CreepMaterial::rigid(glass, Fidelity::Creep)),
    );
    let (h, _) = w.insert(
        RigidBodyBuilder::dynamic()
            .translation(Vector::new(-0.02, 0.0, 0.0))
            .linvel(v0),
        ball(r, &glass, 0.5, 0.5),
        compliant(glass),
    );
    let steps = (0.06 / (10.0 * dt)) as usize;
    let mut unsupported = 0;
    for _ in 0..steps {
        let counts = w.step().expect("step");
        assert_eq!(rigid_contacts(&counts), 0);
        let c = w.compliant().counts();
        assert_eq!(c.contacts, 0);
        unsupported += c.unsupported;
    }
    let rb = &w.physics.bodies[h];
    println!(
        "compliant ball through a rigid-regime capsule: {unsupported} unsupported pair-steps of \
         {steps}, x = {:.4} m",
        rb.translation().x
    );
    assert!(unsupported > 0, "the passed-through pair was not counted");
    assert!(rb.translation().x > 0.03, "the ball did not pass");
    assert_eq!(rb.linvel(), v0);
}
