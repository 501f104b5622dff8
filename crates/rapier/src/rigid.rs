//! The rigid regime: a `PhysicsHooks` whose `modify_solver_contacts` turns Rapier's Coulomb
//! tangential response into creep-friction.
//!
//! For every solver contact of an opted-in pair (`ActiveHooks::MODIFY_SOLVER_CONTACTS` on a
//! collider, both colliders registered), the hook sets `tangent_velocity` — the target of the
//! friction solve for the relative velocity of body 2's surface against body 1's at the contact —
//! to the creep slip velocity of Kuhn's rule in its stiff-contact limit (`c_CM -> 0`: the elastic
//! term vanishes and the creep term remains; Kuhn 2011, eq. 1):
//!
//! `v_disp = F_ss(|Q|/(mu P)) |v_roll| Q/|Q|`
//!
//! with `F_ss` Kalker's steady creepage (creep-law), `v_roll` Kuhn & Bagi's rolling velocity
//! (creep-law kinematics), `P` and `Q` the contact's normal and friction force of the previous
//! step (total impulses of the step divided by `dt`), and the contact radius from Hertz. Below
//! the Coulomb limit the implicit friction solve enforces that slip; at the limit it slides.
//!
//! # Three-dimensional creep (crate module `creep3d`)
//! The slip target is built in Kalker's rolling frame (`x = -v_roll/|v_roll|`, `y = n × x`):
//! along `x` the configured law `F_ss` as above, across it Kalker's `C22` (the force direction
//! of Kalker's simplified theory: the creepage for a force `Q` is `F_ss(|Q|/(mu P)) (u_x,
//! (C11/C22) u_y)`, `u = Q/|Q|`), plus spin creep for balls: the spin creepage
//! `phi = (w_q - w_p).n / |v_roll|` gives a lateral force (`C23`) that takes its share of the
//! friction capacity and a twisting moment (`C33`, both from creep-law's `Steady3d`), the
//! moment applied after the step as an angular impulse that never reverses the relative spin
//! (as the rolling torque). A relative spin within 16 f32 ulps of the bodies' angular speeds
//! counts as none. With `C22 = C11` (`nu = 0`) and no spin this is the circular law below.
//! Cylinder colliders on a flat collider are wheels (crate module `wheel`: Carter's line
//! contact, or Hertz's ellipse for a crown radius set with [`CreepHooks::set_wheel_crown`]):
//! one slip target for the whole manifold.
//!
//! # Stability of the feedback Q -> slip -> Q
//! The slip target depends on the force the solver then transmits. Explicitly (target from the
//! last force), one step maps a force error `e` to `-g e` with the loop gain
//! `g = m_t |v_roll| dF_ss/dQ / dt` (`m_t` the contact's effective mass along `Q`,
//! `dF_ss/dQ = (1 - s)^(-2/3) / (G a^2 C11)`), unstable for `g > 1` (soft materials, light
//! bodies, long steps, fast spin, `s -> 1`). The hook instead solves the local relation
//! implicitly: had the last step's target been `tau` instead of `tau_prev`, the solver would
//! have transmitted `Q* - (m_t/dt) tau` with `Q* = Q_measured + (m_t/dt) tau_prev`; with
//! `tau = F_ss(|Q|/(mu P)) |v_roll| Q/|Q|` this is the scalar equation
//! `|Q| + (m_t |v_roll| / dt) F_ss(|Q|) = |Q*|` along `Q*`, whose root is unique (`F_ss`
//! increases) and is found by safeguarded Newton iterations, capped at `mu P`. It holds for any
//! `g`; in steady state (`tau = tau_prev`) it returns the measured force. The largest `g` of each
//! step is reported in [`StepCounts::max_loop_gain`].
//!
//! # Rolling at game steps: the spin cap and the rotation gap
//! Rapier 0.36 caps every body's spin at 45 degrees per step (for CCD), so a 0.1 m ball rolling
//! faster than 2.4 m/s at 1/30 s, 4.7 m/s at 1/60 s or 9.4 m/s at 1/120 s slides and loses most
//! of its energy within seconds; with one solver substep (the default,
//! [`SolverPreset::Rolling`]) the pipeline lifts the cap on bodies of registered balls
//! ([`CreepSettings::lift_rotation_cap`]; a ball's rotation does not change its swept volume;
//! with more substeps the cap stays, see the setting).
//! Rapier also tracks each solver contact's point as a point fixed in its body, so within a step
//! the point of a rolling sphere turns with it, away from the lowest point: the solver reads a
//! growing gap `R (1 - cos(omega t))` and lets the sphere sink, then pushes it back (energy is
//! lost). The hook corrects the contact's `dist` and the rate at which the tracked point moves
//! along the normal ([`CreepSettings::anchor_drift_correction`], on by default, every
//! registered pair, Coulomb fidelity included; the `gap` module has the formulas): exact with
//! one solver substep (`num_solver_iterations = 1`, the default of [`configure_parameters`]
//! and [`crate::CreepWorld::new`]: a free 0.1 m ball then keeps its energy to 1e-5 and its
//! height to 1e-7 m at 2-20 m/s and 1/30-1/120 s), the gap's mean over the substeps otherwise
//! (measured at 1/60 s, 4 substeps, 2.4 m/s: sinking -2.4 mm without, -0.33 mm with it; it can
//! lift a fast ball by millimetres and add energy, see `gap`). With substeps kept
//! ([`SolverPreset::Rapier`]) a registered ball or wheel that turns more than
//! [`crate::ROTATION_GAP_TURN`] in a step gets a [`crate::CreepWarning::RotationGap`].
//!
//! # What remains of the engine's own error
//! Plain Rapier shows a spurious slip of a rolling contact (from positions, `(dx - R dtheta) /
//! dx`): on a 20 degree incline (0.1 m steel ball, 4 substeps) about -5e-3 at 1/60 s and -4e-4
//! at 1/240 s; in the friction drive (0.05 m spheres, 10 rad/s) -2.3e-3, -5.7e-4, -1.4e-4,
//! -3.5e-5 at 1/120, 1/240, 1/480, 1/960 s (second order in dt). It does not come from the
//! friction model, the solver iterations (8 substeps are worse), friction in the bias pass or
//! the sinking. It is larger than the creepage of stiff materials (~3e-4) at game steps, so the
//! scenes measure creep against a Coulomb run of the same scene and step; the creep slip the
//! plugin adds is within 0.1 % of Kalker's there (`creep run incline`, `creep run
//! friction-drive`). Use dt <= 1/240 s where the absolute slip matters.
//!
//! Known limitation: with locked rotation axes against a kinematic or fixed body, Rapier's coupled
//! 2x2 friction solve can become singular in one tangent direction and turn any tangential
//! target (even rounding noise) into a saturated friction force there; give such bodies their
//! rotations (the friction-drive scene locks translations only).
//!
//! # Cost
//! Where things move, most of the plugin's cost is not the hook's: a pair with any active hook
//! flag is never recycled by Rapier (docs/RAPIER_CONTACT_RECYCLING.md), so a pair that creeps
//! pays a full contact update and the solver-graph upkeep every step. Inside the hook the
//! per-pair constants are cached (crate::pair_cache) and each collider's shape is read once
//! (one typed-shape call); what remains is the shard's lock, the record's lookup and the law.
//! `creep bench pile --moving` measures it. Where things rest the hooks go off below
//! [`CreepSettings::activation_speed`] and Rapier's recycling returns; bodies sleep as in plain
//! Rapier, and the step's preparation visits only the colliders of awake bodies
//! (`creep bench pile --settled`).
//!
//! The per-contact records live in shards keyed by the collider pair (one without feature
//! `parallel`, 64 with it): a hook call locks only its pair's shard, never a global lock, and
//! the moments are applied after the step in key order, so that one thread and several step to
//! the same bits (`tests/parallel.rs`, run with `cargo test -p creep-rapier --features
//! parallel --release --test parallel`; it passes).
//!
//! Requirements (checked by [`check_parameters`]): `FrictionModel::Coulomb` (per-point friction
//! impulses are only written then) and `contact_clustering = false`.

