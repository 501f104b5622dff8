//! The rigid hook's wheel path: a cylinder on a flat collider gets one contact record and one
//! slip target for its whole manifold, one call of `creep_law::rigid::wheel_creep` (Carter's
//! line-contact law or, for a crowned wheel, the elliptic contact's 3-D law and spin creep); an
//! upright wheel's manifold is solved as one solver contact at its patch centre
//! (`patch_contact`, and "The patch contact" in module `crowns`). Called from the dispatch
//! (`modify_solver_contacts`).

use creep_law::rigid::{LawCache, RigidContact, RigidPair, WheelInput, wheel_creep};
use creep_law::{Surface, Vec3};
use rapier3d::prelude::*;

use super::counts::StepCounts;
use super::crowns::Crowns;
use super::settings::CreepSettings;
use crate::convert::{inverse_mass, motion, solver_tangents, v3, vf};
use crate::gap::rotation_gap_correction;
use crate::registry::Fidelity;
use crate::store::{ContactKey, ContactStore};

/// What the wheel path needs of the hook's call.
pub(crate) struct WheelCtx<'a> {
    pub(crate) colliders: (ColliderHandle, ColliderHandle),
    pub(crate) handles: (Option<RigidBodyHandle>, Option<RigidBodyHandle>),
    pub(crate) materials: (
        &'a crate::registry::CreepMaterial,
        &'a crate::registry::CreepMaterial,
    ),
    pub(crate) bodies: &'a RigidBodySet,
    pub(crate) colliders_set: &'a ColliderSet,
    pub(crate) dt: f64,
    /// Rapier's prediction distance \[m\] (`IntegrationParameters::prediction_distance`).
    pub(crate) prediction: f64,
    /// The rotation-gap correction's substeps (`None`: the correction is off).
    pub(crate) gap_substeps: Option<usize>,
    pub(crate) settings: &'a CreepSettings,
    /// The pair's fidelity (`Regime::pair` of the two materials).
    pub(crate) fidelity: Fidelity,
    /// The pair's constants (`None`: a pair the law refuses).
    pub(crate) consts: Option<&'a RigidPair>,
}

