//! Times creep-dem on a packing that `creep bench dem --export DIR` wrote (`packing.data`,
//! `params.lmp`), with the engine set up as `creep_scenes::dem_engine` sets it up (balls:
//! the exported material and friction; six frictionless walls at the box faces; Kuhn's creep;
//! the exported dt and skin), so a profiler can run the engine alone without compacting a
//! packing first:
//!
//! ```sh
//! cargo run --release -p creep-dem --example packing -- DIR [steps] [rounds] [tiers]
//! perf record -g target/release/examples/packing DIR 2000 1 cheap
//! ```
//!
//! `tiers`: `cheap`, `exact` or `both` (default; interleaved per round). Prints, per round and
//! tier, the mean CPU seconds per step and the particle-steps per second, then the same from
//! the wall clock, and the medians (CPU time).

use std::collections::HashMap;
use std::time::Instant;

use creep_dem::{Cheap, Dem, DemConfig, Exact, MaterialTable, Particle, TangentialLaw, Wall};
use creep_law::pair::PairConstants;
use creep_law::{CreepModel, Material, Vec3};

type Res<T> = Result<T, Box<dyn std::error::Error>>;

struct Packing {
    particles: Vec<Particle>,
    walls: Vec<Wall>,
    table: MaterialTable,
    dt: f64,
    skin: f64,
}

fn load(dir: &str) -> Res<Packing> {
    let params = std::fs::read_to_string(format!("{dir}/params.lmp"))?;
    let mut v: HashMap<String, f64> = HashMap::new();
    for line in params.lines() {
        let cols: Vec<&str> = line.split_whitespace().collect();
        if cols.len() >= 4 && cols[0] == "variable" && cols[2] == "equal" {
            v.insert(cols[1].to_string(), cols[3].parse()?);
        }
    }
    let get = |k: &str| v.get(k).copied().ok_or(format!("params.lmp: no {k}"));
    let data = std::fs::read_to_string(format!("{dir}/packing.data"))?;
    let atoms = data
        .split("\nAtoms\n\n")
        .nth(1)
        .and_then(|s| s.split("\n\nVelocities\n\n").next())
        .ok_or("packing.data: no Atoms section")?;
    let vels = data
        .split("\n\nVelocities\n\n")
        .nth(1)
        .ok_or("packing.data: no Velocities section")?;
    let num = |l: &str| -> Res<Vec<f64>> {
        l.split_whitespace()
            .map(|c| c.parse::<f64>().map_err(Into::into))
            .collect()
    };
    let mut particles = Vec::new();
    for (a, w) in atoms.lines().zip(vels.lines()) {
        let a = num(a)?;
        let w = num(w)?;
        particles.push(Particle {
            position: Vec3::new(a[4], a[5], a[6]),
            velocity: Vec3::new(w[1], w[2], w[3]),
            angular_velocity: Vec3::new(w[4], w[5], w[6]),
            radius: 0.5 * a[2],
            material: 0,
        });
    }
    let m = Material::new(get("shear")?, get("poisson")?, get("mu")?, get("density")?)?;
    let ball = m.with_friction(get("mu")?)?;
    let wall = m.with_friction(0.0)?;
    let e = get("restitution")?;
    let model = Some(CreepModel::Kuhn);
    let mut table = MaterialTable::new(&[ball, wall], e, model, None)?;
    table.set_pair(0, 1, PairConstants::new(&ball, &wall, 0.0, e, model, None)?)?;
    let mut walls = Vec::new();
    for (axis, (lo, hi)) in [("xlo", "xhi"), ("ylo", "yhi"), ("zlo", "zhi")]
        .iter()
        .enumerate()
    {
        for (face, sign) in [(get(lo)?, 1.0), (get(hi)?, -1.0)] {
            let mut point = [0.0; 3];
            point[axis] = face;
            let mut normal = [0.0; 3];
            normal[axis] = sign;
            walls.push(Wall {
                point: Vec3::new(point[0], point[1], point[2]),
                normal: Vec3::new(normal[0], normal[1], normal[2]),
                velocity: Vec3::ZERO,
                material: 1,
            });
        }
    }
    Ok(Packing {
        particles,
        walls,
        table,
        dt: get("dt")?,
        skin: 0.02 * get("d_mean")?,
    })
}

/// CPU time of this thread \[s\] (Linux: the first field of `/proc/thread-self/schedstat`, in
/// ns), so that other jobs' load on a shared machine does not enter; `None` elsewhere.
fn cpu_s() -> Option<f64> {
    let s = std::fs::read_to_string("/proc/thread-self/schedstat").ok()?;
    Some(s.split_whitespace().next()?.parse::<f64>().ok()? * 1e-9)
}

/// Mean seconds per step of `steps` steps (the set-up excluded): `(CPU time of the thread,
/// wall-clock time)`; the CPU time is the wall-clock time where the system does not report it.
fn time<T: TangentialLaw>(p: &Packing, steps: usize) -> Res<(f64, f64)> {
    let cfg = DemConfig {
        dt: p.dt,
        skin: p.skin,
        ..DemConfig::default()
    };
    let mut d = Dem::<T>::new(cfg, p.table.clone(), &p.particles, &p.walls)?;
    let (t, c) = (Instant::now(), cpu_s());
    for _ in 0..steps {
        d.step()?;
    }
    let wall = t.elapsed().as_secs_f64();
    let cpu = match (c, cpu_s()) {
        (Some(a), Some(b)) => b - a,
        _ => wall,
    };
    Ok((cpu / steps as f64, wall / steps as f64))
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

fn main() -> Res<()> {
    let args: Vec<String> = std::env::args().collect();
    let dir = args
        .get(1)
        .ok_or("usage: packing DIR [steps] [rounds] [cheap|exact|both]")?;
    let steps: usize = args.get(2).map_or(Ok(400), |s| s.parse())?;
    let rounds: usize = args.get(3).map_or(Ok(3), |s| s.parse())?;
    let tiers = args.get(4).map_or("both", String::as_str);
    let p = load(dir)?;
    let n = p.particles.len() as f64;
    let (mut cheap, mut exact) = (Vec::new(), Vec::new());
    for round in 1..=rounds {
        if tiers != "exact" {
            let (s, w) = time::<Cheap>(&p, steps)?;
            println!(
                "round {round} dem-cheap {s:.4e} s/step {:.4e} particle-steps/s wall {w:.4e} s/step {:.4e} particle-steps/s",
                n / s,
                n / w
            );
            cheap.push(n / s);
        }
        if tiers != "cheap" {
            let (s, w) = time::<Exact>(&p, steps)?;
            println!(
                "round {round} dem-exact {s:.4e} s/step {:.4e} particle-steps/s wall {w:.4e} s/step {:.4e} particle-steps/s",
                n / s,
                n / w
            );
            exact.push(n / s);
        }
    }
    if !cheap.is_empty() {
        println!("median dem-cheap {:.4e} particle-steps/s", median(cheap));
    }
    if !exact.is_empty() {
        println!("median dem-exact {:.4e} particle-steps/s", median(exact));
    }
    Ok(())
}