use std::sync::Mutex;
use std::sync::atomic::{AtomicUsize, Ordering};

use creep_law::{Surface, Vec3};
use rapier3d::prelude::*;

use crate::ball_hook::{BallManifold, ball_manifold};
use crate::convert::{body_motion, v3, vf};
use crate::error::PluginError;
use crate::gap::rotation_gap_correction;
use crate::registry::{CreepMaterial, Fidelity, MaterialRegistry, RollingResistance};
use crate::rolling::apply_rolling_impulse;
use crate::store::{ContactKey, ContactRecord, ContactStore};
use crate::warning::{CreepWarning, ROTATION_GAP_TURN, WarnedSet};
use crate::wheel::Crowns;
use crate::wheel_hook::{WheelCtx, wheel_manifold};
use creep_law::rigid::LawCache;
use creep_law::rigid::RigidPairCache as PairCache;

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

/// What the plugin did in the last step.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct StepCounts {
    /// Contacts with a collider the registry does not know: left to Coulomb (each such
    /// collider touching a registered one is also named once in [`StepCounts::warnings`]).
    pub coulomb_unregistered: usize,
    /// Contacts with a shape the rigid regime does not model (not a ball, cuboid, half-space,
    /// triangle mesh, heightfield or convex polyhedron, nor a cylinder on one of the flat
    /// shapes (a wheel): capsules, cones, compounds, ...): Coulomb.
    pub coulomb_unsupported: usize,
    /// Contacts between two flat shapes (no ball on either side; Hertz's contact needs a
    /// curved side): Coulomb.
    pub coulomb_no_sphere: usize,
    /// Contacts whose pair asked for Coulomb.
    pub coulomb_requested: usize,
    /// `Auto` contacts whose creep bound was below the tolerance: Coulomb.
    pub coulomb_auto: usize,
    /// Contacts that took the creep-friction path.
    pub creep: usize,
    /// Contacts with a contact-torque rolling model.
    pub rolling_torque: usize,
    /// Power dissipated by creep, `sum Q . v_disp` \[W\] (>= 0).
    pub creep_power: f64,
    /// Largest loop gain `g` of the Q -> slip -> Q feedback this step (see the module docs).
    pub max_loop_gain: f64,
    /// Registered colliders whose hook was on for this step, among those the step visited (the
    /// colliders of awake bodies; every registered collider on a full visit; set by
    /// [`crate::CreepPipeline`]).
    pub hooks_on: usize,
    /// Contacts of pairs whose two colliders are below the activation speed, in the one step
    /// before their hooks go off: left as plain Rapier contacts (their targets cleared, so that
    /// Rapier's contact recycling does not keep a stale creep target).
    pub quiet: usize,
    /// What the plugin reports once, first seen in this step ([`crate::CreepWarning`]: a fast
    /// ball or wheel with substeps, an unregistered collider touching a registered one, no
    /// registered collider, a quarantined body). Print them with `Display`.
    pub warnings: Vec<CreepWarning>,
    /// Bodies Rapier quarantined in this step (their state went non-finite; rapier3d's
    /// `PhysicsPipeline::quarantine`): disabled. Filled by [`crate::CreepPipeline::step`]; a
    /// host that runs Rapier's step itself passes Rapier's report to
    /// [`crate::CreepPipeline::report_quarantine`].
    pub quarantined_bodies: Vec<RigidBodyHandle>,
    /// Colliders Rapier quarantined in this step (non-finite geometry): disabled.
    pub quarantined_colliders: Vec<ColliderHandle>,
}

