//! The whole test on creep-dem (compaction, then the Coulomb-Mindlin and the creep-friction
//! shears) as one run that can stop at any step boundary and continue from a checkpoint to the
//! same results, bit for bit, as a run that never stopped.
//!
//! A checkpoint (creep-dem's framed file, kind [`RUN_KIND`]) holds the configuration (its
//! TOML), the phase, the compaction's or the shear's loop state (step, settling count, the
//! servo's last stress input; the shear's reference height and volume, step count, rows so
//! far), the engines (the compacted packing and, in a shear, the sheared copy, each with every
//! contact history: [`creep_dem::Dem::write_checkpoint`]), the finished phases' results and
//! the time spent so far.

use std::path::Path;

use creep_dem::checkpoint::{
    CheckpointError, CheckpointReader, CheckpointWriter, read_file, seal, unseal, write_atomic,
};
use creep_dem::{Dem, Exact};

use super::dem::{DemSpecimen, table};
use super::params::{TriaxialConfig, TriaxialEngine};
use super::protocol::{CompactLoop, CompactionSummary, ShearLoop, ShearRun};
use super::report::TriaxialRow;
use super::stress::Stress;
use crate::SceneError;

/// The kind of a triaxial run's checkpoint.
pub const RUN_KIND: &str = "creep triaxial run";

/// Why a run could not go on.
#[derive(Debug, thiserror::Error)]
pub enum RunError {
    /// The test refused something.
    #[error(transparent)]
    Scene(#[from] SceneError),
    /// The checkpoint could not be written or read.
    #[error(transparent)]
    Checkpoint(#[from] CheckpointError),
}

/// The phases of a run.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Phase {
    /// Isotropic compaction, frictionless.
    Compaction,
    /// A shear, with creep-friction on or off.
    Shear {
        /// Kuhn's creep term on.
        creep: bool,
    },
}

impl Phase {
    /// `compaction`, `shear_coulomb` or `shear_creep`.
    pub fn name(self) -> &'static str {
        match self {
            Self::Compaction => "compaction",
            Self::Shear { creep: false } => "shear_coulomb",
            Self::Shear { creep: true } => "shear_creep",
        }
    }
    fn index(self) -> usize {
        match self {
            Self::Compaction => 0,
            Self::Shear { creep: false } => 1,
            Self::Shear { creep: true } => 2,
        }
    }
}

/// What to do at a step boundary.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Boundary {
    /// Go on.
    Continue,
    /// Write the checkpoint, then go on.
    Checkpoint,
    /// Write the checkpoint and return [`Outcome::Stopped`].
    Stop,
}

/// How [`DemRun::run`] ended.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Outcome {
    /// Every phase is done.
    Finished,
    /// Stopped at a boundary, the checkpoint written.
    Stopped {
        /// The phase it stopped in.
        phase: Phase,
        /// The engine's step count there.
        steps: u64,
    },
}

/// [`RunHooks::boundary`]'s type.
pub type BoundaryHook<'a> = dyn FnMut(Phase, &Dem<Exact>) -> Result<Boundary, RunError> + 'a;
/// [`RunHooks::phase_done`]'s type.
pub type PhaseDoneHook<'a> = dyn FnMut(Phase, &Dem<Exact>, &DemRun) -> Result<(), RunError> + 'a;

/// The callbacks of [`DemRun::run`].
pub struct RunHooks<'a> {
    /// Progress of a phase, `[0, 1]`.
    pub progress: &'a mut dyn FnMut(Phase, f64),
    /// At every step boundary (and once more when a phase ends), with the engine: what to do
    /// (e.g. write a snapshot, ask for a checkpoint every so many steps or on Ctrl-C).
    pub boundary: &'a mut BoundaryHook<'a>,
    /// When a phase ends, with the engine as it ended and the run (its results so far).
    pub phase_done: &'a mut PhaseDoneHook<'a>,
    /// `[wall, cpu]` seconds now on some clock (differences are added to [`DemRun::seconds`]).
    pub clock: &'a mut dyn FnMut() -> [f64; 2],
    /// Where [`Boundary::Checkpoint`] and [`Boundary::Stop`] write.
    pub checkpoint: Option<&'a Path>,
}

