//! The boundaries of a bed: Rapier colliders as moving boundaries of the grains, their
//! candidate lists and the exchange of impulses (the crate docs: the sub-stepping rule,
//! finding the contacts).

use creep_dem::{Dem, DemError, ExternalForces, ExternalView, MaterialTable, TangentialLaw};
use creep_law::pair::{ContactGeometry, ContactHistory, PairBody, pair_force, release};
use creep_law::{Surface, Vec3};
use rapier3d::glamx::{DQuat, DVec3};
use rapier3d::prelude::{ColliderHandle, ColliderSet, RigidBodyHandle, RigidBodySet};

use crate::convert::{dq, dv, gv, lv};
use crate::{BedConfig, BedError, BoundaryEnergy, BoundaryShape, Exchange};

/// One boundary: a collider, its body's motion over the game step and its candidate grains.
#[derive(Debug, Clone)]
pub(crate) struct Boundary<T: TangentialLaw> {
    collider: ColliderHandle,
    pub(crate) body: Option<RigidBodyHandle>,
    material: usize,
    shape: BoundaryShape,
    /// Collider origin relative to the body's centre of mass, in the body's frame \[m\].
    offset: DVec3,
    /// Collider rotation relative to the body.
    rot_c: DQuat,
    /// Collider pose when it has no body.
    fixed: (DVec3, DQuat),
    /// Largest distance from the centre of mass to the collider's bounding box \[m\].
    reach: f64,
    // Motion over the game step (world frame).
    pub(crate) com0: DVec3,
    rot0: DQuat,
    v: DVec3,
    w: DVec3,
    mass: f64,
    // Pose at the last refresh of the candidates.
    com_ref: DVec3,
    rot_ref: DQuat,
    // Candidates: engine index, grain id, contact history.
    cand_i: Vec<u32>,
    cand_id: Vec<u32>,
    cand_h: Vec<ContactHistory<T>>,
    // Exchange accumulators over the game step (weights dt), and the last sub-step's terms.
    j: DVec3,
    a: DVec3,
    last_f: DVec3,
    last_a: DVec3,
    /// Half the last sub-step's terms of the previous game step (the pending half-kick).
    pend_j: DVec3,
    pend_a: DVec3,
    contacts: usize,
    pub(crate) last: Exchange,
}

impl<T: TangentialLaw> Boundary<T> {
    /// The collider's pose at `t` \[s\] into the game step.
    #[inline]
    fn pose_at(&self, t: f64) -> (DVec3, DQuat, DVec3, DQuat) {
        if self.body.is_none() {
            return (self.fixed.0, self.fixed.1, self.fixed.0, self.fixed.1);
        }
        let rot = DQuat::from_scaled_axis(self.w * t) * self.rot0;
        let com = self.com0 + self.v * t;
        (com + rot * self.offset, rot * self.rot_c, com, rot)
    }

    /// How far the boundary's surface may have moved since the last refresh \[m\].
    fn moved(&self, t: f64) -> f64 {
        let (_, _, com, rot) = self.pose_at(t);
        let turn = (rot * self.rot_ref.inverse()).normalize();
        let angle = 2.0 * turn.w.abs().min(1.0).acos();
        (com - self.com_ref).length() + angle * self.reach
    }
}

/// The boundaries of a bed: implements [`ExternalForces`] for [`Dem::step_with`].
#[derive(Debug, Clone)]
pub struct BoundarySet<T: TangentialLaw> {
    cfg: BedConfig,
    table: MaterialTable,
    pub(crate) boundaries: Vec<Boundary<T>>,
    /// Grain positions at the last refresh, by grain id.
    x_ref: Vec<DVec3>,
    /// Scratch, by grain id: the old candidate slot of each grain during a refresh.
    slot: Vec<u32>,
    /// Scratch: engine index of each grain id (rebuilt after the engine re-sorts).
    index: Vec<u32>,
    /// Start time of the game step \[s\].
    t0: f64,
    refreshed: bool,
    refreshes: usize,
    energy: BoundaryEnergy,
}

impl<T: TangentialLaw> BoundarySet<T> {
    /// An empty set for a bed of `n` grains with the engine's material `table`.
    pub fn new(cfg: BedConfig, table: MaterialTable, n: usize) -> Result<Self, BedError> {
        if !(cfg.skin.is_finite() && cfg.skin > 0.0) {
            return Err(BedError::Parameter {
                name: "skin",
                value: cfg.skin,
                why: "must be finite and > 0 [m]",
            });
        }
        Ok(Self {
            cfg,
            table,
            boundaries: Vec::new(),
            x_ref: vec![DVec3::ZERO; n],
            slot: vec![u32::MAX; n],
            index: vec![0; n],
            t0: 0.0,
            refreshed: false,
            refreshes: 0,
            energy: BoundaryEnergy::default(),
        })
    }

