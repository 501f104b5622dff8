//! The rigid regime's settings and the integration parameters it needs.

use rapier3d::prelude::*;

use crate::error::PluginError;

/// Checks that Rapier's integration parameters suit the plugin.
pub fn check_parameters(params: &IntegrationParameters) -> Result<(), PluginError> {
    if !(params.dt.is_finite() && params.dt > 0.0) {
        return Err(PluginError::TimeStep(params.dt));
    }
    if params.friction_model != FrictionModel::Coulomb {
        return Err(PluginError::FrictionModel);
    }
    if params.contact_clustering {
        return Err(PluginError::ContactClustering);
    }
    Ok(())
}

/// Sets `params` to what the plugin needs and what rolling balls and wheels need at game steps:
/// [`configure_parameters_for`] with [`SolverPreset::Rolling`] (the default of
/// [`crate::CreepWorld::new`]).
pub fn configure_parameters(params: &mut IntegrationParameters) {
    configure_parameters_for(params, SolverPreset::Rolling);
}

/// Sets `params` to what the plugin requires (checked by [`check_parameters`]):
/// `FrictionModel::Coulomb` (the hook reads each contact point's friction impulse, which Rapier
/// writes only then) and `contact_clustering = false` (clustered manifolds hide the per-point
/// impulses); and, with [`SolverPreset::Rolling`], the solver of rolling bodies:
/// `num_solver_iterations = 1` (one substep: the rotation-gap correction is exact and the
/// pipeline lifts Rapier's spin cap on registered balls, crate module `gap`) and
/// `num_internal_pgs_iterations =` [`ROLLING_PGS_ITERATIONS`]. [`SolverPreset::Rapier`] leaves
/// the solver's iterations as they are.
pub fn configure_parameters_for(params: &mut IntegrationParameters, preset: SolverPreset) {
    params.friction_model = FrictionModel::Coulomb;
    params.contact_clustering = false;
    if preset == SolverPreset::Rolling {
        params.num_solver_iterations = 1;
        params.num_internal_pgs_iterations = ROLLING_PGS_ITERATIONS;
    }
}

/// Gauss-Seidel iterations per substep of [`SolverPreset::Rolling`]: with one substep, the
/// solves that Rapier's four substeps would have spent (about the same cost), and what a wheel
/// on a revolute joint needs: at 1/60 s a driven rubber wheel on its joint follows Carter's
/// law within 2 % of `mu P` up to 0.9 `mu P` with 4 (and with 16), while with 1 its joint and
/// contact do not converge together and at 0.9 `mu P` it slides (10 % of `mu P` off;
/// creep-scenes' `wheel_from_the_recipe_follows_carter`). Vehicles whose joints and several
/// contacts couple may want more (creep-scenes' robot uses 16).
pub const ROLLING_PGS_ITERATIONS: usize = 4;

/// The solver parameters [`configure_parameters_for`] (and [`crate::CreepWorld::new`], from
/// [`CreepSettings::solver`]) choose beyond what the plugin requires.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum SolverPreset {
    /// What rolling balls and wheels need at game steps (default): one solver substep
    /// (`num_solver_iterations = 1`) with [`ROLLING_PGS_ITERATIONS`] Gauss-Seidel iterations.
    /// Rapier reads a rolling body's contact at each substep as a point fixed in the body
    /// (its rotation gap, crate module `gap`); the plugin's correction is exact with one
    /// substep only, and only then does the pipeline lift Rapier's spin cap (45 degrees a
    /// step) on registered balls. Measured: a 0.1 m steel ball launched rolling at 5 m/s at
    /// 1/60 s keeps 0.99997 of its energy over 10 s and its height within 0.1 mm; with
    /// Rapier's four substeps it floats 2.2 mm and loses 17 % in the first second.
    #[default]
    Rolling,
    /// Leave the solver's iterations as they are (Rapier's defaults in a fresh world: four
    /// substeps, one Gauss-Seidel iteration), for scenes that need substeps more than rolling
    /// accuracy (tall stacks, long joint chains, stiff mass ratios). A registered ball or wheel
    /// that then rolls fast enough for the rotation gap to matter gets a
    /// [`crate::CreepWarning::RotationGap`].
    Rapier,
}

