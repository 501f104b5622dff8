//! `creep-lammps-ref`: the reference side of the LAMMPS plugin's tests (see `test.sh`).
//!
//! ```text
//! creep-lammps-ref gen DIR [N]            test packing: N^3 spheres (default 8) -> DIR/packing.data, DIR/params.lmp
//! creep-lammps-ref shear IN OUT RATE      IN data file + shear v_x += RATE (z - z_mid) -> OUT
//! creep-lammps-ref run DATA PARAMS STEPS [OPTIONS]
//!                                         prints `step pressure ke contacts` per step (17 digits);
//!                                         OPTIONS as pair_style granular/creep's keywords:
//!                                         [tier exact|spring] [creep yes|no]
//!                                         [rolling none|constant MU_R|epsd MU_R ETA]
//!                                         (also the positional `exact`, `spring`, `nocreep`)
//! creep-lammps-ref dem DATA PARAMS STEPS [exact|spring]
//!                                         the same with the creep-dem engine: prints
//!                                         `step nan ke contacts` (it reports no pair virial);
//!                                         PARAMS `variable zwalls equal 1`: plane walls at the
//!                                         z faces, the upper one moving with velocity
//!                                         (zhi_vx, 0, zhi_vz) m/s if those variables are set
//! creep-lammps-ref kernel DATA PARAMS STEPS [exact|spring] [store|flat]
//!                                         the kernel alone on the packing's contacts: prints
//!                                         `Loop time of S` (S = STEPS batches) and the batch size;
//!                                         store: compute_pairs (one contact at a time, histories
//!                                         in a HistoryStore, the default), flat: Model::compute on
//!                                         flat histories (read and written per contact)
//! ```

use creep_lammps::driver::{Packing, Sim, lammps_variable};
use creep_lammps::{Model, Settings, Tier};
use std::process::ExitCode;

type Res<T> = Result<T, Box<dyn std::error::Error>>;

/// Material of the test packing: the triaxial test's glass-like spheres of `creep bench dem`
/// (G = 29 MPa, nu = 0.2, rho = 2500 kg/m^3, e = 0.5, mu = 0.5), radius 1 mm.
const G: f64 = 29e6;
const NU: f64 = 0.2;
const RHO: f64 = 2500.0;
const E_REST: f64 = 0.5;
const MU: f64 = 0.5;
const RADIUS: f64 = 1e-3;

fn generate(dir: &str, n: usize) -> Res<()> {
    std::fs::create_dir_all(dir)?;
    // Overlaps of ~1e-3 of the diameter (the compacted packing's order at 100 kPa).
    let p = Packing::lattice(n, RADIUS, RHO, 1e-3, 4e-4);
    let boundary = if p.periodic { "p p p" } else { "f f f" };
    std::fs::write(
        format!("{dir}/packing.data"),
        p.write_data(&format!(
            "creep-lammps-ref gen: {n}^3 spheres on a perturbed lattice (SI)"
        )),
    )?;
    let young = 2.0 * G * (1.0 + NU);
    let r_min = p.radius.iter().cloned().fold(f64::INFINITY, f64::min);
    let material = creep_law::Material::new(G, NU, MU, RHO)?;
    let dt = 0.2 * creep_law::hertz::rayleigh_time_step(&material, r_min);
    let mut s = format!(
        "# creep-lammps-ref gen: material and time step (SI)\nvariable boundary string \"{boundary}\"\n"
    );
    for (name, v) in [
        ("xlo", p.lo[0]),
        ("xhi", p.hi[0]),
        ("ylo", p.lo[1]),
        ("yhi", p.hi[1]),
        ("zlo", p.lo[2]),
        ("zhi", p.hi[2]),
        ("dt", dt),
        ("young", young),
        ("shear", G),
        ("poisson", NU),
        ("density", RHO),
        ("mu", MU),
        ("restitution", E_REST),
        ("skin", 0.02 * 2.0 * RADIUS),
        ("periodic", 1.0),
    ] {
        s.push_str(&format!("variable {name} equal {v:.16e}\n"));
    }
    std::fs::write(format!("{dir}/params.lmp"), s)?;
    println!(
        "wrote {dir}/packing.data ({} spheres) and {dir}/params.lmp (dt {dt:.6e} s)",
        p.tag.len()
    );
    Ok(())
}

fn shear(input: &str, output: &str, rate: f64) -> Res<()> {
    let mut p = Packing::read_data(&std::fs::read_to_string(input)?)?;
    p.add_shear(rate);
    std::fs::write(
        output,
        p.write_data(&format!("{input} with shear rate {rate:e} 1/s (SI)")),
    )?;
    Ok(())
}

/// The law's options, as `pair_style granular/creep`'s keywords.
#[derive(Debug, Clone, Copy)]
struct Opts {
    tier: Tier,
    creep: bool,
    rolling: Option<creep_law::rolling_torque::RollingModel>,
}

