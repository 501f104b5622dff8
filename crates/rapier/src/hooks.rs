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
//! # Anchor-drift correction
//! Rapier stores each solver contact's anchor in its body's frame, so within a step the anchor of
//! a rolling sphere turns with it, away from the lowest point: the solver reads a growing gap and
//! lets the sphere sink (measured: -2.4 mm for a 0.1 m steel ball at 2.4 m/s, 1/60 s, 4
//! substeps). The hook subtracts the mean spurious gap over the substeps from the contact's
//! `dist` ([`CreepSettings::anchor_drift_correction`], on by default; it applies to every
//! registered pair, Coulomb fidelity included): the sinking falls to -0.33 mm there.
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
//! Requirements (checked by [`check_parameters`]): `FrictionModel::Coulomb` (per-point friction
//! impulses are only written then) and `contact_clustering = false`.

use std::collections::HashMap;
use std::sync::Mutex;

use creep_law::kinematics::{BodyMotion, contact_rates};
use creep_law::rolling_torque::{RollingInput, RollingModel, RollingState, epsd_rolling_inertia};
use creep_law::root::illinois;
use creep_law::steady_law::SteadyLaw;
use creep_law::{PairMaterial, Surface, Vec3, hertz, kalker};
use rapier3d::geometry::NEW_CONTACT_BIT;
use rapier3d::prelude::*;

use crate::error::PluginError;
use crate::registry::{Fidelity, MaterialRegistry, RollingResistance, surface_of};

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

/// Sets `params` to what the plugin needs (`FrictionModel::Coulomb`, no clustering).
pub fn configure_parameters(params: &mut IntegrationParameters) {
    params.friction_model = FrictionModel::Coulomb;
    params.contact_clustering = false;
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
    /// a step ([`CreepHooks::update_activation`]): its contacts then stay plain Coulomb and keep
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
}

impl Default for CreepSettings {
    fn default() -> Self {
        Self {
            auto_tolerance: 1e-7,
            anchor_drift_correction: true,
            activation_speed: 1e-2,
            creep_model: creep_law::CreepModel::Kuhn,
        }
    }
}

impl CreepSettings {
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
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct StepCounts {
    /// Contacts with a collider the registry does not know: left to Coulomb.
    pub coulomb_unregistered: usize,
    /// Contacts whose shapes creep-law does not model (not ball, cuboid or half-space): Coulomb.
    pub coulomb_unsupported: usize,
    /// Contacts whose pair asked for Coulomb.
    pub coulomb_requested: usize,
    /// `Auto` contacts whose creep bound was below the tolerance: Coulomb.
    pub coulomb_auto: usize,
    /// Contacts that took the creep-friction path.
    pub creep: usize,
    /// Contacts with a contact-torque rolling model.
    pub rolling_torque: usize,
    /// Power dissipated by creep, `sum Q . v_disp` [W] (>= 0).
    pub creep_power: f64,
    /// Largest loop gain `g` of the Q -> slip -> Q feedback this step (see the module docs).
    pub max_loop_gain: f64,
    /// Registered colliders whose hook was on for this step ([`CreepHooks::update_activation`]).
    pub hooks_on: usize,
}

/// Stable identity of one contact point across steps: the collider pair and the two shape
/// features (Rapier may re-order a manifold's points; the features do not change).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct ContactKey {
    /// Collider 1 of the pair.
    pub collider1: ColliderHandle,
    /// Collider 2 of the pair.
    pub collider2: ColliderHandle,
    /// Feature of collider 1.
    pub feature1: u32,
    /// Feature of collider 2.
    pub feature2: u32,
}