    /// Number of boundaries.
    pub fn len(&self) -> usize {
        self.boundaries.len()
    }
    /// Whether there are no boundaries.
    pub fn is_empty(&self) -> bool {
        self.boundaries.is_empty()
    }
    /// Candidate-list refreshes so far.
    pub fn refreshes(&self) -> usize {
        self.refreshes
    }

    /// Adds `collider` as a boundary of material `material` (an id of the engine's table).
    /// Returns the boundary's index.
    pub fn add(
        &mut self,
        collider: ColliderHandle,
        material: usize,
        bodies: &RigidBodySet,
        colliders: &ColliderSet,
    ) -> Result<usize, BedError> {
        if material >= self.table.len() {
            return Err(DemError::Material(material).into());
        }
        let co = colliders
            .get(collider)
            .ok_or(BedError::MissingCollider(collider))?;
        let shape =
            BoundaryShape::from_shape(co.shared_shape()).ok_or_else(|| BedError::Shape {
                collider,
                shape: format!("{:?}", co.shape().shape_type()),
            })?;
        let aabb = co.shape().compute_local_aabb();
        let (lo, hi) = (dv(aabb.mins), dv(aabb.maxs));
        let corner = lo.abs().max(hi.abs()).length();
        let (body, offset, rot_c, fixed, reach) = match co.parent() {
            Some(h) => {
                let rb = bodies.get(h).ok_or(BedError::MissingBody(h))?;
                let rel = co.position_wrt_parent().copied().unwrap_or_default();
                let offset = dv(rel.translation) - dv(rb.local_center_of_mass());
                (
                    Some(h),
                    offset,
                    dq(rel.rotation),
                    (DVec3::ZERO, DQuat::IDENTITY),
                    offset.length() + corner,
                )
            }
            None => {
                let p = co.position();
                (
                    None,
                    DVec3::ZERO,
                    DQuat::IDENTITY,
                    (dv(p.translation), dq(p.rotation)),
                    corner,
                )
            }
        };
        self.boundaries.push(Boundary {
            collider,
            body,
            material,
            shape,
            offset,
            rot_c,
            fixed,
            reach,
            // A collider without a body: torques are reported about its origin.
            com0: fixed.0,
            rot0: DQuat::IDENTITY,
            v: DVec3::ZERO,
            w: DVec3::ZERO,
            mass: f64::INFINITY,
            com_ref: DVec3::ZERO,
            rot_ref: DQuat::IDENTITY,
            cand_i: Vec::new(),
            cand_id: Vec::new(),
            cand_h: Vec::new(),
            j: DVec3::ZERO,
            a: DVec3::ZERO,
            last_f: DVec3::ZERO,
            last_a: DVec3::ZERO,
            pend_j: DVec3::ZERO,
            pend_a: DVec3::ZERO,
            contacts: 0,
            last: Exchange::default(),
        });
        self.refreshed = false;
        Ok(self.boundaries.len() - 1)
    }

    /// Reads each boundary body's pose and velocity from Rapier for a game step starting at
    /// engine time `t0` \[s\] and clears the accumulators.
    pub fn begin(&mut self, t0: f64, bodies: &RigidBodySet) -> Result<(), BedError> {
        self.t0 = t0;
        for b in &mut self.boundaries {
            b.j = DVec3::ZERO;
            b.a = DVec3::ZERO;
            b.last_f = DVec3::ZERO;
            b.last_a = DVec3::ZERO;
            let Some(h) = b.body else { continue };
            let rb = bodies.get(h).ok_or(BedError::MissingBody(h))?;
            let pose = rb.position();
            b.rot0 = dq(pose.rotation);
            b.com0 = dv(rb.center_of_mass());
            b.v = dv(rb.linvel());
            b.w = dv(rb.angvel());
            b.mass = if rb.is_dynamic() {
                f64::from(rb.mass())
            } else {
                f64::INFINITY
            };
            if !(b.com0.is_finite() && b.rot0.is_finite() && b.v.is_finite() && b.w.is_finite()) {
                return Err(BedError::NonFinite(h));
            }
        }
        Ok(())
    }

    /// Ends a game step of `dt_rigid` \[s\] with DEM step `dt` \[s\]: the impulses of the step
    /// with the velocity-Verlet weights (module docs), per boundary.
    pub fn finish(&mut self, dt_rigid: f64, dt: f64) {
        let h = 0.5 * dt;
        for b in &mut self.boundaries {
            let j = b.j - b.last_f * h + b.pend_j;
            let a = b.a - b.last_a * h + b.pend_a;
            b.pend_j = b.last_f * h;
            b.pend_a = b.last_a * h;
            let tau = a - b.com0.cross(j);
            b.last = Exchange {
                impulse: lv(j),
                torque_impulse: lv(tau),
                mean_force: lv(j / dt_rigid),
                mean_torque: lv(tau / dt_rigid),
                contacts: b.contacts,
            };
        }
    }