/// The wheel path of the hook (module `crowns`): one record and one slip target for the whole
/// manifold of a cylinder (`side` 0: collider 1, 1: collider 2) on a flat collider. Returns
/// false when the collider is not a wheel (the caller then falls back to Coulomb).
pub(crate) fn wheel_manifold(
    ctx: &WheelCtx,
    rigid: &mut ModifiableManifold,
    side: usize,
    store: &mut ContactStore,
    counts: &mut StepCounts,
    laws: &mut LawCache,
    crowns: &mut Crowns,
) -> bool {
    let (c1, c2) = ctx.colliders;
    let (h1, h2) = ctx.handles;
    let (m1, m2) = ctx.materials;
    let wc = if side == 0 { c1 } else { c2 };
    let n_contacts = rigid.solver_contacts.len();
    let Some(co) = ctx.colliders_set.get(wc) else {
        return false;
    };
    let Some(cyl) = co.shape().as_cylinder() else {
        return false;
    };
    let radius = f64::from(cyl.radius);
    let wheel_surface = Surface::Sphere(radius);
    let (s1, s2) = if side == 0 {
        (wheel_surface, Surface::Plane)
    } else {
        (Surface::Plane, wheel_surface)
    };
    // The pair's constants once per pair of materials, as the ball path.
    let Some(pair) = ctx.consts.and_then(|k| k.pair_for(s1, s2)) else {
        counts.coulomb_unsupported += n_contacts;
        return true;
    };
    let crown = if side == 0 { m1.crown } else { m2.crown };
    let Some(wheel) = crowns.wheel(co, crown, pair.e_star) else {
        return false;
    };
    crowns.keep_template(rigid.solver_contacts.first());
    let centre = v3(co.translation());
    let floor = ctx.colliders_set.get(if side == 0 { c2 } else { c1 });
    // The floor's face under the wheel from the shapes themselves (a cuboid or a half-space),
    // not from Rapier's manifold (`ExactPatch`).
    let face = floor
        .and_then(|f| floor_face(f, centre, wheel.axle, radius, f64::from(cyl.half_height)))
        .filter(|f| wheel.axle.dot(f.m).abs() < UPRIGHT);
    // One solver contact at the centre of the wheel's contact patch (module docs of
    // module `crowns`), for every fidelity, so that a Coulomb twin has the same contact.
    let n_manifold = v3(*rigid.normal);
    let patched = if let Some(face) = face {
        let n = if side == 0 { -face.m } else { face.m };
        *rigid.normal = vf(n);
        let skins =
            f64::from(co.contact_skin()) + floor.map_or(0.0, |f| f64::from(f.contact_skin()));
        let patch = ExactPatch {
            face,
            centre,
            axle: wheel.axle,
            radius,
            n,
            skins,
            surfaces: (s1, s2),
        };
        patch.apply(ctx, rigid, crowns);
        true
    } else if wheel.axle.dot(n_manifold).abs() < UPRIGHT {
        let n = n_manifold;
        let towards_floor = if side == 0 { n } else { -n };
        patch_contact(rigid, centre, wheel.axle, radius, towards_floor, n);
        true
    } else {
        false
    };
    let n = v3(*rigid.normal);
    // Last step's loads: of the patch contact's manifold point (the one solved last step), or
    // of a tilted wheel's solver contacts.
    let loads = manifold_loads(rigid);
    let n_contacts = rigid.solver_contacts.len();
    let fidelity = ctx.fidelity;
    if fidelity == Fidelity::Coulomb {
        counts.coulomb_requested += n_contacts;
        return true;
    }
    let dt = ctx.dt;
    // The whole manifold: total normal force, contact centre.
    let key = ContactKey {
        collider1: c1,
        collider2: c2,
        feature1: u32::MAX,
        feature2: u32::MAX,
    };
    let generation = store.generation;
    let rec = store.touch(key);
    let n_prev = std::mem::replace(&mut rec.normal, n);
    let (t1, t2) = solver_tangents(if n_prev == Vec3::ZERO { n } else { n_prev });
    let (mut centre, mut count) = (Vec3::ZERO, 0.0);
    for sc in rigid.solver_contacts.iter() {
        centre += (v3(sc.anchor1) + v3(sc.anchor2)) * 0.5;
        count += 1.0;
    }
    rec.bodies = (h1, h2);
    rec.torque = Vec3::ZERO;
    rec.spin_torque = Vec3::ZERO;
    rec.p = loads.0 / dt;
    if !(count > 0.0) {
        rec.q_used = Vec3::ZERO;
        rec.target = Vec3::ZERO;
        return true;
    }
    let c = centre * (1.0 / count);
    let contact = RigidContact {
        normal: n,
        point: c,
        p: motion(ctx.bodies, h1, c - n, s1),
        q: motion(ctx.bodies, h2, c + n, s2),
        normal_impulse: loads.0,
        tangent_impulse: t1 * loads.1 + t2 * loads.2,
        last_target: rec.target,
        dt,
        auto_tolerance: (fidelity == Fidelity::Auto).then_some(ctx.settings.auto_tolerance),
    };
    let input = WheelInput {
        axle: wheel.axle,
        radius,
        contact: wheel.contact,
        wheel_is_p: side == 0,
        // Spin creep on the patch contact only (a tilted wheel's several friction points
        // resist a twist as Coulomb does).
        spin: patched,
    };
    // The wheel's turn about n over the last step from its poses (`Crowns::axle_turn`: its
    // angular velocity holds the last spin impulse, which a joint shares out only in the next
    // solve).
    let out = wheel_creep(
        &pair,
        &input,
        &contact,
        laws,
        || crowns.axle_turn(wc, wheel.axle, n, generation),
        |d| inverse_mass(ctx.bodies, [h1, h2], vf(c), vf(d), vf(d)),
    );
    counts.book(&out, n_contacts);
    rec.set_creep(&out);
    if out.creeps() {
        for sc in rigid.solver_contacts.iter_mut() {
            sc.tangent_velocity += vf(out.target);
        }
    }
    true
}

