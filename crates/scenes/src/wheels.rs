//! Wheels in the rigid regime: a cylinder collider rolling on a floor, with
//! a line contact (Carter 1926) or crowned (Hertz's ellipse, Kalker's theory).
//!
//! * [`driven`]: a wheel driven by a torque `T` about its axle and held back at the axle by the
//!   force `T/R`, so that in steady state the floor's traction is `Q = T/R` at any speed
//!   (Rapier's lever arm is shortened by the contact's overlap: `Q` is measured from the
//!   contact impulses). The creepage `xi = v_disp . x / V` (`creep_law::rigid`:
//!   slip of the floor's surface relative to the wheel's along the travel, over Kuhn & Bagi's
//!   rolling speed) is measured from the bodies' velocities, less the creepage of a Coulomb run
//!   of the same scene (the engine's spurious slip, Rapier's rolling about a point inside the
//!   overlap, not creep). Closed forms: Carter's `Q/(mu P) = 1 - (1 - xi/(mu a/R))^2` (Carter
//!   1926; Johnson 1985, §8.2; creep-reference `carter`) for the line contact; for the crowned
//!   wheel, Kalker's exact theory (creep-reference's boundary elements, `steady3d::table`).
//! * [`lateral`]: a wheel rolling along `x` and pushed sideways at its axle, held upright with
//!   its heading held: it settles at the slip angle `alpha` whose lateral force balances the
//!   push, lateral creepage `eta = tan(alpha)`; Kalker's linear theory gives the slope
//!   `G a b C22` (Kalker 1967; Kalker 1990, Table E.3), the boundary elements the curve, and
//!   the force saturates at `mu P`.
//! * [`driven_on_joint`]: the driven wheel built from creep-rapier's documented recipe only
//!   (`CreepWorld::new`'s defaults, the wheel on a revolute joint to a chassis). [`driven`] and
//!   [`lateral`] use their own solver settings (one substep, 16 Gauss-Seidel iterations, the
//!   wheel's radius as Rapier's length unit) and hold the wheel by locked axes instead of a
//!   joint (the axle's sideways translation locked in [`driven`]).

use std::f64::consts::FRAC_PI_2;

use creep_law::elliptic::elliptic_hertz;
use creep_law::{Material, PairMaterial, Surface, Vec3};
use creep_rapier::{CreepMaterial, CreepSettings, CreepWorld, Fidelity};
use rapier3d::prelude::*;

use crate::measure::{SceneError, positive};

/// Parameters of a wheel on a floor.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WheelParams {
    /// Wheel radius \[m\].
    pub radius: f64,
    /// Wheel width (cylinder length) \[m\].
    pub width: f64,
    /// Crown radius \[m\] (`None`: a line contact).
    pub crown: Option<f64>,
    /// Material of the wheel and the floor.
    pub material: Material,
    /// Speed [m/s].
    pub speed: f64,
    /// Time step \[s\].
    pub dt: f64,
    /// Duration \[s\]; measured over the second half.
    pub duration: f64,
}

/// A rubber-like material at a node of the 3-D law's table (`nu = 0.5`): G = 1 MPa,
/// nu = 0.5, mu = 0.9, rho = 1100 kg/m^3.
pub fn wheel_rubber() -> Material {
    Material::new(1.0e6, 0.5, 0.9, 1100.0).unwrap_or_else(|_| Material::rubber())
}

impl Default for WheelParams {
    fn default() -> Self {
        Self {
            radius: 0.05,
            width: 0.04,
            crown: None,
            material: wheel_rubber(),
            speed: 0.1,
            dt: 1.0 / 240.0,
            duration: 1.0,
        }
    }
}

