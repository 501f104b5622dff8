//! `creep bench dem`: particle-steps per second of the dense packing of the triaxial test in
//! the compliant regime (Coulomb-Mindlin and creep-friction) and in plain Rapier, measured side
//! by side in one process (medians over the steps).
//!
//! For the peers (LAMMPS, LIGGGHTS; `bench/peers/`): `--export DIR` writes the compacted
//! packing as a LAMMPS data file with the material, the walls and the time step, and
//! `--rounds R --between CMD` repeats the timing `R` times on the one compacted packing,
//! running `CMD` (e.g. the peers' runs) after each round, so that the tools are interleaved on
//! a shared machine without compacting again (about a minute at 4,096 spheres).

use creep_law::{PairMaterial, Surface, hertz};
use std::io::Write;
use std::path::{Path, PathBuf};

use crate::output::{self, CsvWriter, create_dir};

use creep_dem::{Cheap, Exact};
use creep_scenes::triaxial::{
    Specimen, TriaxialParams, compact, dem_engine_tiled, time_compliant_steps, time_dem_steps,
    time_plain_rapier_steps,
};

type Res = Result<(), Box<dyn std::error::Error>>;

/// Benchmarks.
#[derive(Debug, clap::Subcommand)]
pub enum BenchCommand {
    /// Particle-steps per second of the triaxial test's dense packing (compacted first, which
    /// takes about a minute at 4,096 spheres), compliant regime against plain Rapier.
    Dem {
        /// Spheres per side of the lattice (n^3 spheres).
        #[arg(long, default_value_t = 16)]
        n: usize,
        /// Timed steps per variant (per round with `--rounds`).
        #[arg(long, default_value_t = 200)]
        steps: usize,
        /// Write the compacted packing to this directory for the peers (LAMMPS, LIGGGHTS):
        /// `packing.data` (LAMMPS data file, atom_style sphere: diameter, density, position,
        /// velocities), `params.lmp` (LAMMPS/LIGGGHTS variables: box = wall faces, material,
        /// dt) and `packing.json` (the same and the stresses of the packing).
        #[arg(long, value_name = "DIR")]
        export: Option<PathBuf>,
        /// Timing rounds on the one compacted packing; each round times every variant for
        /// `--steps` steps and prints a `round` line with the mean seconds per step.
        #[arg(long, default_value_t = 1)]
        rounds: usize,
        /// Shell command (`sh -c`) run after each round, with `CREEP_BENCH_ROUND` set to the
        /// round (1-based), e.g. the peers' runs, so that they interleave with ours.
        #[arg(long, value_name = "CMD")]
        between: Option<String>,
        /// Threads of the DEM engine's second set of rows (0: none); the first set is one
        /// thread.
        #[arg(long, default_value_t = 2)]
        dem_threads: usize,
        /// Scale table instead: the DEM engine (cheap tier with creep, one thread) on the
        /// packing tiled k x k x k for each k given (e.g. `1,2,4`: 4k, 32k, 256k spheres).
        #[arg(long, value_delimiter = ',', value_name = "K,K,..")]
        scale: Vec<usize>,
    },
    /// The plugin's cost on a poured pile while it moves, against plain Rapier (crate::bench_pile).
    Pile(crate::bench_pile::PileArgs),
}

/// The columns of the speed tables (`creep bench dem`, and the first of its `--scale` table).
const SPEED_COLUMNS: [&str; 5] = [
    "engine",
    "threads",
    "particles",
    "steps",
    "particle_steps_per_s",
];

/// The median of `v` (creep_scenes::stats::median); NaN when empty (a variant not run).
fn median(mut v: Vec<f64>) -> f64 {
    creep_scenes::stats::median(&mut v).unwrap_or(f64::NAN)
}

fn mean(v: &[f64]) -> f64 {
    if v.is_empty() {
        f64::NAN
    } else {
        v.iter().sum::<f64>() / v.len() as f64
    }
}

