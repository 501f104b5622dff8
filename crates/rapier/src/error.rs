//! Errors of the plugin: settings a world must have, and invalid parameters.

use creep_law::LawError;

/// Why the plugin cannot run on a world, or a parameter was refused.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum PluginError {
    /// The rigid regime reads each contact's total friction impulse, which Rapier writes per
    /// contact point only with `FrictionModel::Coulomb`.
    #[error(
        "creep-friction needs IntegrationParameters::friction_model = FrictionModel::Coulomb \
         (Rapier's default `Simplified` model keeps no per-point friction impulse)"
    )]
    FrictionModel,
    /// Contact clustering moves impulses to cluster manifolds the hook does not see.
    #[error(
        "creep-friction needs IntegrationParameters::contact_clustering = false (clustered \
         manifolds hide the per-point impulses the plugin reads)"
    )]
    ContactClustering,
    /// The time step must be positive and finite.
    #[error("IntegrationParameters::dt must be finite and > 0 (got {0}) [s]")]
    TimeStep(f32),
    /// A setting outside its valid range.
    #[error("{name} = {value} is invalid: {why}")]
    Setting {
        /// Setting name.
        name: &'static str,
        /// Value given.
        value: f64,
        /// The valid range, in words.
        why: &'static str,
    },
    /// Compliant regime: the time step exceeds the safe fraction of the Rayleigh time step.
    #[error(
        "dt = {dt} s exceeds {fraction} x the Rayleigh time step {rayleigh} s of the compliant \
         spheres (explicit DEM; lower dt or set CompliantSettings::rayleigh_check)"
    )]
    RayleighTimeStep {
        /// Time step \[s\].
        dt: f64,
        /// Smallest Rayleigh time step of the compliant balls \[s\].
        rayleigh: f64,
        /// Largest accepted dt / T_R [-].
        fraction: f64,
    },
    /// Compliant regime: the pair's combined restitution (Rapier's `Collider::restitution`
    /// with its combine rule) is outside [0.01, 1].
    #[error(
        "restitution {0} of a compliant pair is outside [0.01, 1] (set Collider::restitution; \
         Rapier's default is 0)"
    )]
    Restitution(f64),
    /// Compliant regime: `IntegrationParameters::num_solver_iterations` must be 1 (the contact
    /// forces are computed once per step; with substeps Rapier re-applies them frozen, which is
    /// not symplectic and gains or loses ~1 % of an impact's energy).
    #[error(
        "the compliant (DEM) regime needs num_solver_iterations = 1 (got {0}): set \
         IntegrationParameters::num_solver_iterations = 1 and use a smaller dt instead"
    )]
    CompliantSubsteps(usize),
    /// The creep hooks were called by a Rapier step that [`crate::CreepPipeline`] did not
    /// prepare (e.g. `PhysicsPipeline::step` given `&pipeline.hooks` directly): those contacts
    /// were left to Rapier's Coulomb friction, with no creep, activation or rolling torque.
    #[error(
        "the creep hooks saw {contacts} contact(s) of a step the CreepPipeline did not prepare \
         (step through CreepPipeline::step, or prepare_host_step / finish_host_step around a \
         host's step); they were left to Coulomb"
    )]
    HookOutsideStep {
        /// Contacts seen outside a prepared step.
        contacts: usize,
    },
    /// `finish_host_step` without a matching `prepare_host_step`.
    #[error("finish_host_step called without prepare_host_step")]
    StepNotPrepared,
    /// `prepare_host_step` twice without `finish_host_step` in between.
    #[error("prepare_host_step called twice without finish_host_step")]
    StepAlreadyPrepared,
    /// A friction coefficient that is NaN, infinite or negative.
    #[error(
        "friction coefficient {value} of collider {collider} is invalid: must be finite and >= 0"
    )]
    Friction {
        /// The collider (its `ColliderHandle`, `{index}v{generation}`).
        collider: String,
        /// Value given.
        value: f64,
    },
    /// A call that needs a registered collider was given one the registry does not know.
    #[error(
        "collider {collider} is not registered (MaterialRegistry::insert or CreepWorld::insert with a material)"
    )]
    NotRegistered {
        /// The collider (`{index}v{generation}`).
        collider: String,
    },
    /// A material or contact-law parameter was refused by creep-law.
    #[error(transparent)]
    Law(#[from] LawError),
}