    /// What the last game step exchanged with boundary `k`.
    pub fn exchange(&self, k: usize) -> Option<Exchange> {
        self.boundaries.get(k).map(|b| b.last)
    }

    /// The half of the last sub-step's impulse (linear, angular about the origin) the grains
    /// have received and the body will receive with the next game step, for boundary `k`.
    pub fn pending(&self, k: usize) -> Option<(Vec3, Vec3)> {
        self.boundaries.get(k).map(|b| (lv(b.pend_j), lv(b.pend_a)))
    }

    /// The collider of boundary `k`.
    pub fn collider(&self, k: usize) -> Option<ColliderHandle> {
        self.boundaries.get(k).map(|b| b.collider)
    }

    /// The grains (ids) touching boundary `k` at the last sub-step (their contact histories
    /// hold a load; a contact that opened was reset); nothing for an unknown `k`. Read-only,
    /// for display (e.g. a viewer marking the grains under a wheel).
    pub fn touching(&self, k: usize) -> impl Iterator<Item = usize> + '_ {
        self.boundaries.get(k).into_iter().flat_map(|b| {
            b.cand_id
                .iter()
                .zip(&b.cand_h)
                .filter(|(_, h)| !h.is_virgin())
                .map(|(&id, _)| id as usize)
        })
    }

    /// Energy of the grain-boundary contacts of the bed `dem`, with the current elastic
    /// energies.
    pub fn energy(&self, dem: &Dem<T>) -> BoundaryEnergy {
        let mut e = self.energy;
        let (mut wn, mut wt) = (0.0, 0.0);
        for b in &self.boundaries {
            for (k, h) in b.cand_h.iter().enumerate() {
                if h.is_virgin() {
                    continue;
                }
                let g = dem.particle(b.cand_id[k] as usize);
                let (a, t) = h.elastic_energy(
                    self.table.pair(b.material, g.material),
                    b.shape.surface(),
                    Surface::Sphere(g.radius),
                );
                wn += a;
                wt += t;
            }
        }
        e.normal_elastic = wn;
        e.tangential_elastic = wt;
        e
    }

    /// Refreshes every boundary's candidate list at the view's positions.
    fn refresh(&mut self, view: &ExternalView<'_>, t: f64) {
        self.refreshes += 1;
        let energy = &mut self.energy;
        let n = view.positions.len();
        for (k, &id) in view.ids.iter().enumerate() {
            self.x_ref[id as usize] = gv(view.positions[k]);
        }
        let skin = self.cfg.skin;
        for b in &mut self.boundaries {
            let (pos, rot, com, brot) = b.pose_at(t);
            b.com_ref = com;
            b.rot_ref = brot;
            let (lo, hi) = b.shape.local_aabb();
            let centre = pos + rot * ((lo + hi) * 0.5);
            let he = (hi - lo) * 0.5;
            let m = rapier3d::glamx::DMat3::from_quat(rot);
            let ext = DVec3::new(
                m.row(0).abs().dot(he),
                m.row(1).abs().dot(he),
                m.row(2).abs().dot(he),
            );
            for (e, &id) in b.cand_id.iter().enumerate() {
                self.slot[id as usize] = e as u32;
            }
            let old_h = std::mem::take(&mut b.cand_h);
            let old_id = std::mem::take(&mut b.cand_id);
            let old_i = std::mem::take(&mut b.cand_i);
            for i in 0..n {
                let g = (gv(view.positions[i]) - centre).abs() - ext;
                let cut = view.radii[i] + skin;
                if g.x < cut && g.y < cut && g.z < cut {
                    let id = view.ids[i];
                    b.cand_i.push(i as u32);
                    b.cand_id.push(id);
                    let s = self.slot[id as usize];
                    self.slot[id as usize] = u32::MAX;
                    b.cand_h.push(if s == u32::MAX {
                        ContactHistory::default()
                    } else {
                        old_h[s as usize]
                    });
                }
            }
            // Contacts that left the list: none touches (a grain leaves only when farther than
            // the skin), but a history still held is released and booked, as the engine does.
            for (e, &id) in old_id.iter().enumerate() {
                if self.slot[id as usize] == u32::MAX {
                    continue;
                }
                self.slot[id as usize] = u32::MAX;
                let mut h = old_h[e];
                let i = old_i[e] as usize;
                let c = self.table.pair(b.material, view.materials[i] as usize);
                energy.slip +=
                    release(c, b.shape.surface(), Surface::Sphere(view.radii[i]), &mut h);
            }
        }
        self.refreshed = true;
    }

    /// Re-indexes the candidates after the engine re-sorted its grains.
    fn reindex(&mut self, ids: &[u32]) {
        for (i, &id) in ids.iter().enumerate() {
            self.index[id as usize] = i as u32;
        }
        for b in &mut self.boundaries {
            for (e, &id) in b.cand_id.iter().enumerate() {
                b.cand_i[e] = self.index[id as usize];
            }
        }
    }
}