/// Parses `[tier exact|spring] [creep yes|no] [rolling none|constant MU_R|epsd MU_R ETA]`
/// (and the positional `exact`, `spring`, `nocreep`).
fn opts(args: &[String]) -> Res<Opts> {
    use creep_law::rolling_torque::RollingModel;
    let mut o = Opts {
        tier: Tier::Exact,
        creep: true,
        rolling: None,
    };
    let mut it = args.iter().map(String::as_str);
    let num = |w: Option<&str>| -> Res<f64> { Ok(w.ok_or("a number is missing")?.parse::<f64>()?) };
    while let Some(w) = it.next() {
        match w {
            "exact" => o.tier = Tier::Exact,
            "spring" => o.tier = Tier::Spring,
            "nocreep" => o.creep = false,
            "tier" => {
                o.tier = match it.next() {
                    Some("exact") => Tier::Exact,
                    Some("spring") => Tier::Spring,
                    t => return Err(format!("tier must be exact or spring, not {t:?}").into()),
                }
            }
            "creep" => {
                o.creep = match it.next() {
                    Some("yes") => true,
                    Some("no") => false,
                    c => return Err(format!("creep yes or no, not {c:?}").into()),
                }
            }
            "rolling" => {
                o.rolling = match it.next() {
                    Some("none") => None,
                    Some("constant") => Some(RollingModel::constant_torque(num(it.next())?)?),
                    Some("epsd") => {
                        let mu_r = num(it.next())?;
                        Some(RollingModel::epsd(mu_r, num(it.next())?)?)
                    }
                    r => {
                        return Err(
                            format!("rolling none|constant MU_R|epsd MU_R ETA, not {r:?}").into(),
                        );
                    }
                }
            }
            w => return Err(format!("unknown option {w}").into()),
        }
    }
    Ok(o)
}

fn sim(data: &str, params: &str, o: Opts) -> Res<(Sim, creep_lammps::driver::Thermo)> {
    let mut p = Packing::read_data(&std::fs::read_to_string(data)?)?;
    let vars = std::fs::read_to_string(params)?;
    // `variable periodic equal 1` in the parameters: LAMMPS runs it with `boundary p p p`.
    p.periodic = lammps_variable(&vars, "periodic").unwrap_or(0.0) == 1.0;
    let v = |n| lammps_variable(&vars, n);
    let model = Model::new(&Settings {
        young_modulus: v("young")?,
        poisson_ratio: v("poisson")?,
        restitution: v("restitution")?,
        friction: v("mu")?,
        tier: o.tier,
        creep: o.creep,
        rolling: o.rolling,
    })?;
    Ok(Sim::new(p, model, v("dt")?)?)
}

fn run(data: &str, params: &str, steps: u64, o: Opts) -> Res<()> {
    let (mut sim, th) = sim(data, params, o)?;
    println!("step pressure ke contacts");
    let print = |t: &creep_lammps::driver::Thermo| {
        println!(
            "{} {:.17e} {:.17e} {}",
            t.step, t.pressure, t.ke, t.contacts
        )
    };
    print(&th);
    for _ in 0..steps {
        print(&sim.step()?);
    }
    Ok(())
}

