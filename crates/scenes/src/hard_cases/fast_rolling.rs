//! The fast-rolling matrix: a 0.1 m ball of steel, glass or rubber rolling freely at 2, 5, 10
//! and 20 m/s, at dt = 1/30, 1/60 and 1/120 s, on a half-space, a flat triangle mesh and a flat
//! heightfield, for 10 s ([`crate::rolling_ball`]). Free rolling carries no tangential load, so
//! creep-friction adds nothing and every change of the energy or of the centre's height is the
//! engine's (or the plugin's) own error. Bounds: the energy never exceeds its start
//! by more than 1e-6 of it; the energy lost over the run is at most 1e-3 of the start; the
//! centre never rises more than 0.1 mm above, nor sinks more than 0.1 mm below, its resting
//! height. Each case runs the plugin (`Fidelity::Creep`) and plain Rapier with the same
//! integration parameters, whose figures stand beside.
//!
//! Rapier reads a rolling ball's rotation gap at `num_solver_iterations + 1` instants of a
//! step and the plugin's correction is a constant and a rate ([`creep_rapier::CreepSettings`]'s
//! `anchor_drift_correction`): exact with one substep ([`SUBSTEPS`]), the setting the matrix
//! runs at; with Rapier's default four substeps no line a hook can write follows the gap (the
//! plugin keeps the gap's mean and the spin cap there, which lets a fast ball hop and gain
//! energy: `creep report` shows both; figures below; creep-rapier's `gap` module has the
//! mechanism and what was tried).
//!
//! The ball is launched rolling without slip about the contact point Rapier's friction solve
//! uses (midway between the surfaces, `R - delta/2` from the centre,
//! `crate::rolling_ball`): launched at `v = w R` it would take a real tangential impulse in
//! the first step, a load that creep-friction then (rightly) answers.
//!
//! Measured (10 s; `cargo test --release -p creep-scenes --test hard_cases -- --ignored
//! fast_rolling_full_matrix --nocapture`, with `CREEP_SUBSTEPS=4` for Rapier's default; worst
//! figures, the plugin's run against plain Rapier's with the same integration parameters):
//!
//! | ground, substeps | plugin: gain, loss, rise, sink | plain Rapier: gain, loss, rise, sink | plugin within all bounds |
//! |---|---|---|---|
//! | plane, 1 | 1.9e-5, 8.2e-5, 0.07 um, 0.10 um | 6.4e-2, 0.99, 0, 2.4 mm | 13 of 36 (36 within loss and height) |
//! | mesh, 1 | 2.0e-5, 1.6e-4, 0.17 um, 25 um | 6.4e-2, 0.99, 0.16 um, 0.10 mm | 18 of 36 (36 within loss and height) |
//! | plane, 4 | 7.3e-3, 0.99, 45 mm, 8.4 mm | 0, 0.99, 0, 8.6 mm | 0 of 36 |
//! | mesh, 4 | 7.7e-3, 0.99, 45 mm, 5.0 mm | 0, 0.99, 0, 8.8 mm | 0 of 36 |
//!
//! * **Plane and triangle mesh, one substep**: the loss and height bounds hold in every case.
//!   The 1e-6 gain bound does not in 41 of 72 (worst 2e-5 of E0): a steady forward drift of
//!   the rolling speed that is **Rapier's own**. The full-matrix test measures it apart for
//!   each such case ([`Case::engine_drift`]: plain Rapier, a ball so slow that the solver never
//!   reads a rotation gap): 6e-6..6e-5 m/s over the 10 s; the plugin's runs drift
//!   3e-6..1.7e-4 m/s (`v gain / 2`), the same order but not the same figure, so the drift is
//!   stated beside, not subtracted. Over 60 s a slow ball gains 1.8e-4..1.0e-3 of E0 in plain
//!   Rapier, and the plugin's Coulomb run is the same run bit for bit
//!   (`plain_rapier_gains_energy_in_slow_free_rolling` in `tests/hard_cases.rs`). It does not
//!   depend on where the ball is (a run started at x = 1000 m gives the same figures bit for
//!   bit), nor on the correction's size (scaling it by 1.001 changes nothing: the solver clamps
//!   the relaxed reading at zero overlap). Creep-friction adds nothing to it: in free rolling the
//!   creep run is the Coulomb run, bit for bit on the plane
//!   (`creep_adds_no_work_in_free_rolling`).
//!   The CI subset ([`ci_subset`]) is held to every bound, the gain bound included.
//! * **Heightfield**: an engine limit. Rapier's ball-heightfield contact bumps the ball at cell
//!   edges (it rises 7 mm at 2 m/s and 1/120 s, up to 2.9 m at 20 m/s) and, landing, it falls
//!   through the heightfield in most cases, with or without the plugin (plain Rapier: 0/36
//!   cases within the bounds, loss 0.77..3.0 of E0 counting the fall, more than 0.2 m below
//!   rest in 33 of 36; the plugin: 0/36, 29 of 36). The triangle
//!   mesh of the same cells rolls right, so a game terrain should be a triangle mesh.
//!   Rapier's `HeightFieldFlags::FIX_INTERNAL_EDGES` is no remedy: with it the flat
//!   heightfield gives the ball no contact at all (it falls 490 m in 10 s, plain Rapier alike).
//!   The bump is not in the plugin's hook (plain Rapier has it).
//! * **Rapier's default 4 substeps**: 0/108 within the bounds, plugin and plain Rapier alike.
//!   The plugin keeps Rapier's 45-degree spin cap there and corrects the gap by its mean over
//!   the substeps (the only line that keeps the hard-case matrix passing, creep-rapier's `gap`
//!   module); plain Rapier loses up to 0.99 of E0 to the cap and sinks 8.6 mm, the plugin
//!   gains up to 7.7e-3 and lifts the ball 45 mm. The setting that lifts it is one substep
//!   (`num_solver_iterations = 1`), the one [`SUBSTEPS`] names.
//!
//! Fixed here (it was the plugin's): fast **rubber** gained up to 1.5e-4 of E0 with creep (20
//! m/s at 1/30 s) and sank 22 um. Not slip noise times the creep target but a runaway: the hook
//! dropped last step's target from its implicit force estimate whenever the solver's force
//! opposed it, which made the solve explicit, and rubber's loop gain there is above 1 (1.07 at
//! 20 m/s and 1/30 s), so a 0.1 N initial load grew to the Coulomb limit in 150 steps. The hook
//! now always keeps the last target in the estimate and leaves to Coulomb a contact whose
//! load is below the f32 rounding of its solve (`creep_rapier`'s rigid hook).