enum Stage {
    Compacting {
        spec: Box<DemSpecimen>,
        lp: Box<CompactLoop>,
    },
    Shearing {
        compacted: Box<DemSpecimen>,
        spec: Box<DemSpecimen>,
        lp: Box<ShearLoop>,
    },
    Done {
        compacted: Box<DemSpecimen>,
    },
    /// Between two phases (only inside [`DemRun::advance`]).
    Taken,
}

/// The test on creep-dem as one resumable run (module docs).
pub struct DemRun {
    config: TriaxialConfig,
    max_compaction_steps: usize,
    stage: Stage,
    compaction: Option<CompactionSummary>,
    shears: Vec<ShearRun>,
    /// `[wall, cpu]` seconds spent per phase (compaction, Coulomb shear, creep shear), over
    /// every session of the run.
    pub seconds: [[f64; 2]; 3],
}

impl DemRun {
    /// A fresh run of `config` (its engine must be `dem`): the packing generated, ready to
    /// compact (an error if it has not settled after `max_compaction_steps`).
    pub fn new(config: TriaxialConfig, max_compaction_steps: usize) -> Result<Self, RunError> {
        if config.engine != TriaxialEngine::Dem {
            return Err(SceneError::Parameter(
                "a resumable triaxial run needs the dem engine".into(),
            )
            .into());
        }
        config.params.validate()?;
        let spec = DemSpecimen::generate(config.params)?;
        let lp = CompactLoop::start(&spec);
        Ok(Self {
            config,
            max_compaction_steps,
            stage: Stage::Compacting {
                spec: Box::new(spec),
                lp: Box::new(lp),
            },
            compaction: None,
            shears: Vec::new(),
            seconds: [[0.0; 2]; 3],
        })
    }

    /// The configuration.
    pub fn config(&self) -> &TriaxialConfig {
        &self.config
    }
    /// The compaction's summary, once done.
    pub fn compaction(&self) -> Option<&CompactionSummary> {
        self.compaction.as_ref()
    }
    /// The finished shears, Coulomb-Mindlin first.
    pub fn shears(&self) -> &[ShearRun] {
        &self.shears
    }
    /// The phase the run is in (`None`: finished).
    pub fn phase(&self) -> Option<Phase> {
        match &self.stage {
            Stage::Compacting { .. } => Some(Phase::Compaction),
            Stage::Shearing { lp, .. } => Some(Phase::Shear { creep: lp.creep }),
            Stage::Done { .. } | Stage::Taken => None,
        }
    }
    /// The engine's step count in the current phase (the compacted packing's once finished).
    pub fn engine_steps(&self) -> u64 {
        match &self.stage {
            Stage::Taken => 0,
            _ => self.engine().steps(),
        }
    }
    /// The engine of the current phase (the compacted packing once finished).
    fn engine(&self) -> &Dem<Exact> {
        match &self.stage {
            Stage::Compacting { spec, .. } | Stage::Shearing { spec, .. } => spec.engine(),
            Stage::Done { compacted } => compacted.engine(),
            Stage::Taken => unreachable!("only between two phases"),
        }
    }

    /// Runs (or continues) to the end, or until `hooks.boundary` says stop.
    pub fn run(&mut self, hooks: &mut RunHooks<'_>) -> Result<Outcome, RunError> {
        let mut mark = (hooks.clock)();
        loop {
            let Some(phase) = self.phase() else {
                return Ok(Outcome::Finished);
            };
            let action = (hooks.boundary)(phase, self.engine())?;
            if action != Boundary::Continue {
                self.tick(phase, &mut mark, hooks);
                let path = hooks.checkpoint.ok_or_else(|| {
                    SceneError::Parameter("a checkpoint was asked for without a path".into())
                })?;
                write_atomic(path, &self.to_checkpoint())?;
                if action == Boundary::Stop {
                    return Ok(Outcome::Stopped {
                        phase,
                        steps: self.engine().steps(),
                    });
                }
            }
            self.advance(phase, &mut mark, hooks)?;
        }
    }