/// Per-contact state that persists across steps.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ContactRecord {
    /// The relaxed friction force used for the slip target, world frame, on body 1 [N].
    pub q_used: Vec3,
    /// Contact-torque rolling state (EPSD spring).
    pub rolling: RollingState,
    /// Torque on body 2 computed this step by the rolling model [N m] (`-torque` on body 1).
    pub torque: Vec3,
    /// Bodies of the contact, for applying the torque.
    pub bodies: (Option<RigidBodyHandle>, Option<RigidBodyHandle>),
    /// Normal force of the previous step, total normal impulse / dt [N].
    pub p: f64,
    /// Creep slip target set in the last step [m/s] (world frame).
    pub target: Vec3,
    /// Contact normal of the last step (the basis of its friction impulse).
    pub normal: Vec3,
    /// Step in which the record was last seen.
    generation: u64,
}

/// A fast, non-cryptographic hasher for [`ContactKey`]s (the multiply-rotate scheme of
/// rustc's FxHash): the keys are small integers, so SipHash's flood resistance buys nothing
/// and costs a sizable part of the hook's time.
#[derive(Debug, Clone, Copy, Default)]
pub struct KeyHasher(u64);

impl std::hash::Hasher for KeyHasher {
    #[inline]
    fn write(&mut self, bytes: &[u8]) {
        for chunk in bytes.chunks(8) {
            let mut buf = [0u8; 8];
            buf[..chunk.len()].copy_from_slice(chunk);
            self.write_u64(u64::from_le_bytes(buf));
        }
    }
    #[inline]
    fn write_u32(&mut self, i: u32) {
        self.write_u64(u64::from(i));
    }
    #[inline]
    fn write_u64(&mut self, i: u64) {
        self.0 = (self.0.rotate_left(5) ^ i).wrapping_mul(0x51_7c_c1_b7_27_22_0a_95);
    }
    #[inline]
    fn finish(&self) -> u64 {
        self.0
    }
}

/// A hash map with [`KeyHasher`] (handles and contact keys are small integers: SipHash's
/// protection against adversarial keys is not needed, its cost is).
pub(crate) type FastMap<K, V> = HashMap<K, V, std::hash::BuildHasherDefault<KeyHasher>>;

type KeyMap<V> = FastMap<ContactKey, V>;

/// Contact records keyed by [`ContactKey`], swept of the contacts not seen in a step.
#[derive(Debug, Clone, Default)]
pub struct ContactStore {
    records: KeyMap<ContactRecord>,
    generation: u64,
}

impl ContactStore {
    /// The record of a contact, created if new, marked as seen in this step.
    pub fn touch(&mut self, key: ContactKey) -> &mut ContactRecord {
        let generation = self.generation;
        let r = self.records.entry(key).or_default();
        r.generation = generation;
        r
    }
    /// Starts a new step.
    pub fn begin_step(&mut self) {
        self.generation += 1;
    }
    /// Drops the records not seen in the current step (pair separated, collider or body
    /// removed, island asleep). Returns how many were dropped.
    pub fn sweep(&mut self) -> usize {
        let before = self.records.len();
        let g = self.generation;
        self.records.retain(|_, r| r.generation == g);
        before - self.records.len()
    }
    /// Number of live records.
    pub fn len(&self) -> usize {
        self.records.len()
    }
    /// Whether there are no records.
    pub fn is_empty(&self) -> bool {
        self.records.is_empty()
    }
    /// Iterates over the live records.
    pub fn iter(&self) -> impl Iterator<Item = (&ContactKey, &ContactRecord)> {
        self.records.iter()
    }
}

struct Inner {
    store: ContactStore,
    counts: StepCounts,
}

/// The creep-friction physics hooks (rigid regime). Give it to `PhysicsPipeline::step` (or use
/// [`crate::CreepWorld`]); call [`CreepHooks::begin_step`] before and [`CreepHooks::end_step`]
/// after every step.
pub struct CreepHooks {
    registry: MaterialRegistry,
    settings: CreepSettings,
    dt: f64,
    substeps: usize,
    inner: Mutex<Inner>,
}

