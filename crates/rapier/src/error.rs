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
    /// A material or contact-law parameter was refused by creep-law.
    #[error(transparent)]
    Law(#[from] LawError),
}