/// The crown radius \[m\] that gives a wheel of radius `radius` an elliptic contact of axis
/// ratio `ab = a/b` (`a` along the rolling direction; `ab < 1`: a crown flatter than the wheel)
/// on a plane: Hertz's ratio depends on the curvature ratio alone (Johnson 1985, eq. 4.39), found
/// by bisection on `ln(R_c)`.
pub fn crown_for_ratio(radius: f64, ab: f64) -> Result<f64, SceneError> {
    positive("radius", radius)?;
    if !(ab > 0.05 && ab < 1.0) {
        return Err(SceneError::Parameter(format!(
            "axis ratio a/b must be in (0.05, 1), got {ab}"
        )));
    }
    let ratio = |rc: f64| -> Result<f64, SceneError> {
        let h = elliptic_hertz(1.0 / radius, 1.0 / rc, 1.0, 1.0e9)?;
        Ok(h.a / h.b)
    };
    let (mut lo, mut hi) = (radius.ln(), (radius * 1e4).ln());
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        // a/b falls as the crown radius grows.
        if ratio(mid.exp())? > ab {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    Ok((0.5 * (lo + hi)).exp())
}

/// Gauss-Seidel iterations per substep of the wheel scenes.
pub const PGS_ITERATIONS: usize = 16;

/// Averages over the measured steps of one run.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct WheelMeasure {
    /// Normal force \[N\].
    pub p: f64,
    /// Tangential force on the wheel along the travel `x` \[N\].
    pub qx: f64,
    /// Tangential force on the wheel across the travel `y = n × x` \[N\].
    pub qy: f64,
    /// Creepage along `x` [-].
    pub xi: f64,
    /// Creepage along `y` [-].
    pub eta: f64,
    /// Mean number of contact points of the pair.
    pub points: f64,
    /// Smallest normal force of one measured step \[N\] (0: a step without contact).
    pub p_min: f64,
    /// Largest normal force of one measured step \[N\] (an impact shows as a multiple of `p`).
    pub p_max: f64,
    /// Largest sideways speed of the wheel's centre (along its axle) of one measured step
    /// \[m/s\].
    pub lateral_speed: f64,
}

fn v3(v: Vector) -> Vec3 {
    Vec3::new(f64::from(v.x), f64::from(v.y), f64::from(v.z))
}

thread_local! {
    /// Contact points counted by the last [`contact_forces`].
    static POINTS: std::cell::Cell<usize> = const { std::cell::Cell::new(0) };
}

/// Normal force and tangential force on `wheel` \[N\] of the last step, from the contact
/// impulses of its pair with `floor`.
pub(crate) fn contact_forces(
    w: &CreepWorld,
    wheel: ColliderHandle,
    floor: ColliderHandle,
    dt: f64,
) -> (f64, Vec3) {
    let Some(pair) = w.physics.narrow_phase.contact_pair(wheel, floor) else {
        return (0.0, Vec3::ZERO);
    };
    let sign = if pair.collider1 == wheel { 1.0 } else { -1.0 };
    let (mut p, mut q) = (0.0, Vec3::ZERO);
    POINTS.with(|c| c.set(0));
    for m in pair.manifolds() {
        POINTS.with(|c| c.set(c.get() + m.points.len()));
        let n = v3(m.data.normal);
        let (t1, t2) = creep_rapier::solver_tangents(n);
        // Only the points the solver used this step (a wheel's manifold is solved as one
        // patch contact; its other points keep no impulse of this step).
        for sc in &m.data.solver_contacts {
            let cid = (sc.contact_id[0] & !NEW_CONTACT_BIT) as usize;
            let Some(pt) = m.points.get(cid) else {
                continue;
            };
            p += f64::from(pt.data.impulse);
            let ti = pt.data.tangent_impulse;
            q += t1 * f64::from(ti.x) + t2 * f64::from(ti.y);
        }
    }
    (p / dt, q * (sign / dt))
}

/// The world of one wheel run: the floor and the wheel (axle along `z`, rolling along `x`; its
/// centre held in `z` with `lock_axial`), with the given fidelity.
struct WheelWorld {
    w: CreepWorld,
    wheel: RigidBodyHandle,
    wheel_co: ColliderHandle,
    floor: RigidBodyHandle,
    floor_co: ColliderHandle,
    /// The chassis of the documented recipe ([`build_on_joint`]).
    chassis: Option<RigidBodyHandle>,
}