impl CreepHooks {
    /// Hooks with the given materials and settings.
    pub fn new(registry: MaterialRegistry, settings: CreepSettings) -> Result<Self, PluginError> {
        settings.validate()?;
        Ok(Self {
            registry,
            settings,
            dt: 1.0 / 60.0,
            substeps: 4,
            inner: Mutex::new(Inner {
                store: ContactStore::default(),
                counts: StepCounts::default(),
            }),
        })
    }

    /// The material registry.
    pub fn registry(&self) -> &MaterialRegistry {
        &self.registry
    }
    /// The material registry, to add or remove colliders.
    pub fn registry_mut(&mut self) -> &mut MaterialRegistry {
        &mut self.registry
    }
    /// The settings.
    pub fn settings(&self) -> &CreepSettings {
        &self.settings
    }

    /// Call before each step with the step's parameters (checks them).
    pub fn begin_step(&mut self, params: &IntegrationParameters) -> Result<(), PluginError> {
        check_parameters(params)?;
        self.dt = f64::from(params.dt);
        self.substeps = params.num_solver_iterations.max(1);
        let inner = self.inner.get_mut().unwrap_or_else(|e| e.into_inner());
        inner.store.begin_step();
        inner.counts = StepCounts::default();
        Ok(())
    }

    /// Call before each step (after [`CreepHooks::begin_step`]), with the world's bodies and
    /// colliders: switches `ActiveHooks::MODIFY_SOLVER_CONTACTS` on for the registered colliders
    /// whose body moves faster than [`CreepSettings::activation_speed`] (always for `Creep`
    /// colliders) and off for the others, so that quiet contacts keep Rapier's contact recycling.
    /// Returns how many are on. Unregistered colliders are left as they are.
    pub fn update_activation(
        &mut self,
        bodies: &RigidBodySet,
        colliders: &mut ColliderSet,
    ) -> usize {
        let v_act = self.settings.activation_speed;
        let mut on_count = 0;
        for (&handle, mat) in self.registry.iter() {
            // Read first: `ColliderSet::get_mut` marks a collider as modified, which makes Rapier
            // re-process it (a large cost if done for every collider every step).
            let Some(co) = colliders.get(handle) else {
                continue;
            };
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
            let on = mat.fidelity == Fidelity::Creep
                || matches!(mat.rolling, RollingResistance::Torque(_))
                || v_act == 0.0
                || co.parent().and_then(|h| bodies.get(h)).is_some_and(|rb| {
                    let r = co.shape().compute_local_bounding_sphere().radius;
                    rb.linvel().length() + rb.angvel().length() * r > v_act as f32
                });
            let flags = co.active_hooks();
            let wanted = if on {
                flags | ActiveHooks::MODIFY_SOLVER_CONTACTS
            } else {
                flags - ActiveHooks::MODIFY_SOLVER_CONTACTS
            };
            if wanted != flags
                && let Some(co) = colliders.get_mut(handle)
            {
                co.set_active_hooks(wanted);
            }
            on_count += usize::from(on);
        }
        let inner = self.inner.get_mut().unwrap_or_else(|e| e.into_inner());
        inner.counts.hooks_on = on_count;
        on_count
    }

    /// Call after each step: applies the contact-torque rolling resistance computed in the step
    /// (as angular impulses `M dt`, capped so that they never reverse the relative rolling) and
    /// drops the records of contacts that ended.
    pub fn end_step(&mut self, bodies: &mut RigidBodySet) {
        let dt = self.dt;
        let inner = self.inner.get_mut().unwrap_or_else(|e| e.into_inner());
        for (_, rec) in inner.store.records.iter() {
            if rec.torque == Vec3::ZERO || rec.generation != inner.store.generation {
                continue;
            }
            apply_rolling_impulse(bodies, rec, dt);
        }
        inner.store.sweep();
    }

    /// What the plugin did in the last step.
    pub fn counts(&self) -> StepCounts {
        self.inner
            .lock()
            .map(|i| i.counts)
            .unwrap_or_else(|e| e.into_inner().counts)
    }

