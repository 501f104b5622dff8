//! [`CreepAvianPlugin`]: the resource, the hook flags and the per-step bookkeeping.

use avian3d::collision::contact_types::ContactGraph;
use avian3d::dynamics::integrator::IntegrationSystems;
use avian3d::dynamics::solver::constraint_graph::ConstraintGraph;
use avian3d::dynamics::solver::contact::{ContactConstraint, ContactTangentPart};
use avian3d::dynamics::solver::schedule::{SolverSystems, SubstepSchedule, SubstepSolverSystems};
use avian3d::dynamics::solver::solver_body::{SolverBodies, SolverBodyInertia};
use avian3d::math::SymmetricTensor;
use avian3d::prelude::*;
use bevy::prelude::*;
use creep_law::CreepModel;

use crate::hooks::{CreepHooks, v3};
use crate::material::CreepMaterial;
use crate::state::{CreepSettings, CreepState, CreepWarning, GapPoint};

/// Creep-friction for Avian. Install [`crate::CreepHooks`] as Avian's collision hooks, add this
/// plugin, and give colliders a [`CreepMaterial`]:
///
/// ```no_run
/// use avian3d::prelude::*;
/// use bevy::prelude::*;
/// use creep_avian::prelude::*;
/// App::new()
///     .add_plugins((MinimalPlugins, TransformPlugin))
///     .add_plugins((
///         PhysicsPlugins::default().with_collision_hooks::<CreepHooks>(),
///         CreepAvianPlugin::default(),
///     ))
///     .add_systems(Startup, |mut commands: Commands| {
///         commands.spawn((RigidBody::Dynamic, Collider::sphere(0.1), CreepMaterial::steel()));
///     })
///     .run();
/// ```
///
/// What it does:
/// - inserts [`CreepState`] (settings, records, counts, warnings);
/// - turns Avian's contact recycling off (`NarrowPhaseConfig::recycle_distance = 0`): a
///   recycled contact skips the hook, so its slip target would not follow its load
///   ([`CreepAvianPlugin::with_contact_recycling`] keeps it);
/// - gives each `CreepMaterial` collider `ActiveCollisionHooks::MODIFY_CONTACTS` (a required
///   component; an existing `ActiveCollisionHooks` without the flag gets it, with a warning);
/// - for the contacts of two creep colliders, after Avian prepares its contact constraints,
///   puts a friction frame that Avian built out of the contact plane back in it and resolves
///   the warm-start friction impulses (components in last step's frame) into the new frame;
/// - with [`CreepAvianPlugin::with_rotation_gap_removal`], takes creep balls' own rotation out
///   of the separation Avian's solver reads at each substep;
/// - after Avian's solver has stored its impulses, reads each creep contact's normal and
///   tangential impulses from Avian's contact constraints into the records (the hook runs
///   before Avian copies last step's impulses into the new manifolds, so it cannot read them
///   there), and closes the step's counts;
/// - warns (Bevy `warn!`, and [`CreepState::warnings`]) and leaves the contact to Coulomb,
///   never panics, on: a collider touching a creep collider without a material, a shape other
///   than a ball or a flat one, an invalid material, invalid settings, the creep hooks not
///   installed as Avian's narrow-phase hooks.
#[derive(Debug, Clone, Copy, Default)]
pub struct CreepAvianPlugin {
    settings: CreepSettings,
    keep_recycling: bool,
}

impl CreepAvianPlugin {
    /// The plugin with these settings (validated when the plugin is built: invalid settings
    /// draw a warning and the defaults are used).
    pub fn with_settings(mut self, settings: CreepSettings) -> Self {
        self.settings = settings;
        self
    }
    /// Keeps Avian's contact recycling (off by default: the plugin sets
    /// `NarrowPhaseConfig::recycle_distance` to 0). A recycled contact skips the narrow phase
    /// and so the hook: it keeps last step's creep slip target, and its target follows the load
    /// only on the steps Avian recomputes it.
    pub fn with_contact_recycling(mut self, keep: bool) -> Self {
        self.keep_recycling = keep;
        self
    }
    /// The saturated creep slip \[m/s\] below which `Fidelity::Auto` contacts stay Coulomb.
    pub fn with_auto_tolerance(mut self, tolerance: f64) -> Self {
        self.settings.auto_tolerance = tolerance;
        self
    }
    /// Removes creep balls' own rotation from the separation Avian's solver reads at each
    /// substep ([`CreepSettings::rotation_gap_removal`], off by default).
    pub fn with_rotation_gap_removal(mut self, on: bool) -> Self {
        self.settings.rotation_gap_removal = on;
        self
    }
    /// The steady creep law (Kalker's `F_ss` by default).
    pub fn with_creep_model(mut self, model: CreepModel) -> Self {
        self.settings.creep_model = model;
        self
    }
}

