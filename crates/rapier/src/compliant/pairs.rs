//! One compliant pair per call: the registry and colliders give its materials and geometry, the
//! pure kernel (creep-law [`pair_force`]) its forces; the contact record is updated in place
//! and the forces and torques are added to the step's per-body sums.

use creep_law::pair::{ContactHistory, Exact, PairBody, PairConstants, pair_force};
use creep_law::rolling_torque::RollingState;
use creep_law::{CreepState, PairMaterial, Vec2, Vec3};
use rapier3d::prelude::*;

use super::colliders::{surface, touch_geometry, touch_of};
use super::{CompliantContact, CompliantRegime};
use crate::error::PluginError;
use crate::hooks::{FastMap, body_motion as motion};
use crate::registry::{MaterialRegistry, Regime, RollingResistance};

impl CompliantRegime {
    /// The contact of one narrow-phase pair at step `dt` \[s\]: skips (and counts) pairs that are
    /// not compliant, not supported or open; for a touching one, runs the pair kernel, updates
    /// its record (marked with this step's generation), the energy totals and counts, adds the
    /// stored elastic energies (normal, tangential) \[J\] to `elastic`, and adds its forces and
    /// torques to `accum`.
    #[allow(clippy::too_many_arguments)]
    pub(super) fn pair_contact(
        &mut self,
        pair: &ContactPair,
        registry: &MaterialRegistry,
        bodies: &RigidBodySet,
        colliders: &ColliderSet,
        dt: f64,
        accum: &mut FastMap<RigidBodyHandle, (Vec3, Vec3, bool)>,
        elastic: &mut (f64, f64),
    ) -> Result<(), PluginError> {
        let (c1, c2) = (pair.collider1, pair.collider2);
        let (Some(m1), Some(m2)) = (registry.get(c1), registry.get(c2)) else {
            let compliant = |c| registry.get(c).is_some_and(|m| m.is_compliant());
            if compliant(c1) || compliant(c2) {
                self.counts.unsupported += 1; // an unregistered partner: passed through
            }
            return Ok(());
        };
        // A pair with one compliant collider is compliant (`Regime::pair`): a rigid-regime
        // partner meets it with its own material.
        if m1.regime.pair(m2.regime) != Regime::Compliant {
            return Ok(());
        }
        let (Some(co1), Some(co2)) = (colliders.get(c1), colliders.get(c2)) else {
            return Ok(());
        };
        let Some(touch) = touch_of(co1, co2) else {
            self.counts.unsupported += 1;
            return Ok(());
        };
        if !(touch.overlap > 0.0) {
            return Ok(()); // open: the record is swept below, the memory is lost
        }
        let (Some(s1), Some(s2)) = (surface(co1), surface(co2)) else {
            self.counts.unsupported += 1;
            return Ok(());
        };
        let mu = f64::from(CoefficientCombineRule::combine(
            co1.friction(),
            co2.friction(),
            co1.friction_combine_rule(),
            co2.friction_combine_rule(),
        ));
        let e = f64::from(CoefficientCombineRule::combine(
            co1.restitution(),
            co2.restitution(),
            co1.restitution_combine_rule(),
            co2.restitution_combine_rule(),
        ));
        let pm =
            PairMaterial::new(&m1.material, &m2.material, s1, s2).and_then(|p| p.with_friction(mu));
        let Ok(pm) = pm else {
            self.counts.unsupported += 1;
            return Ok(());
        };
        let alpha = self.alpha(e)?;
        let (h1, h2) = (co1.parent(), co2.parent());
        let b1 = h1.and_then(|h| bodies.get(h));
        let b2 = h2.and_then(|h| bodies.get(h));
        let inv_m = |b: Option<&RigidBody>| match b {
            Some(rb) if rb.is_dynamic() && rb.mass() > 0.0 => 1.0 / f64::from(rb.mass()),
            _ => 0.0,
        };
        let inv_sum = inv_m(b1) + inv_m(b2);
        if !(inv_sum > 0.0) {
            return Ok(());
        }
        let n = touch.normal;
        let c = touch.point;
        let p_motion = motion(b1, c - n, s1);
        let q_motion = motion(b2, c + n, s2);
        let mass = |b: Option<&RigidBody>| match b {
            Some(rb) if rb.is_dynamic() && rb.mass() > 0.0 => f64::from(rb.mass()),
            _ => f64::INFINITY,
        };
        let body = |m: &creep_law::kinematics::BodyMotion, mass: f64| PairBody {
            position: m.position,
            velocity: m.velocity,
            angular_velocity: m.angular_velocity,
            surface: m.surface,
            mass,
        };
        let (bp, bq) = (body(&p_motion, mass(b1)), body(&q_motion, mass(b2)));
        let rolling = match (m1.rolling, m2.rolling) {
            (RollingResistance::Torque(m), _) | (_, RollingResistance::Torque(m)) => Some(m),
            _ => None,
        };
        let creep = self.settings.creep.then_some(self.settings.creep_model);
        let Ok(constants) = PairConstants::from_parts(&pm, alpha, creep, rolling) else {
            self.counts.unsupported += 1;
            return Ok(());
        };

        // Contact record, its tangent basis carried with the contact.
        let generation = self.generation;
        let rec = self.contacts.entry((c1, c2)).or_insert_with(|| {
            let (t1, _) = n.tangent_basis();
            CompliantContact {
                state: CreepState::new(),
                t1,
                t2: n.cross(t1),
                normal: n,
                point: c,
                overlap: 0.0,
                normal_force: 0.0,
                tangential_force: Vec3::ZERO,
                rolling: RollingState::default(),
                sliding: false,
                creep_ratio: 0.0,
                v_disp: Vec3::ZERO,
                v_roll: Vec3::ZERO,
                generation,
            }
        });
        let mut history = ContactHistory::<Exact> {
            tangential: rec.state,
            t1: rec.t1,
            normal: rec.normal,
            rolling: rec.rolling,
            overlap: rec.overlap,
        };
        // The pure pair kernel (creep-law `pair`): the DEM engine calls the same function.
        let f = pair_force(
            &constants,
            &bp,
            &bq,
            &touch_geometry(&touch),
            &mut history,
            dt,
        );
        if !f.touching {
            return Ok(()); // degenerate basis: the record is swept below
        }
        let d = f.dissipation;
        self.energy.damping += d.damping;
        self.energy.slip += d.slip;
        self.energy.creep += d.creep;
        self.energy.truncation += d.truncation;
        self.energy.rolling += d.rolling;

        rec.state = history.tangential;
        rec.t1 = history.t1;
        rec.t2 = history.normal.cross(history.t1);
        rec.normal = history.normal;
        rec.rolling = history.rolling;
        rec.point = c;
        rec.overlap = history.overlap;
        rec.normal_force = f.normal_force;
        rec.tangential_force = f.tangential_force;
        rec.sliding = f.sliding;
        let creep_len = f.creep_displacement.length();
        rec.creep_ratio = if f.slide_length > 0.0 {
            creep_len / f.slide_length
        } else if f.creep_displacement != Vec2::ZERO {
            f64::INFINITY
        } else {
            0.0
        };
        rec.v_disp = f.v_disp;
        rec.v_roll = f.v_roll;
        rec.generation = generation;
        let (wn, wt) = history.elastic_energy(&constants, s1, s2);
        elastic.0 += wn;
        elastic.1 += wt;
        self.counts.contacts += 1;
        self.counts.sliding += usize::from(f.sliding);
        self.counts.creeping += usize::from(f.creep_displacement != Vec2::ZERO);

        // Whether a body of the pair moves (is awake): a sleeping body it touches is woken
        // (below); two sleeping bodies leave each other asleep.
        let awake = [b1, b2]
            .into_iter()
            .flatten()
            .any(|rb| !rb.is_fixed() && !rb.is_sleeping());
        // Forces and torques (about the centres of mass), equal and opposite.
        for (b, h, f, m) in [
            (b1, h1, f.force_p, f.torque_p),
            (b2, h2, -f.force_p, f.torque_q),
        ] {
            let (Some(rb), Some(h)) = (b, h) else {
                continue;
            };
            if !rb.is_dynamic() {
                continue;
            }
            let e = accum.entry(h).or_insert((Vec3::ZERO, Vec3::ZERO, false));
            e.0 += f;
            e.1 += m;
            e.2 |= awake;
        }
        Ok(())
    }
}