use creep_law::Material;

use crate::measure::SceneError;
use crate::rolling_ball::{
    FidelityChoice, Ground, RADIUS, RollingBall, Stepper, Summary, rest_height,
};

/// Solver substeps the matrix runs at (the setting that lifts the rotation-gap limit).
pub const SUBSTEPS: usize = 1;
/// Rapier's default substeps, reported beside.
pub const DEFAULT_SUBSTEPS: usize = 4;
/// Run length \[s\].
pub const DURATION: f64 = 10.0;
/// Largest energy gain, relative to the start.
pub const MAX_GAIN: f64 = 1e-6;
/// Largest energy loss over the run, relative to the start.
pub const MAX_LOSS: f64 = 1e-3;
/// Largest rise or sinking of the centre from its resting height \[m\].
pub const MAX_HEIGHT_ERROR: f64 = 1e-4;

/// One case of the matrix.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Case {
    /// Material name (`steel`, `glass`, `rubber`).
    pub material: &'static str,
    /// Launch speed [m/s].
    pub speed: f64,
    /// Time step \[s\].
    pub dt: f64,
    /// Ground.
    pub ground: Ground,
}

/// The materials of the matrix.
pub fn material(name: &str) -> Result<Material, SceneError> {
    match name {
        "steel" => Ok(Material::steel()),
        "glass" => Ok(Material::glass()),
        "rubber" => Ok(Material::rubber()),
        _ => Err(SceneError::Parameter(format!("unknown material {name:?}"))),
    }
}

/// The full matrix: 3 materials x 4 speeds x 3 steps x 3 grounds.
pub fn matrix() -> Vec<Case> {
    let mut v = Vec::new();
    for ground in Ground::ALL {
        for material in ["steel", "glass", "rubber"] {
            for speed in [2.0, 5.0, 10.0, 20.0] {
                for dt in [1.0 / 30.0, 1.0 / 60.0, 1.0 / 120.0] {
                    v.push(Case {
                        material,
                        speed,
                        dt,
                        ground,
                    });
                }
            }
        }
    }
    v
}

/// A CI-sized subset that meets every bound of the matrix, the 1e-6 gain bound included, with
/// one substep: glass at 20 m/s and 1/30 s on the half-space and on the triangle mesh, glass
/// on the mesh at 2 m/s and 1/120 s, steel at 2 m/s on the half-space at 1/120 s and on the
/// mesh at 1/30 s, rubber on the half-space at 2 m/s and 1/120 s. Fast steel is not in it:
/// it meets the loss and height bounds but gains 2e-6..2e-5 of E0 through Rapier's own f32
/// drift (module docs; [`Case::engine_drift`] measures that drift apart).
pub fn ci_subset() -> Vec<Case> {
    let case = |material, speed, dt, ground| Case {
        material,
        speed,
        dt,
        ground,
    };
    vec![
        case("glass", 20.0, 1.0 / 30.0, Ground::Plane),
        case("steel", 2.0, 1.0 / 120.0, Ground::Plane),
        case("steel", 2.0, 1.0 / 30.0, Ground::Trimesh),
        case("glass", 20.0, 1.0 / 30.0, Ground::Trimesh),
        case("glass", 2.0, 1.0 / 120.0, Ground::Trimesh),
        case("rubber", 2.0, 1.0 / 120.0, Ground::Plane),
    ]
}