fn build(
    params: &WheelParams,
    fidelity: Fidelity,
    lock_axial: bool,
) -> Result<WheelWorld, SceneError> {
    positive("radius", params.radius)?;
    positive("width", params.width)?;
    positive("speed", params.speed)?;
    positive("dt", params.dt)?;
    positive("duration", params.duration)?;
    if let Some(rc) = params.crown {
        positive("crown", rc)?;
    }
    let mut w = CreepWorld::new(
        params.dt as f32,
        CreepSettings::default().with_rapier_solver(),
    )?;
    // One substep (the rotation-gap correction is exact there) with enough Gauss-Seidel
    // iterations for the line contact's two or three coupled friction points (one iteration
    // leaves the Coulomb twin slipping by up to 10 % at 0.9 mu P).
    w.physics.integration_parameters.num_solver_iterations = 1;
    w.physics.integration_parameters.num_internal_pgs_iterations = PGS_ITERATIONS;
    // Rapier's allowed overlap is 1e-3 length units: with 1 m the wheel sinks by ~2 mm, a
    // rolling-radius error (2-4 %) larger than the rubber's creepage; the wheel's radius as the
    // unit leaves ~0.05 mm.
    w.physics.integration_parameters.length_unit = params.radius as f32;
    let mu = params.material.friction() as f32;
    let mat = CreepMaterial::new(params.material).with_fidelity(fidelity);
    let (floor, floor_co) = w.insert(
        RigidBodyBuilder::kinematic_velocity_based().translation(Vector::new(0.0, -0.5, 0.0)),
        ColliderBuilder::cuboid(1.0e3, 0.5, 1.0e3).friction(mu),
        Some(mat),
    );
    let r = params.radius as f32;
    let v = params.speed as f32;
    let (wheel, wheel_co) = w.insert(
        RigidBodyBuilder::dynamic()
            .translation(Vector::new(0.0, r, 0.0))
            .rotation(Vector::new(FRAC_PI_2 as f32, 0.0, 0.0))
            .linvel(Vector::new(v, 0.0, 0.0))
            .angvel(Vector::new(0.0, 0.0, -v / r))
            // No yaw (the heading is held). The wheel's contact is one point at its patch
            // (creep-rapier's wheel module), so a wheel free to slide along its axle is also
            // held upright (like a vehicle's axle); with the axle's translation locked the tilt
            // stays free (locking both would leave the lateral friction row no mobility: the
            // 2x2 friction solve against the fixed floor would be singular).
            .enabled_rotations(lock_axial, false, true)
            .enabled_translations(true, true, !lock_axial)
            .can_sleep(false),
        ColliderBuilder::cylinder(0.5 * params.width as f32, r).friction(mu),
        Some(mat),
    );
    w.hooks.set_wheel_crown(wheel_co, params.crown)?;
    Ok(WheelWorld {
        w,
        wheel,
        wheel_co,
        floor,
        floor_co,
        chassis: None,
    })
}

/// Steps a wheel world and averages the contact's forces and creepages over the second half
/// (wheel = body p, floor = q, `n = -y`; the frame of `creep_law::rigid`).
fn measure(ww: &mut WheelWorld, params: &WheelParams) -> Result<WheelMeasure, SceneError> {
    let steps = (params.duration / params.dt).round() as usize;
    let mut sum = WheelMeasure::default();
    let mut count = 0.0;
    let (mut p_min, mut p_max) = (f64::INFINITY, 0.0f64);
    let mut lateral = 0.0f64;
    let n = Vec3::new(0.0, -1.0, 0.0);
    for i in 0..steps {
        ww.w.step()?;
        if i < steps / 2 {
            continue;
        }
        let (p, q) = contact_forces(&ww.w, ww.wheel_co, ww.floor_co, params.dt);
        let rb = &ww.w.physics.bodies[ww.wheel];
        let fl = &ww.w.physics.bodies[ww.floor];
        let (v, om) = (v3(rb.linvel()), v3(rb.angvel()));
        let centre = v3(rb.translation());
        let contact = Vec3::new(centre.x, 0.0, centre.z);
        let u_wheel = v + om.cross(contact - centre);
        let u_floor = v3(fl.linvel());
        let v_disp = (u_floor - u_wheel).reject(n);
        let v_roll = ((u_floor + u_wheel) * 0.5 - v).reject(n);
        // x along the heading (the wheel's axle stays along z), with the rolling.
        let x = if v_roll.x > 0.0 {
            Vec3::new(-1.0, 0.0, 0.0)
        } else {
            Vec3::new(1.0, 0.0, 0.0)
        };
        let y = n.cross(x);
        let speed = v_roll.dot(x).abs();
        sum.p += p;
        p_min = p_min.min(p);
        p_max = p_max.max(p);
        lateral = lateral.max(v.z.abs());
        sum.qx += q.dot(x);
        sum.qy += q.dot(y);
        sum.xi += v_disp.dot(x) / speed;
        sum.eta += v_disp.dot(y) / speed;
        sum.points += POINTS.with(|c| c.get()) as f64;
        count += 1.0;
    }
    let k = 1.0 / count;
    Ok(WheelMeasure {
        p: sum.p * k,
        qx: sum.qx * k,
        qy: sum.qy * k,
        xi: sum.xi * k,
        eta: sum.eta * k,
        points: sum.points * k,
        p_min,
        p_max,
        lateral_speed: lateral,
    })
}