impl Plugin for CreepAvianPlugin {
    fn build(&self, app: &mut App) {
        let state = match self.settings.validate() {
            Ok(()) => CreepState::new(self.settings),
            Err(why) => {
                let state = CreepState::new(CreepSettings::default());
                state.lock().warn(CreepWarning::InvalidSettings(why));
                state
            }
        };
        app.insert_resource(state);
        app.register_required_components_with::<CreepMaterial, ActiveCollisionHooks>(|| {
            ActiveCollisionHooks::MODIFY_CONTACTS
        });
        app.add_systems(
            SubstepSchedule,
            (
                accumulate_substep.after(SubstepSolverSystems::Relax),
                remove_rotation_gap
                    .after(SubstepSolverSystems::WarmStart)
                    .before(SubstepSolverSystems::SolveConstraints),
                remove_rotation_gap
                    .after(IntegrationSystems::Position)
                    .before(SubstepSolverSystems::Relax),
            ),
        );
        app.add_systems(
            PhysicsSchedule,
            (
                (add_missing_hook_flags, begin_step).in_set(PhysicsStepSystems::First),
                repair_friction_frames.in_set(SolverSystems::PreSubstep),
                (keep_friction_frames, harvest)
                    .chain()
                    .in_set(PhysicsStepSystems::Solver)
                    .after(SolverSystems::StoreContactImpulses),
            ),
        );
    }

    fn finish(&self, app: &mut App) {
        if !self.keep_recycling
            && let Some(mut config) = app.world_mut().get_resource_mut::<NarrowPhaseConfig>()
        {
            config.recycle_distance = 0.0;
        }
        if !app.is_plugin_added::<NarrowPhasePlugin<Collider, CreepHooks>>()
            && let Some(state) = app.world().get_resource::<CreepState>()
        {
            state.lock().warn(CreepWarning::HooksNotInstalled);
        }
    }
}

/// Gives `MODIFY_CONTACTS` to creep colliders whose `ActiveCollisionHooks` lack it.
fn add_missing_hook_flags(
    mut commands: Commands,
    state: Res<CreepState>,
    query: Query<(Entity, &ActiveCollisionHooks), With<CreepMaterial>>,
) {
    for (e, flags) in &query {
        if !flags.contains(ActiveCollisionHooks::MODIFY_CONTACTS) {
            state.lock().warn(CreepWarning::HookFlagAdded(e));
            commands
                .entity(e)
                .insert(*flags | ActiveCollisionHooks::MODIFY_CONTACTS);
        }
    }
}