/// Runs a benchmark.
pub fn run(cmd: &BenchCommand, out: &mut dyn Write) -> Res {
    match cmd {
        BenchCommand::Pile(args) => crate::bench_pile::run(args, out),
        BenchCommand::Dem {
            n,
            steps,
            export,
            rounds,
            between,
            dem_threads,
            scale,
        } => {
            if *steps == 0 {
                return Err("--steps must be at least 1".into());
            }
            if *rounds == 0 {
                return Err("--rounds must be at least 1".into());
            }
            if let Some(dir) = export {
                // Fail before the minute of compaction, not after it.
                create_dir(dir).map_err(|e| format!("--export: {e}"))?;
            }
            let params = TriaxialParams {
                n_per_side: *n,
                ..TriaxialParams::default()
            };
            let count = n.pow(3) as f64;
            writeln!(
                out,
                "Dense packing of the triaxial test: {} spheres, compacted to {:.0} Pa ({})",
                n.pow(3),
                params.confining_pressure,
                if cfg!(feature = "parallel") {
                    "rapier3d with its `parallel` feature (rayon); the compliant forces are computed on one thread"
                } else {
                    "single thread: rapier3d without its `parallel` feature"
                }
            )?;
            let mut s = Specimen::generate(params)?;
            let c = compact(&mut s, 2_000_000, &mut |_| {})?;
            writeln!(
                out,
                "compacted in {} steps: solid fraction {:.4}, coordination {:.2}",
                c.steps, c.solid_fraction, c.coordination
            )?;
            if let Some(dir) = export {
                let e = export_packing(&s, dir)?;
                writeln!(
                    out,
                    "exported to {}: {} spheres, dt {:.6e} s, wall stress {:.5e} Pa, ball-ball contact pressure {:.5e} Pa",
                    dir.display(),
                    e.spheres,
                    e.dt,
                    e.p_walls,
                    e.p_ball_ball
                )?;
                out.flush()?;
            }
            if !scale.is_empty() {
                return scale_table(&s, scale, *steps, out);
            }
            // Interleave the variants in blocks so the machine's load drifts hit all alike.
            let two = *dem_threads > 1;
            let names = [
                "cm",
                "creep",
                "plain",
                "dem-cheap",
                "dem-exact",
                "dem-cheap-mt",
                "dem-exact-mt",
            ];
            let mut all: Vec<Vec<f64>> = vec![vec![]; names.len()];
            let block = (*steps / 4).max(1);
            for round in 1..=*rounds {
                let mut r: Vec<Vec<f64>> = vec![vec![]; names.len()];
                let mut left = *steps;
                while left > 0 {
                    let k = block.min(left);
                    r[0].extend(time_compliant_steps(&s, false, k)?);
                    r[1].extend(time_compliant_steps(&s, true, k)?);
                    r[2].extend(time_plain_rapier_steps(&s, k));
                    r[3].extend(time_dem_steps::<Cheap>(&s, true, 1, k)?);
                    r[4].extend(time_dem_steps::<Exact>(&s, true, 1, k)?);
                    if two {
                        r[5].extend(time_dem_steps::<Cheap>(&s, true, *dem_threads, k)?);
                        r[6].extend(time_dem_steps::<Exact>(&s, true, *dem_threads, k)?);
                    }
                    left -= k;
                }
                if *rounds > 1 || between.is_some() {
                    // Means, like a loop time divided by its steps (LAMMPS' "Loop time").
                    let cols: Vec<String> = names
                        .iter()
                        .zip(&r)
                        .filter(|(_, v)| !v.is_empty())
                        .map(|(n, v)| format!("{n} {:.6e}", mean(v)))
                        .collect();
                    writeln!(
                        out,
                        "round {round} of {rounds}, mean s/step: {}",
                        cols.join(" ")
                    )?;
                    out.flush()?;
                }
                for (a, b) in all.iter_mut().zip(r) {
                    a.extend(b);
                }
                if let Some(command) = between {
                    run_between(command, round)?;
                }
            }
            let med: Vec<f64> = all.into_iter().map(median).collect();
            let total = *steps * *rounds;
            let mut rows = vec![("dem-cheap", 1, med[3]), ("dem-exact", 1, med[4])];
            if two {
                rows.push(("dem-cheap", *dem_threads, med[5]));
                rows.push(("dem-exact", *dem_threads, med[6]));
            }
            rows.push(("rapier-compliant", 1, med[1]));
            rows.push(("rapier-compliant-cm", 1, med[0]));
            rows.push(("rapier-plain", 1, med[2]));
            let mut csv = CsvWriter::new(out, &SPEED_COLUMNS)?;
            for (name, threads, m) in rows {
                csv.row(&[
                    &name,
                    &threads,
                    &n.pow(3),
                    &total,
                    &format_args!("{:.4e}", count / m),
                ])?;
            }
            Ok(())
        }
    }
}

