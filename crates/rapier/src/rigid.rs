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
//! # The law (creep-law's rigid kernel)
//! Each contact is one call of [`creep_law::rigid`]: [`creep_law::rigid::ball_creep`] for a
//! ball on a ball or on a flat collider, [`creep_law::rigid::wheel_creep`] for a wheel. The
//! kernel's module docs give the law: the slip target in Kalker's rolling frame (the configured
//! law `F_ss` along the rolling direction, Kalker's `C22` across it, spin creep with its lateral
//! force and twisting moment for balls and crowned wheels; the moment applied after the step as
//! an angular impulse that never reverses the relative spin, as the rolling torque), and the
//! implicit solve of the feedback `Q -> slip -> Q` that keeps it stable at any loop gain
//! `g = m_t |v_roll| dF_ss/dQ / dt` (the largest `g` of each step is in
//! [`StepCounts::max_loop_gain`]). Cylinder colliders on a flat collider are wheels (module
//! `wheel`: Carter's line contact, or Hertz's ellipse for a crown radius set with
//! [`CreepHooks::set_wheel_crown`]): one slip target for the whole manifold.
//!
//! The host's share (this module): which contacts the law sees (registered pairs of supported
//! shapes, fidelity, activation), what Rapier gives it (the solver contact's anchors, last
//! step's normal and friction impulses of the manifold point, in the solver's tangent basis of
//! last step's normal), the effective mass of the contact along a direction, the records that
//! carry each contact's last target across steps, the counts, the moments after the step, and
//! Rapier's rotation gap.
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
//! flag is never recycled by crates.io's Rapier (docs/RAPIER_CONTACT_RECYCLING.md), so a pair
//! that creeps pays a full contact update and the solver-graph upkeep every step. With the
//! feature `rapier-patched` (the patch series in `upstream/rapier/`) an `Auto` or `Creep`
//! collider moving slower than 0.1 m/s opts in to recycling
//! (`ActiveHooks::RECYCLE_MODIFIED_SOLVER_CONTACTS`; not a wheel), and on a recycled step the
//! hook rewrites each ball contact's slip target on the kept solver contacts from this step's
//! state, as on a full update ([`StepCounts::recycled`] counts them). Inside the hook the
//! per-pair constants are cached (`creep_law::rigid::RigidPairCache`) and each collider's shape is read once
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

mod ball;
mod counts;
mod crowns;
mod dispatch;
mod hooks;
mod settings;
mod wheel;

pub use counts::StepCounts;
pub use hooks::CreepHooks;
pub use settings::{
    CreepSettings, ROLLING_PGS_ITERATIONS, SolverPreset, check_parameters, configure_parameters,
    configure_parameters_for,
};