/// Applies spin creep's twisting moment `m` (on body 2; `-m` on body 1) over `dt` as an
/// angular impulse, scaled down so that it never reverses the bodies' relative spin about `n`
/// (the creep moment resists the spin; it cannot drive it past zero).
fn apply_moment(
    bodies: &mut Query<(
        &RigidBody,
        &mut AngularVelocity,
        &ComputedAngularInertia,
        &Rotation,
    )>,
    (b1, b2): (Option<Entity>, Option<Entity>),
    m: creep_law::Vec3,
    n: creep_law::Vec3,
    dt: f64,
) {
    let n = crate::hooks::vf(n);
    let impulse = crate::hooks::vf(m * dt);
    let change = |b: Option<Entity>, j: Vec3, bodies: &Query<_, _>| -> (Vec3, f32) {
        let Some(Ok((rb, w, i, rot))) = b.map(|e| bodies.get(e)) else {
            return (Vec3::ZERO, 0.0);
        };
        let (rb, w, i, rot): (
            &RigidBody,
            &AngularVelocity,
            &ComputedAngularInertia,
            &Rotation,
        ) = (rb, w, i, rot);
        if !rb.is_dynamic() {
            return (Vec3::ZERO, w.0.dot(n));
        }
        (i.rotated(rot.0).inverse() * j, w.0.dot(n))
    };
    let (d1, w1) = change(b1, -impulse, bodies);
    let (d2, w2) = change(b2, impulse, bodies);
    let spin = w2 - w1;
    let d = (d2 - d1).dot(n);
    let scale = if spin * (spin + d) < 0.0 && d != 0.0 {
        (-spin / d).clamp(0.0, 1.0)
    } else {
        1.0
    };
    for (b, dw) in [(b1, d1), (b2, d2)] {
        if let Some(Ok((_, mut w, _, _))) = b.map(|e| bodies.get_mut(e)) {
            w.0 += dw * scale;
        }
    }
}

/// Largest `|t1 . n|` of a friction frame taken as lying in the contact plane.
const FRAME_TOLERANCE: f32 = 1e-3;

/// Whether both colliders of the contact have a [`CreepMaterial`].
fn creep_pair(
    contacts: &ContactGraph,
    materials: &Query<(), With<CreepMaterial>>,
    c: &ContactConstraint,
) -> bool {
    contacts.get_by_id(c.contact_id).is_some_and(|(_, pair)| {
        materials.contains(pair.collider1) && materials.contains(pair.collider2)
    })
}

/// Gives each contact of two creep colliders a friction frame in its contact plane and a warm
/// start that is last step's friction impulse.
///
/// Avian builds the frame each step from the relative velocity of the two bodies' centres
/// (`compute_tangent_directions` in avian3d's `dynamics/solver/contact/mod.rs`) and carries the
/// warm-start friction impulse over as its two components in that frame. When the centres
/// move apart or together only along the normal (a ball driven by a ball spinning in place, a
/// ball spinning on a vertical bounce), the tangential part of that velocity is rounding: the
/// frame turns at random from step to step and can lie along the normal (a normal of length
/// `1 + 1e-7` leaves a residual along itself). Last step's impulse is then applied in another
/// direction, the friction solve works against the normal, and a contact that must carry a
/// steady friction force chatters and slips. Here a frame out of the contact plane is replaced
/// by one in it (its effective masses recomputed as Avian does), and each warm-started friction
/// impulse is resolved from last step's frame, kept per manifold, into the new one.
fn repair_friction_frames(
    mut graph: ResMut<ConstraintGraph>,
    contacts: Res<ContactGraph>,
    materials: Query<(), With<CreepMaterial>>,
    solver_bodies: Res<SolverBodies>,
    colliders: Query<&Collider>,
    state: Res<CreepState>,
) {
    let mut guard = state.lock();
    let inner = &mut *guard;
    let step = inner.steps;
    let removal = inner.settings.rotation_gap_removal;
    inner.gaps.clear();
    let is_ball = |e: Entity| {
        colliders
            .get(e)
            .is_ok_and(|c| c.shape_scaled().as_ball().is_some())
    };
    for (ci, color) in graph.colors.iter_mut().enumerate() {
        for (k, c) in color.contact_constraints.iter_mut().enumerate() {
            if !creep_pair(&contacts, &materials, c) {
                continue;
            }
            if removal && let Some((_, pair)) = contacts.get_by_id(c.contact_id) {
                let balls = (is_ball(pair.collider1), is_ball(pair.collider2));
                if balls.0 || balls.1 {
                    for (pi, point) in c.points.iter().enumerate() {
                        inner.gaps.push(GapPoint {
                            at: (ci, k, pi),
                            balls,
                            base: point.initial_separation,
                        });
                    }
                }
            }
            let n = c.normal.normalize_or_zero();
            if n == Vec3::ZERO {
                continue;
            }
            let degenerate = c.tangent1.dot(n).abs() > FRAME_TOLERANCE;
            if degenerate {
                c.tangent1 = n.any_orthonormal_vector();
            }
            let t1 = c.tangent1;
            let t2 = t1.cross(c.normal);
            let last = inner
                .frames
                .get(c.contact_id.0 as usize)
                .filter(|f| f.0 + 1 == step)
                .and_then(|f| f.1.get(c.manifold_index))
                .copied();
            let masses = degenerate.then(|| inverse_masses(&solver_bodies, c));
            for point in c.points.iter_mut() {
                let Some(part) = point.tangent_part.as_mut() else {
                    continue;
                };
                // Avian warm-starts a matched point only (else its impulse is zero), with
                // its components in last step's frame.
                if part.impulse != Vec2::ZERO
                    && let Some([u1, u2]) = last
                {
                    let j = part.impulse.x * u1 + part.impulse.y * u2;
                    part.impulse = Vec2::new(j.dot(t1), j.dot(t2));
                }
                if let Some((sum, i1, i2)) = masses {
                    *part = ContactTangentPart::generate(
                        sum,
                        &i1,
                        &i2,
                        point.anchor1,
                        point.anchor2,
                        [t1, t2],
                        Some(part.impulse),
                    );
                }
            }
        }
    }
}

