//! `creep report [--quick] [--out DIR]`: the speed-against-error report. Measures on
//! this machine what each model tier costs per contact update and how wrong it is against the
//! exact theory, and writes `REPORT.md`, the CSVs behind it and SVG/PNG plots into `DIR`.
//!
//! The report is a list of sections ([`SECTIONS`]), each a function that measures, writes its
//! files and returns its Markdown, under its own progress bar: the tiers (speed against error,
//! this file), the time step ([`timestep`]), the scale ([`scale`]) and the stability
//! ([`stability`]) of the Rapier plugin.
//!
//! Errors are graded by [`creep_reference::tiers`] against the checked-in boundary-element tables
//! of `crates/reference/data` (so the report is fast); costs are timed in this process (median
//! of repeated timed loops, inputs and outputs through [`std::hint::black_box`]). The criterion
//! benches (`cargo bench -p creep-law --bench law`, `cargo bench -p creep-reference --bench bem`)
//! hold the authoritative timings.

mod fit;
mod scale;
mod stability;
mod tiers;
mod timestep;

use crate::output::{OutputError, create_dir};
use crate::plot::PlotError;
use clap::Args;
use creep_reference::RefError;
use creep_reference::fastsim::FastsimOptions;
use creep_reference::tiers::GradeOptions;
use indicatif::ProgressBar;
use std::fmt::Write as _;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::time::Instant;

/// Arguments of `creep report`.
#[derive(Debug, Args)]
pub struct ReportArgs {
    /// Coarse grids, fewer repetitions and cases: under a minute (for CI).
    #[arg(long)]
    quick: bool,
    /// Output directory (created if missing): REPORT.md, CSVs, SVG and PNG plots.
    #[arg(long, default_value = "report")]
    out: PathBuf,
}

/// Why the report could not be written.
#[derive(Debug, thiserror::Error)]
pub enum ReportError {
    /// A file or directory could not be written.
    #[error(transparent)]
    Output(#[from] OutputError),
    /// A reference solver or table failed.
    #[error("reference: {0}")]
    Reference(#[from] RefError),
    /// A plot could not be drawn.
    #[error("plot: {0}")]
    Plot(#[from] PlotError),
    /// A scene (time step, scale, stability) could not run.
    #[error("scene: {0}")]
    Scene(#[from] creep_scenes::SceneError),
}

/// Settings of one report run.
#[derive(Debug, Clone, Copy)]
pub struct Config {
    /// `--quick`.
    pub quick: bool,
    /// Timed loops per tier (the median is reported).
    pub reps: usize,
    /// Target duration of one timed loop [s].
    pub loop_seconds: f64,
    /// Live references used while grading.
    pub grade: GradeOptions,
    /// Boundary-element grid whose cost is timed (the grid of the tabulated curve it is graded
    /// by).
    pub bem_grid: usize,
    /// Force increments per branch of the Cattaneo-Mindlin cycle.
    pub mindlin_steps: usize,
}

impl Config {
    /// The quick (CI) or full settings.
    pub fn new(quick: bool) -> Self {
        let grade = GradeOptions {
            fastsim: FastsimOptions {
                strips: if quick { 40 } else { 100 },
                elements: if quick { 40 } else { 100 },
                ..FastsimOptions::default()
            },
            bem_grid: if quick { 12 } else { 32 },
            steady_roll_steps: if quick { 200 } else { 800 },
        };
        Config {
            quick,
            // Many short loops: on a loaded machine the median is a loop that ran without
            // being preempted (a loop is shorter than a scheduler time slice).
            reps: if quick { 21 } else { 101 },
            loop_seconds: if quick { 5e-4 } else { 1e-3 },
            grade,
            bem_grid: 32,
            mindlin_steps: if quick { 20 } else { 200 },
        }
    }
}

/// One section of the report: its Markdown and the files it wrote.
#[derive(Debug, Default)]
pub struct Section {
    /// Markdown, starting with a `##` heading.
    pub markdown: String,
    /// Files written (relative to the output directory).
    pub files: Vec<String>,
}

/// A section of the report: measures, writes its files into the directory, returns its Markdown.
type SectionFn = fn(&Config, &Path, &ProgressBar) -> Result<Section, ReportError>;

/// The sections, in order.
const SECTIONS: [(&str, SectionFn); 4] = [
    ("tiers", tiers::section),
    ("time step", timestep::section),
    ("scale", scale::section),
    ("stability", stability::section),
];

/// Runs `creep report`.
pub fn run(args: &ReportArgs, out: &mut dyn Write) -> Result<(), Box<dyn std::error::Error>> {
    let cfg = Config::new(args.quick);
    let dir = &args.out;
    create_dir(dir)?;
    let started = Instant::now();
    let mut md = String::from("# Speed against error\n\n");
    let _ = writeln!(
        md,
        "Written by `creep report{}` ({} build, {} hardware threads). Sections: the model \
         tiers' speed against error (graded against the boundary-element solution of Kalker's \
         exact theory, `creep-reference`), the time step, the scale (Rapier's step with and \
         without the plugin) and the stability (the rigid regime's hard cases) of the Rapier \
         plugin. Every time is measured in this process.\n",
        if cfg.quick { " --quick" } else { "" },
        if cfg!(debug_assertions) {
            "debug"
        } else {
            "release"
        },
        std::thread::available_parallelism().map_or(1, |n| n.get()),
    );
    let mut files = Vec::new();
    for (name, section) in SECTIONS {
        let pb = progress_bar(name);
        let s = section(&cfg, dir, &pb)?;
        pb.finish_and_clear();
        md += &s.markdown;
        files.extend(s.files);
    }
    let _ = writeln!(
        md,
        "\nReport written in {:.1} s.",
        started.elapsed().as_secs_f64()
    );
    crate::output::write(&dir.join("REPORT.md"), &md)?;
    writeln!(out, "{}", dir.join("REPORT.md").display())?;
    for f in files {
        writeln!(out, "{}", dir.join(f).display())?;
    }
    Ok(())
}

/// A progress bar for one section; its length is set by the section.
fn progress_bar(section: &str) -> ProgressBar {
    crate::progress::bar(1, &format!("report: {section}"))
}
