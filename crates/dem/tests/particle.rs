//! Particle-level checks of the creep-dem engine, the set the compliant regime of creep-rapier
//! passes (crates/rapier/tests/compliant.rs, after Chung & Ooi 2011, "Benchmark tests for
//! verifying discrete element modelling codes at particle impact level", Granular Matter 13,
//! 643-656) with the same tolerances, for both tangential tiers where the tier matters:
//! 1. elastic normal impact of two identical spheres and of a sphere on a wall: contact duration
//!    and peak force vs Hertz (Johnson 1985, §11.4), rebound, energy;
//! 2. restitution sweep;
//! 3. oblique impact on a wall: gross sliding vs Coulomb's impulse; sticking vs an independent
//!    quadrature of Mindlin's no-slip law (exact tier);
//! 4. energy bookkeeping of a settling packing (kinetic + potential + elastic + dissipated);
//! 5. the neighbour list against a brute-force search, periodic boundaries, determinism (also
//!    between the portable and the AVX2 copies of the force loops).
//!
//! `cargo test -p creep-dem --test particle -- --nocapture` prints the numbers.

use creep_dem::{
    Cheap, Dem, DemConfig, Exact, ExternalForces, ExternalView, Kernels, MaterialTable, Particle,
    Wall,
};
use creep_law::pair::TangentialLaw;
use creep_law::{CreepModel, Material, Vec3};

const MU_STICK: f64 = 30.0;

fn alloy(mu: f64) -> Material {
    let (e, nu) = (70e9, 0.33);
    Material::new(e / (2.0 * (1.0 + nu)), nu, mu, 2700.0).unwrap()
}

fn alumina(mu: f64) -> Material {
    let (e, nu) = (380e9, 0.23);
    Material::new(e / (2.0 * (1.0 + nu)), nu, mu, 4000.0).unwrap()
}

fn e_star(p: &Material, q: &Material) -> f64 {
    1.0 / ((1.0 - p.poisson_ratio().powi(2)) / p.young_modulus()
        + (1.0 - q.poisson_ratio().powi(2)) / q.young_modulus())
}

fn g_star(p: &Material, q: &Material) -> f64 {
    1.0 / ((2.0 - p.poisson_ratio()) / p.shear_modulus()
        + (2.0 - q.poisson_ratio()) / q.shear_modulus())
}

/// Hertz impact (Johnson 1985, §11.4): duration and peak force.
fn hertz_impact(m_star: f64, r_star: f64, e_star: f64, v: f64) -> (f64, f64) {
    let t_c = 2.87 * (m_star * m_star / (r_star * e_star * e_star * v)).powf(0.2);
    let d = (15.0 * m_star * v * v / (16.0 * e_star * r_star.sqrt())).powf(0.4);
    (t_c, 4.0 / 3.0 * e_star * r_star.sqrt() * d.powf(1.5))
}

fn sphere_mass(m: &Material, r: f64) -> f64 {
    m.density() * 4.0 / 3.0 * std::f64::consts::PI * r.powi(3)
}

#[derive(Debug, Default)]
struct Impact {
    duration: f64,
    peak_force: f64,
    energy_error: f64,
    steps: usize,
}

/// Steps until the contact has opened again. Energy: kinetic + elastic + dissipated.
fn run<T: TangentialLaw>(d: &mut Dem<T>, max_steps: usize) -> Impact {
    let dt = d.config().dt;
    let mut out = Impact::default();
    let e0 = d.kinetic_energy();
    let mut touched = false;
    for _ in 0..max_steps {
        d.step().unwrap();
        out.steps += 1;
        let en = d.energy();
        let total = d.kinetic_energy() + en.elastic() + en.dissipated();
        out.energy_error = out.energy_error.max((total - e0).abs() / e0);
        let c = d.counts();
        if c.contacts + c.wall_contacts > 0 {
            touched = true;
            out.duration += dt;
            let mut peak: f64 = 0.0;
            for k in 0..d.walls().len() {
                peak = peak.max(d.wall_force(k).length());
            }
            if d.walls().is_empty() {
                // Two spheres: the force on one of them.
                let m = d.mass(0);
                let _ = m;
            }
            out.peak_force = out.peak_force.max(peak);
        } else if touched {
            return out;
        }
    }
    panic!("impact did not end in {max_steps} steps");
}

