//! Times creep-dem on a packing that `creep bench dem --export DIR` wrote (`packing.data`,
//! `params.lmp`), with the engine set up as `creep_scenes::dem_engine` sets it up (balls:
//! the exported material and friction; six frictionless walls at the box faces; Kuhn's creep;
//! the exported dt and skin), so a profiler can run the engine alone without compacting a
//! packing first:
//!
//! ```sh
//! cargo run --release -p creep-dem --example packing -- DIR [steps] [rounds] [tiers] [tiles] [threads]
//! perf record -g target/release/examples/packing DIR 2000 1 cheap
//! target/release/examples/packing DIR 20 3 cheap 1,2,4        # the scale table: 4k, 32k, 256k
//! cargo build --release -p creep-dem --features parallel --example packing
//! target/release/examples/packing DIR 300 5 cheap 1 1,2       # one thread against two
//! target/release/examples/packing DIR 40 1 exact 1 1 0.1      # skin 0.1 d (default 0.02 d)
//! ```
//!
//! `tiers`: `cheap`, `exact` or `both` (default; interleaved per round). `tiles`: a list
//! `k,k,..` (default 1): the packing repeated `k` times along each axis, `k^3` copies side by
//! side, box dimensions apart, inside six walls around the whole; unlike creep-scenes'
//! `dem_engine_tiled` (plain copies, whose seams push apart and rebuild the neighbour list
//! every few steps at first), every other copy is mirrored, so that each sphere at a seam
//! meets its own image with the force the wall gave it. `threads`: a list
//! (default 1; more needs the `parallel` feature). Every round runs every tier, tiling and
//! thread count in turn (interleaved). Prints, per round and variant, the mean CPU seconds per
//! step and the particle-steps per second (one thread: the thread's CPU time; more: the
//! process's), the same from the wall clock, then the particles, threads, neighbour-list
//! entries and touching contacts per particle, the engine's bytes per particle, the
//! neighbour-list rebuilds during the timed steps and the median CPU time of one step (which
//! leaves the rebuild steps out when most steps have none: the tiled packings' seams, as
//! dense as a wall, push apart at first and rebuild the list often), the time per step the
//! process's threads waited for a CPU (`run-delay`, from schedstat: what other jobs took; a
//! wall-clock timing on more than one thread means something only where it is near 0), a
//! digest of the final state's bits (`state`: two builds that step alike print the same); and
//! the medians over the rounds (CPU time; wall clock for more than one thread).

use std::collections::HashMap;
use std::time::Instant;

use creep_dem::{Cheap, Dem, DemConfig, Exact, MaterialTable, Particle, TangentialLaw, Wall};
use creep_law::pair::PairConstants;
use creep_law::{CreepModel, Material, Vec3};

type Res<T> = Result<T, Box<dyn std::error::Error>>;

#[derive(Clone)]
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

/// `p` repeated `k` times along each axis (`k^3` copies, box dimensions apart, mirrored on
/// odd indices), the walls moved to the faces of the whole.
fn tiled(p: &Packing, k: usize) -> Packing {
    if k <= 1 {
        return p.clone();
    }
    // The box: the walls' points along their normals (`lo` faces look +, `hi` faces look -).
    let mut lo = [0.0; 3];
    let mut hi = [0.0; 3];
    for w in &p.walls {
        let n = [w.normal.x, w.normal.y, w.normal.z];
        let x = [w.point.x, w.point.y, w.point.z];
        for a in 0..3 {
            if n[a] > 0.5 {
                lo[a] = x[a];
            } else if n[a] < -0.5 {
                hi[a] = x[a];
            }
        }
    }
    let dims: [f64; 3] = std::array::from_fn(|a| hi[a] - lo[a]);
    let mut particles = Vec::with_capacity(p.particles.len() * k * k * k);
    for t in 0..k * k * k {
        let (i, j, l) = (t % k, (t / k) % k, t / (k * k));
        // Copy (i, j, l) is the packing mirrored across each axis whose index is odd: a
        // sphere pressed `delta` into a wall meets its own image across the seam with the
        // overlap `2 delta` at `R* = r/2`, which carries the same Hertz force as the wall did
        // (`E*` of two spheres is half that of a sphere on a half-space of the same material),
        // so the seams start in equilibrium instead of pushing apart.
        let idx = [i, j, l];
        particles.extend(p.particles.iter().map(|&q| {
            let x = [q.position.x, q.position.y, q.position.z];
            let v = [q.velocity.x, q.velocity.y, q.velocity.z];
            let w = [
                q.angular_velocity.x,
                q.angular_velocity.y,
                q.angular_velocity.z,
            ];
            let mut xn = [0.0; 3];
            let mut vn = v;
            let mut wn = w;
            for a in 0..3 {
                let k = idx[a] as f64;
                if idx[a] % 2 == 0 {
                    xn[a] = x[a] + k * dims[a];
                } else {
                    // Reflection x -> -x: v_a flips, and w (a pseudovector) flips in the
                    // two other components.
                    xn[a] = lo[a] + (k + 1.0) * dims[a] - (x[a] - lo[a]);
                    vn[a] = -vn[a];
                    for (b, wb) in wn.iter_mut().enumerate() {
                        if b != a {
                            *wb = -*wb;
                        }
                    }
                }
            }
            Particle {
                position: Vec3::new(xn[0], xn[1], xn[2]),
                velocity: Vec3::new(vn[0], vn[1], vn[2]),
                angular_velocity: Vec3::new(wn[0], wn[1], wn[2]),
                ..q
            }
        }));
    }
    let walls = p
        .walls
        .iter()
        .map(|w| {
            let mut w = *w;
            if w.normal.x < -0.5 {
                w.point.x = lo[0] + k as f64 * dims[0];
            } else if w.normal.y < -0.5 {
                w.point.y = lo[1] + k as f64 * dims[1];
            } else if w.normal.z < -0.5 {
                w.point.z = lo[2] + k as f64 * dims[2];
            }
            w
        })
        .collect();
    Packing {
        particles,
        walls,
        ..p.clone()
    }
}