impl StepCounts {
    /// Adds another part's counts (the shards' of one step): sums, and the larger loop gain.
    fn add(&mut self, o: &StepCounts) {
        self.coulomb_unregistered += o.coulomb_unregistered;
        self.coulomb_unsupported += o.coulomb_unsupported;
        self.coulomb_no_sphere += o.coulomb_no_sphere;
        self.coulomb_requested += o.coulomb_requested;
        self.coulomb_auto += o.coulomb_auto;
        self.creep += o.creep;
        self.rolling_torque += o.rolling_torque;
        self.creep_power += o.creep_power;
        self.max_loop_gain = self.max_loop_gain.max(o.max_loop_gain);
        self.hooks_on += o.hooks_on;
        self.quiet += o.quiet;
    }
}

/// One shard of the hooks' mutable state: the records and counts of the collider pairs that
/// hash to it, and its own copies of the caches (module docs of crate::pair_cache).
#[derive(Default)]
struct Shard {
    store: ContactStore,
    counts: StepCounts,
    /// Unregistered colliders seen touching a registered one (and the registered one), not
    /// yet reported by this shard.
    unregistered: Vec<(ColliderHandle, ColliderHandle)>,
    /// The unregistered colliders this shard has reported.
    unregistered_seen: WarnedSet,
    /// A collider of a pair the hook saw with a NaN, infinite or negative friction.
    bad_friction: Option<(ColliderHandle, f32)>,
    /// The 3-D creep laws by contact shape (crate::creep3d; the wheel path's).
    laws: LawCache,
    /// The wheels' axle tracks and elliptic Hertz cache (crate::wheel).
    crowns: Crowns,
    /// The per-pair constants (crate::pair_cache).
    pairs: PairCache,
}

/// Number of shards of the hooks' state. With feature `parallel` Rapier calls the hook for
/// different pairs on several threads at once; each call locks only the shard of its collider
/// pair, never a global lock, so calls on different shards never wait for each other (two
/// given calls meet on one shard with probability 1/64). Without it there is one thread and one
/// shard: one uncontended lock per manifold, and the records in one map.
const SHARDS: usize = if cfg!(feature = "parallel") { 64 } else { 1 };

/// The shard of a collider pair (a multiplicative hash of the two indices; the pair's order
/// is Rapier's, fixed for the pair's lifetime).
#[cfg(feature = "parallel")]
#[inline]
fn shard_of(c1: ColliderHandle, c2: ColliderHandle) -> usize {
    let (i1, i2) = (c1.into_raw_parts().0, c2.into_raw_parts().0);
    let h = ((u64::from(i1) << 32) | u64::from(i2)).wrapping_mul(0x9e37_79b9_7f4a_7c15);
    // The top 6 bits: one of the 64 shards.
    (h >> 58) as usize
}

/// The shard of a collider pair: the only one without feature `parallel`.
#[cfg(not(feature = "parallel"))]
#[inline]
fn shard_of(_: ColliderHandle, _: ColliderHandle) -> usize {
    0
}

/// The mark of a collider in its clearing step (see [`CreepHooks::update_activation`]): kept on
/// the collider itself, not in the hooks, so that a copied world (`clone_physics` with fresh
/// hooks) steps exactly as the original. `FILTER_INTERSECTION_PAIR` is used because it does
/// nothing for a non-sensor pair and the hooks keep Rapier's default for sensors.
const CLEARING_MARK: ActiveHooks = ActiveHooks::FILTER_INTERSECTION_PAIR;

/// Whether a collider's hook is in its clearing step or off (below the activation speed); a
/// collider no longer in the set counts as quiet.
fn quiet_collider(co: Option<&Collider>) -> bool {
    co.is_none_or(|co| {
        let f = co.active_hooks();
        !f.contains(ActiveHooks::MODIFY_SOLVER_CONTACTS) || f.contains(CLEARING_MARK)
    })
}

/// The creep-friction physics hooks (rigid regime). Rapier calls them inside a step that a
/// [`crate::CreepPipeline`] prepared (through [`crate::CreepPipeline::step`],
/// [`crate::CreepWorld::step`] or the host pair); given to Rapier otherwise they leave every
/// contact to Coulomb and the next step returns [`PluginError::HookOutsideStep`].
pub struct CreepHooks {
    registry: MaterialRegistry,
    settings: CreepSettings,
    dt: f64,
    substeps: usize,
    /// Rapier's prediction distance of the step \[m\] (`IntegrationParameters::prediction_distance`;
    /// the wheel path keeps a patch contact by Rapier's own rule, crate::wheel_hook).
    prediction: f64,
    /// Whether the step owner has prepared the current step (dt, substeps, counts, store).
    prepared: bool,
    /// Contacts the hook saw while no step was prepared (left to Rapier), reported as
    /// [`PluginError::HookOutsideStep`] by the next step.
    outside: AtomicUsize,
    /// The mutable state, sharded by collider pair ([`SHARDS`]).
    shards: Box<[Mutex<Shard>]>,
    /// Registered colliders whose hook is on this step (`update_activation`).
    hooks_on: usize,
    /// Scratch list of the records with a moment to apply (`end_step`, feature `parallel`:
    /// applied in key order so that the bodies' sums do not depend on the threads).
    #[cfg(feature = "parallel")]
    moments: Vec<(ContactKey, ContactRecord)>,
    /// The warnings of this step (`StepCounts::warnings`).
    warnings: Vec<CreepWarning>,
    /// Colliders warned about as unregistered.
    warned_unregistered: WarnedSet,
    /// Whether the rotation-gap warning was given.
    warned_gap: bool,
    /// Whether the nothing-registered warning was given.
    warned_nothing: bool,
    /// What Rapier quarantined in this step.
    quarantined: (Vec<RigidBodyHandle>, Vec<ColliderHandle>),
    /// Rapier's linear speed cap of the step \[m/s\] (`max_linear_velocity`).
    max_linvel: f64,
    /// Steps until the next scan of the contact pairs for unregistered colliders.
    scan_countdown: u32,
    /// The registered colliders the step's preparation visits ([`CreepHooks::select_colliders`]).
    selected: Vec<ColliderHandle>,
    /// Steps until the next preparation that visits every registered collider.
    full_countdown: u32,
    /// Whether the registry may have changed since the last full visit (`registry_mut`).
    registry_dirty: bool,
    /// Colliders in the world at the last full visit.
    last_collider_count: usize,
}

