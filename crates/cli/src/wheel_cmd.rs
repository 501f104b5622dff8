//! `creep run wheel-on-sand`: a driven rigid wheel (a Rapier cylinder) on a granular bed
//! (creep-dem), coupled both ways by creep-bed; CSV on stdout.

use std::io::Write;

use creep_bed::wheel::{WheelOnSand, wheel_on_sand};
use creep_dem::Cheap;

type Res = Result<(), Box<dyn std::error::Error>>;

/// Arguments of `creep run wheel-on-sand`.
#[derive(Debug, clap::Args)]
pub struct WheelArgs {
    /// Grains in the bed (about; 4 layers, 6 across, the rest along the travel).
    #[arg(long, default_value_t = 2000)]
    grains: usize,
    /// Slip ratio s = 1 - v/(w R) of the driven wheel, in [0, 1].
    #[arg(long, default_value_t = 0.2)]
    slip: f64,
    /// Game steps driven (each 20 DEM steps).
    #[arg(long, default_value_t = 400)]
    steps: usize,
    /// Coulomb-Mindlin only at the contacts (no creep).
    #[arg(long)]
    no_creep: bool,
    /// Instead of the scene: the coupling's cost against the bed alone, interleaved
    /// (`--grains` grains, 5 layers, 20 across; `--rounds` blocks of 1,000 DEM steps each);
    /// prints `grains,rounds,steps_per_block,bed_alone_s_per_step,coupled_s_per_step,ratio,wheel_contacts,refreshes`.
    #[arg(long)]
    cost: bool,
    /// Rounds of `--cost`.
    #[arg(long, default_value_t = 5)]
    rounds: usize,
}

/// Runs the scene; prints `t,slip,sinkage,drawbar_pull,torque` (s, -, m, N, N m).
pub fn run(a: &WheelArgs, out: &mut dyn Write) -> Res {
    if a.cost {
        let nx = (a.grains / 100).max(4);
        let c = creep_bed::cost::coupling_cost([nx, 5, 20], a.rounds)?;
        writeln!(
            out,
            "grains,rounds,steps_per_block,bed_alone_s_per_step,coupled_s_per_step,ratio,wheel_contacts,refreshes"
        )?;
        writeln!(
            out,
            "{},{},{},{:.4e},{:.4e},{:.4},{},{}",
            c.grains,
            c.rounds,
            c.steps,
            c.alone,
            c.coupled,
            c.coupled / c.alone,
            c.contacts,
            c.refreshes
        )?;
        return Ok(());
    }
    let mut s = WheelOnSand::with_grains(a.grains, a.slip);
    s.drive_steps = a.steps;
    if a.no_creep {
        s.bed.creep = None;
    }
    writeln!(out, "t,slip,sinkage,drawbar_pull,torque")?;
    let mut failed = None;
    wheel_on_sand::<Cheap>(&s, |r| {
        if failed.is_none()
            && let Err(e) = writeln!(
                out,
                "{},{},{},{},{}",
                r.t, r.slip, r.sinkage, r.drawbar_pull, r.torque
            )
        {
            failed = Some(e);
        }
    })?;
    if let Some(e) = failed {
        return Err(e.into());
    }
    Ok(())
}