/// CPU time of this process \[s\] (Linux: user + system time of `/proc/self/stat`, in clock
/// ticks of 1/100 s), for runs on more than one thread.
fn process_cpu_s() -> Option<f64> {
    let s = std::fs::read_to_string("/proc/self/stat").ok()?;
    // Fields after the command name (which may hold spaces) : state is field 3; utime 14, stime 15.
    let rest = s.rsplit_once(')')?.1;
    let f: Vec<&str> = rest.split_whitespace().collect();
    let ticks = f.get(11)?.parse::<f64>().ok()? + f.get(12)?.parse::<f64>().ok()?;
    Some(ticks / 100.0)
}

/// CPU time of this thread \[s\] (Linux: the first field of `/proc/thread-self/schedstat`, in
/// ns), so that other jobs' load on a shared machine does not enter; `None` elsewhere.
fn cpu_s() -> Option<f64> {
    let s = std::fs::read_to_string("/proc/thread-self/schedstat").ok()?;
    Some(s.split_whitespace().next()?.parse::<f64>().ok()? * 1e-9)
}

/// Sums over this process's threads of `/proc/self/task/*/schedstat`: CPU time and time spent
/// waiting for a CPU (run delay) \[s\]; `None` where the system does not report them. The run
/// delay tells how much other jobs took from a timing (0 on an otherwise idle machine).
fn threads_cpu_and_delay() -> Option<(f64, f64)> {
    let mut cpu = 0.0;
    let mut delay = 0.0;
    for e in std::fs::read_dir("/proc/self/task").ok()? {
        let s = std::fs::read_to_string(e.ok()?.path().join("schedstat")).ok()?;
        let mut f = s.split_whitespace();
        cpu += f.next()?.parse::<f64>().ok()? * 1e-9;
        delay += f.next()?.parse::<f64>().ok()? * 1e-9;
    }
    Some((cpu, delay))
}

/// What one timing measured.
struct Timing {
    /// Digest of the final state's bits.
    digest: u64,
    /// Mean CPU seconds per step (the thread's for one thread, the process's for more; the
    /// wall clock where the system does not report it).
    cpu: f64,
    /// Mean wall-clock seconds per step.
    wall: f64,
    /// Neighbour-list entries per particle.
    neighbours: f64,
    /// Touching contacts (particle-particle and particle-wall) per particle.
    contacts: f64,
    /// The engine's bytes per particle (`Dem::bytes_per_particle`).
    bytes: f64,
    /// Neighbour-list rebuilds during the timed steps.
    rebuilds: usize,
    /// Median CPU seconds of one step (the steps without a rebuild, when most are).
    step_median: f64,
    /// Mean time per step the process's threads waited for a CPU \[s\] (NaN where unknown).
    run_delay: f64,
}

/// Mean seconds per step of `steps` steps (the set-up excluded) on `threads` threads.
fn time<T: TangentialLaw>(p: &Packing, steps: usize, threads: usize) -> Res<Timing> {
    let cfg = DemConfig {
        dt: p.dt,
        skin: p.skin,
        parallel: threads > 1,
        ..DemConfig::default()
    };
    let run = || -> Res<Timing> {
        let mut d = Dem::<T>::new(cfg, p.table.clone(), &p.particles, &p.walls)
            .map_err(|e| e.to_string())?;
        let clock = if threads > 1 { process_cpu_s } else { cpu_s };
        let rebuilds = d.counts().rebuilds;
        let cd0 = threads_cpu_and_delay();
        let (t, c) = (Instant::now(), clock());
        let mut per_step = Vec::with_capacity(steps);
        let mut last = c;
        for _ in 0..steps {
            d.step().map_err(|e| e.to_string())?;
            let now = clock();
            if let (Some(a), Some(b)) = (last, now) {
                per_step.push(b - a);
            }
            last = now;
        }
        let wall = t.elapsed().as_secs_f64();
        let run_delay = match (cd0, threads_cpu_and_delay()) {
            (Some(a), Some(b)) => (b.1 - a.1) / steps as f64,
            _ => f64::NAN,
        };
        let cpu = match (c, clock()) {
            (Some(a), Some(b)) => b - a,
            _ => wall,
        };
        let n = d.len() as f64;
        let counts = d.counts();
        // A digest of the final state (FNV-1a of the positions', velocities' and forces' bits,
        // in the engine's order):
        // two builds that step to the same bits print the same digest.
        let mut digest: u64 = 0xcbf2_9ce4_8422_2325;
        for i in 0..d.len() {
            let (x, v, f) = (d.positions()[i], d.velocities()[i], d.particle_forces()[i]);
            for v in [x, v, f] {
                for c in [v.x, v.y, v.z] {
                    digest = (digest ^ c.to_bits()).wrapping_mul(0x0100_0000_01b3);
                }
            }
        }
        Ok(Timing {
            digest,
            cpu: cpu / steps as f64,
            wall: wall / steps as f64,
            neighbours: counts.neighbours as f64 / n,
            contacts: (counts.contacts + counts.wall_contacts) as f64 / n,
            bytes: d.bytes_per_particle(),
            rebuilds: counts.rebuilds - rebuilds,
            step_median: if per_step.len() == steps {
                median(per_step)
            } else {
                f64::NAN
            },
            run_delay,
        })
    };
    creep_dem::with_threads(threads, || run().map_err(|e| e.to_string()))?.map_err(Into::into)
}