/// Steps between two preparations that visit every registered collider (the others visit the
/// colliders of awake bodies only, [`CreepHooks::select_colliders`]): what only such a visit
/// finds is a registered collider of a fixed body whose friction was made invalid since, which
/// the hook also refuses as soon as a moving registered body touches it.
const FULL_PASS_STEPS: u32 = 600;

/// Steps between two scans of the narrow phase's contact pairs for unregistered colliders
/// touching registered ones ([`CreepHooks::scan_unregistered`]; a pair whose hook runs is seen
/// at once).
const UNREGISTERED_SCAN_STEPS: u32 = 32;

impl CreepHooks {
    /// Hooks with the given materials and settings.
    pub fn new(registry: MaterialRegistry, settings: CreepSettings) -> Result<Self, PluginError> {
        settings.validate()?;
        Ok(Self {
            registry,
            settings,
            dt: 1.0 / 60.0,
            substeps: 4,
            prediction: 0.002,
            prepared: false,
            outside: AtomicUsize::new(0),
            shards: (0..SHARDS).map(|_| Mutex::new(Shard::default())).collect(),
            hooks_on: 0,
            #[cfg(feature = "parallel")]
            moments: Vec::new(),
            warnings: Vec::new(),
            warned_unregistered: WarnedSet::default(),
            warned_gap: false,
            warned_nothing: false,
            quarantined: (Vec::new(), Vec::new()),
            max_linvel: f64::MAX,
            scan_countdown: 0,
            selected: Vec::new(),
            full_countdown: 0,
            registry_dirty: true,
            last_collider_count: 0,
        })
    }

    /// The material registry.
    pub fn registry(&self) -> &MaterialRegistry {
        &self.registry
    }
    /// The material registry, to add or remove colliders.
    pub fn registry_mut(&mut self) -> &mut MaterialRegistry {
        self.registry_dirty = true;
        &mut self.registry
    }

    /// Chooses the registered colliders the step's preparation visits (friction check, spin
    /// cap, hook activation), so that a settled world whose bodies sleep costs no more than in
    /// plain Rapier: the colliders of the bodies `islands` has awake (a sleeping body's flags
    /// stay as they were when it fell asleep, when it was below the activation speed), and
    /// every registered collider (after forgetting those Rapier no longer has) on the first
    /// step, after any change through [`CreepHooks::registry_mut`], when the number of
    /// colliders changed, every [`FULL_PASS_STEPS`] steps, or without `islands`.
    pub(crate) fn select_colliders(
        &mut self,
        islands: Option<&IslandManager>,
        bodies: &RigidBodySet,
        colliders: &ColliderSet,
    ) {
        let mut selected = std::mem::take(&mut self.selected);
        selected.clear();
        let full = match islands {
            None => true,
            Some(_) => {
                self.registry_dirty
                    || self.full_countdown == 0
                    || colliders.len() != self.last_collider_count
            }
        };
        match islands {
            Some(islands) if !full => {
                self.full_countdown -= 1;
                for b in islands.active_bodies() {
                    if let Some(rb) = bodies.get(b) {
                        selected.extend(
                            rb.colliders()
                                .iter()
                                .filter(|&&c| self.registry.get(c).is_some()),
                        );
                    }
                }
            }
            _ => {
                self.full_countdown = FULL_PASS_STEPS - 1;
                self.registry_dirty = false;
                self.last_collider_count = colliders.len();
                self.registry.retain(|handle, _| colliders.contains(handle));
                selected.extend(self.registry.iter().map(|(h, _)| *h));
            }
        }
        self.selected = selected;
    }

    /// The registered colliders selected for this step ([`CreepHooks::select_colliders`]).
    pub(crate) fn selected(&self) -> &[ColliderHandle] {
        &self.selected
    }
    /// The settings.
    pub fn settings(&self) -> &CreepSettings {
        &self.settings
    }

    /// Gives a registered cylinder collider (a wheel) a crown radius `crown` \[m\] (finite
    /// and positive), or none (`None`: a line contact, Carter's law): sets its material's
    /// [`crate::CreepMaterial::crown`] (as [`crate::CreepMaterial::with_crown`] does before
    /// registration). A crowned wheel's contact is Hertz's ellipse with the curvature sums
    /// `1/R` and `1/crown` (crate module `wheel`). A bad radius is [`PluginError::Setting`], an
    /// unregistered collider [`PluginError::NotRegistered`].
    pub fn set_wheel_crown(
        &mut self,
        collider: ColliderHandle,
        crown: Option<f64>,
    ) -> Result<(), PluginError> {
        let Some(m) = self.registry.get_mut(collider) else {
            return Err(PluginError::NotRegistered {
                collider: crate::registry::handle_name(collider),
            });
        };
        let candidate = CreepMaterial { crown, ..*m };
        candidate.validate()?;
        *m = candidate;
        Ok(())
    }