/// Largest `|axle . n|` of a wheel whose manifold becomes one patch contact (a camber up to
/// ~11.5 degrees); a wheel tilted further touches on its rim's edge and keeps Rapier's points.
const UPRIGHT: f64 = 0.2;

/// Last step's total normal impulse and total friction impulse (in the solver's tangent basis
/// of last step's normal, components `t1`, `t2`) of the manifold's solver contacts \[N s\].
fn manifold_loads(rigid: &ModifiableManifold) -> (f64, f64, f64) {
    let (mut p, mut q1, mut q2) = (0.0, 0.0, 0.0);
    for sc in rigid.solver_contacts.iter() {
        let cid = (sc.contact_id[0] & !NEW_CONTACT_BIT) as usize;
        let Some(point) = rigid.manifold.points.get(cid) else {
            continue;
        };
        p += f64::from(point.data.impulse);
        q1 += f64::from(point.data.tangent_impulse.x);
        q2 += f64::from(point.data.tangent_impulse.y);
    }
    (p, q1, q2)
}

/// A flat face of the floor under a wheel (world): its outward unit normal `m` (from the floor
/// towards the wheel) and a point of it \[m\].
#[derive(Debug, Clone, Copy, PartialEq)]
struct Face {
    m: Vec3,
    point: Vec3,
}

/// The face of a cuboid or half-space `floor` that a wheel (centre `centre`, unit axle `axle`,
/// radius \[m\], half-width \[m\] along the axle) stands on, from the shapes alone; `None` for
/// other shapes, for a wheel whose centre is inside the cuboid's slab of every face, or whose
/// line of contact (its mid-plane rim point +- the half-width along the axle) leaves the face
/// (at an edge: Rapier's manifold then stays). A cuboid's face is the one whose slab the
/// centre lies farthest outside of (`max_i |p_i| - h_i`, `p` the centre in the cuboid's frame,
/// `h` its half-extents).
fn floor_face(
    floor: &Collider,
    centre: Vec3,
    axle: Vec3,
    radius: f64,
    half_width: f64,
) -> Option<Face> {
    let rot = floor.rotation();
    let t = v3(floor.translation());
    if let Some(hs) = floor.shape().as_halfspace() {
        let m = v3(rot * hs.normal).try_normalize()?;
        return (m.dot(centre - t) > 0.0).then_some(Face { m, point: t });
    }
    let h = floor.shape().as_cuboid()?.half_extents;
    let h = [f64::from(h.x), f64::from(h.y), f64::from(h.z)];
    let inv = rot.inverse();
    let local = |v: Vec3| {
        let l = v3(inv * vf(v));
        [l.x, l.y, l.z]
    };
    let p = local(centre - t);
    let mut i = 0;
    for j in 1..3 {
        if p[j].abs() - h[j] > p[i].abs() - h[i] {
            i = j;
        }
    }
    if !(p[i].abs() > h[i]) {
        return None;
    }
    let mut m_local = [0.0f32; 3];
    m_local[i] = if p[i] > 0.0 { 1.0 } else { -1.0 };
    let m = v3(rot * Vector::new(m_local[0], m_local[1], m_local[2]));
    let point = t + m * h[i];
    let d = (-m).reject(axle).try_normalize()?;
    let rim = local(centre + d * radius - t);
    let ax = local(axle);
    for j in (0..3).filter(|&j| j != i) {
        if !(rim[j].abs() + half_width * ax[j].abs() <= h[j]) {
            return None;
        }
    }
    Some(Face { m, point })
}