    /// Adds the time since `mark` to the phase's.
    fn tick(&mut self, phase: Phase, mark: &mut [f64; 2], hooks: &mut RunHooks<'_>) {
        let now = (hooks.clock)();
        let s = &mut self.seconds[phase.index()];
        for k in 0..2 {
            s[k] += now[k] - mark[k];
        }
        *mark = now;
    }

    /// One step of the current phase, and the move to the next phase when it ends.
    fn advance(
        &mut self,
        phase: Phase,
        mark: &mut [f64; 2],
        hooks: &mut RunHooks<'_>,
    ) -> Result<(), RunError> {
        let mut progress = |f: f64| (hooks.progress)(phase, f);
        let ended = match &mut self.stage {
            Stage::Compacting { spec, lp } => lp
                .advance(
                    spec.as_mut(),
                    self.max_compaction_steps,
                    &mut progress,
                    &mut |_| {},
                )?
                .map(|sum| {
                    self.compaction = Some(sum);
                }),
            Stage::Shearing { spec, lp, .. } => lp
                .advance(spec.as_mut(), &mut progress, &mut |_, _| {})?
                .then_some(()),
            Stage::Done { .. } | Stage::Taken => None,
        };
        if ended.is_none() {
            return Ok(());
        }
        self.tick(phase, mark, hooks);
        // The phase's last state to the boundary hook (a last snapshot), the phase's results
        // to `phase_done`, then the next phase.
        (hooks.boundary)(phase, self.engine())?;
        match std::mem::replace(&mut self.stage, Stage::Taken) {
            Stage::Compacting { spec, .. } => {
                (hooks.phase_done)(phase, spec.engine(), self)?;
                let (s, lp) = ShearLoop::start(spec.as_ref(), false)?;
                self.stage = Stage::Shearing {
                    compacted: spec,
                    spec: Box::new(s),
                    lp: Box::new(lp),
                };
            }
            Stage::Shearing {
                compacted,
                spec,
                lp,
                ..
            } => {
                let creep = lp.creep;
                self.shears
                    .push(lp.finish(spec.as_ref(), compacted.as_ref()));
                (hooks.phase_done)(phase, spec.engine(), self)?;
                self.stage = if creep {
                    Stage::Done { compacted }
                } else {
                    let (s, lp) = ShearLoop::start(compacted.as_ref(), true)?;
                    Stage::Shearing {
                        compacted,
                        spec: Box::new(s),
                        lp: Box::new(lp),
                    }
                };
            }
            other => self.stage = other,
        }
        // The next phase's start (the shear's copy and its first step at rest) is its time.
        if let Some(p) = self.phase() {
            self.tick(p, mark, hooks);
        }
        Ok(())
    }

    /// The checkpoint's bytes (module docs).
    pub fn to_checkpoint(&self) -> Vec<u8> {
        let mut w = CheckpointWriter::default();
        // The configuration's TOML was validated when the run was made.
        w.str(&self.config.to_toml().unwrap_or_default());
        w.usize(self.max_compaction_steps);
        for s in self.seconds {
            w.f64(s[0]);
            w.f64(s[1]);
        }
        w.bool(self.compaction.is_some());
        if let Some(c) = &self.compaction {
            write_compaction(&mut w, c);
        }
        w.usize(self.shears.len());
        for s in &self.shears {
            write_shear(&mut w, s);
        }
        match &self.stage {
            Stage::Compacting { spec, lp } => {
                w.u8(0);
                w.usize(lp.i);
                w.usize(lp.settled_for);
                write_stress(&mut w, &lp.last);
                spec.write_checkpoint(&mut w);
            }
            Stage::Shearing {
                compacted,
                spec,
                lp,
            } => {
                w.u8(1);
                compacted.write_checkpoint(&mut w);
                w.bool(lp.creep);
                w.usize(lp.i);
                for v in [lp.h0, lp.v0, lp.solids, lp.mismatch] {
                    w.f64(v);
                }
                w.usize(lp.total_steps);
                w.usize(lp.record_every);
                w.usize(lp.rows.len());
                for r in &lp.rows {
                    write_row(&mut w, r);
                }
                spec.write_checkpoint(&mut w);
            }
            Stage::Done { compacted } => {
                w.u8(2);
                compacted.write_checkpoint(&mut w);
            }
            Stage::Taken => w.u8(3),
        }
        seal(RUN_KIND, &w.into_bytes())
    }