/// The packing in creep-dem (one material from PARAMS and the data file's density), stepped
/// `steps` times: translational kinetic energy per step.
fn dem<T: creep_law::pair::TangentialLaw>(data: &str, params: &str, steps: u64) -> Res<()> {
    use creep_dem::{Dem, DemConfig, MaterialTable, Particle};
    let mut p = Packing::read_data(&std::fs::read_to_string(data)?)?;
    let vars = std::fs::read_to_string(params)?;
    p.periodic = lammps_variable(&vars, "periodic").unwrap_or(0.0) == 1.0;
    let v = |n| lammps_variable(&vars, n);
    let rho = p.density[0];
    if p.density.iter().any(|&d| d != rho) {
        return Err("dem: one density for all spheres expected".into());
    }
    let nu = v("poisson")?;
    let m = creep_law::Material::new(v("young")? / (2.0 * (1.0 + nu)), nu, v("mu")?, rho)?;
    let table = MaterialTable::new(
        &[m],
        v("restitution")?,
        Some(creep_law::CreepModel::Kuhn),
        None,
    )?;
    let mut cfg = DemConfig {
        dt: v("dt")?,
        skin: v("skin")?,
        ..DemConfig::default()
    };
    // `variable zwalls equal 1`: flat walls at the box's z faces instead of periodic z (LAMMPS:
    // `boundary p p f` and `fix wall/creep ... zplane zlo zhi`).
    let zwalls = lammps_variable(&vars, "zwalls").unwrap_or(0.0) == 1.0;
    if p.periodic {
        cfg.periodic = std::array::from_fn(|a| (a < 2 || !zwalls).then_some((p.lo[a], p.hi[a])));
    }
    // The upper wall's velocity (LAMMPS: `fix ... wall/creep ... velocity VX 0 VZ zplane NULL
    // zhi`): creep-dem moves the plane by `velocity dt` per step.
    let top = creep_law::Vec3::new(
        lammps_variable(&vars, "zhi_vx").unwrap_or(0.0),
        0.0,
        lammps_variable(&vars, "zhi_vz").unwrap_or(0.0),
    );
    let walls: Vec<creep_dem::Wall> = if zwalls {
        [(p.lo[2], 1.0, creep_law::Vec3::ZERO), (p.hi[2], -1.0, top)]
            .iter()
            .map(|&(z, side, velocity)| creep_dem::Wall {
                point: creep_law::Vec3::new(0.0, 0.0, z),
                normal: creep_law::Vec3::new(0.0, 0.0, side),
                velocity,
                material: 0,
            })
            .collect()
    } else {
        Vec::new()
    };
    let v3 = |a: [f64; 3]| creep_law::Vec3::new(a[0], a[1], a[2]);
    let particles: Vec<Particle> = (0..p.tag.len())
        .map(|i| Particle {
            position: v3(p.x[i]),
            velocity: v3(p.v[i]),
            angular_velocity: v3(p.omega[i]),
            radius: p.radius[i],
            material: 0,
        })
        .collect();
    let mut d = Dem::<T>::new(cfg, table, &particles, &walls)?;
    let ke = |d: &Dem<T>| {
        d.velocities()
            .iter()
            .zip(d.ids())
            .map(|(v, &id)| 0.5 * d.mass(id as usize) * v.dot(*v))
            .sum::<f64>()
    };
    println!("step pressure ke contacts");
    println!("0 nan {:.17e} {}", ke(&d), d.counts().contacts);
    for s in 1..=steps {
        d.step()?;
        println!("{s} nan {:.17e} {}", ke(&d), d.counts().contacts);
    }
    Ok(())
}

fn main() -> ExitCode {
    let a: Vec<String> = std::env::args().skip(1).collect();
    let arg = |i: usize| a.get(i).map(String::as_str);
    let r: Res<()> = (|| {
        match arg(0) {
        Some("gen") => generate(arg(1).ok_or("gen DIR [N]")?, arg(2).unwrap_or("8").parse()?),
        Some("shear") => shear(
            arg(1).ok_or("shear IN OUT RATE")?,
            arg(2).ok_or("shear IN OUT RATE")?,
            arg(3).ok_or("shear IN OUT RATE")?.parse()?,
        ),
        Some("run") => run(
            arg(1).ok_or("run DATA PARAMS STEPS")?,
            arg(2).ok_or("run DATA PARAMS STEPS")?,
            arg(3).ok_or("run DATA PARAMS STEPS")?.parse()?,
            opts(a.get(4..).unwrap_or(&[]))?,
        ),
        Some("dem") => {
            let (data, params) = (arg(1).ok_or("dem DATA PARAMS STEPS")?, arg(2).ok_or("dem DATA PARAMS STEPS")?);
            let steps: u64 = arg(3).ok_or("dem DATA PARAMS STEPS")?.parse()?;
            match arg(4).unwrap_or("exact") {
                "exact" => dem::<creep_law::pair::Exact>(data, params, steps),
                "spring" => dem::<creep_law::pair::Cheap>(data, params, steps),
                t => Err(format!("tier must be exact or spring, not {t}").into()),
            }
        }
        Some("kernel") => {
            let tier = match arg(4).unwrap_or("exact") {
                "exact" => Tier::Exact,
                "spring" => Tier::Spring,
                t => return Err(format!("tier must be exact or spring, not {t}").into()),
            };
            let steps: usize = arg(3).ok_or("kernel DATA PARAMS STEPS")?.parse()?;
            let (mut s, _) = sim(
                arg(1).ok_or("kernel DATA PARAMS STEPS")?,
                arg(2).ok_or("kernel DATA PARAMS STEPS")?,
                Opts { tier, creep: true, rolling: None },
            )?;
            let (per, n) = match arg(5).unwrap_or("store") {
                "store" => s.time_kernel_store(steps)?,
                "flat" => s.time_kernel(steps)?,
                w => return Err(format!("kernel path must be store or flat, not {w}").into()),
            };
            println!("Loop time of {:.6} for {steps} batches of {n} contacts", per * steps as f64);
            Ok(())
        }
        _ => Err("usage: creep-lammps-ref gen DIR [N] | shear IN OUT RATE | run DATA PARAMS STEPS [OPTIONS] | dem DATA PARAMS STEPS [exact|spring] | kernel DATA PARAMS STEPS [exact|spring] [store|flat]".into()),
    }
    })();
    match r {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("creep-lammps-ref: {e}");
            ExitCode::FAILURE
        }
    }
}