    /// Number of live per-contact records.
    pub fn live_contacts(&self) -> usize {
        self.inner
            .lock()
            .map(|i| i.store.len())
            .unwrap_or_else(|e| e.into_inner().store.len())
    }

    /// Copies of all live contact records.
    pub fn records(&self) -> Vec<(ContactKey, ContactRecord)> {
        let inner = self.inner.lock().unwrap_or_else(|e| e.into_inner());
        inner.store.iter().map(|(k, r)| (*k, *r)).collect()
    }

    /// A copy of the record of one contact, if live.
    pub fn record(&self, key: &ContactKey) -> Option<ContactRecord> {
        let inner = self.inner.lock().unwrap_or_else(|e| e.into_inner());
        inner.store.records.get(key).copied()
    }
}

/// A Rapier (f32) vector in creep-law's f64 vector.
pub(crate) fn v3(v: Vector) -> Vec3 {
    Vec3::new(f64::from(v.x), f64::from(v.y), f64::from(v.z))
}

/// A creep-law f64 vector rounded to Rapier's f32.
pub(crate) fn vf(v: Vec3) -> Vector {
    Vector::new(v.x as f32, v.y as f32, v.z as f32)
}

/// Motion of a body at the contact (a missing body is at rest at `fallback`).
pub(crate) fn body_motion(
    body: Option<&RigidBody>,
    fallback: Vec3,
    surface: Surface,
) -> BodyMotion {
    match body {
        Some(rb) => BodyMotion {
            position: v3(rb.center_of_mass()),
            velocity: v3(rb.linvel()),
            angular_velocity: v3(rb.angvel()),
            surface,
        },
        None => BodyMotion {
            position: fallback,
            velocity: Vec3::ZERO,
            angular_velocity: Vec3::ZERO,
            surface,
        },
    }
}

/// [`body_motion`] of a body of `bodies` by handle.
fn motion(
    bodies: &RigidBodySet,
    handle: Option<RigidBodyHandle>,
    fallback: Vec3,
    surface: Surface,
) -> BodyMotion {
    body_motion(handle.and_then(|h| bodies.get(h)), fallback, surface)
}

/// Inverse effective mass of a contact between the unit directions `t` and `u` at `point`:
/// `sum_i [t . M_i^-1 u + (r_i x t) . I_i^-1 (r_i x u)]` over the dynamic bodies [1/kg] (the
/// Delassus operator of the contact; `t = u` gives the inverse mass along `t`).
fn inverse_mass(
    bodies: &RigidBodySet,
    handles: [Option<RigidBodyHandle>; 2],
    point: Vector,
    t: Vector,
    u: Vector,
) -> f64 {
    let mut inv = 0.0;
    for h in handles {
        let Some(rb) = h.and_then(|h| bodies.get(h)) else {
            continue;
        };
        if !rb.is_dynamic() {
            continue;
        }
        let mp = rb.mass_properties();
        let r = point - rb.center_of_mass();
        let (rt, ru) = (r.cross(t), r.cross(u));
        inv += f64::from((mp.effective_inv_mass * t).dot(u))
            + f64::from(rt.dot(mp.effective_world_inv_inertia * ru));
    }
    inv
}

/// Inverse effective rotational inertia of the pair about the unit axis `w` [1/(kg m^2)].
fn inverse_rotational_inertia(
    bodies: &RigidBodySet,
    handles: [Option<RigidBodyHandle>; 2],
    w: Vector,
) -> f64 {
    let mut inv = 0.0;
    for h in handles {
        let Some(rb) = h.and_then(|h| bodies.get(h)) else {
            continue;
        };
        if rb.is_dynamic() {
            inv += f64::from(w.dot(rb.mass_properties().effective_world_inv_inertia * w));
        }
    }
    inv
}