/// Sets each creep-ball contact point's separation offset for the substep so that the
/// solver's separation leaves out the balls' own rotation.
///
/// Avian's solver (`ContactConstraint::solve` in avian3d's `dynamics/solver/contact/mod.rs`)
/// reads a point's separation at each substep as
/// `(dx2 - dx1) . n + (q2 r2 - q1 r1) . n + initial_separation`, the anchors `r` turned by
/// each body's rotation `q` since the step began. A ball turned about its centre is the same
/// ball, so for a ball's side the turned anchor opens a gap, `R (1 - cos(w t))`, that is not
/// there: the contact of a rolling or spinning ball goes slack in the last substeps of a step.
/// Here `initial_separation` is set, before the solve and before the relaxation of every
/// substep, to Avian's value less the ball's term `(q r - r) . n` (plus for body 1).
fn remove_rotation_gap(
    mut graph: ResMut<ConstraintGraph>,
    bodies: Res<SolverBodies>,
    state: Res<CreepState>,
) {
    let inner = state.lock();
    for g in &inner.gaps {
        let Some(c) = graph
            .colors
            .get_mut(g.at.0)
            .and_then(|color| color.contact_constraints.get_mut(g.at.1))
        else {
            continue;
        };
        let n = c.normal;
        let turn = |index, r: Vec3| {
            bodies
                .get(index)
                .map_or(0.0, |b| (b.delta_rotation * r - r).dot(n))
        };
        let (i1, i2) = (c.body_index1, c.body_index2);
        let Some(point) = c.points.get_mut(g.at.2) else {
            continue;
        };
        let mut separation = g.base;
        if g.balls.0 {
            separation += turn(i1, point.anchor1);
        }
        if g.balls.1 {
            separation -= turn(i2, point.anchor2);
        }
        point.initial_separation = separation;
    }
}

/// The inverse mass sum and inverse inertias of a contact's bodies as Avian's
/// `ContactConstraint::generate` takes them (the dominant body's as zero).
fn inverse_masses(
    bodies: &SolverBodies,
    c: &ContactConstraint,
) -> (Vec3, SymmetricTensor, SymmetricTensor) {
    let a = bodies
        .get_inertia(c.body_index1)
        .unwrap_or(&SolverBodyInertia::DUMMY);
    let b = bodies
        .get_inertia(c.body_index2)
        .unwrap_or(&SolverBodyInertia::DUMMY);
    let (m1, i1) = (a.effective_inv_mass(), a.effective_inv_angular_inertia());
    let (m2, i2) = (b.effective_inv_mass(), b.effective_inv_angular_inertia());
    match c.relative_dominance.cmp(&0) {
        std::cmp::Ordering::Equal => (m1 + m2, i1, i2),
        std::cmp::Ordering::Greater => (m2, SymmetricTensor::ZERO, i2),
        std::cmp::Ordering::Less => (m1, i1, SymmetricTensor::ZERO),
    }
}

