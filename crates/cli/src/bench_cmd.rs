//! `creep bench dem`: particle-steps per second of the dense packing of the triaxial test in
//! the compliant regime (Coulomb-Mindlin and creep-friction) and in plain Rapier, measured side
//! by side in one process (medians over the steps).

use std::io::Write;

use creep_scenes::triaxial::{
    Specimen, TriaxialParams, compact, time_compliant_steps, time_plain_rapier_steps,
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
        /// Timed steps per variant.
        #[arg(long, default_value_t = 200)]
        steps: usize,
    },
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v.get(v.len() / 2).copied().unwrap_or(f64::NAN)
}

/// Runs a benchmark.
pub fn run(cmd: &BenchCommand, out: &mut dyn Write) -> Res {
    match cmd {
        BenchCommand::Dem { n, steps } => {
            if *steps == 0 {
                return Err("--steps must be at least 1".into());
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
            // Interleave the variants in blocks so the machine's load drifts hit all alike.
            let (mut cm, mut cr, mut pr) = (vec![], vec![], vec![]);
            let block = (*steps / 4).max(1);
            let mut left = *steps;
            while left > 0 {
                let k = block.min(left);
                cm.extend(time_compliant_steps(&s, false, k)?);
                cr.extend(time_compliant_steps(&s, true, k)?);
                pr.extend(time_plain_rapier_steps(&s, k));
                left -= k;
            }
            let (m_cm, m_cr, m_pr) = (median(cm), median(cr), median(pr));
            writeln!(
                out,
                "| variant | ms/step (median) | particle-steps/s | vs plain Rapier |"
            )?;
            writeln!(out, "|---|---|---|---|")?;
            for (name, m) in [
                ("compliant, Coulomb-Mindlin", m_cm),
                ("compliant, creep-friction", m_cr),
                ("plain Rapier (rigid contacts)", m_pr),
            ] {
                writeln!(
                    out,
                    "| {name} | {:.3} | {:.3e} | {:.2} |",
                    m * 1e3,
                    count / m,
                    m / m_pr
                )?;
            }
            Ok(())
        }
    }
}
