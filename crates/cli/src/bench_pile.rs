//! `creep bench pile --settled --n N [--steps S]`: the cost of the plugin on a poured pile once
//! it sleeps: `N` steel balls (rounded to a cube `n^3`) poured into a box with sleeping on and
//! `CreepWorld::new`'s defaults, four piles (plain Rapier, the plugin at `Coulomb`, `Auto` and
//! `Creep`) each settled for `--settle` steps, then `S` steps of each timed in turn; prints how
//! many balls sleep and the median step times and ratios (`creep_scenes::pile::settled_costs`).
//!
//! `creep bench pile --moving --n N [--steps S]`: the cost of the plugin on a poured pile while
//! it moves. `N` spheres (rounded to a cube `n^3`) fall into a box and settle; plain Rapier
//! (the plugin's integration parameters), the plugin at `Fidelity::Auto` and the plugin with
//! creep on every contact step from the same state, in turn each step; prints the medians of
//! the per-step ratios over the pour (the first `creep_scenes::pile::POUR_STEPS` steps) and,
//! last, over all the steps (`creep_scenes::pile::moving_ratios`).

use std::io::Write;

type Res = Result<(), Box<dyn std::error::Error>>;

/// Arguments of `creep bench pile`.
#[derive(Debug, clap::Args)]
pub struct PileArgs {
    /// Time the pile while it moves (pour and settling).
    #[arg(long)]
    pub moving: bool,
    /// Time the settled pile, asleep (pour, settle for `--settle` steps, then time `--steps`).
    #[arg(long, conflicts_with = "moving")]
    pub settled: bool,
    /// Settling steps of `--settled` (1/60 s each).
    #[arg(long, default_value_t = 900)]
    pub settle: usize,
    /// Spheres (rounded to the nearest cube n^3; 1,000 = 10^3, 4,096 = 16^3).
    #[arg(long, default_value_t = 1000)]
    pub n: usize,
    /// Steps timed (1/60 s each): with `--moving` from the release of the lattice (300 = 5 s:
    /// the pour and the settling), with `--settled` after the settling.
    #[arg(long, default_value_t = 300)]
    pub steps: usize,
    /// Step only one of the plugin copies beside plain Rapier (`auto` or `creep`; the other's
    /// ratio prints as NaN): to profile one fidelity at a time.
    #[arg(long)]
    pub only: Option<OnlyWorld>,
}

/// The plugin copy `creep bench pile --only` steps.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum OnlyWorld {
    /// `Fidelity::Auto`.
    Auto,
    /// Creep on every contact.
    Creep,
}

/// Runs `creep bench pile`.
pub fn run(args: &PileArgs, out: &mut dyn Write) -> Res {
    if !args.moving && !args.settled {
        return Err("creep bench pile needs --moving or --settled (the awake settled pile is `cargo bench -p creep-scenes --bench pile`)".into());
    }
    if args.n == 0 {
        return Err("--n must be at least 1".into());
    }
    let side = (args.n as f64).cbrt().round().max(1.0) as usize;
    if args.settled {
        let c = creep_scenes::pile::settled_costs(side, args.settle, args.steps)?;
        writeln!(
            out,
            "settled pile: {} steel balls, settled {} steps of 1/60 s, {} steps timed; asleep: plain {} coulomb {} auto {} creep {}",
            c.spheres,
            c.settle_steps,
            c.timed_steps,
            c.asleep[0],
            c.asleep[1],
            c.asleep[2],
            c.asleep[3]
        )?;
        writeln!(
            out,
            "median step [us]: plain {:.3} coulomb {:.3} auto {:.3} creep {:.3}",
            c.step[0] * 1e6,
            c.step[1] * 1e6,
            c.step[2] * 1e6,
            c.step[3] * 1e6
        )?;
        writeln!(
            out,
            "mean step [us]: plain {:.3} coulomb {:.3} auto {:.3} creep {:.3}",
            c.mean[0] * 1e6,
            c.mean[1] * 1e6,
            c.mean[2] * 1e6,
            c.mean[3] * 1e6
        )?;
        writeln!(
            out,
            "median step ratios: coulomb/plain {:.3} auto/plain {:.3} creep/plain {:.3}",
            c.step[1] / c.step[0],
            c.step[2] / c.step[0],
            c.step[3] / c.step[0]
        )?;
        return Ok(());
    }
    let worlds = match args.only {
        None => [true, true],
        Some(OnlyWorld::Auto) => [true, false],
        Some(OnlyWorld::Creep) => [false, true],
    };
    let r = creep_scenes::pile::moving_ratios_of(side, args.steps, worlds)?;
    writeln!(
        out,
        "moving pile: {} spheres, {} steps of 1/60 s from release, {} active contact pairs at the end; plain Rapier median step {:.3} ms",
        r.spheres,
        r.steps,
        r.contacts,
        r.plain_step * 1e3
    )?;
    writeln!(
        out,
        "median per-step ratios over the pour ({} steps): auto/plain {:.3} creep/plain {:.3}",
        r.pour_steps, r.pour_auto, r.pour_creep
    )?;
    writeln!(
        out,
        "median per-step ratios: auto/plain {:.3} creep/plain {:.3}",
        r.auto, r.creep
    )?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn prints_the_ratios_last() {
        let mut out = Vec::new();
        run(
            &PileArgs {
                settled: false,
                settle: 0,
                moving: true,
                n: 8,
                steps: 6,
                only: None,
            },
            &mut out,
        )
        .unwrap();
        let text = String::from_utf8(out).unwrap();
        let last = text.lines().last().unwrap();
        assert!(
            last.starts_with("median per-step ratios: auto/plain "),
            "{last}"
        );
        let nums: Vec<f64> = last
            .split_whitespace()
            .filter_map(|w| w.parse().ok())
            .collect();
        assert_eq!(nums.len(), 2, "{last}");
        assert!(nums.iter().all(|r| *r > 0.0 && r.is_finite()));
        // One copy only: its ratio, the other's NaN.
        let mut out = Vec::new();
        run(
            &PileArgs {
                settled: false,
                settle: 0,
                moving: true,
                n: 8,
                steps: 4,
                only: Some(OnlyWorld::Creep),
            },
            &mut out,
        )
        .unwrap();
        let text = String::from_utf8(out).unwrap();
        let last = text.lines().last().unwrap();
        assert!(last.contains("auto/plain NaN creep/plain "), "{last}");
        // The settled pile: its three ratios last.
        let mut out = Vec::new();
        run(
            &PileArgs {
                settled: true,
                settle: 30,
                moving: false,
                n: 8,
                steps: 3,
                only: None,
            },
            &mut out,
        )
        .unwrap();
        let text = String::from_utf8(out).unwrap();
        let last = text.lines().last().unwrap();
        assert!(
            last.starts_with("median step ratios: coulomb/plain "),
            "{last}"
        );
        assert!(
            run(
                &PileArgs {
                    settled: false,
                    settle: 0,
                    moving: false,
                    n: 8,
                    steps: 1,
                    only: None,
                },
                &mut Vec::new()
            )
            .is_err()
        );
        assert!(
            run(
                &PileArgs {
                    settled: false,
                    settle: 0,
                    moving: true,
                    n: 8,
                    steps: 0,
                    only: None,
                },
                &mut Vec::new()
            )
            .is_err()
        );
    }
}