/// Keeps, per contact of two creep colliders, each manifold's friction frame of the step (the
/// frame of the warm-start impulses Avian carries over), for [`repair_friction_frames`].
fn keep_friction_frames(
    graph: Res<ConstraintGraph>,
    contacts: Res<ContactGraph>,
    materials: Query<(), With<CreepMaterial>>,
    state: Res<CreepState>,
) {
    let mut inner = state.lock();
    let step = inner.steps;
    for color in &graph.colors {
        for c in &color.contact_constraints {
            if !creep_pair(&contacts, &materials, c) {
                continue;
            }
            let i = c.contact_id.0 as usize;
            if i >= inner.frames.len() {
                inner.frames.resize_with(i + 1, Default::default);
            }
            let frame = &mut inner.frames[i];
            if frame.0 != step {
                frame.0 = step;
                frame.1.clear();
            }
            if frame.1.len() <= c.manifold_index {
                frame.1.resize(c.manifold_index + 1, [Vec3::ZERO; 2]);
            }
            frame.1[c.manifold_index] = [c.tangent1, c.tangent1.cross(c.normal)];
        }
    }
}

/// Starts a step's counts.
fn begin_step(state: Res<CreepState>) {
    let mut inner = state.lock();
    inner.current = Default::default();
    inner.hook_calls = 0;
}

/// Adds each creep contact's impulses of a substep (after the relaxation solve: the impulse
/// the substep applied, its warm start included) to its record. The friction impulse is
/// solved only there, and a substep's accumulated impulse is what it applied, so the sum over
/// the substeps is the step's impulse; the last substep alone is not (a rolling ball's
/// rotation gap opens the contact in the last substeps, which then carry no load).
fn accumulate_substep(graph: Res<ConstraintGraph>, state: Res<CreepState>) {
    let mut inner = state.lock();
    if inner.records.is_empty() {
        return;
    }
    for color in &graph.colors {
        for c in &color.contact_constraints {
            let Some(Some(rec)) = inner.records.get_mut(c.contact_id.0 as usize) else {
                continue;
            };
            let (Some(prev), Some(point)) =
                (rec.points.get_mut(c.manifold_index), c.points.first())
            else {
                continue;
            };
            let t1 = c.tangent1;
            let t2 = t1.cross(c.normal);
            let j = point
                .tangent_part
                .as_ref()
                .map_or(Vec3::ZERO, |t| t.impulse.x * t1 + t.impulse.y * t2);
            prev.acc_normal += f64::from(point.normal_part.impulse);
            prev.acc_tangent += v3(j);
        }
    }
}

/// Turns each creep contact's summed impulses into the step's forces, marks the records whose
/// pairs generated constraints (the others are dropped), applies spin creep's moments, closes
/// the counts.
fn harvest(
    graph: Res<ConstraintGraph>,
    mut bodies: Query<(
        &RigidBody,
        &mut AngularVelocity,
        &ComputedAngularInertia,
        &Rotation,
    )>,
    state: Res<CreepState>,
    time: Res<Time>,
) {
    let dt = time.delta_secs_f64();
    let mut inner = state.lock();
    inner.steps += 1;
    if dt > 0.0 {
        for rec in inner.records.iter_mut().flatten() {
            for point in rec.points.iter_mut() {
                // The solver applies +j to body 2 and -j to body 1.
                point.p = point.acc_normal / dt;
                point.q_meas = point.acc_tangent * (-1.0 / dt);
                point.acc_normal = 0.0;
                point.acc_tangent = creep_law::Vec3::ZERO;
            }
        }
    }
    for color in &graph.colors {
        for c in &color.contact_constraints {
            if let Some(Some(rec)) = inner.records.get_mut(c.contact_id.0 as usize) {
                rec.harvested = true;
            }
        }
    }
    for slot in inner.records.iter_mut() {
        if let Some(rec) = slot {
            for point in &rec.points {
                if point.moment != creep_law::Vec3::ZERO {
                    apply_moment(&mut bodies, rec.bodies, point.moment, point.normal, dt);
                }
            }
            if rec.harvested {
                rec.harvested = false;
            } else {
                *slot = None;
            }
        }
    }
    inner.last_step = inner.current;
}