/// The documented wheel recipe (creep-rapier's crate docs, "Wheels"): a world from
/// `CreepWorld::new` with default settings and nothing else, a fixed floor, and the wheel, a
/// cylinder collider turned so that its axis (Rapier's local `y`) lies along its body's `z`,
/// on its own dynamic body, held by a revolute joint about `z` (contacts between the two
/// disabled) to a chassis body; the chassis' rotations are locked, standing for the rest of a
/// vehicle that holds its axle level (its other wheels). Nothing else is locked: the wheel
/// may slide along its axle with the chassis. The chassis (a box of the wheel's mass, clear of
/// the floor) and the wheel start at `params.speed`.
fn build_on_joint(params: &WheelParams, fidelity: Fidelity) -> Result<WheelWorld, SceneError> {
    positive("radius", params.radius)?;
    positive("width", params.width)?;
    positive("speed", params.speed)?;
    positive("dt", params.dt)?;
    positive("duration", params.duration)?;
    let mut w = CreepWorld::new(params.dt as f32, CreepSettings::default())?;
    let mu = params.material.friction() as f32;
    let mut mat = CreepMaterial::new(params.material).with_fidelity(fidelity);
    let (floor, floor_co) = w.insert(
        RigidBodyBuilder::fixed().translation(Vector::new(0.0, -0.5, 0.0)),
        ColliderBuilder::cuboid(1.0e3, 0.5, 1.0e3).friction(mu),
        Some(mat),
    );
    if let Some(rc) = params.crown {
        mat = mat.with_crown(rc);
    }
    let r = params.radius as f32;
    let v = params.speed as f32;
    let (wheel, wheel_co) = w.insert(
        RigidBodyBuilder::dynamic()
            .translation(Vector::new(0.0, r, 0.0))
            .linvel(Vector::new(v, 0.0, 0.0))
            .angvel(Vector::new(0.0, 0.0, -v / r)),
        // Rapier's cylinder has its axis along local y: turned onto the body's z.
        ColliderBuilder::cylinder(0.5 * params.width as f32, r)
            .rotation(Vector::new(FRAC_PI_2 as f32, 0.0, 0.0))
            .friction(mu),
        Some(mat),
    );
    let wheel_mass = f64::from(w.physics.bodies[wheel].mass());
    let (hx, hy, hz) = (0.5 * r, 0.3 * r, 0.3 * r);
    let volume = 8.0 * f64::from(hx * hy * hz);
    let (chassis, _) = w.insert(
        RigidBodyBuilder::dynamic()
            .translation(Vector::new(0.0, r, 0.0))
            .linvel(Vector::new(v, 0.0, 0.0))
            .lock_rotations(),
        ColliderBuilder::cuboid(hx, hy, hz).density((wheel_mass / volume) as f32),
        None,
    );
    let joint = RevoluteJointBuilder::new(Vector::Z).contacts_enabled(false);
    w.physics.impulse_joints.insert(chassis, wheel, joint, true);
    Ok(WheelWorld {
        w,
        wheel,
        wheel_co,
        floor,
        floor_co,
        chassis: Some(chassis),
    })
}