    /// Prepares a step with its parameters (checks them). Called by [`crate::CreepPipeline`]
    /// only: a step the hooks see without it is [`PluginError::HookOutsideStep`].
    pub(crate) fn begin_step(&mut self, params: &IntegrationParameters) -> Result<(), PluginError> {
        let outside = std::mem::take(self.outside.get_mut());
        if outside > 0 {
            return Err(PluginError::HookOutsideStep { contacts: outside });
        }
        if self.prepared {
            return Err(PluginError::StepAlreadyPrepared);
        }
        check_parameters(params)?;
        self.prepared = true;
        self.dt = f64::from(params.dt);
        self.substeps = params.num_solver_iterations.max(1);
        self.prediction = f64::from(params.prediction_distance());
        self.max_linvel = f64::from(params.max_linear_velocity());
        self.warnings.clear();
        self.quarantined.0.clear();
        self.quarantined.1.clear();
        for shard in self.shards.iter_mut() {
            let shard = shard.get_mut().unwrap_or_else(|e| e.into_inner());
            shard.store.begin_step();
            shard.counts = StepCounts::default();
        }
        self.hooks_on = 0;
        Ok(())
    }

    /// Before each step (after `begin_step`), with the world's bodies and
    /// colliders: switches `ActiveHooks::MODIFY_SOLVER_CONTACTS` on for the registered colliders
    /// whose body moves faster than [`CreepSettings::activation_speed`] (always for `Creep`
    /// colliders) and off for the others, so that quiet contacts keep Rapier's contact recycling.
    /// A collider that becomes quiet keeps its flag for one clearing step ([`CLEARING_MARK`]): a
    /// recycled pair keeps the solver contacts of its last full update, `tangent_velocity` and
    /// `dist` included, so switching the flag off right away would leave the last creep target
    /// and gap correction in force for as long as Rapier recycles the pair.
    /// Returns how many are on. Unregistered colliders are left as they are.
    pub(crate) fn update_activation(
        &mut self,
        bodies: &RigidBodySet,
        colliders: &mut ColliderSet,
    ) -> usize {
        let v_act = self.settings.activation_speed;
        let mut on_count = 0;
        if self.registry.is_empty() && !colliders.is_empty() && !self.warned_nothing {
            self.warned_nothing = true;
            self.warnings.push(CreepWarning::NothingRegistered {
                colliders: colliders.len(),
            });
        }
        let check_gap = self.substeps > 1 && !self.warned_gap;
        for &handle in &self.selected {
            let Some(mat) = self.registry.get(handle) else {
                continue;
            };
            // Read first: `ColliderSet::get_mut` marks a collider as modified, which makes Rapier
            // re-process it (a large cost if done for every collider every step).
            let Some(co) = colliders.get(handle) else {
                continue;
            };
            if check_gap && !self.warned_gap {
                // With substeps, a ball or wheel turning fast reads Rapier's rotation gap
                // (crate module `gap`): say so once, naming the setting.
                let radius = match crate::shape::supported_shape(co) {
                    Some(crate::SupportedShape::Ball { radius })
                    | Some(crate::SupportedShape::Wheel { radius, .. }) => Some(radius),
                    _ => None,
                };
                if let Some(radius) = radius
                    && let Some(rb) = co.parent().and_then(|h| bodies.get(h))
                    && rb.is_dynamic()
                {
                    let w = f64::from(rb.angvel().length());
                    let turn = w * self.dt;
                    if turn > ROTATION_GAP_TURN {
                        self.warned_gap = true;
                        self.warnings.push(CreepWarning::RotationGap {
                            collider: handle,
                            rim_speed: w * radius,
                            turn,
                            substeps: self.substeps,
                        });
                    }
                }
            }
            if mat.fidelity == Fidelity::Compliant {
                // Out of Rapier's contact solve altogether (no solver contacts, no hook), so its
                // pairs keep Rapier's contact recycling: the compliant regime needs only the
                // narrow phase's pair list, and computes the geometry itself.
                let flags = co.active_hooks() - ActiveHooks::MODIFY_SOLVER_CONTACTS;
                if (flags != co.active_hooks() || co.solver_groups() != InteractionGroups::none())
                    && let Some(co) = colliders.get_mut(handle)
                {
                    co.set_active_hooks(flags);
                    co.set_solver_groups(InteractionGroups::none());
                }
                continue;
            }
            let moving = mat.fidelity == Fidelity::Creep
                || matches!(mat.rolling, RollingResistance::Torque(_))
                || v_act == 0.0
                || co.parent().and_then(|h| bodies.get(h)).is_some_and(|rb| {
                    let r = co.shape().compute_local_bounding_sphere().radius;
                    rb.linvel().length() + rb.angvel().length() * r > v_act as f32
                });
            let flags = co.active_hooks();
            // Active (flag on) -> clearing (flag on, marked: pairs of two quiet colliders are
            // left as Rapier built them) -> off (flag off: recycled clean).
            let modify = ActiveHooks::MODIFY_SOLVER_CONTACTS;
            let wanted = if moving {
                (flags | modify) - CLEARING_MARK
            } else if flags.contains(modify) && !flags.contains(CLEARING_MARK) {
                flags | CLEARING_MARK
            } else {
                flags - modify - CLEARING_MARK
            };
            let on = wanted.contains(modify);
            if wanted != flags
                && let Some(co) = colliders.get_mut(handle)
            {
                co.set_active_hooks(wanted);
            }
            on_count += usize::from(on);
        }
        self.hooks_on = on_count;
        on_count
    }