/// Applies `M dt` on body 2 and `-M dt` on body 1, shortened so that it brings the relative
/// rolling angular velocity at most to zero, never past it.
fn apply_rolling_impulse(bodies: &mut RigidBodySet, rec: &ContactRecord, dt: f64) {
    let Some(axis) = rec.torque.try_normalize() else {
        return;
    };
    let handles = [rec.bodies.0, rec.bodies.1];
    let inv_i = inverse_rotational_inertia(bodies, handles, vf(axis));
    if !(inv_i > 0.0) {
        return;
    }
    // Current relative rolling rate along the torque axis (the torque opposes it).
    let w_of = |h: Option<RigidBodyHandle>, b: &RigidBodySet| {
        h.and_then(|h| b.get(h))
            .map(|rb| v3(rb.angvel()))
            .unwrap_or_default()
    };
    let w_rel = (w_of(rec.bodies.1, bodies) - w_of(rec.bodies.0, bodies)).dot(axis);
    let mut impulse = rec.torque.length() * dt;
    if w_rel < 0.0 {
        impulse = impulse.min(-w_rel / inv_i);
    } else {
        return; // already reversed or stopped: no torque pushes it further
    }
    let j = vf(axis * impulse);
    for (handle, jj) in [(rec.bodies.1, j), (rec.bodies.0, -j)] {
        if let Some(rb) = handle.and_then(|h| bodies.get_mut(h))
            && rb.is_dynamic()
        {
            rb.apply_torque_impulse(jj, true);
        }
    }
}