/// [`driven`] with the wheel of the documented recipe (creep-rapier's crate docs, "Wheels": a
/// cylinder on its own body, a revolute joint to a chassis whose rotations are locked, the
/// plugin's defaults and nothing else): the drive
/// torque `T = share mu (m_w + m_c) g R` on the wheel, the holding force `T/R` on the chassis.
pub fn driven_on_joint(params: &WheelParams, share: f64) -> Result<DrivenRow, SceneError> {
    if !(share.is_finite() && (0.0..1.0).contains(&share)) {
        return Err(SceneError::Parameter(format!(
            "share must be in [0, 1), got {share}"
        )));
    }
    let run = |fidelity| -> Result<WheelMeasure, SceneError> {
        let mut ww = build_on_joint(params, fidelity)?;
        let chassis = ww.chassis.unwrap_or(ww.wheel);
        let m = f64::from(ww.w.physics.bodies[ww.wheel].mass())
            + f64::from(ww.w.physics.bodies[chassis].mass());
        let t = share * params.material.friction() * m * crate::incline::G * params.radius;
        ww.w.physics.bodies[ww.wheel].add_torque(Vector::new(0.0, 0.0, -t as f32), true);
        ww.w.physics.bodies[chassis]
            .add_force(Vector::new((-t / params.radius) as f32, 0.0, 0.0), true);
        measure(&mut ww, params)
    };
    Ok(DrivenRow {
        share,
        creep: run(Fidelity::Creep)?,
        coulomb: run(Fidelity::Coulomb)?,
    })
}

/// One driven-wheel run pair (creep and its Coulomb twin).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DrivenRow {
    /// Drive torque over `mu m g R` [-].
    pub share: f64,
    /// The creep run.
    pub creep: WheelMeasure,
    /// The Coulomb twin.
    pub coulomb: WheelMeasure,
}

impl DrivenRow {
    /// The creep run's traction over `mu P` [-].
    pub fn force_ratio(&self, mu: f64) -> f64 {
        self.creep.qx / (mu * self.creep.p)
    }
    /// The creepage of creep, the creep run's less the twin's [-].
    pub fn creepage(&self) -> f64 {
        self.creep.xi - self.coulomb.xi
    }
}

/// A wheel rolling at `params.speed` along `x` on a fixed floor, driven by the torque
/// `T = share mu m g R` and held back at the axle by `T/R` (module docs), with its Coulomb twin.
pub fn driven(params: &WheelParams, share: f64) -> Result<DrivenRow, SceneError> {
    if !(share.is_finite() && (0.0..1.0).contains(&share)) {
        return Err(SceneError::Parameter(format!(
            "share must be in [0, 1), got {share}"
        )));
    }
    let run = |fidelity| -> Result<WheelMeasure, SceneError> {
        let mut ww = build(params, fidelity, true)?;
        let rb = &mut ww.w.physics.bodies[ww.wheel];
        let m = f64::from(rb.mass());
        let t = share * params.material.friction() * m * crate::incline::G * params.radius;
        rb.add_torque(Vector::new(0.0, 0.0, -t as f32), true);
        rb.add_force(Vector::new((-t / params.radius) as f32, 0.0, 0.0), true);
        measure(&mut ww, params)
    };
    Ok(DrivenRow {
        share,
        creep: run(Fidelity::Creep)?,
        coulomb: run(Fidelity::Coulomb)?,
    })
}

/// A wheel rolling at `params.speed` along `x` on a fixed floor and pushed sideways at its axle
/// by the force `share mu m g` along the axle: it settles at the lateral creepage (slip angle
/// `atan(eta)`) whose lateral force balances the push, or, beyond `share = 1`, slides sideways
/// with the floor's force at `mu P` (module docs).
pub fn lateral(params: &WheelParams, share: f64) -> Result<WheelMeasure, SceneError> {
    if !(share.is_finite() && share >= 0.0) {
        return Err(SceneError::Parameter(format!(
            "share must be finite and >= 0, got {share}"
        )));
    }
    let mut ww = build(params, Fidelity::Creep, false)?;
    let rb = &mut ww.w.physics.bodies[ww.wheel];
    let m = f64::from(rb.mass());
    let f = share * params.material.friction() * m * crate::incline::G;
    // The push acts at the contact's height (a force at the centre and its moment about it),
    // so that it does not tip the wheel over its line contact.
    rb.add_force(Vector::new(0.0, 0.0, f as f32), true);
    rb.add_torque(Vector::new((-params.radius * f) as f32, 0.0, 0.0), true);
    measure(&mut ww, params)
}