/// A timed variant: tier, tiles per axis, threads.
type Variant = (&'static str, usize, usize);

/// A comma-separated list of counts.
fn list(arg: Option<&String>, default: usize) -> Res<Vec<usize>> {
    match arg {
        None => Ok(vec![default]),
        Some(s) => s
            .split(',')
            .map(|k| k.trim().parse::<usize>().map_err(Into::into))
            .collect(),
    }
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

fn main() -> Res<()> {
    let args: Vec<String> = std::env::args().collect();
    let dir = args.get(1).ok_or(
        "usage: packing DIR [steps] [rounds] [cheap|exact|both] [tiles k,k,..] [threads t,t,..] [skin/d]",
    )?;
    let steps: usize = args.get(2).map_or(Ok(400), |s| s.parse())?;
    let rounds: usize = args.get(3).map_or(Ok(3), |s| s.parse())?;
    let tiers = args.get(4).map_or("both", String::as_str);
    let tiles = list(args.get(5), 1)?;
    let threads = list(args.get(6), 1)?;
    // The neighbour skin as a fraction of the mean diameter (default the peers' 0.02).
    let skin_d: f64 = args.get(7).map_or(Ok(0.02), |s| s.parse())?;
    if !(skin_d.is_finite() && skin_d > 0.0) {
        return Err("skin/d must be finite and > 0".into());
    }
    if steps == 0 || rounds == 0 || tiles.contains(&0) || threads.contains(&0) {
        return Err("steps, rounds, tiles and threads must be at least 1".into());
    }
    let mut base = load(dir)?;
    base.skin *= skin_d / 0.02;
    let packings: Vec<Packing> = tiles.iter().map(|&k| tiled(&base, k)).collect();
    let mut names = Vec::new();
    for tier in ["cheap", "exact"] {
        if tiers == "both" || tiers == tier {
            names.push(tier);
        }
    }
    if names.is_empty() {
        return Err(format!("tiers: cheap, exact or both, not {tiers}").into());
    }
    // (tier, tiles, threads) -> particle-steps/s per round.
    let mut all: Vec<(Variant, Vec<f64>)> = Vec::new();
    for round in 1..=rounds {
        for &tier in &names {
            for (p, &k) in packings.iter().zip(&tiles) {
                for &th in &threads {
                    let t = if tier == "cheap" {
                        time::<Cheap>(p, steps, th)?
                    } else {
                        time::<Exact>(p, steps, th)?
                    };
                    let n = p.particles.len() as f64;
                    println!(
                        "round {round} dem-{tier} {:.4e} s/step {:.4e} particle-steps/s wall {:.4e} s/step {:.4e} particle-steps/s particles {n} threads {th} neighbours/particle {:.3} contacts/particle {:.3} bytes/particle {:.0} rebuilds {} median-step {:.4e} s {:.4e} particle-steps/s run-delay {:.1} us/step state {:016x}",
                        t.cpu,
                        n / t.cpu,
                        t.wall,
                        n / t.wall,
                        t.neighbours,
                        t.contacts,
                        t.bytes,
                        t.rebuilds,
                        t.step_median,
                        n / t.step_median,
                        t.run_delay * 1e6,
                        t.digest
                    );
                    let v = if th > 1 { n / t.wall } else { n / t.cpu };
                    let key = (tier, k, th);
                    match all.iter_mut().find(|(kk, _)| *kk == key) {
                        Some((_, r)) => r.push(v),
                        None => all.push((key, vec![v])),
                    }
                }
            }
        }
    }
    for ((tier, k, th), v) in all {
        println!(
            "median dem-{tier} {:.4e} particle-steps/s tiles {k} threads {th} ({})",
            median(v),
            if th > 1 { "wall clock" } else { "CPU time" }
        );
    }
    Ok(())
}
