//! `creep bench pile --moving --n N [--steps S]`: the cost of the plugin on a poured pile while
//! it moves. `N` spheres (rounded to a cube `n^3`) fall into a box and settle; plain Rapier
//! (the plugin's integration parameters), the plugin at `Fidelity::Auto` and the plugin with
//! creep on every contact step from the same state, in turn each step; the last line prints the
//! medians of the per-step ratios (`creep_scenes::pile::moving_ratios`).

use std::io::Write;

type Res = Result<(), Box<dyn std::error::Error>>;

/// Arguments of `creep bench pile`.
#[derive(Debug, clap::Args)]
pub struct PileArgs {
    /// Time the pile while it moves (pour and settling); the only mode.
    #[arg(long)]
    pub moving: bool,
    /// Spheres (rounded to the nearest cube n^3; 1,000 = 10^3, 4,096 = 16^3).
    #[arg(long, default_value_t = 1000)]
    pub n: usize,
    /// Steps timed, from the release of the lattice (1/60 s each; 300 = 5 s: the pour and the
    /// settling).
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
    if !args.moving {
        return Err("creep bench pile needs --moving (the settled pile is `cargo bench -p creep-scenes --bench pile`)".into());
    }
    if args.n == 0 {
        return Err("--n must be at least 1".into());
    }
    let side = (args.n as f64).cbrt().round().max(1.0) as usize;
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
        assert!(
            run(
                &PileArgs {
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