/// The elliptic Hertz contact of a crowned wheel on the floor at the normal force `p` \[N\]:
/// `(a, b)` \[m\] (Johnson 1985, §4.2).
pub fn crowned_contact(params: &WheelParams, p: f64) -> Result<(f64, f64), SceneError> {
    let rc = params
        .crown
        .ok_or_else(|| SceneError::Parameter("crowned_contact needs a crown radius".to_string()))?;
    let pair = wheel_on_floor(params)?;
    let h = elliptic_hertz(1.0 / params.radius, 1.0 / rc, p, pair.e_star)?;
    Ok((h.a, h.b))
}

/// The pair's combined shear modulus and contact modulus `(G, E*)` \[Pa\].
pub fn moduli(params: &WheelParams) -> Result<(f64, f64), SceneError> {
    let pair = wheel_on_floor(params)?;
    Ok((pair.g, pair.e_star))
}

/// The wheel's material against the floor's (the same), the wheel's rolling radius against a plane.
fn wheel_on_floor(params: &WheelParams) -> Result<PairMaterial, SceneError> {
    Ok(PairMaterial::new(
        &params.material,
        &params.material,
        Surface::Sphere(params.radius),
        Surface::Plane,
    )?)
}

/// The closed form a driven-wheel row is measured against, as `Q/(mu P)` at the row's
/// creepage (the creep run's less its Coulomb twin's): Carter's `1 - (1 - xi/(mu a/R))^2`
/// (Carter 1926; creep-reference `carter`) for a line contact; for a crowned wheel, Kalker's
/// exact theory (creep-reference's boundary elements, `steady3d::table`, linear between its
/// points), which is tabulated at `a/b = 1, 0.5, 0.2` and `nu = 0, 0.25, 0.5` only (another
/// shape or material is [`SceneError::Parameter`]).
pub fn reference_force_ratio(params: &WheelParams, row: &DrivenRow) -> Result<f64, SceneError> {
    let (g, e_star) = moduli(params)?;
    let mu = params.material.friction();
    let p = row.creep.p;
    let xi = row.creepage();
    let refer = |e: creep_reference::RefError| SceneError::Parameter(e.to_string());
    if params.crown.is_none() {
        let carter =
            creep_reference::carter::Carter::from_load(p / params.width, params.radius, e_star, mu)
                .map_err(refer)?;
        return carter.force_ratio(xi).map_err(refer);
    }
    let (a, b) = crowned_contact(params, p)?;
    let nu = params.material.poisson_ratio();
    let xi_n = xi.abs() * g * a * b / (mu * p);
    let table = creep_reference::steady3d::table().map_err(refer)?;
    let mut pts: Vec<(f64, f64)> = table
        .iter()
        .filter(|q| {
            q.kind == creep_reference::steady3d::Kind::Longitudinal
                && (q.ab - a / b).abs() < 1e-6
                && (q.nu - nu).abs() < 1e-12
        })
        .map(|q| (q.creepage[0], q.load[0]))
        .collect();
    if pts.is_empty() {
        return Err(SceneError::Parameter(format!(
            "no boundary-element table at a/b = {:.4}, nu = {nu} (nodes: a/b 1, 0.5, 0.2; nu 0, 0.25, 0.5)",
            a / b
        )));
    }
    pts.insert(0, (0.0, 0.0));
    pts.sort_by(|x, y| x.0.total_cmp(&y.0));
    for w in pts.windows(2) {
        if xi_n <= w[1].0 {
            let t = (xi_n - w[0].0) / (w[1].0 - w[0].0);
            return Ok((w[0].1 + t * (w[1].1 - w[0].1)).copysign(xi));
        }
    }
    Ok(pts[pts.len() - 1].1.copysign(xi))
}