/// The lower of two fidelities (Coulomb < Auto < Creep), except that a `Compliant` collider
/// makes the pair compliant (it takes part in no Rapier contact solve).
fn pair_fidelity(a: Fidelity, b: Fidelity) -> Fidelity {
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
        let mut inner = self.inner.lock().unwrap_or_else(|e| e.into_inner());
        let Inner { store, counts } = &mut *inner;
        let (c1, c2) = (context.collider1, context.collider2);
        let (h1, h2) = (context.rigid_body1, context.rigid_body2);
        let bodies = context.bodies;
        let colliders = context.colliders;
        let Some(rigid) = context.rigid_mut() else {
            return;
        };
        let n_contacts = rigid.solver_contacts.len();
        let (Some(m1), Some(m2)) = (self.registry.get(c1), self.registry.get(c2)) else {
            counts.coulomb_unregistered += n_contacts;
            return;
        };
        // --- Compliant regime (crate::compliant applies this pair's forces itself). ---
        if m1.fidelity == Fidelity::Compliant || m2.fidelity == Fidelity::Compliant {
            rigid.solver_contacts.clear();
            return;
        }
        // --- end compliant ---
        let surfaces = (
            colliders.get(c1).and_then(surface_of),
            colliders.get(c2).and_then(surface_of),
        );
        let (Some(s1), Some(s2)) = surfaces else {
            counts.coulomb_unsupported += n_contacts;
            return;
        };
        let mu = f64::from(*rigid.friction);
        let Ok(pair) =
            PairMaterial::new(&m1.material, &m2.material, s1, s2).and_then(|p| p.with_friction(mu))
        else {
            counts.coulomb_unsupported += n_contacts;
            return;
        };
        let fidelity = pair_fidelity(m1.fidelity, m2.fidelity);
        let rolling = match (m1.rolling, m2.rolling) {
            (RollingResistance::Torque(m), _) | (_, RollingResistance::Torque(m)) => Some(m),
            _ => None,
        };
        let n = v3(*rigid.normal);
        let dt = self.dt;
        for sc in rigid.solver_contacts.iter_mut() {
            let cid = (sc.contact_id[0] & !NEW_CONTACT_BIT) as usize;
            let Some(point) = rigid.manifold.points.get(cid) else {
                continue;
            };
            let key = ContactKey {
                collider1: c1,
                collider2: c2,
                feature1: point.fid1.0,
                feature2: point.fid2.0,
            };
            let (a1, a2) = (v3(sc.anchor1), v3(sc.anchor2));
            let c = (a1 + a2) * 0.5;
            let p_motion = motion(bodies, h1, a1 - n, s1);
            let q_motion = motion(bodies, h2, a2 + n, s2);
            let rates = contact_rates(&p_motion, &q_motion, c, n);
            if self.settings.anchor_drift_correction {
                let drift = anchor_drift(&q_motion, a2, n, dt, self.substeps)
                    - anchor_drift(&p_motion, a1, n, dt, self.substeps);
                sc.dist -= drift as f32;
            }
            let rec = store.touch(key);
            rec.bodies = (h1, h2);
            let p_force = f64::from(point.data.impulse) / dt;
            rec.p = p_force;
            let n_prev_step = rec.normal;
            rec.normal = n;
            let roll = rates.v_roll.length();

            // Contact-torque rolling resistance (computed here, applied in end_step).
            rec.torque = Vec3::ZERO;
            if let Some(model) = rolling {
                counts.rolling_torque += 1;
                rec.torque = rolling_torque(
                    &model,
                    rec,
                    bodies,
                    (h1, h2),
                    &pair,
                    p_force,
                    rates.w_roll,
                    n,
                    dt,
                );
            }

            if fidelity == Fidelity::Coulomb {
                counts.coulomb_requested += 1;
                rec.target = Vec3::ZERO;
                continue;
            }
            if !(p_force > 0.0) || !(roll > 0.0) || !(mu > 0.0) {
                // New contact (no impulse yet), no rolling, or frictionless: nothing creeps.
                rec.q_used = Vec3::ZERO;
                counts.coulomb_auto += 1;
                rec.target = Vec3::ZERO;
                continue;
            }
            let a = hertz::contact_radius(&pair, p_force);
            let mu_p = mu * p_force;
            let bound = kalker::steady_creepage(1.0, mu_p, pair.g, a, pair.c11) * roll;
            if fidelity == Fidelity::Auto && bound < self.settings.auto_tolerance {
                counts.coulomb_auto += 1;
                rec.q_used = Vec3::ZERO;
                rec.target = Vec3::ZERO;
                continue;
            }
            // Measured friction force of the last step, on body 1: the step's total tangent
            // impulse in the solver's tangent basis, built from the normal of that step.
            // (`warmstart_tangent_world` holds the last substep only and reads zero on most
            // rolling steps: a direction taken from it never follows a reversal.)
            let ti = point.data.tangent_impulse;
            let n_prev = if n_prev_step == Vec3::ZERO {
                n
            } else {
                n_prev_step
            };
            let (t1, t2) = solver_tangents(n_prev);
            let q_meas = (t1 * f64::from(ti.x) + t2 * f64::from(ti.y)).reject(n) * (1.0 / dt);
            // Local implicit solve of the creep relation (module docs): the force the solver
            // would transmit for a target tau is Q* - (m_t/dt) tau, with
            // Q* = Q_meas + (m_t/dt) tau_prev; tau = F_ss(|Q|/mu P) |v_roll| Q/|Q|.
            // If the force the solver transmitted opposed last step's target (the demanded force
            // reversed), that target did negative work: drop it from the estimate instead of
            // carrying it into this step.
            let tau_prev = if q_meas.dot(rec.target) < 0.0 {
                Vec3::ZERO
            } else {
                rec.target.reject(n)
            };
            let probe = (q_meas + tau_prev).try_normalize().unwrap_or(Vec3::X);
            let inv_m = inverse_mass(bodies, [h1, h2], vf(c), vf(probe), vf(probe));
            let q_star = if inv_m > 0.0 {
                q_meas + tau_prev * (1.0 / (inv_m * dt))
            } else {
                q_meas
            };
            let Some(q_hat) = q_star.try_normalize() else {
                rec.q_used = Vec3::ZERO;
                rec.target = Vec3::ZERO;
                counts.coulomb_auto += 1;
                continue;
            };
            let k = if inv_m > 0.0 {
                roll / (inv_m * dt)
            } else {
                0.0
            };
            let law = SteadyLaw::with_c11(self.settings.creep_model, pair.nu, pair.c11);
            let creepage = |q: f64| law.creepage_for_force(q, mu_p, pair.g, a);
            let q_abs = solve_creep_force(q_star.length(), k, mu_p, &creepage);
            let dq = 1e-6 * mu_p;
            let gain = k * (creepage((q_abs + dq).min(mu_p)) - creepage((q_abs - dq).max(0.0)))
                / (2.0 * dq);
            counts.max_loop_gain = counts.max_loop_gain.max(gain);
            let q_used = q_hat * q_abs;
            rec.q_used = q_used;
            let slip = creepage(q_abs) * roll;
            let target = q_hat * slip;
            rec.target = target;
            counts.creep += 1;
            counts.creep_power += q_used.dot(target).max(0.0);
            sc.tangent_velocity = vf(target);
        }
    }
}