fn cfg(dt: f64, skin: f64) -> DemConfig {
    DemConfig {
        dt,
        skin,
        ..DemConfig::default()
    }
}

fn particle(x: Vec3, v: Vec3, r: f64) -> Particle {
    Particle {
        position: x,
        velocity: v,
        angular_velocity: Vec3::ZERO,
        radius: r,
        material: 0,
    }
}

#[test]
fn elastic_normal_impact_of_two_spheres() {
    let glass = Material::glass();
    let (r, v) = (0.01, 1.0);
    let m = sphere_mass(&glass, r);
    let (t_c, p_max) = hertz_impact(0.5 * m, 0.5 * r, e_star(&glass, &glass), v);
    let table = MaterialTable::new(&[glass], 1.0, Some(CreepModel::Kuhn), None).unwrap();
    let gap = 5e-7;
    let ps = [
        particle(
            Vec3::new(-(r + gap), 0.0, 0.0),
            Vec3::new(v / 2.0, 0.0, 0.0),
            r,
        ),
        particle(
            Vec3::new(r + gap, 0.0, 0.0),
            Vec3::new(-v / 2.0, 0.0, 0.0),
            r,
        ),
    ];
    let mut d = Dem::<Exact>::new(cfg(t_c / 300.0, 0.1 * r), table, &ps, &[]).unwrap();
    // Peak force from the particles' accelerations: track the largest |dv| m / dt.
    let dt = t_c / 300.0;
    let (mut peak, mut dur, mut touched, mut err) = (0.0f64, 0.0, false, 0.0f64);
    let e0 = d.kinetic_energy();
    for _ in 0..20_000 {
        let v0 = d.particle(0).velocity;
        d.step().unwrap();
        let f = (d.particle(0).velocity - v0).length() * m / dt;
        let en = d.energy();
        err = err.max(((d.kinetic_energy() + en.elastic() + en.dissipated()) - e0).abs() / e0);
        if d.counts().contacts > 0 {
            touched = true;
            dur += dt;
            peak = peak.max(f);
        } else if touched {
            break;
        }
    }
    let rebound = (d.particle(1).velocity.x - d.particle(0).velocity.x) / v;
    println!(
        "two glass spheres: t_c {:+.3} %, P_max {:+.3} %, rebound {rebound:.6}, energy error {err:.2e}",
        (dur / t_c - 1.0) * 100.0,
        (peak / p_max - 1.0) * 100.0
    );
    assert!((dur / t_c - 1.0).abs() < 0.01);
    assert!((peak / p_max - 1.0).abs() < 0.01);
    assert!((rebound - 1.0).abs() < 1e-3);
    assert!(err < 1e-3, "energy error {err}");
}

/// A sphere launched onto the wall y = 0 (normal +y) with normal speed `v_n`, tangential `v_t`.
fn sphere_on_wall<T: TangentialLaw>(
    m: &Material,
    r: f64,
    v_n: f64,
    v_t: f64,
    e: f64,
    steps_per_contact: f64,
) -> (Dem<T>, f64) {
    let mass = sphere_mass(m, r);
    let (t_c, _) = hertz_impact(mass, r, e_star(m, m), v_n);
    let dt = t_c / steps_per_contact;
    let table = MaterialTable::new(&[*m], e, Some(CreepModel::Kuhn), None).unwrap();
    let gap = 3.0 * v_n * dt;
    let ps = [particle(
        Vec3::new(0.0, r + gap, 0.0),
        Vec3::new(v_t, -v_n, 0.0),
        r,
    )];
    let wall = Wall {
        point: Vec3::ZERO,
        normal: Vec3::Y,
        velocity: Vec3::ZERO,
        material: 0,
    };
    (
        Dem::<T>::new(cfg(dt, 0.1 * r), table, &ps, &[wall]).unwrap(),
        t_c,
    )
}