/// A case's figures: the plugin's and plain Rapier's.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Outcome {
    /// The case.
    pub case: Case,
    /// Solver substeps of both runs.
    pub substeps: usize,
    /// The plugin (`Fidelity::Creep`).
    pub plugin: Summary,
    /// Plain Rapier, same integration parameters.
    pub plain: Summary,
}

impl Outcome {
    /// Whether the plugin's run meets the bounds.
    pub fn passed(&self) -> bool {
        bounds_met(&self.plugin)
    }
}

/// Plain Rapier's own energy drift in free rolling ([`Case::engine_drift`]), as a drift of the
/// rolling speed. Measured (1 substep, 10 s): 6e-6..6e-5 m/s on the half-space and the mesh
/// (1.2e-5 m/s for steel on the half-space at 1/30 s, plain Rapier at 0.056 m/s; the plugin's
/// steel ball at 20 m/s there drifts 2.2e-5 m/s). The drift is not a constant of the engine
/// (it depends on speed, step and material), so it is stated beside the plugin's figures, not
/// subtracted from them.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EngineDrift {
    /// Speed of the measuring run [m/s].
    pub speed: f64,
    /// Its largest energy gain over the run, relative to its start [-].
    pub gain: f64,
}

impl EngineDrift {
    /// The drift of the rolling speed over the run [m/s]: the kinetic energy of a ball rolling
    /// without slip is `(1/2) m_eff v^2`, so a relative gain `g` is `dv = v g / 2` (first order).
    pub fn velocity_drift(&self) -> f64 {
        0.5 * self.speed * self.gain.max(0.0)
    }

    /// The relative energy gain \[-\] the same velocity drift gives a ball rolling at `speed`
    /// [m/s]: `2 dv / v` (zero at rest).
    pub fn gain_at(&self, speed: f64) -> f64 {
        if speed > 0.0 {
            2.0 * self.velocity_drift() / speed
        } else {
            0.0
        }
    }
}

/// Whether a run meets the matrix's bounds.
pub fn bounds_met(s: &Summary) -> bool {
    s.max_gain <= MAX_GAIN
        && s.loss <= MAX_LOSS
        && s.max_rise <= MAX_HEIGHT_ERROR
        && s.max_sink <= MAX_HEIGHT_ERROR
}

impl Case {
    /// Runs the case with the plugin and with plain Rapier at `substeps`.
    pub fn run(&self, substeps: usize) -> Result<Outcome, SceneError> {
        let one = |stepper| {
            RollingBall {
                material: material(self.material)?,
                speed: self.speed,
                dt: self.dt,
                ground: self.ground,
                stepper,
                steps: (DURATION / self.dt).round() as usize,
                substeps,
            }
            .run(|_| {})
        };
        Ok(Outcome {
            case: *self,
            substeps,
            plugin: one(Stepper::Plugin(FidelityChoice::Creep))?,
            plain: one(Stepper::Plain)?,
        })
    }

    /// Plain Rapier's own energy drift on this case's material, ground, step and `substeps`,
    /// measured apart from the plugin: plain Rapier (no plugin, the cap on) rolls the ball for
    /// [`DURATION`] at the speed whose rotation gap at the step's end, `R (omega dt)^2 / 2`, is
    /// a quarter of the contact's resting overlap, so the solver never reads a spurious gap
    /// and the rotation-gap error plays no part; what energy the ball gains there is the f32
    /// drift of Rapier's solve (module docs).
    pub fn engine_drift(&self, substeps: usize) -> Result<EngineDrift, SceneError> {
        let material = material(self.material)?;
        let rest = rest_height(material, self.dt, self.ground, Stepper::Plain, substeps)?;
        let overlap = RADIUS - rest;
        if !(overlap > 0.0) {
            return Err(SceneError::Parameter(format!(
                "{}: no resting overlap ({overlap} m): the drift run needs one",
                self.label()
            )));
        }
        // R (omega dt)^2 / 2 = overlap / 4.
        let speed = RADIUS * (overlap / (2.0 * RADIUS)).sqrt() / self.dt;
        let run = RollingBall {
            material,
            speed,
            dt: self.dt,
            ground: self.ground,
            stepper: Stepper::Plain,
            steps: (DURATION / self.dt).round() as usize,
            substeps,
        }
        .run(|_| {})?;
        Ok(EngineDrift {
            speed,
            gain: run.max_gain,
        })
    }

    /// A short label, e.g. `steel 10 m/s 1/60 s plane`.
    pub fn label(&self) -> String {
        format!(
            "{} {} m/s 1/{:.0} s {}",
            self.material,
            self.speed,
            1.0 / self.dt,
            self.ground.label()
        )
    }
}