/// The friction basis of Rapier's Coulomb contact constraint for a manifold of normal `n`
/// (rapier3d 0.36 `compute_tangent_contact_directions`: `t1 = orthonormal_vector(-n)`, the
/// branchless basis of Duff et al. 2017, `t2 = -n x t1`); `ContactData::tangent_impulse` is in it.
fn solver_tangents(n: Vec3) -> (Vec3, Vec3) {
    let d = -n;
    let sign = 1f64.copysign(d.z);
    let a = -1.0 / (sign + d.z);
    let b = d.x * d.y * a;
    let t1 = Vec3::new(b, sign + d.y * d.y * a, -d.y);
    (t1, d.cross(t1))
}

/// Solves `q + k F(q) = q_star` for `0 <= q <= mu P` by the Illinois variant of regula falsi
/// (bracketed, superlinear), with `F(q)` the steady creepage of the chosen law at force `q`
/// and `k = m_t |v_roll| / dt` [N]: the force a rolling contact of effective mass `m_t`
/// transmits when its slip target follows the force it transmits. `F` increases, so the root is
/// unique; beyond `mu P` the contact slides at `mu P`.
fn solve_creep_force(q_star: f64, k: f64, mu_p: f64, creepage: &dyn Fn(f64) -> f64) -> f64 {
    let hi0 = q_star.min(mu_p);
    if !(k > 0.0) || !(hi0 > 0.0) {
        return hi0.max(0.0);
    }
    let h = |q: f64| q + k * creepage(q) - q_star;
    let (fa, fb) = (h(0.0), h(hi0));
    if fb <= 0.0 {
        return hi0;
    }
    illinois(h, (0.0, fa), (hi0, fb), 100, |_, fc, k| {
        (k.b - k.a).abs() <= 1e-13 * hi0 || fc == 0.0
    })
    .root_or_midpoint()
}

/// Mean spurious change of the separation along `n` caused by a body's contact anchor riding
/// with the body's rotation through the solver substeps: the anchor `a` (world, at the start
/// of the step) turns about the centre of mass by `w t`; its normal component changes by
/// `(Rot(w t) r - r) . n`, `r = a - x` (Rodrigues' rotation formula), which the solver reads as
/// a gap (or overlap) although the surface of a sphere does not move. Averaged over the
/// substep midpoints `t = (k - 1/2) dt / n`, `k = 1..n`, in closed form (two sine-cosine
/// evaluations instead of one per substep). Zero for a body that does not turn.
fn anchor_drift(body: &BodyMotion, a: Vec3, n: Vec3, dt: f64, substeps: usize) -> f64 {
    let w = body.angular_velocity;
    let wl = w.length();
    if !(wl > 0.0) || !matches!(body.surface, Surface::Sphere(_)) {
        return 0.0;
    }
    let axis = w * (1.0 / wl);
    let r = a - body.position;
    // Means of cos and sin of phi_k = (k + 1/2) h over k = 0..n-1, h = |w| dt / n, in closed
    // form (sum of a geometric series of e^{i phi_k}): sum = e^{i n h / 2} sin(n h / 2) / sin(h / 2).
    let count = substeps.max(1) as f64;
    let h = wl * dt / count;
    let (sh, ch) = (0.5 * count * h).sin_cos();
    let s_half = (0.5 * h).sin();
    let ratio = if s_half != 0.0 {
        sh / (count * s_half)
    } else {
        1.0
    };
    let (mean_cos, mean_sin) = (ch * ratio, sh * ratio);
    // Rodrigues: Rot(phi) r - r = (cos phi - 1) (r - axis (axis . r)) + sin phi (axis x r).
    let r_perp = r - axis * axis.dot(r);
    (r_perp * (mean_cos - 1.0) + axis.cross(r) * mean_sin).dot(n)
}