#[test]
fn elastic_normal_impact_on_a_wall() {
    let al = alloy(0.3);
    let (r, v) = (0.1, 0.2);
    let (mut d, t_c) = sphere_on_wall::<Exact>(&al, r, v, 0.0, 1.0, 300.0);
    let (_, p_max) = hertz_impact(d.mass(0), r, e_star(&al, &al), v);
    let imp = run(&mut d, 20_000);
    let vy = d.particle(0).velocity.y;
    println!(
        "alloy sphere on wall: t_c {:+.3} %, P_max {:+.3} %, rebound {:.6}, energy error {:.2e}",
        (imp.duration / t_c - 1.0) * 100.0,
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
    let al = alloy(0.3);
    let (r, v) = (0.1, 0.2);
    for e in [0.1, 0.3, 0.5, 0.7, 0.9] {
        let (mut d, _) = sphere_on_wall::<Cheap>(&al, r, v, 0.0, e, 500.0);
        let imp = run(&mut d, 20_000);
        let got = d.particle(0).velocity.y / v;
        let ke0 = 0.5 * d.mass(0) * v * v;
        let balance = (d.kinetic_energy() + d.energy().dissipated()) / ke0 - 1.0;
        println!(
            "restitution {e}: got {got:.5} ({:+.3} %), balance {balance:+.2e}, {} steps",
            (got / e - 1.0) * 100.0,
            imp.steps
        );
        assert!((got / e - 1.0).abs() < 0.01, "e = {e}: {got}");
        assert!(balance.abs() < 1e-2);
    }
}

// The independent no-slip quadrature of crates/rapier/tests/compliant.rs (a copy).
include!("common/no_slip_reference.rs");

#[test]
fn oblique_impact_gross_sliding_and_sticking() {
    let (r, v_n, mu) = (2.5e-3, 3.9, 0.092);
    let ox = alumina(mu);
    for ratio in [1.0, 2.0, 4.0] {
        let v_t = ratio * v_n;
        for tier in ["exact", "cheap"] {
            let (vt, om, m, err) = if tier == "exact" {
                let (mut d, _) = sphere_on_wall::<Exact>(&ox, r, v_n, v_t, 1.0, 1000.0);
                let imp = run(&mut d, 20_000);
                let p = d.particle(0);
                (
                    p.velocity.x,
                    p.angular_velocity.z,
                    d.mass(0),
                    imp.energy_error,
                )
            } else {
                let (mut d, _) = sphere_on_wall::<Cheap>(&ox, r, v_n, v_t, 1.0, 1000.0);
                let imp = run(&mut d, 20_000);
                let p = d.particle(0);
                (
                    p.velocity.x,
                    p.angular_velocity.z,
                    d.mass(0),
                    imp.energy_error,
                )
            };
            let jt = mu * 2.0 * m * v_n;
            let vt_expect = v_t - jt / m;
            let om_expect = -jt * r / (0.4 * m * r * r);
            println!(
                "oblique sliding ({tier}) v_t/v_n = {ratio}: v_t' {:+.3} %, w' {:+.3} %, energy error {err:.2e}",
                (vt / vt_expect - 1.0) * 100.0,
                (om / om_expect - 1.0) * 100.0
            );
            assert!((vt / vt_expect - 1.0).abs() < 0.01);
            assert!((om / om_expect - 1.0).abs() < 0.01);
            assert!(err < 1e-3, "energy error {err}");
        }
    }
    let ox = alumina(MU_STICK);
    for ratio in [0.02, 0.05, 0.1, 0.2] {
        let v_t = ratio * v_n;
        let (mut d, t_c) = sphere_on_wall::<Exact>(&ox, r, v_n, v_t, 1.0, 1000.0);
        let imp = run(&mut d, 20_000);
        let p = d.particle(0);
        let m = d.mass(0);
        let (vt, om) = (p.velocity.x, p.angular_velocity.z);
        let (vt_ref, om_ref) =
            no_slip_reference(m, r, e_star(&ox, &ox), g_star(&ox, &ox), v_n, v_t, t_c);
        let (dv, dv_ref) = (vt - v_t, vt_ref - v_t);
        println!(
            "oblique sticking v_t/v_n = {ratio}: impulse {:+.3} %, w' {:+.3} %, energy error {:.2e}",
            (dv / dv_ref - 1.0) * 100.0,
            (om / om_ref - 1.0) * 100.0,
            imp.energy_error
        );
        assert!((m * r * dv / (0.4 * m * r * r * om) - 1.0).abs() < 2e-3);
        assert!(imp.energy_error < 1e-3, "energy error {}", imp.energy_error);
        assert!((dv / dv_ref - 1.0).abs() < 0.01, "dv {dv} vs {dv_ref}");
        assert!((om / om_ref - 1.0).abs() < 0.01);
    }
}

/// Gravity of the settling tests [m/s^2]: a centrifuge's, so that 512 particles settle into a
/// packing in a few thousand steps.
const G: f64 = 300.0;

/// A small random cloud in a box of walls settling under gravity with friction and creep.
fn settling<T: TangentialLaw>(
    n: usize,
    dt_fraction: f64,
    parallel: bool,
    periodic: bool,
) -> Dem<T> {
    let glass = Material::new(29e6, 0.23, 0.5, 2500.0).unwrap();
    let r = 1e-3;
    let table = MaterialTable::new(&[glass], 0.5, Some(CreepModel::Kuhn), None).unwrap();
    let t_r = creep_law::hertz::rayleigh_time_step(&glass, 0.8 * r);
    let mut ps = Vec::new();
    let mut s: u64 = 12345;
    let mut rnd = || {
        s = s
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (s >> 11) as f64 / (1u64 << 53) as f64
    };
    for i in 0..n {
        for j in 0..n {
            for k in 0..n {
                ps.push(Particle {
                    position: Vec3::new(
                        (i as f64 + 0.5) * 2.2 * r + 0.1 * r * rnd(),
                        (k as f64 + 0.5) * 2.2 * r + 0.1 * r * rnd(),
                        (j as f64 + 0.5) * 2.2 * r + 0.1 * r * rnd(),
                    ),
                    velocity: Vec3::new(rnd() - 0.5, rnd() - 0.5, rnd() - 0.5) * 0.05,
                    angular_velocity: Vec3::new(rnd() - 0.5, rnd() - 0.5, rnd() - 0.5) * 20.0,
                    radius: r * (0.8 + 0.2 * rnd()),
                    material: 0,
                });
            }
        }
    }
    let side = n as f64 * 2.2 * r;
    let mut walls = vec![Wall {
        point: Vec3::ZERO,
        normal: Vec3::Y,
        velocity: Vec3::ZERO,
        material: 0,
    }];
    let mut per = [None; 3];
    if periodic {
        per[0] = Some((0.0, side));
        per[2] = Some((0.0, side));
    } else {
        for (p, nrm) in [
            (Vec3::ZERO, Vec3::X),
            (Vec3::new(side, 0.0, 0.0), -Vec3::X),
            (Vec3::ZERO, Vec3::Z),
            (Vec3::new(0.0, 0.0, side), -Vec3::Z),
        ] {
            walls.push(Wall {
                point: p,
                normal: nrm,
                velocity: Vec3::ZERO,
                material: 0,
            });
        }
    }
    let c = DemConfig {
        dt: dt_fraction * t_r,
        skin: 0.2 * r,
        periodic: per,
        gravity: Vec3::new(0.0, -G, 0.0),
        parallel,
    };
    Dem::<T>::new(c, table, &ps, &walls).unwrap()
}

fn potential<T: TangentialLaw>(d: &Dem<T>) -> f64 {
    (0..d.len())
        .map(|i| d.mass(i) * G * d.particle(i).position.y)
        .sum()
}

/// Kinetic + potential + elastic + dissipated stays constant while the packing settles.
fn energy_closes<T: TangentialLaw>() {
    let mut d = settling::<T>(5, 0.05, false, false);
    let e0 = d.kinetic_energy() + potential(&d) + d.energy().elastic();
    let mut worst: f64 = 0.0;
    let mut scale: f64 = 0.0;
    for i in 0..12000 {
        d.step().unwrap();
        if i % 400 == 0 {
            let en = d.energy();
            let e = d.kinetic_energy() + potential(&d) + en.elastic() + en.dissipated();
            worst = worst.max((e - e0).abs());
            scale = scale.max(en.dissipated().abs());
        }
    }
    let c = d.counts();
    println!(
        "settling ({}): {} contacts, {} wall contacts, {} rebuilds, dissipated {scale:.3e} J, \
         worst balance error {worst:.3e} J ({:.2e} of dissipated)",
        T::NAME,
        c.contacts,
        c.wall_contacts,
        c.rebuilds,
        worst / scale
    );
    assert!(c.contacts > 150 && c.rebuilds > 2, "{c:?}");
    assert!(worst < 1e-2 * scale, "balance error {worst} of {scale}");
}

#[test]
fn energy_bookkeeping_closes_in_a_settling_packing() {
    energy_closes::<Exact>();
    energy_closes::<Cheap>();
}

/// Touching pairs found by brute force (minimum image on periodic axes).
fn brute_contacts<T: TangentialLaw>(d: &Dem<T>, period: Option<f64>) -> usize {
    let mut n = 0;
    for i in 0..d.len() {
        for j in i + 1..d.len() {
            let (a, b) = (d.particle(i), d.particle(j));
            let mut dx = b.position - a.position;
            if let Some(l) = period {
                dx.x -= l * (dx.x / l).round();
                dx.z -= l * (dx.z / l).round();
            }
            if dx.length() < a.radius + b.radius {
                n += 1;
            }
        }
    }
    n
}

#[test]
fn neighbour_list_finds_every_contact_and_periodic_wraps() {
    for periodic in [false, true] {
        let mut d = settling::<Cheap>(6, 0.2, false, periodic);
        for _ in 0..3000 {
            d.step().unwrap();
        }
        let side = 6.0 * 2.2e-3;
        let brute = brute_contacts(&d, periodic.then_some(side));
        let mut seen = 0;
        d.for_each_contact(|c| seen += usize::from(c.p.is_some()));
        println!(
            "periodic {periodic}: {} contacts, brute force {brute}",
            d.counts().contacts
        );
        assert!(brute > 200);
        assert_eq!(d.counts().contacts, brute);
        assert_eq!(seen, brute);
        if periodic {
            // Particles stay in the box.
            for i in 0..d.len() {
                let x = d.particle(i).position;
                assert!((0.0..side).contains(&x.x) && (0.0..side).contains(&x.z));
            }
        }
    }
}

#[test]
fn bad_input_is_a_typed_error() {
    let m = Material::glass();
    let table = MaterialTable::new(&[m], 0.5, None, None).unwrap();
    let p = particle(Vec3::ZERO, Vec3::ZERO, 1e-3);
    assert!(Dem::<Cheap>::new(cfg(0.0, 1e-4), table.clone(), &[p], &[]).is_err());
    assert!(Dem::<Cheap>::new(cfg(1e-7, f64::NAN), table.clone(), &[p], &[]).is_err());
    let bad = Particle { radius: -1.0, ..p };
    assert!(Dem::<Cheap>::new(cfg(1e-7, 1e-4), table.clone(), &[bad], &[]).is_err());
    let bad = Particle { material: 3, ..p };
    assert!(Dem::<Cheap>::new(cfg(1e-7, 1e-4), table.clone(), &[bad], &[]).is_err());
    let transient = MaterialTable::new(&[m], 0.5, Some(CreepModel::FittedTransient), None).unwrap();
    assert!(Dem::<Cheap>::new(cfg(1e-7, 1e-4), transient.clone(), &[p], &[]).is_err());
    assert!(Dem::<Exact>::new(cfg(1e-7, 1e-4), transient, &[p], &[]).is_ok());
    assert!(MaterialTable::new(&[m], 0.0, None, None).is_err());
    let small_box = DemConfig {
        periodic: [Some((0.0, 1e-3)), None, None],
        ..cfg(1e-7, 1e-4)
    };
    assert!(Dem::<Cheap>::new(small_box, table.clone(), &[p], &[]).is_err());
    // A new time step: finite and > 0, else a typed error and the step unchanged.
    let mut d = Dem::<Cheap>::new(cfg(1e-7, 1e-4), table, &[p], &[]).unwrap();
    for dt in [0.0, -1e-7, f64::NAN, f64::INFINITY] {
        assert!(matches!(
            d.set_time_step(dt),
            Err(creep_dem::DemError::Parameter { .. })
        ));
    }
    assert_eq!(d.config().dt, 1e-7);
    d.set_time_step(2e-7).unwrap();
    d.step().unwrap();
    assert_eq!((d.config().dt, d.time()), (2e-7, 2e-7));
}

/// `Dem::set_skin`: a bad skin is a typed error (the settings unchanged); a larger skin
/// rebuilds the list at once with every contact's history carried over (the stored elastic
/// energy and the touching contacts unchanged, more candidate pairs), and the run continues
/// with the same physics: positions within rounding-level distance of a run with the old
/// skin after 300 more steps (the list's order, and so the force sums' order, differs).
#[test]
fn set_skin_carries_the_histories_and_keeps_the_physics() {
    let mut a = settling::<Cheap>(5, 0.2, false, false);
    for _ in 0..600 {
        a.step().unwrap();
    }
    let mut b = a.clone();
    let skin = b.config().skin;
    for bad in [0.0, -1e-4, f64::NAN, f64::INFINITY] {
        assert!(matches!(
            b.set_skin(bad),
            Err(creep_dem::DemError::Parameter { .. })
        ));
    }
    assert_eq!(b.config().skin, skin);
    let (e0, rebuilds) = (b.energy(), b.counts().rebuilds);
    b.set_skin(3.0 * skin).unwrap();
    assert_eq!(b.config().skin, 3.0 * skin);
    assert_eq!(b.counts().rebuilds, rebuilds + 1);
    let e1 = b.energy();
    // The same terms summed in the new list's order.
    let close = |x: f64, y: f64| (x - y).abs() <= 1e-12 * y.abs();
    assert!(
        close(e1.tangential_elastic, e0.tangential_elastic),
        "{e1:?} {e0:?}"
    );
    assert!(close(e1.normal_elastic, e0.normal_elastic), "{e1:?} {e0:?}");
    assert!(e0.tangential_elastic > 0.0 && e0.normal_elastic > 0.0);
    a.step().unwrap();
    b.step().unwrap();
    assert_eq!(a.counts().contacts, b.counts().contacts);
    assert!(b.counts().neighbours > a.counts().neighbours);
    for _ in 0..300 {
        a.step().unwrap();
        b.step().unwrap();
    }
    assert!(b.counts().rebuilds - rebuilds - 1 < a.counts().rebuilds - rebuilds);
    let worst = (0..a.len())
        .map(|i| (a.particle(i).position - b.particle(i).position).length())
        .fold(0.0, f64::max);
    println!("largest position difference after 300 steps: {worst:e} m");
    assert!(worst < 1e-12, "{worst}");
}

/// The `parallel` force loop: the same bits as the serial loop (each particle's force and
/// torque summed in list order, energies and counts per block of particles in both, see
/// `par.rs`), so also identical run to run, over a settling run whose contacts amplify any
/// rounding difference (the sums in different orders drifted 4e-14 to 3.5e-7 m apart in
/// 1500 steps, depending on the Cattaneo-Mindlin memory's rounding).
/// The portable, the AVX2 and (where the CPU has it) the AVX-512 copies of the force loops
/// (`Kernels`) step a settling packing
/// (sliding, creeping, walls, list rebuilds) to the same bits, serial and (with the `parallel`
/// feature) on two threads.
#[test]
fn kernels_give_the_same_bits() {
    same_bits_both_kernels::<Exact>();
    same_bits_both_kernels::<Cheap>();
}

fn same_bits_both_kernels<T: TangentialLaw>() {
    if !Kernels::Avx2.available() {
        println!("kernels: this CPU has no AVX2 and FMA, only the portable copy runs");
        assert!(
            Dem::<T>::new(DemConfig::default(), table1(), &[], &[])
                .unwrap()
                .set_kernels(Kernels::Avx2)
                .is_err()
        );
        return;
    }
    let bits = |v: Vec3| [v.x.to_bits(), v.y.to_bits(), v.z.to_bits()];
    let run = |kernels: Kernels, parallel: bool| {
        let threads = if parallel { 2 } else { 1 };
        creep_dem::with_threads(threads, || {
            let mut d = settling::<T>(8, 0.2, parallel, false);
            d.set_kernels(kernels).unwrap();
            assert_eq!(d.kernels(), kernels);
            for _ in 0..1500 {
                d.step().unwrap();
            }
            let state = (0..d.len())
                .map(|i| {
                    let p = d.particle(i);
                    [bits(p.position), bits(p.velocity), bits(p.angular_velocity)]
                })
                .collect::<Vec<_>>();
            let e = d.energy();
            let energy = [e.damping, e.slip, e.creep, e.rolling, e.truncation].map(f64::to_bits);
            let walls = (0..d.walls().len())
                .map(|k| bits(d.wall_force(k)))
                .collect::<Vec<_>>();
            (state, energy, d.counts(), walls)
        })
        .unwrap()
    };
    let mut variants = vec![false];
    if cfg!(feature = "parallel") {
        variants.push(true);
    }
    for parallel in variants {
        let p = run(Kernels::Portable, parallel);
        assert!(
            p.2.contacts > 100 && p.2.sliding > 0 && p.2.creeping > 0,
            "{:?}",
            p.2
        );
        let mut wide = vec![Kernels::Avx2];
        if Kernels::Avx512.available() {
            wide.push(Kernels::Avx512);
        } else {
            println!("kernels: this CPU has no AVX-512F and AVX-512VL, that copy is not run");
        }
        for k in wide {
            let a = run(k, parallel);
            let differ = a.0.iter().zip(&p.0).filter(|(x, y)| x != y).count();
            println!(
                "kernels ({}, parallel {parallel}): {} vs portable after 1500 steps: {differ} \
                 particles differ in any bit",
                T::NAME,
                k.name()
            );
            assert_eq!(differ, 0);
            assert_eq!(a.1, p.1, "energies");
            assert_eq!(a.2, p.2, "counts");
            assert_eq!(a.3, p.3, "wall forces");
        }
    }
}

/// A one-material table (glass, friction 0.5, Kuhn's creep).
fn table1() -> MaterialTable {
    let glass = Material::new(29e6, 0.23, 0.5, 2500.0).unwrap();
    MaterialTable::new(&[glass], 0.5, Some(CreepModel::Kuhn), None).unwrap()
}

#[cfg(feature = "parallel")]
#[test]
fn parallel_force_loop_is_deterministic() {
    deterministic::<Exact>();
    // The cheap tier's serial loop runs most contacts through the block kernel, adding its
    // lanes as they come (`sphere_block_lanes`), the parallel one through the block with a
    // buffer of outputs (the exact tier: the one-contact kernel in both): the same bits.
    deterministic::<Cheap>();
}

#[cfg(feature = "parallel")]
fn deterministic<T: TangentialLaw>() {
    /// An external force that adds nothing but does not say so (`adds_forces` is `true`): the
    /// parallel step then sums the forces, calls it, and kicks in a separate pass.
    struct Nothing;
    impl ExternalForces for Nothing {
        fn add_forces(&mut self, _view: ExternalView<'_>) -> Result<(), creep_dem::DemError> {
            Ok(())
        }
    }
    let bits = |v: Vec3| [v.x.to_bits(), v.y.to_bits(), v.z.to_bits()];
    let run = |parallel: bool, threads: usize, external: bool| {
        creep_dem::with_threads(threads, || {
            // 512 particles: 4 blocks of the contact loop, 2 of the parallel list build.
            let mut d = settling::<T>(8, 0.2, parallel, false);
            for _ in 0..1500 {
                if external {
                    d.step_with(&mut Nothing).unwrap();
                } else {
                    d.step().unwrap();
                }
            }
            let state = (0..d.len())
                .map(|i| {
                    let p = d.particle(i);
                    [bits(p.position), bits(p.velocity), bits(p.angular_velocity)]
                })
                .collect::<Vec<_>>();
            let e = d.energy();
            let energy = [e.damping, e.slip, e.creep, e.rolling, e.truncation].map(f64::to_bits);
            let walls = (0..d.walls().len())
                .map(|k| bits(d.wall_force(k)))
                .collect::<Vec<_>>();
            (state, energy, d.counts(), walls)
        })
        .unwrap()
    };
    let s = run(false, 1, false);
    assert!(s.2.contacts > 100, "{:?}", s.2);
    assert!(s.2.wall_contacts > 10, "{:?}", s.2);
    assert!(s.2.rebuilds > 5, "{:?}", s.2);
    for (threads, external) in [(2, false), (2, false), (1, false), (3, false), (2, true)] {
        let a = run(true, threads, external);
        let differ = a.0.iter().zip(&s.0).filter(|(p, q)| p != q).count();
        println!(
            "parallel ({threads} threads, external {external}) vs serial after 1500 steps: \
             {differ} particles differ in any bit"
        );
        assert_eq!(differ, 0);
        assert_eq!(a.1, s.1, "energies");
        assert_eq!(a.2, s.2, "counts");
        assert_eq!(a.3, s.3, "wall forces");
    }
}

/// A constant external force on one free particle (no gravity, no contacts) through
/// `Dem::step_with`: velocity Verlet integrates a constant force exactly, so after n steps
/// to rounding. The first step's first half-kick uses the forces `Dem::new` evaluated (no
/// external force yet), so with h = dt/2: v = F (t - h) / m and x = F h (t - dt)/m +
/// F (t - dt)^2 / (2 m). The view reports ids and the end time.
#[test]
fn external_forces_enter_the_step_like_contact_forces() {
    struct Push {
        force: Vec3,
        calls: usize,
        last_time: f64,
    }
    impl ExternalForces for Push {
        fn add_forces(&mut self, view: ExternalView<'_>) -> Result<(), creep_dem::DemError> {
            assert_eq!(view.ids, &[0]);
            view.forces[0] += self.force;
            self.calls += 1;
            self.last_time = view.time;
            Ok(())
        }
    }
    let dt = 1e-4;
    let mut c = cfg(dt, 1e-3);
    c.gravity = Vec3::ZERO;
    let mat = alloy(0.3);
    let r = 0.01;
    let m = sphere_mass(&mat, r);
    let table = MaterialTable::new(&[mat], 0.5, Some(CreepModel::Kuhn), None).unwrap();
    let mut d = Dem::<Exact>::new(c, table, &[particle(Vec3::ZERO, Vec3::ZERO, r)], &[]).unwrap();
    let mut push = Push {
        force: Vec3::new(2.0, -1.0, 0.5),
        calls: 0,
        last_time: 0.0,
    };
    let n = 100;
    for _ in 0..n {
        d.step_with(&mut push).unwrap();
    }
    let t = n as f64 * dt;
    assert_eq!(push.calls, n);
    assert!((push.last_time - t).abs() < 1e-15);
    let p = d.particle(0);
    let h = 0.5 * dt;
    let v = push.force * ((t - h) / m);
    let x = push.force * ((h * (t - dt) + 0.5 * (t - dt) * (t - dt)) / m);
    assert!(
        (p.velocity - v).length() <= 1e-12 * v.length(),
        "{:?} vs {:?}",
        p.velocity,
        v
    );
    assert!(
        (p.position - x).length() <= 1e-12 * x.length(),
        "{:?} vs {:?}",
        p.position,
        x
    );
}