/// The patch contact of an upright wheel on a flat face known exactly ([`floor_face`]): the
/// normal is the face's, the separation that of the wheel's mid-plane rim point from the face
/// plane (less the colliders' contact skins), both from the two colliders' poses and shapes
/// alone. Rapier's narrow phase (parry3d 0.31 `contact_manifold_pfm_pfm`: GJK, and EPA once
/// the shapes overlap) computes a cylinder on a cuboid in f32 on the Minkowski difference,
/// whose support points lie at the cuboid's corners: on the scenes' 1000 m floor their
/// rounding (~6e-5 m at 1000 m) swamps the 5e-5 m a resting wheel overlaps by, and on some
/// steps the manifold came back with a wrong normal (`(0.970, 0.017, 0.242)` for the floor's
/// `(0, 1, 0)`) and points separated by +0.7..+1.4 mm while the wheel overlapped by 1.5 mm:
/// no solver contact, or one that carried nothing, the wheel falling for one to five steps and
/// then stopped by 2-7 `m g dt` (the lateral slide's "intermittent impacts", creep-scenes'
/// `slip_angle_saturation`). The face's contact has Rapier's own rule for a solver contact
/// (`dist < prediction`, or within it after the step at the current approach speed, rapier3d
/// 0.36 `pair_update.rs`), the rotation-gap correction of the rigid hook (crate::gap), and
/// the contact id of the manifold point that carried last step's load (or, when Rapier left
/// the manifold's points without a solver contact, a solver contact built on the point with
/// the largest impulse; none when the manifold has no point at all).
struct ExactPatch {
    face: Face,
    centre: Vec3,
    axle: Vec3,
    radius: f64,
    /// The manifold's normal, from collider 1 to collider 2 (`-m` or `m`).
    n: Vec3,
    /// Sum of the two colliders' contact skins \[m\].
    skins: f64,
    /// The two bodies' surfaces for the rotation-gap correction (the wheel a sphere of its
    /// radius, the floor a plane).
    surfaces: (Surface, Surface),
}

impl ExactPatch {
    fn apply(&self, ctx: &WheelCtx, rigid: &mut ModifiableManifold, crowns: &Crowns) {
        let Face { m, point } = self.face;
        let n = self.n;
        let Some(d) = (-m).reject(self.axle).try_normalize() else {
            return;
        };
        let on_wheel = self.centre + d * self.radius;
        let dist0 = m.dot(on_wheel - point) - self.skins;
        let (h1, h2) = ctx.handles;
        let on_floor = on_wheel - m * m.dot(on_wheel - point);
        // anchor1 on collider 1 (the wheel when `n = -m`).
        let (a1, a2) = if n.dot(m) < 0.0 {
            (on_wheel, on_floor)
        } else {
            (on_floor, on_wheel)
        };
        let (c, b) = match ctx.gap_substeps {
            Some(substeps) => {
                let (s1, s2) = self.surfaces;
                let p_motion = motion(ctx.bodies, h1, a1 - n, s1);
                let q_motion = motion(ctx.bodies, h2, a2 + n, s2);
                rotation_gap_correction(&p_motion, a1, &q_motion, a2, n, ctx.dt, substeps)
            }
            None => (0.0, 0.0),
        };
        let dist = dist0 - c;
        let tv = n * b;
        let (a1, a2) = if n.dot(m) < 0.0 {
            (on_wheel, on_wheel + n * dist)
        } else {
            (on_wheel - n * dist, on_wheel)
        };
        if rigid.solver_contacts.is_empty() {
            // Rapier's rule for a solver contact, on the exact separation.
            let velocity = |h: Option<RigidBodyHandle>| {
                h.and_then(|h| ctx.bodies.get(h))
                    .map_or(Vec3::ZERO, |rb| v3(rb.velocity_at_point(vf(on_wheel))))
            };
            let approach = (velocity(h2) - velocity(h1)).dot(n) * ctx.dt;
            if !(dist0 < ctx.prediction || dist0 + approach < ctx.prediction) {
                return;
            }
            let mut best: Option<(usize, f32)> = None;
            for (i, p) in rigid.manifold.points.iter().enumerate() {
                if best.is_none_or(|(_, load)| p.data.impulse > load) {
                    best = Some((i, p.data.impulse));
                }
            }
            let Some((cid, load)) = best else {
                return;
            };
            let id = cid as u32 | if load == 0.0 { NEW_CONTACT_BIT } else { 0 };
            if let Some(sc) = crowns.solver_contact(id, vf(a1), vf(a2), dist as f32, vf(tv)) {
                rigid.solver_contacts.push(sc);
            }
            return;
        }
        let keep = loaded_contact(rigid);
        keep_one_contact(rigid, keep, a1, a2, dist, tv);
    }
}

