//! The fast-rolling matrix: a 0.1 m ball of steel, glass or rubber rolling freely at 2, 5, 10
//! and 20 m/s, at dt = 1/30, 1/60 and 1/120 s, on a half-space, a flat triangle mesh and a flat
//! heightfield, for 10 s ([`crate::rolling_ball`]). Free rolling carries no tangential load, so
//! creep-friction adds nothing and every change of the energy or of the centre's height is the
//! engine's (or the plugin's) own error. Bounds (issue 14): the energy never exceeds its start
//! by more than 1e-6 of it; the energy lost over the run is at most 1e-3 of the start; the
//! centre never rises more than 0.1 mm above, nor sinks more than 0.1 mm below, its resting
//! height. Each case runs the plugin (`Fidelity::Creep`) and plain Rapier with the same
//! integration parameters, whose figures stand beside.
//!
//! Rapier reads a rolling ball's rotation gap at `num_solver_iterations + 1` instants of a step
//! and the plugin's correction is a constant and a rate ([`creep_rapier::CreepSettings`]'s
//! `anchor_drift_correction`): exact with one substep ([`SUBSTEPS`]), the setting the matrix
//! runs at; with Rapier's default four substeps it is the gap's mean over the substeps, which
//! lets a fast ball hop and gain energy (`creep report` shows both; figures below).
//!
//! The ball is launched rolling without slip about the contact point Rapier's friction solve
//! uses (midway between the surfaces, `R - delta/2` from the centre,
//! `crate::rolling_ball`): launched at `v = w R` it would take a real tangential impulse in
//! the first step, a load that creep-friction then (rightly) answers.
//!
//! Measured (1 substep, 10 s, `cargo test --release -p creep-scenes --test hard_cases --
//! --ignored fast_rolling_full_matrix --nocapture`):
//!
//! * **Plane and triangle mesh**: the loss bound (worst 1.6e-4 of E0) and the height bounds
//!   (worst 25 um of sinking, on the mesh at 2 m/s and 1/120 s; 0.1 um on the plane) hold in
//!   every case. The 1e-6 gain bound does not (worst 2e-5 of E0): that drift is **Rapier's
//!   own**. A ball rolling so slowly that the rotation gap stays inside the contact's overlap
//!   (so the plugin's correction changes nothing the solver reads) gains 1.8e-4..1.0e-3 of E0 in
//!   60 s in plain Rapier, and the plugin's run is the same run bit for bit
//!   (`plain_rapier_gains_energy_in_slow_free_rolling` in `tests/hard_cases.rs`): a steady
//!   forward drift of `v` and `w` together of about a third of an f32 ulp per step. It does not
//!   depend on where the ball is (a run started at x = 1000 m gives the same figures bit for
//!   bit), nor on the correction's size (scaling it by 1.001 changes nothing: the solver clamps
//!   the relaxed reading at zero overlap). Creep-friction adds nothing to it: in free rolling the
//!   creep run is the Coulomb run, bit for bit on the plane
//!   (`creep_adds_no_work_in_free_rolling`, `fast_rolling_ci_subset_plugin_share`).
//! * **Heightfield**: an engine limit. Rapier's ball-heightfield contact bumps the ball at cell
//!   edges (it rises 7 mm at 2 m/s and 1/120 s, up to 2.9 m at 20 m/s) and, landing, it falls
//!   through the heightfield in most cases, with or without the plugin (plain Rapier: 0/36
//!   cases within the bounds, loss 0.77..3.0 of E0 counting the fall, more than 0.2 m below
//!   rest in 33 of 36; the plugin: 0/36, 29 of 36). The triangle
//!   mesh of the same cells rolls right, so a game terrain should be a triangle mesh.
//!   Rapier's `HeightFieldFlags::FIX_INTERNAL_EDGES` is no remedy: with it the flat
//!   heightfield gives the ball no contact at all (it falls 490 m in 10 s, plain Rapier alike).
//!   The bump is not in the plugin's hook (plain Rapier has it).
//! * **Rapier's default 4 substeps**: 0/108 within the bounds, plugin and plain Rapier alike
//!   (the correction cannot follow the gap through five instants and Rapier's 45-degree spin cap
//!   stays: plugin worst gain 7.7e-3 of E0, rise 45 mm on the plane; plain Rapier loses up to
//!   0.99 of E0 and sinks 8.6 mm). The setting that lifts it is one substep
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
use crate::rolling_ball::{FidelityChoice, Ground, RollingBall, Stepper, Summary};

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

/// A CI-sized subset: steel on the half-space and glass on the triangle mesh, each at 20 m/s
/// and 1/30 s and at 2 m/s and 1/120 s, and rubber on the half-space at 2 m/s and 1/120 s.
/// (Known failures, in the full matrix: the heightfield, and the 1e-6 gain bound where
/// Rapier's own drift exceeds it: module docs.)
pub fn ci_subset() -> Vec<Case> {
    let case = |material, speed, dt, ground| Case {
        material,
        speed,
        dt,
        ground,
    };
    vec![
        case("steel", 20.0, 1.0 / 30.0, Ground::Plane),
        case("steel", 2.0, 1.0 / 120.0, Ground::Plane),
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