    /// The run of a checkpoint written by [`DemRun::to_checkpoint`].
    pub fn from_checkpoint(file: &[u8]) -> Result<Self, RunError> {
        let payload = unseal(RUN_KIND, file)?;
        let mut r = CheckpointReader::new(payload);
        let config = TriaxialConfig::from_toml(&r.str()?)?;
        let p = config.params;
        let max_compaction_steps = r.usize()?;
        let mut seconds = [[0.0; 2]; 3];
        for s in &mut seconds {
            *s = [r.f64()?, r.f64()?];
        }
        let compaction = if r.bool()? {
            Some(read_compaction(&mut r)?)
        } else {
            None
        };
        let n = r.count(8)?;
        let mut shears = Vec::with_capacity(n);
        for _ in 0..n {
            shears.push(read_shear(&mut r)?);
        }
        let frictionless = || table(&p, 0.0, false);
        let stage = match r.u8()? {
            0 => {
                let i = r.usize()?;
                let settled_for = r.usize()?;
                let last = read_stress(&mut r)?;
                let spec = DemSpecimen::read_checkpoint(&mut r, p, frictionless()?)?;
                Stage::Compacting {
                    spec: Box::new(spec),
                    lp: Box::new(CompactLoop {
                        i,
                        settled_for,
                        last,
                    }),
                }
            }
            1 => {
                let compacted = DemSpecimen::read_checkpoint(&mut r, p, frictionless()?)?;
                let creep = r.bool()?;
                let i = r.usize()?;
                let [h0, v0, solids, mismatch] = [r.f64()?, r.f64()?, r.f64()?, r.f64()?];
                let total_steps = r.usize()?;
                let record_every = r.usize()?;
                let nr = r.count(8)?;
                let mut rows = Vec::with_capacity(nr);
                for _ in 0..nr {
                    rows.push(read_row(&mut r)?);
                }
                let spec = DemSpecimen::read_checkpoint(&mut r, p, table(&p, p.mu, creep)?)?;
                Stage::Shearing {
                    compacted: Box::new(compacted),
                    spec: Box::new(spec),
                    lp: Box::new(ShearLoop {
                        creep,
                        i,
                        h0,
                        v0,
                        solids,
                        total_steps,
                        record_every,
                        rows,
                        mismatch,
                    }),
                }
            }
            2 => Stage::Done {
                compacted: Box::new(DemSpecimen::read_checkpoint(&mut r, p, frictionless()?)?),
            },
            s => {
                return Err(CheckpointError::Damaged(format!("run stage {s}")).into());
            }
        };
        r.finish()?;
        if shears.len()
            != usize::from(matches!(&stage, Stage::Shearing { lp, .. } if lp.creep))
                + 2 * usize::from(matches!(stage, Stage::Done { .. }))
            || compaction.is_none() != matches!(stage, Stage::Compacting { .. })
        {
            return Err(CheckpointError::Damaged(
                "the finished phases do not match the run's stage".into(),
            )
            .into());
        }
        Ok(Self {
            config,
            max_compaction_steps,
            stage,
            compaction,
            shears,
            seconds,
        })
    }

    /// Writes the checkpoint to `path` (atomically).
    pub fn save(&self, path: &Path) -> Result<(), RunError> {
        Ok(write_atomic(path, &self.to_checkpoint())?)
    }

    /// Reads the checkpoint at `path`.
    pub fn load(path: &Path) -> Result<Self, RunError> {
        Self::from_checkpoint(&read_file(path)?)
    }
}

fn write_stress(w: &mut CheckpointWriter, s: &Stress) {
    for v in s
        .dims
        .iter()
        .chain(&s.walls)
        .chain(&s.each)
        .chain(s.love.iter().flatten())
        .chain(&s.stiffness)
    {
        w.f64(*v);
    }
}

