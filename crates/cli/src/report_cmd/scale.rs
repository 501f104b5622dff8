//! The scale section: Rapier's step time with and without the plugin on settled piles of about
//! 1k, 4k, 16k and 64k spheres (`creep_scenes::pile`'s stacked packings; `--quick`: 1k and 4k),
//! measured in this process with the two copies of each pile stepped alternately from the same
//! settled state (`pile::interleaved`), and how the cost grows with the number of contacts
//! (the slope of `ln t` against `ln contacts`, [`super::fit::power_fit`]). The criterion bench
//! `cargo bench -p creep-scenes --bench pile` (group `pile_scale_step`) times the same piles.

use std::fmt::Write as _;
use std::path::Path;

use creep_scenes::pile::{self, Interleaved};
use indicatif::ProgressBar;

use super::fit::{PowerFit, power_fit};
use super::{Config, ReportError, Section};
use crate::output::Csv;
use crate::plot::{Legend, LineChart, Series};

/// One pile's measurement.
#[derive(Debug, Clone, Copy)]
struct Row {
    spheres: usize,
    settle_steps: usize,
    settle_seconds: f64,
    max_speed: f64,
    t: Interleaved,
}

/// The piles (`n` per side of the full layers) and the pairs of steps timed on each.
fn plan(cfg: &Config) -> Vec<(usize, usize)> {
    let [s1, s4, s16, s64] = pile::SCALE_SIDES;
    if cfg.quick {
        vec![(s1, 40), (s4, 10)]
    } else {
        vec![(s1, 200), (s4, 80), (s16, 30), (s64, 16)]
    }
}

fn fit_text(f: Option<PowerFit>) -> String {
    f.map_or("n/a".into(), |f| {
        format!("{:.2} (R^2 {:.3})", f.exponent, f.r2)
    })
}