    /// Call after each step: applies the contact-torque rolling resistance computed in the step
    /// (as angular impulses `M dt`, capped so that they never reverse the relative rolling) and
    /// drops the records of contacts that ended.
    pub(crate) fn end_step(&mut self, bodies: &mut RigidBodySet) -> Result<(), PluginError> {
        if !std::mem::take(&mut self.prepared) {
            return Err(PluginError::StepNotPrepared);
        }
        // The shards' reports: unregistered colliders (once each), a bad friction.
        let mut bad_friction = None;
        for shard in self.shards.iter_mut() {
            let shard = shard.get_mut().unwrap_or_else(|e| e.into_inner());
            bad_friction = bad_friction.or(shard.bad_friction.take());
            for (collider, touching) in shard.unregistered.drain(..) {
                if self.warned_unregistered.insert(collider) {
                    self.warnings
                        .push(CreepWarning::Unregistered { collider, touching });
                }
            }
        }
        let dt = self.dt;
        let has_moment =
            |rec: &ContactRecord| rec.torque != Vec3::ZERO || rec.spin_torque != Vec3::ZERO;
        #[cfg(feature = "parallel")]
        {
            // Several threads filled the shards' maps in no fixed order, and the capped
            // impulses of one body do not commute in f32: apply them in key order.
            self.moments.clear();
            for shard in self.shards.iter_mut() {
                let shard = shard.get_mut().unwrap_or_else(|e| e.into_inner());
                let g = shard.store.generation;
                self.moments.extend(
                    shard
                        .store
                        .records
                        .iter()
                        .filter(|(_, r)| r.generation == g && has_moment(r))
                        .map(|(k, r)| (*k, *r)),
                );
                shard.store.sweep();
            }
            self.moments.sort_unstable_by_key(|(k, _)| k.order());
            for (_, rec) in &self.moments {
                apply_rolling_impulse(bodies, rec, dt);
            }
        }
        #[cfg(not(feature = "parallel"))]
        for shard in self.shards.iter_mut() {
            // One pass: the moments of this step's contacts applied, the ended ones dropped.
            let shard = shard.get_mut().unwrap_or_else(|e| e.into_inner());
            let g = shard.store.generation;
            shard.store.records.retain(|_, rec| {
                let live = rec.generation == g;
                if live && has_moment(rec) {
                    apply_rolling_impulse(bodies, rec, dt);
                }
                live
            });
        }
        match bad_friction {
            Some((collider, value)) => crate::registry::check_friction(collider, value),
            None => Ok(()),
        }
    }

    /// Every [`UNREGISTERED_SCAN_STEPS`] steps (with [`CreepSettings::warn_unregistered`]):
    /// warns once about each unregistered collider in contact with a registered one. The hook
    /// sees such pairs only while the registered collider's hook is on; this scan also finds
    /// them against a resting or fixed registered collider (a floor), at the cost of one pass
    /// over the contact pairs every few steps while some collider (of `colliders` in the
    /// world) is not registered.
    pub(crate) fn scan_unregistered(&mut self, narrow_phase: &NarrowPhase, colliders: usize) {
        // Nothing to find when every collider is registered (or none is).
        if !self.settings.warn_unregistered
            || self.registry.is_empty()
            || colliders <= self.registry.len()
        {
            return;
        }
        if self.scan_countdown > 0 {
            self.scan_countdown -= 1;
            return;
        }
        self.scan_countdown = UNREGISTERED_SCAN_STEPS - 1;
        for pair in narrow_phase.contact_pairs() {
            let (c1, c2) = (pair.collider1, pair.collider2);
            let (known, stranger) = match (self.registry.get(c1), self.registry.get(c2)) {
                (Some(_), None) => (c1, c2),
                (None, Some(_)) => (c2, c1),
                _ => continue,
            };
            if pair.has_any_active_contact() && self.warned_unregistered.insert(stranger) {
                self.warnings.push(CreepWarning::Unregistered {
                    collider: stranger,
                    touching: known,
                });
            }
        }
    }

    /// Records what Rapier quarantined in the step (rapier3d's `PhysicsPipeline::quarantine`):
    /// in [`StepCounts::quarantined_bodies`] and `quarantined_colliders`, each body also as a
    /// [`CreepWarning::Quarantined`].
    pub(crate) fn report_quarantine(&mut self, q: &rapier3d::pipeline::Quarantine) {
        for &body in q.bodies() {
            self.quarantined.0.push(body);
            self.warnings.push(CreepWarning::Quarantined { body });
        }
        self.quarantined.1.extend_from_slice(q.colliders());
    }

    /// Whether a step is prepared and not yet finished.
    pub fn is_step_prepared(&self) -> bool {
        self.prepared
    }

    /// Abandons a prepared step (its host did not step): the counts of the step stay, no
    /// rolling torque is applied, no record is swept.
    pub(crate) fn abandon_step(&mut self) {
        self.prepared = false;
    }