/// Reduces the manifold's solver contacts to the one at index `keep` (the most loaded, so the
/// solver's warm start carries over) and places it at the patch: anchors `a1` on collider 1 and
/// `a2` on collider 2 \[m\], separation `dist` along the normal \[m\] (negative: overlap),
/// target tangent velocity `tv` \[m/s\].
fn keep_one_contact(
    rigid: &mut ModifiableManifold,
    keep: usize,
    a1: Vec3,
    a2: Vec3,
    dist: f64,
    tv: Vec3,
) {
    rigid.solver_contacts.swap(0, keep);
    rigid.solver_contacts.truncate(1);
    let sc = &mut rigid.solver_contacts[0];
    sc.anchor1 = vf(a1);
    sc.anchor2 = vf(a2);
    sc.dist = dist as f32;
    sc.tangent_velocity = vf(tv);
}

/// The index of the solver contact whose manifold point carried the largest normal impulse
/// last step (the first on a tie).
fn loaded_contact(rigid: &ModifiableManifold) -> usize {
    let (mut keep, mut best) = (0, f32::NEG_INFINITY);
    for (i, sc) in rigid.solver_contacts.iter().enumerate() {
        let cid = (sc.contact_id[0] & !NEW_CONTACT_BIT) as usize;
        let load = rigid
            .manifold
            .points
            .get(cid)
            .map_or(0.0, |p| p.data.impulse);
        if load > best {
            (keep, best) = (i, load);
        }
    }
    keep
}

/// Replaces a wheel's solver contacts by one at the centre of its contact patch: the point of
/// the wheel's mid-plane rim nearest the floor, `c = x_w + R d`, `d` the unit direction towards
/// the floor in the wheel's plane (`towards_floor` less its part along the axle), with the
/// manifold's mean separation, gap correction and target (module docs of `crowns`: a
/// rigid wheel's friction acts at its patch, not at Rapier's two to four points along the
/// cylinder's line, whose per-point friction limits let a Coulomb wheel slip from 0.8 `mu P`).
/// Keeps the contact id of the point that carried last step's load (only it is solved, so only
/// it carries warm starts and impulses into the next step).
fn patch_contact(
    rigid: &mut ModifiableManifold,
    centre: Vec3,
    axle: Vec3,
    radius: f64,
    towards_floor: Vec3,
    n: Vec3,
) {
    let k = rigid.solver_contacts.len();
    if k == 0 {
        return;
    }
    let Some(d) = towards_floor.reject(axle).try_normalize() else {
        return;
    };
    let keep = loaded_contact(rigid);
    // The separation at the mid-plane: least squares of the points' separations against
    // their positions `s` along the axle (the mean for points at one `s`).
    let (mut s1, mut s2, mut d1, mut sd, mut tv) = (0.0, 0.0, 0.0, 0.0, Vec3::ZERO);
    for sc in rigid.solver_contacts.iter() {
        let s = (v3(sc.anchor1) - centre).dot(axle);
        let dist = f64::from(sc.dist);
        s1 += s;
        s2 += s * s;
        d1 += dist;
        sd += s * dist;
        tv += v3(sc.tangent_velocity);
    }
    let inv = 1.0 / k as f64;
    let (s_mean, d_mean) = (s1 * inv, d1 * inv);
    let var = s2 * inv - s_mean * s_mean;
    let slope = if var > 1e-12 * radius * radius {
        (sd * inv - s_mean * d_mean) / var
    } else {
        0.0
    };
    let dist = d_mean - slope * s_mean;
    let tv = tv * inv;
    let on_wheel = centre + d * radius;
    // anchor1 on collider 1; the normal points from collider 1 to collider 2, and the
    // separation along it is `dist` (negative: overlap).
    let (a1, a2) = if towards_floor.dot(n) > 0.0 {
        (on_wheel, on_wheel + n * dist)
    } else {
        (on_wheel - n * dist, on_wheel)
    };
    keep_one_contact(rigid, keep, a1, a2, dist, tv);
}