/// The DEM engine's scale table: the cheap tier with creep, one thread, on the packing tiled
/// `k^3` times for each `k`, particle-step cost relative to the first; and the engine's memory
/// per particle (both tiers, arrays + neighbour list + histories).
fn scale_table(s: &Specimen, tiles: &[usize], steps: usize, out: &mut dyn Write) -> Res {
    let columns: Vec<&str> = SPEED_COLUMNS
        .into_iter()
        .chain(["cost_vs_first", "bytes_per_particle"])
        .collect();
    let mut csv = CsvWriter::new(out, &columns)?;
    let mut first = None;
    for &k in tiles {
        let mut d = dem_engine_tiled::<Cheap>(s, true, false, k)?;
        let n = d.len();
        let mut times = Vec::with_capacity(steps);
        for _ in 0..steps {
            let t = std::time::Instant::now();
            d.step().map_err(|e| format!("DEM engine: {e}"))?;
            times.push(t.elapsed().as_secs_f64());
        }
        let per = median(times) / n as f64;
        let f = *first.get_or_insert(per);
        let exact = dem_engine_tiled::<Exact>(s, true, false, k)?;
        csv.row(&[
            &"dem-cheap",
            &1,
            &n,
            &steps,
            &format_args!("{:.4e}", 1.0 / per),
            &format_args!("{:.3}", per / f),
            &format_args!("{:.0}", d.bytes_per_particle()),
        ])?;
        csv.comment(&format!(
            "dem-exact memory at {n} particles: {:.0} bytes per particle",
            exact.bytes_per_particle()
        ))?;
        csv.flush()?;
    }
    Ok(())
}

/// Runs `command` with `sh -c`, its output going to ours; an error if it cannot start or
/// fails.
fn run_between(command: &str, round: usize) -> Res {
    let status = std::process::Command::new("sh")
        .arg("-c")
        .arg(command)
        .env("CREEP_BENCH_ROUND", round.to_string())
        .status()
        .map_err(|e| format!("--between: cannot run `sh -c {command}`: {e}"))?;
    if !status.success() {
        return Err(format!("--between: `{command}` failed after round {round} ({status})").into());
    }
    Ok(())
}

/// What [`export_packing`] wrote.
struct Exported {
    spheres: usize,
    dt: f64,
    p_walls: f64,
    p_ball_ball: f64,
}

/// One of the six walls: the inner face of a kinematic cuboid.
struct Face {
    axis: usize,
    /// +1: the face looks towards -axis (the upper wall).
    side: f64,
    /// Position of the inner face along `axis` [m].
    at: f64,
}

/// `packing.json`: the number of spheres, the variables of `params.lmp` (name: value), then the
/// packing's figures (SI units, as in `params.lmp`).
#[derive(serde::Serialize)]
struct PackingJson<'a> {
    spheres: usize,
    #[serde(flatten)]
    vars: Vars<'a>,
    /// dt / Rayleigh time of the smallest radius [-].
    dt_over_rayleigh: f64,
    /// Sphere volume / box volume [-].
    solid_fraction: f64,
    /// Normal stress of each wall [Pa] (-x, +x, -y, +y, -z, +z).
    wall_stress: [f64; 6],
    ball_ball_contacts: usize,
    ball_wall_contacts: usize,
}

/// `params.lmp`'s variables (name, value, comment) as a JSON map of name to value, in order.
struct Vars<'a>(&'a [(&'a str, f64, &'a str)]);

impl serde::Serialize for Vars<'_> {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.collect_map(self.0.iter().map(|(name, value, _)| (name, value)))
    }
}