/// Plugin-wide settings.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CreepSettings {
    /// Creep slip-speed bound [m/s] below which an `Auto` contact is left to Coulomb
    /// (default 1e-7 m/s).
    pub auto_tolerance: f64,
    /// Compensate the contact-anchor drift of rolling spheres within a step (see the module
    /// docs; default true).
    pub anchor_drift_correction: bool,
    /// Speed [m/s] below which a body's `Auto` and `Coulomb` colliders switch the hook off before
    /// a step ([`crate::CreepPipeline`] does it): its contacts then stay plain Coulomb and keep
    /// Rapier's contact recycling (a collider with `MODIFY_SOLVER_CONTACTS` loses it). The speed
    /// is `|v| + |w| r` with `r` the collider's bounding radius; a contact moving at it creeps at
    /// most `F_ss(1)` times it (1e-5..1e-2 for steel to rubber). `Creep` colliders and colliders
    /// with a contact-torque rolling model are always on.
    /// Default 1e-2 m/s; 0 keeps every hook on.
    pub activation_speed: f64,
    /// The steady creep law of the slip target: `Kuhn` (Kalker's closed form `F_ss`, the
    /// talk's model, default) or `Fitted` (creep-law's boundary-element-fitted law, ten times
    /// more accurate; `FittedTransient` uses the fitted law too, the rigid regime having no
    /// transient state).
    pub creep_model: creep_law::CreepModel,
    /// Lift Rapier's angular speed cap (45 degrees per step) on bodies with a registered ball
    /// collider when the step has one solver substep (`num_solver_iterations = 1`, where the
    /// rotation-gap correction is exact; default true). Without it a 0.1 m ball rolling faster
    /// than 2.4 m/s at 1/30 s, 4.7 m/s at 1/60 s or 9.4 m/s at 1/120 s slides.
    pub lift_rotation_cap: bool,
    /// The solver parameters [`crate::CreepWorld::new`] sets ([`configure_parameters_for`]):
    /// [`SolverPreset::Rolling`] (default: one substep) or [`SolverPreset::Rapier`] (Rapier's
    /// own).
    pub solver: SolverPreset,
    /// Warn once per collider ([`crate::CreepWarning::Unregistered`]) when an unregistered
    /// collider touches a registered one (default true; false: no such warning).
    pub warn_unregistered: bool,
}

impl Default for CreepSettings {
    fn default() -> Self {
        Self {
            auto_tolerance: 1e-7,
            anchor_drift_correction: true,
            activation_speed: 1e-2,
            creep_model: creep_law::CreepModel::Kuhn,
            lift_rotation_cap: true,
            solver: SolverPreset::Rolling,
            warn_unregistered: true,
        }
    }
}

impl CreepSettings {
    /// These settings with Rapier's own solver parameters ([`SolverPreset::Rapier`]).
    pub fn with_rapier_solver(mut self) -> Self {
        self.solver = SolverPreset::Rapier;
        self
    }
    /// Validates the settings.
    pub fn validate(&self) -> Result<(), PluginError> {
        if !(self.auto_tolerance >= 0.0 && self.auto_tolerance.is_finite()) {
            return Err(PluginError::Setting {
                name: "auto_tolerance",
                value: self.auto_tolerance,
                why: "must be finite and >= 0 [m/s]",
            });
        }
        if !(self.activation_speed >= 0.0 && self.activation_speed.is_finite()) {
            return Err(PluginError::Setting {
                name: "activation_speed",
                value: self.activation_speed,
                why: "must be finite and >= 0 [m/s]",
            });
        }
        Ok(())
    }
}