fn read_stress(r: &mut CheckpointReader<'_>) -> Result<Stress, CheckpointError> {
    let mut s = Stress::default();
    for v in s
        .dims
        .iter_mut()
        .chain(&mut s.walls)
        .chain(&mut s.each)
        .chain(s.love.iter_mut().flatten())
        .chain(&mut s.stiffness)
    {
        *v = r.f64()?;
    }
    Ok(s)
}

fn write_opt(w: &mut CheckpointWriter, v: Option<usize>) {
    w.bool(v.is_some());
    w.usize(v.unwrap_or(0));
}

fn read_opt(r: &mut CheckpointReader<'_>) -> Result<Option<usize>, CheckpointError> {
    let some = r.bool()?;
    let v = r.usize()?;
    Ok(some.then_some(v))
}

fn write_compaction(w: &mut CheckpointWriter, c: &CompactionSummary) {
    w.usize(c.steps);
    for v in [
        c.solid_fraction,
        c.p_walls,
        c.p_contacts,
        c.max_wall_error,
        c.coordination,
    ] {
        w.f64(v);
    }
    write_opt(w, c.rebuilds);
}

fn read_compaction(r: &mut CheckpointReader<'_>) -> Result<CompactionSummary, CheckpointError> {
    Ok(CompactionSummary {
        steps: r.usize()?,
        solid_fraction: r.f64()?,
        p_walls: r.f64()?,
        p_contacts: r.f64()?,
        max_wall_error: r.f64()?,
        coordination: r.f64()?,
        rebuilds: read_opt(r)?,
    })
}

fn write_row(w: &mut CheckpointWriter, x: &TriaxialRow) {
    for v in [
        x.axial_strain,
        x.volumetric_strain,
        x.q_over_p,
        x.p,
        x.q,
        x.sigma_axial,
        x.sigma_lateral,
        x.p_contacts,
        x.q_contacts,
    ] {
        w.f64(v);
    }
    w.usize(x.contacts);
    for v in [
        x.coordination,
        x.share_sliding,
        x.share_rolling,
        x.share_creeping,
        x.solid_fraction,
        x.kinetic_energy,
    ] {
        w.f64(v);
    }
}

fn read_row(r: &mut CheckpointReader<'_>) -> Result<TriaxialRow, CheckpointError> {
    Ok(TriaxialRow {
        axial_strain: r.f64()?,
        volumetric_strain: r.f64()?,
        q_over_p: r.f64()?,
        p: r.f64()?,
        q: r.f64()?,
        sigma_axial: r.f64()?,
        sigma_lateral: r.f64()?,
        p_contacts: r.f64()?,
        q_contacts: r.f64()?,
        contacts: r.usize()?,
        coordination: r.f64()?,
        share_sliding: r.f64()?,
        share_rolling: r.f64()?,
        share_creeping: r.f64()?,
        solid_fraction: r.f64()?,
        kinetic_energy: r.f64()?,
    })
}

fn write_shear(w: &mut CheckpointWriter, s: &ShearRun) {
    w.bool(s.creep);
    w.usize(s.steps);
    w.usize(s.rows.len());
    for r in &s.rows {
        write_row(w, r);
    }
    for v in [
        s.max_stress_mismatch,
        s.creep_dissipation,
        s.slip_dissipation,
    ] {
        w.f64(v);
    }
    write_opt(w, s.rebuilds);
}

fn read_shear(r: &mut CheckpointReader<'_>) -> Result<ShearRun, CheckpointError> {
    let creep = r.bool()?;
    let steps = r.usize()?;
    let n = r.count(8)?;
    let mut rows = Vec::with_capacity(n);
    for _ in 0..n {
        rows.push(read_row(r)?);
    }
    Ok(ShearRun {
        creep,
        steps,
        rows,
        max_stress_mismatch: r.f64()?,
        creep_dissipation: r.f64()?,
        slip_dissipation: r.f64()?,
        rebuilds: read_opt(r)?,
    })
}