    /// Lifts Rapier's angular speed cap (45 degrees per step, `RigidBody::set_allow_fast_rotation`)
    /// on the dynamic bodies of registered ball colliders: the cap exists for the swept volume of
    /// rotating shapes in CCD, which a ball's rotation does not change, and it makes a ball
    /// rolling faster than `(pi/4) R / dt` slide (0.1 m at 1/60 s: 4.7 m/s) and lose most of its
    /// energy. Only bodies whose flag must change are touched.
    pub(crate) fn lift_rotation_cap(&self, bodies: &mut RigidBodySet, colliders: &ColliderSet) {
        // Only with one substep, where the rotation-gap correction is exact: with Rapier's
        // substeps a ball spinning past the cap (100 rad/s at 1/60 s in the hard-case matrix)
        // gains 4.0e-6 of E0 per step against its Coulomb twin (the mean correction's error).
        if !self.settings.lift_rotation_cap || self.substeps != 1 {
            return;
        }
        for &handle in &self.selected {
            let Some(mat) = self.registry.get(handle) else {
                continue;
            };
            if mat.fidelity == Fidelity::Compliant {
                continue;
            }
            let Some(co) = colliders.get(handle) else {
                continue;
            };
            if co.shape().as_ball().is_none() {
                continue;
            }
            let Some(parent) = co.parent() else { continue };
            let Some(rb) = bodies.get(parent).filter(|rb| rb.is_dynamic()) else {
                continue;
            };
            // Rapier caps every body's linear speed (`max_linear_velocity`, 400 m/s per length
            // unit) but no lifted spin: a ball at that cap keeps the spin cap too, so that its
            // rim speed `|omega| R` never runs past the linear cap (friction spins a lifted
            // ball only towards `|v|/R`).
            let radius = f64::from(co.shape().as_ball().map_or(0.0, |b| b.radius));
            let cap = 0.99 * self.max_linvel;
            let lift = f64::from(rb.linvel().length()) < cap
                && f64::from(rb.angvel().length()) * radius < cap;
            if rb.is_fast_rotation_allowed() != lift
                && let Some(rb) = bodies.get_mut(parent)
            {
                rb.set_allow_fast_rotation(lift);
            }
        }
    }

    /// What the plugin did in the last step.
    /// (The shards' counts summed in shard order; with feature `parallel` and several threads
    /// `creep_power` is summed in the threads' order within a shard, so it may differ from one
    /// run to another in its last bits; the physics does not.)
    pub fn counts(&self) -> StepCounts {
        let mut c = StepCounts {
            hooks_on: self.hooks_on,
            warnings: self.warnings.clone(),
            quarantined_bodies: self.quarantined.0.clone(),
            quarantined_colliders: self.quarantined.1.clone(),
            ..StepCounts::default()
        };
        for shard in self.shards.iter() {
            c.add(&shard.lock().unwrap_or_else(|e| e.into_inner()).counts);
        }
        c
    }

    /// Number of live per-contact records.
    pub fn live_contacts(&self) -> usize {
        self.shards
            .iter()
            .map(|s| s.lock().unwrap_or_else(|e| e.into_inner()).store.len())
            .sum()
    }

    /// Copies of all live contact records.
    pub fn records(&self) -> Vec<(ContactKey, ContactRecord)> {
        let mut all = Vec::new();
        for shard in self.shards.iter() {
            let shard = shard.lock().unwrap_or_else(|e| e.into_inner());
            all.extend(shard.store.iter().map(|(k, r)| (*k, *r)));
        }
        all
    }

    /// A copy of the record of one contact, if live.
    pub fn record(&self, key: &ContactKey) -> Option<ContactRecord> {
        let shard = self.shards[shard_of(key.collider1, key.collider2)]
            .lock()
            .unwrap_or_else(|e| e.into_inner());
        shard.store.records.get(key).copied()
    }
}

/// The lower of two fidelities (Coulomb < Auto < Creep), except that a `Compliant` collider
/// makes the pair compliant (it takes part in no Rapier contact solve).
pub(crate) fn pair_fidelity(a: Fidelity, b: Fidelity) -> Fidelity {
    use Fidelity::*;
    match (a, b) {
        (Coulomb, _) | (_, Coulomb) => Coulomb,
        (Auto, _) | (_, Auto) => Auto,
        (Compliant, _) | (_, Compliant) => Compliant,
        _ => Creep,
    }
}