/// Writes the compacted packing to `dir` (see `--export`).
fn export_packing(s: &Specimen, dir: &Path) -> Result<Exported, Box<dyn std::error::Error>> {
    let params = s.params();
    let physics = &s.world().physics;
    let (bodies, colliders) = (&physics.bodies, &physics.colliders);

    // Balls and walls, as the specimen built them (walls: axis-aligned cuboids, thinnest
    // along their axis).
    let mut atoms = Vec::new();
    let mut faces = Vec::new();
    let mut index = std::collections::HashMap::new();
    for (h, co) in colliders.iter() {
        let Some(body) = co.parent().and_then(|b| bodies.get(b)) else {
            continue;
        };
        if let Some(ball) = co.shape().as_ball() {
            index.insert(h, atoms.len());
            atoms.push((
                ball.radius,
                body.translation(),
                body.linvel(),
                body.angvel(),
            ));
        } else if let Some(cub) = co.shape().as_cuboid() {
            let he = cub.half_extents;
            let t = co.translation();
            let axis = (0..3).min_by(|&a, &b| he[a].total_cmp(&he[b])).unwrap_or(0);
            let side = if t[axis] > 0.0 { 1.0 } else { -1.0 };
            faces.push(Face {
                axis,
                side,
                at: f64::from(t[axis]) - side * f64::from(he[axis]),
            });
        }
    }
    if atoms.is_empty() {
        return Err("--export: the packing has no spheres".into());
    }
    let face = |axis: usize, side: f64| {
        faces
            .iter()
            .find(|f| f.axis == axis && f.side == side)
            .map(|f| f.at)
    };
    let mut lo = [0.0; 3];
    let mut hi = [0.0; 3];
    for axis in 0..3 {
        match (face(axis, -1.0), face(axis, 1.0)) {
            (Some(l), Some(h)) if h > l => {
                lo[axis] = l;
                hi[axis] = h;
            }
            _ => {
                return Err(format!(
                    "--export: expected two walls across axis {axis} (found {} walls)",
                    faces.len()
                )
                .into());
            }
        }
    }
    let dims = [hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]];
    let volume = dims[0] * dims[1] * dims[2];

    // Stresses of the last step's contacts: each wall's normal stress and the ball-ball part
    // of the Love-Weber stress (LAMMPS' pair virial: `(1/3V) sum r_ij . f_ij`).
    let centre = |h| {
        colliders
            .get(h)
            .and_then(|co| co.parent())
            .and_then(|b| bodies.get(b))
            .map(|b| b.translation())
            .map(|x| [f64::from(x.x), f64::from(x.y), f64::from(x.z)])
    };
    let mut wall_force = [0.0; 6];
    let mut virial = 0.0;
    // Mean Mindlin stiffness 8 G* a of the ball-ball contacts (a = sqrt(R* delta)): the scale
    // the peers' rolling springs are set to.
    let mut kt_sum = 0.0;
    let (mut ball_ball, mut ball_wall) = (0usize, 0usize);
    for (&(c1, c2), rec) in s.world().compliant().contacts() {
        // Force on p (collider 1) from q.
        let f = rec.tangential_force - rec.normal * rec.normal_force;
        let f = [f.x, f.y, f.z];
        match (index.contains_key(&c1), index.contains_key(&c2)) {
            (true, true) => {
                if let (Some(xp), Some(xq)) = (centre(c1), centre(c2)) {
                    virial -= (0..3).map(|i| (xq[i] - xp[i]) * f[i]).sum::<f64>();
                    let (rp, rq) = (
                        f64::from(atoms[index[&c1]].0),
                        f64::from(atoms[index[&c2]].0),
                    );
                    let pair = PairMaterial::new(
                        &params.material,
                        &params.material,
                        Surface::Sphere(rp),
                        Surface::Sphere(rq),
                    )?;
                    let a = hertz::contact_radius_from_overlap(&pair, rec.overlap.max(0.0));
                    kt_sum += pair.tangential_stiffness(a);
                    ball_ball += 1;
                }
            }
            (false, false) => {}
            (p_is_ball, _) => {
                // The wall's share: the force on the wall, and the normal from it into the ball.
                let (on_wall, n) = if !p_is_ball {
                    (f, rec.normal)
                } else {
                    ([-f[0], -f[1], -f[2]], -rec.normal)
                };
                // The normal from the wall into the ball picks the wall: -side along its axis.
                let n = [n.x, n.y, n.z];
                let axis = (0..3)
                    .max_by(|&a, &b| n[a].abs().total_cmp(&n[b].abs()))
                    .unwrap_or(0);
                let side = if n[axis] < 0.0 { 1.0 } else { -1.0 };
                let k = 2 * axis + usize::from(side > 0.0);
                wall_force[k] += side * on_wall[axis];
                ball_wall += 1;
            }
        }
    }
    let mut wall_stress = [0.0; 6];
    for (k, w) in wall_stress.iter_mut().enumerate() {
        let axis = k / 2;
        *w = wall_force[k] / (dims[(axis + 1) % 3] * dims[(axis + 2) % 3]);
    }
    let p_walls = wall_stress.iter().sum::<f64>() / 6.0;
    let p_ball_ball = virial / (3.0 * volume);

    let m = &params.material;
    let g = m.shear_modulus();
    let nu = m.poisson_ratio();
    let young = m.young_modulus();
    let dt = f64::from(physics.integration_parameters.dt);
    let r_min = params.radius * (1.0 - params.radius_spread);
    let t_r = creep_law::hertz::rayleigh_time_step(m, r_min);
    let prediction = f64::from(physics.integration_parameters.prediction_distance());
    let solids: f64 = atoms
        .iter()
        .map(|a| 4.0 / 3.0 * std::f64::consts::PI * f64::from(a.0).powi(3))
        .sum();
    let d_mean = atoms.iter().map(|a| 2.0 * f64::from(a.0)).sum::<f64>() / atoms.len() as f64;

    let write = |name: &str, text: String| {
        output::write(&dir.join(name), &text).map_err(|e| format!("--export: {e}"))
    };

    // LAMMPS data file (atom_style sphere; LIGGGHTS' atom_style granular reads the same):
    // f32 values printed with 9 significant digits round-trip exactly.
    let mut data = String::new();
    data.push_str(&format!(
        "creep bench dem --export: {} spheres compacted to {:.0} Pa (SI units)\n\n",
        atoms.len(),
        params.confining_pressure
    ));
    data.push_str(&format!("{} atoms\n2 atom types\n\n", atoms.len()));
    for (axis, name) in ["x", "y", "z"].iter().enumerate() {
        data.push_str(&format!(
            "{:.9e} {:.9e} {name}lo {name}hi\n",
            lo[axis], hi[axis]
        ));
    }
    // Section names without LAMMPS' `# style` hints: LIGGGHTS' reader refuses them. Columns
    // (atom_style sphere): atom-ID atom-type diameter density x y z; then atom-ID vx vy vz wx
    // wy wz.
    data.push_str("\nAtoms\n\n");
    for (i, (r, x, _, _)) in atoms.iter().enumerate() {
        data.push_str(&format!(
            "{} 1 {:.9e} {:.9e} {:.9e} {:.9e} {:.9e}\n",
            i + 1,
            2.0 * f64::from(*r),
            m.density(),
            x.x,
            x.y,
            x.z
        ));
    }
    data.push_str("\nVelocities\n\n");
    for (i, (_, _, v, w)) in atoms.iter().enumerate() {
        data.push_str(&format!(
            "{} {:.9e} {:.9e} {:.9e} {:.9e} {:.9e} {:.9e}\n",
            i + 1,
            v.x,
            v.y,
            v.z,
            w.x,
            w.y,
            w.z
        ));
    }
    write("packing.data", data)?;

    let vars: Vec<(&str, f64, &str)> = vec![
        ("xlo", lo[0], "wall faces [m] (the box)"),
        ("xhi", hi[0], ""),
        ("ylo", lo[1], ""),
        ("yhi", hi[1], ""),
        ("zlo", lo[2], ""),
        ("zhi", hi[2], ""),
        ("dt", dt, "time step [s], as Rapier steps it (f32)"),
        (
            "rayleigh_time",
            t_r,
            "Rayleigh time of the smallest radius [s]",
        ),
        ("young", young, "E = 2 G (1 + nu) [Pa]"),
        ("shear", g, "G [Pa]"),
        ("poisson", nu, "nu [-]"),
        ("density", m.density(), "rho [kg/m^3]"),
        ("mu", params.mu, "ball-ball friction [-] (walls: 0)"),
        ("restitution", params.restitution, "e [-]"),
        ("d_mean", d_mean, "mean diameter [m]"),
        ("p0", params.confining_pressure, "confining pressure [Pa]"),
        (
            "skin",
            prediction,
            "Rapier's prediction distance [m]: the peers' neighbour skin",
        ),
        (
            "kt_mean",
            kt_sum / ball_ball.max(1) as f64,
            "mean Mindlin stiffness 8 G* a of the ball-ball contacts [N/m]",
        ),
        ("p_walls", p_walls, "mean wall stress of the packing [Pa]"),
        (
            "p_ball_ball",
            p_ball_ball,
            "ball-ball part of the Love-Weber pressure [Pa] (LAMMPS: pair virial)",
        ),
    ];
    let mut lmp = String::from(
        "# creep bench dem --export: the packing's box, material and time step (SI units)\n",
    );
    for (name, value, what) in &vars {
        let comment = if what.is_empty() {
            String::new()
        } else {
            format!("  # {what}")
        };
        lmp.push_str(&format!("variable {name} equal {value:.9e}{comment}\n"));
    }
    write("params.lmp", lmp)?;

    let json = PackingJson {
        spheres: atoms.len(),
        vars: Vars(&vars),
        dt_over_rayleigh: dt / t_r,
        solid_fraction: solids / volume,
        wall_stress,
        ball_ball_contacts: ball_ball,
        ball_wall_contacts: ball_wall,
    };
    let json = serde_json::to_string_pretty(&json)? + "\n";
    write("packing.json", json)?;

    Ok(Exported {
        spheres: atoms.len(),
        dt,
        p_walls,
        p_ball_ball,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    // The export of a generated (not compacted: that takes a minute at any size in a debug
    // build) packing: the files' shape and numbers.
    #[test]
    fn export_writes_the_packing() {
        let dir = std::env::temp_dir().join(format!("creep-bench-export-{}", std::process::id()));
        std::fs::create_dir_all(&dir).expect("temp dir");
        let params = TriaxialParams {
            n_per_side: 2,
            ..TriaxialParams::default()
        };
        let s = Specimen::generate(params).expect("specimen");
        let e = export_packing(&s, &dir).expect("export");
        assert_eq!(e.spheres, 8);
        assert!((e.dt - params.time_step()).abs() < 1e-6 * e.dt);
        let data = std::fs::read_to_string(dir.join("packing.data")).expect("data file");
        assert!(data.contains("8 atoms\n2 atom types\n"), "{data}");
        let atoms = data
            .split("\nAtoms\n\n")
            .nth(1)
            .and_then(|s| s.split("\n\nVelocities\n\n").next())
            .expect("Atoms section");
        assert_eq!(atoms.lines().count(), 8);
        for line in atoms.lines() {
            let cols: Vec<f64> = line
                .split_whitespace()
                .map(|c| c.parse().expect("number"))
                .collect();
            assert_eq!(cols.len(), 7);
            assert!(cols[2] >= 1.6e-3 && cols[2] <= 2.4e-3, "diameter {line}");
            assert_eq!(cols[3], 2500.0);
        }
        let params_lmp = std::fs::read_to_string(dir.join("params.lmp")).expect("params");
        for v in ["xlo", "zhi", "dt", "young", "skin", "kt_mean", "p_walls"] {
            assert!(params_lmp.contains(&format!("variable {v} equal ")), "{v}");
        }
        assert!(params_lmp.contains("variable young equal 6.960000000e7"));
        let json = std::fs::read_to_string(dir.join("packing.json")).expect("json");
        let v: serde_json::Value = serde_json::from_str(&json).expect("valid JSON");
        // 0.2 to the six decimals the file used to print.
        let ratio = v["dt_over_rayleigh"].as_f64().expect("dt_over_rayleigh");
        assert!((ratio - 0.2).abs() < 5e-7, "{json}");
        assert_eq!(v["spheres"].as_u64(), Some(8), "{json}");
        let young = v["young"].as_f64().expect("young");
        assert!((young / 6.96e7 - 1.0).abs() < 1e-12, "{json}");
        assert_eq!(v["wall_stress"].as_array().map(Vec::len), Some(6), "{json}");
        let _ = std::fs::remove_dir_all(&dir);
    }

    #[test]
    fn bad_input_is_an_error() {
        let mut out = Vec::new();
        let dem = |rounds, steps| BenchCommand::Dem {
            n: 2,
            steps,
            export: None,
            rounds,
            between: None,
            dem_threads: 2,
            scale: vec![],
        };
        assert!(run(&dem(0, 2), &mut out).is_err());
        assert!(run(&dem(1, 0), &mut out).is_err());
        assert!(run_between("true", 1).is_ok());
        let e = run_between("exit 3", 2).expect_err("a failing --between");
        assert!(e.to_string().contains("after round 2"), "{e}");
    }
}