/// The contact-torque model's torque on body 2 for this step.
#[allow(clippy::too_many_arguments)]
fn rolling_torque(
    model: &RollingModel,
    rec: &mut ContactRecord,
    bodies: &RigidBodySet,
    handles: (Option<RigidBodyHandle>, Option<RigidBodyHandle>),
    pair: &PairMaterial,
    p: f64,
    w_roll: Vec3,
    n: Vec3,
    dt: f64,
) -> Vec3 {
    let a = hertz::contact_radius(pair, p);
    // Each dynamic sphere contributes its mass, its inertia about a diameter (2/5) m r^2 and its
    // radius to Ai et al.'s (2011) rolling inertia; walls and fixed bodies contribute nothing.
    let term = |h: Option<RigidBodyHandle>, s: Surface| {
        let body = h.and_then(|h| bodies.get(h)).filter(|rb| rb.is_dynamic());
        match (body, s) {
            (Some(rb), Surface::Sphere(r)) => {
                let m = f64::from(rb.mass());
                (m, 0.4 * m * r * r, r)
            }
            _ => (f64::INFINITY, f64::INFINITY, 1.0),
        }
    };
    let (m1, i1, rr1) = term(handles.0, pair.surface_p);
    let (m2, i2, rr2) = term(handles.1, pair.surface_q);
    let input = RollingInput {
        p,
        r_star: pair.r_star,
        k_n: 2.0 * pair.e_star * a,
        w_roll,
        normal: n,
        dt,
        rolling_inertia: epsd_rolling_inertia(m1, i1, rr1, m2, i2, rr2),
    };
    model.torque(&mut rec.rolling, &input).torque
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn anchor_drift_closed_form_equals_the_substep_average() {
        let body = BodyMotion {
            position: Vec3::new(0.1, 0.2, -0.3),
            velocity: Vec3::ZERO,
            angular_velocity: Vec3::new(3.0, -24.0, 7.0),
            surface: Surface::Sphere(0.1),
        };
        let n = Vec3::new(0.2, 0.9, -0.1).try_normalize().unwrap();
        let a = body.position - n * 0.1 + Vec3::new(0.01, 0.0, 0.02);
        for (dt, substeps) in [(1.0 / 60.0, 4), (1.0 / 30.0, 1), (1.0 / 240.0, 8)] {
            // Direct average of (Rot(w t_k) r - r) . n over the substep midpoints.
            let w = body.angular_velocity;
            let axis = w.try_normalize().unwrap();
            let r = a - body.position;
            let mut sum = 0.0;
            for k in 0..substeps {
                let phi = w.length() * (k as f64 + 0.5) * dt / substeps as f64;
                let (sn, cs) = phi.sin_cos();
                let rot = r * cs + axis.cross(r) * sn + axis * (axis.dot(r) * (1.0 - cs));
                sum += (rot - r).dot(n);
            }
            let direct = sum / substeps as f64;
            let closed = anchor_drift(&body, a, n, dt, substeps);
            assert!(
                (closed - direct).abs() <= 1e-15 + 1e-12 * direct.abs(),
                "{closed} vs {direct}"
            );
        }
    }
}