impl<T: TangentialLaw> ExternalForces for BoundarySet<T> {
    fn add_forces(&mut self, view: ExternalView<'_>) -> Result<(), DemError> {
        let t = view.time - self.t0;
        let dt = view.dt;
        let n = view.positions.len();
        if self.x_ref.len() != n {
            return Err(DemError::Parameter {
                name: "number of grains",
                value: n as f64,
                why: "differs from the boundary set's",
            });
        }
        // Re-index if the engine re-sorted.
        let stale = self.boundaries.iter().any(|b| {
            b.cand_i
                .iter()
                .zip(&b.cand_id)
                .any(|(&i, &id)| view.ids.get(i as usize) != Some(&id))
        });
        if stale {
            self.reindex(view.ids);
        }
        // Refresh when a grain and a boundary together may have moved more than the skin.
        let mut d2: f64 = 0.0;
        for k in 0..n {
            let d = gv(view.positions[k]) - self.x_ref[view.ids[k] as usize];
            d2 = d2.max(d.length_squared());
        }
        let dg = d2.sqrt();
        let db = self
            .boundaries
            .iter()
            .map(|b| b.moved(t))
            .fold(0.0, f64::max);
        if !self.refreshed || dg + db > self.cfg.skin {
            self.refresh(&view, t);
        }

        let mut energy = self.energy;
        for b in &mut self.boundaries {
            let (pos, rot, com, _) = b.pose_at(t);
            let inv = rot.inverse();
            let surface = b.shape.surface();
            let (f_acc, a_acc, contacts) = {
                let mut f_acc = DVec3::ZERO;
                let mut a_acc = DVec3::ZERO;
                let mut contacts = 0usize;
                for e in 0..b.cand_i.len() {
                    let i = b.cand_i[e] as usize;
                    let h = &mut b.cand_h[e];
                    let xg = gv(view.positions[i]);
                    let r = view.radii[i];
                    let c = self.table.pair(b.material, view.materials[i] as usize);
                    let local = inv * (xg - pos);
                    let Some(hit) = b.shape.closest(local, r) else {
                        energy.slip += release(c, surface, Surface::Sphere(r), h);
                        continue;
                    };
                    // Reference point of the boundary body: the ball's centre for a ball (the
                    // kernel's contact-point kinematics need the centre of curvature), else
                    // the centre of mass.
                    let (xref, geo) = match b.shape {
                        BoundaryShape::Ball { radius } => {
                            match ContactGeometry::sphere_sphere(lv(pos), radius, lv(xg), r) {
                                Some(g) => (pos, g),
                                None => {
                                    energy.slip += release(c, surface, Surface::Sphere(r), h);
                                    continue;
                                }
                            }
                        }
                        _ => (
                            com,
                            ContactGeometry::plane_sphere(
                                lv(pos + rot * hit.point),
                                lv(rot * hit.normal),
                                lv(xg),
                                r,
                            ),
                        ),
                    };
                    if !(geo.overlap > 0.0) {
                        energy.slip += release(c, surface, Surface::Sphere(r), h);
                        continue;
                    }
                    let bp = PairBody {
                        position: lv(xref),
                        velocity: lv(b.v + b.w.cross(xref - com)),
                        angular_velocity: lv(b.w),
                        surface,
                        mass: b.mass,
                    };
                    let bq = PairBody {
                        position: lv(xg),
                        velocity: view.velocities[i],
                        angular_velocity: view.angular_velocities[i],
                        surface: Surface::Sphere(r),
                        mass: view.masses[i],
                    };
                    let out = pair_force(c, &bp, &bq, &geo, h, dt);
                    let d = out.dissipation;
                    energy.damping += d.damping;
                    energy.slip += d.slip;
                    energy.creep += d.creep;
                    energy.rolling += d.rolling;
                    energy.truncation += d.truncation;
                    if !out.touching {
                        continue;
                    }
                    view.forces[i] -= out.force_p;
                    view.torques[i] += out.torque_q;
                    let f = gv(out.force_p);
                    f_acc += f;
                    a_acc += xref.cross(f) + gv(out.torque_p);
                    contacts += 1;
                }
                (f_acc, a_acc, contacts)
            };
            b.j += f_acc * dt;
            b.a += a_acc * dt;
            b.last_f = f_acc;
            b.last_a = a_acc;
            b.contacts = contacts;
        }
        self.energy = energy;
        Ok(())
    }
}