impl PhysicsHooks for CreepHooks {
    fn modify_solver_contacts(&self, context: &mut ContactModificationContext) {
        let (c1, c2) = (context.collider1, context.collider2);
        let (h1, h2) = (context.rigid_body1, context.rigid_body2);
        let bodies = context.bodies;
        let colliders = context.colliders;
        let Some(rigid) = context.rigid_mut() else {
            return;
        };
        let n_contacts = rigid.solver_contacts.len();
        if !self.prepared {
            // Stepped without the step owner: leave the contact to Rapier, and say so at the
            // next step (PluginError::HookOutsideStep).
            self.outside.fetch_add(n_contacts.max(1), Ordering::Relaxed);
            return;
        }
        // Only this pair's shard (never a global lock: crate docs of `SHARDS`).
        let mut shard = self.shards[shard_of(c1, c2)]
            .lock()
            .unwrap_or_else(|e| e.into_inner());
        let Shard {
            store,
            counts,
            laws,
            crowns,
            pairs,
            unregistered,
            unregistered_seen,
            bad_friction,
        } = &mut *shard;
        let (co1, co2) = (colliders.get(c1), colliders.get(c2));
        // Both colliders' friction (a registered collider's is checked before the step, its
        // partner's only here): the step returns PluginError::Friction, and the pair is
        // solved without friction meanwhile so that no NaN reaches the bodies.
        for (handle, co) in [(c1, co1), (c2, co2)] {
            if let Some(co) = co
                && !(co.friction().is_finite() && co.friction() >= 0.0)
            {
                *bad_friction = Some((handle, co.friction()));
                *rigid.friction = 0.0;
                return;
            }
        }
        let (Some(m1), Some(m2)) = (self.registry.get(c1), self.registry.get(c2)) else {
            counts.coulomb_unregistered += n_contacts;
            if self.settings.warn_unregistered {
                let (stranger, known) = if self.registry.get(c1).is_some() {
                    (c2, c1)
                } else {
                    (c1, c2)
                };
                if self.registry.get(known).is_some() && unregistered_seen.insert(stranger) {
                    unregistered.push((stranger, known));
                }
            }
            return;
        };
        // --- Compliant regime (crate::compliant applies this pair's forces itself). ---
        if m1.fidelity == Fidelity::Compliant || m2.fidelity == Fidelity::Compliant {
            rigid.solver_contacts.clear();
            return;
        }
        // --- end compliant ---
        if quiet_collider(co1) && quiet_collider(co2) {
            // Both below the activation speed: plain Rapier contacts (as with the hook off),
            // rebuilt clean before Rapier starts recycling them.
            counts.quiet += n_contacts;
            return;
        }
        // The shapes (one typed-shape call per collider): the contact law's surfaces and, for
        // Rapier's rotation gap, a wheel (cylinder) turning about its axle like a sphere of its
        // radius (crate::wheel).
        let (law1, gap1) = co1.map_or((None, None), shape_surfaces);
        let (law2, gap2) = co2.map_or((None, None), shape_surfaces);
        // The bodies, looked up once per manifold.
        let rbs = [
            h1.and_then(|h| bodies.get(h)),
            h2.and_then(|h| bodies.get(h)),
        ];
        let is_sphere = |s: Surface| matches!(s, Surface::Sphere(_));
        // A ball on either side of a supported shape: the ball path (crate::ball_hook), with
        // the pair's constants computed once per pair of materials (crate::pair_cache).
        let mu = f64::from(*rigid.friction);
        let ball = match (law1, law2) {
            (Some(s1), Some(s2)) if is_sphere(s1) || is_sphere(s2) => pairs
                .get(&m1.material, &m2.material, mu, self.settings.creep_model)
                .and_then(|k| k.pair_for(s1, s2).map(|p| (s1, s2, k, p))),
            _ => None,
        };
        if let Some((s1, s2, consts, pair)) = ball {
            let rolling = match (m1.rolling, m2.rolling) {
                (RollingResistance::Torque(m), _) | (_, RollingResistance::Torque(m)) => Some(m),
                _ => None,
            };
            let manifold = BallManifold {
                colliders: (c1, c2),
                handles: (h1, h2),
                bodies: rbs,
                body_set: bodies,
                surfaces: (s1, s2),
                pair,
                consts,
                fidelity: pair_fidelity(m1.fidelity, m2.fidelity),
                rolling,
                dt: self.dt,
                gap_substeps: self
                    .settings
                    .anchor_drift_correction
                    .then_some(self.substeps),
                settings: &self.settings,
            };
            // (The rotation-gap correction below is done there, contact by contact, on the
            // same motions as the creep.)
            ball_manifold(&manifold, rigid, store, counts);
            return;
        }
        if self.settings.anchor_drift_correction {
            // Every registered pair, whatever its shapes and fidelity: Rapier's rotation gap
            // (see `rotation_gap`) is the engine's, not creep's.
            let n = v3(*rigid.normal);
            let dt = self.dt;
            let flat = Surface::Plane;
            for sc in rigid.solver_contacts.iter_mut() {
                let (a1, a2) = (v3(sc.anchor1), v3(sc.anchor2));
                let p_motion = body_motion(rbs[0], a1 - n, gap1.unwrap_or(flat));
                let q_motion = body_motion(rbs[1], a2 + n, gap2.unwrap_or(flat));
                let (c, b) =
                    rotation_gap_correction(&p_motion, a1, &q_motion, a2, n, dt, self.substeps);
                sc.dist -= c as f32;
                sc.tangent_velocity += vf(n * b);
            }
        }
        // A cylinder on a flat collider: a wheel (crate::wheel).
        let wheel_side = match (law1, law2) {
            (None, Some(Surface::Plane)) => Some(0),
            (Some(Surface::Plane), None) => Some(1),
            _ => None,
        };
        if let Some(side) = wheel_side {
            let ctx = WheelCtx {
                colliders: (c1, c2),
                handles: (h1, h2),
                materials: (m1, m2),
                bodies,
                colliders_set: colliders,
                dt: self.dt,
                prediction: self.prediction,
                gap_substeps: self
                    .settings
                    .anchor_drift_correction
                    .then_some(self.substeps),
                settings: &self.settings,
                consts: pairs.get(&m1.material, &m2.material, mu, self.settings.creep_model),
            };
            if wheel_manifold(&ctx, rigid, side, store, counts, laws, crowns) {
                return;
            }
        }
        match (law1, law2) {
            (Some(s1), Some(s2)) if !is_sphere(s1) && !is_sphere(s2) => {
                // Two flat sides (a box on a box or on a mesh): Hertz needs a curved one.
                counts.coulomb_no_sphere += n_contacts;
            }
            // No supported shape, or a ball pair the law refuses (a bad radius or friction).
            _ => counts.coulomb_unsupported += n_contacts,
        }
    }
}

/// The friction basis of Rapier's Coulomb contact constraint for a manifold of normal `n`
/// (rapier3d 0.36 `compute_tangent_contact_directions`: `t1 = orthonormal_vector(-n)`, the
/// branchless basis of Duff et al. 2017, `t2 = -n x t1`); `ContactData::tangent_impulse` is in it
/// (public so that scenes reading Rapier's friction impulses use the same basis).
pub fn solver_tangents(n: Vec3) -> (Vec3, Vec3) {
    let d = -n;
    let sign = 1f64.copysign(d.z);
    let a = -1.0 / (sign + d.z);
    let b = d.x * d.y * a;
    let t1 = Vec3::new(b, sign + d.y * d.y * a, -d.y);
    (t1, d.cross(t1))
}

/// The surfaces a collider presents to the rigid hook, from one typed-shape call
/// ([`crate::supported_shape`]): the contact law's ([`crate::SupportedShape::rigid_surface`])
/// and the rotation-gap correction's (the same, and a wheel as a sphere of its radius: it turns
/// about its axle).
fn shape_surfaces(co: &Collider) -> (Option<Surface>, Option<Surface>) {
    match crate::shape::supported_shape(co) {
        Some(shape) => (shape.rigid_surface(), Some(shape.gap_surface())),
        None => (None, None),
    }
}