/// The scale section (`scale.csv`, `scale.svg`/`.png`).
pub fn section(cfg: &Config, dir: &Path, pb: &ProgressBar) -> Result<Section, ReportError> {
    let plan = plan(cfg);
    pb.set_length(2 * plan.len() as u64);
    let mut rows = Vec::new();
    for (n, pairs) in plan {
        let count = pile::stacked_count(n, pile::SCALE_LAYERS);
        pb.set_message(format!("scale: settle {count}"));
        let p = pile::stacked(n, pile::SCALE_LAYERS, pile::SCALE_SETTLE_STEPS)?;
        pb.inc(1);
        pb.set_message(format!("scale: time {count}"));
        let (mut plain, mut auto) = pile::plain_and_auto(&p)?;
        let row = Row {
            spheres: p.spheres,
            settle_steps: p.settle_steps,
            settle_seconds: p.settle_seconds,
            max_speed: p.max_speed,
            t: pile::interleaved(&mut plain, &mut auto, pairs)?,
        };
        // Free the three copies before the next, larger pile.
        drop((p, plain, auto));
        rows.push(row);
        pb.inc(1);
    }
    pb.set_message("scale: writing");
    let mut csv = Csv::new(&[
        "spheres",
        "active_contact_pairs",
        "settle_steps",
        "settle_s",
        "max_speed_m_s",
        "pairs",
        "plain_step_s",
        "plugin_step_s",
        "ratio_median_of_pairs",
        "ratio_of_medians",
        "hooks_on",
    ]);
    for r in &rows {
        csv.row(&[
            &r.spheres,
            &r.t.contacts,
            &r.settle_steps,
            &format_args!("{:.3}", r.settle_seconds),
            &format_args!("{:.3e}", r.max_speed),
            &r.t.pairs,
            &format_args!("{:.6e}", r.t.plain),
            &format_args!("{:.6e}", r.t.plugin),
            &format_args!("{:.4}", r.t.ratio),
            &format_args!("{:.4}", r.t.plugin / r.t.plain),
            &r.t.hooks_on,
        ]);
    }
    csv.write(&dir.join("scale.csv"))?;
    let plain_pts: Vec<(f64, f64)> = rows
        .iter()
        .map(|r| (r.t.contacts as f64, r.t.plain))
        .collect();
    let plugin_pts: Vec<(f64, f64)> = rows
        .iter()
        .map(|r| (r.t.contacts as f64, r.t.plugin))
        .collect();
    let (fit_plain, fit_plugin) = (power_fit(&plain_pts), power_fit(&plugin_pts));
    let mut csv = Csv::new(&[
        "variant",
        "exponent_vs_contacts",
        "prefactor_s",
        "r2",
        "points",
    ]);
    for (name, f) in [("plain", fit_plain), ("plugin_auto", fit_plugin)] {
        let (k, c, r2, n) = f.map_or((String::new(), String::new(), String::new(), 0), |f| {
            (
                format!("{:.6}", f.exponent),
                format!("{:.6e}", f.prefactor),
                format!("{:.6}", f.r2),
                f.points,
            )
        });
        csv.row(&[&name, &k, &c, &r2, &n]);
    }
    csv.write(&dir.join("scale_fit.csv"))?;

    // The plot: step time against contacts, both variants, with the fitted power laws.
    let mut chart = LineChart::new(
        "Rapier's step on settled piles: plain and with the plugin",
        "active contact pairs",
        "step time (median) [s]",
    )
    .legend(Legend::UpperLeft);
    chart = chart
        .series(Series::line("plain Rapier", plain_pts.clone()).color(1))
        .series(Series::line("with the plugin (Auto)", plugin_pts.clone()).color(2));
    for (f, pts, k, name) in [
        (fit_plain, &plain_pts, 1, "plain fit"),
        (fit_plugin, &plugin_pts, 2, "plugin fit"),
    ] {
        if let Some(f) = f {
            let line = pts
                .iter()
                .map(|&(x, _)| (x, f.prefactor * x.powf(f.exponent)))
                .collect();
            chart = chart.series(
                Series::line(format!("{name}: contacts^{:.2}", f.exponent), line)
                    .color(k)
                    .dashed(),
            );
        }
    }
    chart.write_log_log(&dir.join("scale"))?;

    let mut md = String::from("## Scale: Rapier's step with and without the plugin\n\n");
    let _ = writeln!(
        md,
        "Settled piles of 5 cm glass spheres in a box (`creep_scenes::pile::stacked`: \
         face-centred cubic packings of {} layers that start at rest in contact, settled by \
         {} steps of plain Rapier at 1/60 s, sleeping off, every collider then registered with \
         the plugin at `Fidelity::Auto`, the default). Each pile is copied twice, plain Rapier \
         (no hook flags) and the plugin, and the two copies are stepped alternately (which one \
         goes first alternates too) so that this shared machine's load hits both alike: step \
         times are medians, the ratio is the median of the per-pair ratios. Settled contacts \
         move slower than the plugin's activation speed (1e-2 m/s), so the plugin keeps their \
         hooks off and Rapier's contact recycling on: its cost on a settled pile is the \
         activation check. Criterion numbers for the same piles: `cargo bench -p creep-scenes \
         --bench pile` (group `pile_scale_step`; `pile_4096_step` for the dropped 4,096-sphere \
         pile with every fidelity). Data: `scale.csv`, `scale_fit.csv`.\n",
        pile::SCALE_LAYERS,
        pile::SCALE_SETTLE_STEPS
    );
    md += "| spheres | active contact pairs | settled: max speed | pairs timed | plain step | \
           with the plugin | plugin / plain (median of pairs) | ratio of medians | hooks on |\n\
           |---|---|---|---|---|---|---|---|---|\n";
    for r in &rows {
        let _ = writeln!(
            md,
            "| {} | {} | {:.1e} m/s ({} steps, {:.1} s) | {} | {:.2} ms | {:.2} ms | {:.3} | {:.3} | {} |",
            r.spheres,
            r.t.contacts,
            r.max_speed,
            r.settle_steps,
            r.settle_seconds,
            r.t.pairs,
            r.t.plain * 1e3,
            r.t.plugin * 1e3,
            r.t.ratio,
            r.t.plugin / r.t.plain,
            r.t.hooks_on
        );
    }
    let per_contact = |t: f64, c: usize| t / c.max(1) as f64 * 1e9;
    let _ = writeln!(
        md,
        "\nStep time against active contact pairs, `t = c N_c^k` (least squares in log-log): \
         plain Rapier k = {}, with the plugin k = {}{}.\n\n\
         ![step time against contacts](scale.png)\n",
        fit_text(fit_plain),
        fit_text(fit_plugin),
        match (rows.first(), rows.last()) {
            (Some(a), Some(b)) if rows.len() > 1 => format!(
                "; per contact pair, plain Rapier takes {:.0} ns at {} spheres and {:.0} ns at {}",
                per_contact(a.t.plain, a.t.contacts),
                a.spheres,
                per_contact(b.t.plain, b.t.contacts),
                b.spheres
            ),
            _ => String::new(),
        }
    );
    Ok(Section {
        markdown: md,
        files: ["scale.csv", "scale_fit.csv", "scale.svg", "scale.png"]
            .map(String::from)
            .to_vec(),
    })
}
