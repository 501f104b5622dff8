//! A ball rolling on a plane while it spins about the normal: the spin creep moment of the rigid
//! regime (`creep_law::rigid`, through creep-rapier) makes the spin decay.
//!
//! # Closed form (Kalker's linear theory, Kalker 1967; Kalker 1990, §1.2 and Table E.3)
//!
//! Ball of radius `R`, mass `m`, rolling at speed `V` along `x` with spin `w_n` about the
//! vertical. Spin creepage `phi = w_n / V` \[1/m\] (its sign as the frame of `creep_law::rigid`
//! sets it). Linear theory (project signs, normalised with `c = a`, Hertz's radius at
//! `P = m g`): `Fy = G a^2 C22 eta + G a^3 C23 phi`, `Mz = -G a^3 C23 eta + G a^4 C33 phi`. The
//! ball is free: any lateral force would change its velocity until the lateral creepage
//! cancels it within a few steps (the contact's time constant `m_t V / (G a^2 C22)` is far
//! below a step), so quasi-statically `Fy = 0`, `eta = -(C23/C22) a phi`, and the twisting
//! moment is `Mz = G a^4 (C33 + C23^2/C22) phi`. With the ball's moment of inertia about the
//! vertical `I = (2/5) m R^2`:
//!
//! `dw_n/dt = -lambda w_n`, `lambda = G a^4 (C33 + C23^2/C22) / (I V)`,
//!
//! an exponential decay at small spin (the non-linear law departs from it by about
//! `phi_n = phi G a^3/(mu P)` relatively). A Coulomb run of the same scene keeps its spin
//! (Rapier's single contact point transmits no moment about the normal).

use creep_law::{Material, PairMaterial, Surface, hertz, kalker3d};
use creep_rapier::{CreepMaterial, CreepSettings, CreepWorld, Fidelity};
use rapier3d::prelude::*;

use crate::incline::G;
use crate::measure::{SceneError, positive};

/// Parameters of the spinning ball.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SpinParams {
    /// Ball radius \[m\].
    pub radius: f64,
    /// Material of the ball and the floor.
    pub material: Material,
    /// Rolling speed at launch [m/s].
    pub speed: f64,
    /// Spin about the vertical at launch [rad/s].
    pub spin: f64,
    /// Time step \[s\].
    pub dt: f64,
    /// Duration \[s\].
    pub duration: f64,
}

impl Default for SpinParams {
    fn default() -> Self {
        Self {
            radius: 0.05,
            material: Material::rubber(),
            speed: 1.0,
            spin: 0.15,
            dt: 1.0 / 240.0,
            duration: 1.0,
        }
    }
}

/// The closed form of the module documentation at one speed.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SpinTheory {
    /// Hertz's contact radius at `P = m g` \[m\].
    pub a: f64,
    /// Kalker's `C22`, `C23`, `C33` at `a/b = 1` and the pair's `nu` (table, interpolated).
    pub c22: f64,
    /// See `c22`.
    pub c23: f64,
    /// See `c22`.
    pub c33: f64,
    /// Decay rate `lambda` [1/s] at the launch speed.
    pub decay_rate: f64,
    /// Lateral creepage per spin creepage, `eta/phi = -(C23/C22) a` \[m\].
    pub eta_per_phi: f64,
    /// Normalised spin creepage `phi_n` at launch [-].
    pub phi_n: f64,
}

impl SpinParams {
    /// Mass of the ball \[kg\].
    pub fn mass(&self) -> f64 {
        crate::measure::sphere_mass(self.material.density(), self.radius)
    }

    /// The linear theory of the module documentation.
    pub fn theory(&self) -> Result<SpinTheory, SceneError> {
        let pair = PairMaterial::new(
            &self.material,
            &self.material,
            Surface::Sphere(self.radius),
            Surface::Plane,
        )?;
        let m = self.mass();
        let p = m * G;
        let a = hertz::contact_radius(&pair, p);
        let k = kalker3d::coefficients(1.0, pair.nu.clamp(0.0, 0.5))?;
        let inertia = 0.4 * m * self.radius * self.radius;
        let c_eff = k.c33 + k.c23 * k.c23 / k.c22;
        Ok(SpinTheory {
            a,
            c22: k.c22,
            c23: k.c23,
            c33: k.c33,
            decay_rate: pair.g * a.powi(4) * c_eff / (inertia * self.speed),
            eta_per_phi: -k.c23 / k.c22 * a,
            phi_n: self.spin / self.speed * pair.g * a.powi(3) / (self.material.friction() * p),
        })
    }
}

/// One run of the spinning ball.
#[derive(Debug, Clone, PartialEq)]
pub struct SpinRun {
    /// Times of the samples \[s\].
    pub t: Vec<f64>,
    /// Spin about the vertical [rad/s].
    pub spin: Vec<f64>,
    /// Rolling speed `|v|` [m/s].
    pub speed: Vec<f64>,
    /// Lateral creepage `eta` of each sample in the frame of `creep_law::rigid` (ball = p,
    /// floor = q): the slip of the floor's surface relative to the ball's across the travel,
    /// over the speed [-].
    pub eta: Vec<f64>,
    /// Spin creepage `phi` of each sample, `w_n/|v|` with the frame's sign \[1/m\].
    pub phi: Vec<f64>,
}

impl SpinRun {
    /// Decay rate [1/s] from a least-squares line through `ln |w_n|` against `t` over the
    /// samples with `t >= t0`, and the mean speed over them [m/s].
    pub fn decay_rate(&self, t0: f64) -> (f64, f64) {
        let (mut n, mut st, mut sy, mut stt, mut sty, mut sv) = (0.0, 0.0, 0.0, 0.0, 0.0, 0.0);
        for i in 0..self.t.len() {
            if self.t[i] < t0 || self.spin[i] == 0.0 {
                continue;
            }
            let (t, y) = (self.t[i], self.spin[i].abs().ln());
            n += 1.0;
            st += t;
            sy += y;
            stt += t * t;
            sty += t * y;
            sv += self.speed[i];
        }
        let slope = (n * sty - st * sy) / (n * stt - st * st);
        (-slope, sv / n)
    }

    /// Median of `eta/phi` over the samples with `t >= t0` \[m\].
    pub fn eta_per_phi(&self, t0: f64) -> f64 {
        let mut v: Vec<f64> = (0..self.t.len())
            .filter(|&i| self.t[i] >= t0 && self.phi[i] != 0.0)
            .map(|i| self.eta[i] / self.phi[i])
            .collect();
        crate::stats::median(&mut v).unwrap_or(f64::NAN)
    }
}

/// Runs the ball with the given fidelity (`Creep` for the plugin, `Coulomb` for the twin).
pub fn run(params: &SpinParams, fidelity: Fidelity) -> Result<SpinRun, SceneError> {
    positive("radius", params.radius)?;
    positive("speed", params.speed)?;
    positive("dt", params.dt)?;
    positive("duration", params.duration)?;
    if !params.spin.is_finite() {
        return Err(SceneError::Parameter(format!(
            "spin must be finite, got {}",
            params.spin
        )));
    }
    let mut w = CreepWorld::new(
        params.dt as f32,
        CreepSettings::default().with_rapier_solver(),
    )?;
    w.physics.integration_parameters.num_solver_iterations = 1;
    let mu = params.material.friction() as f32;
    let mat = CreepMaterial::new(params.material).with_fidelity(fidelity);
    w.insert(
        RigidBodyBuilder::fixed().translation(Vector::new(0.0, -0.5, 0.0)),
        ColliderBuilder::cuboid(1.0e3, 0.5, 1.0e3).friction(mu),
        Some(mat),
    );
    let r = params.radius;
    let v = params.speed;
    let (ball, _) = w.insert(
        RigidBodyBuilder::dynamic()
            .translation(Vector::new(0.0, r as f32, 0.0))
            .linvel(Vector::new(v as f32, 0.0, 0.0))
            .angvel(Vector::new(0.0, params.spin as f32, (-v / r) as f32))
            .can_sleep(false),
        ColliderBuilder::ball(r as f32).friction(mu),
        Some(mat),
    );
    let steps = (params.duration / params.dt).round() as usize;
    let mut out = SpinRun {
        t: Vec::with_capacity(steps),
        spin: Vec::with_capacity(steps),
        speed: Vec::with_capacity(steps),
        eta: Vec::with_capacity(steps),
        phi: Vec::with_capacity(steps),
    };
    let n = creep_law::Vec3::new(0.0, -1.0, 0.0);
    for i in 0..steps {
        w.step()?;
        let rb = &w.physics.bodies[ball];
        let lv = rb.linvel();
        let av = rb.angvel();
        let vel = creep_law::Vec3::new(f64::from(lv.x), 0.0, f64::from(lv.z));
        let om = creep_law::Vec3::new(f64::from(av.x), f64::from(av.y), f64::from(av.z));
        let speed = vel.length();
        // Ball = p, floor = q, n from p to q; the frame of creep_law::rigid: x along the travel (the
        // contact moves with the ball), y = n x x.
        let x = vel
            .try_normalize()
            .unwrap_or(creep_law::Vec3::new(1.0, 0.0, 0.0));
        let y = n.cross(x);
        let u_ball = vel + om.cross(n * r);
        let v_disp = -u_ball;
        out.t.push((i + 1) as f64 * params.dt);
        out.spin.push(om.y);
        out.speed.push(speed);
        out.eta.push(v_disp.dot(y) / speed);
        // phi = (w_q - w_p) . n / V = (-w) . (-Y) / V.
        out.phi.push(om.y / speed);
    }
    Ok(out)
}

/// A ball rolling at `params.speed` along `x` on the floor and pushed sideways by the force
/// `share mu m g` along `z` acting at the contact's height (a force at the centre and its
/// moment about it: the ball's spin stays as it is). It settles at the lateral creepage whose
/// force balances the push (linear theory: `Fy = G a^2 C22 eta`, Kalker 1967), or beyond
/// `share = 1` slides sideways with the floor's force at `mu P`. Forces and creepage in the
/// frame of `creep_law::rigid` (ball = p), averaged over the second half of the run.
pub fn lateral_push(params: &SpinParams, share: f64) -> Result<LateralPush, SceneError> {
    positive("radius", params.radius)?;
    positive("speed", params.speed)?;
    positive("dt", params.dt)?;
    positive("duration", params.duration)?;
    if !(share.is_finite() && share >= 0.0) {
        return Err(SceneError::Parameter(format!(
            "share must be finite and >= 0, got {share}"
        )));
    }
    let mut w = CreepWorld::new(
        params.dt as f32,
        CreepSettings::default().with_rapier_solver(),
    )?;
    w.physics.integration_parameters.num_solver_iterations = 1;
    let mu = params.material.friction() as f32;
    let mat = CreepMaterial::new(params.material).with_fidelity(Fidelity::Creep);
    let (_, floor_co) = w.insert(
        RigidBodyBuilder::fixed().translation(Vector::new(0.0, -0.5, 0.0)),
        ColliderBuilder::cuboid(1.0e3, 0.5, 1.0e3).friction(mu),
        Some(mat),
    );
    let r = params.radius;
    let v = params.speed;
    let (ball, ball_co) = w.insert(
        RigidBodyBuilder::dynamic()
            .translation(Vector::new(0.0, r as f32, 0.0))
            .linvel(Vector::new(v as f32, 0.0, 0.0))
            .angvel(Vector::new(0.0, 0.0, (-v / r) as f32))
            .can_sleep(false),
        ColliderBuilder::ball(r as f32).friction(mu),
        Some(mat),
    );
    let rb = &mut w.physics.bodies[ball];
    let f = share * params.material.friction() * f64::from(rb.mass()) * G;
    rb.add_force(Vector::new(0.0, 0.0, f as f32), true);
    rb.add_torque(Vector::new((-r * f) as f32, 0.0, 0.0), true);
    let steps = (params.duration / params.dt).round() as usize;
    let n = creep_law::Vec3::new(0.0, -1.0, 0.0);
    let (mut sp, mut sq, mut sx, mut se, mut count) = (0.0, 0.0, 0.0, 0.0, 0.0);
    for i in 0..steps {
        w.step()?;
        if i < steps / 2 {
            continue;
        }
        let (p, q) = crate::wheels::contact_forces(&w, ball_co, floor_co, params.dt);
        let rb = &w.physics.bodies[ball];
        let (lv, av) = (rb.linvel(), rb.angvel());
        let vel = creep_law::Vec3::new(f64::from(lv.x), f64::from(lv.y), f64::from(lv.z));
        let om = creep_law::Vec3::new(f64::from(av.x), f64::from(av.y), f64::from(av.z));
        let u_ball = vel + om.cross(n * r);
        let v_disp = (-u_ball).reject(n);
        // Kuhn & Bagi's rolling velocity on a fixed plane: the surfaces' mean less the
        // contact point's (under the centre).
        let v_roll = (u_ball * 0.5 - vel).reject(n);
        let x = (-v_roll)
            .try_normalize()
            .unwrap_or(creep_law::Vec3::new(1.0, 0.0, 0.0));
        let y = n.cross(x);
        sp += p;
        sq += q.dot(y);
        sx += q.dot(x);
        se += v_disp.dot(y) / v_roll.length();
        count += 1.0;
    }
    Ok(LateralPush {
        p: sp / count,
        qx: sx / count,
        qy: sq / count,
        eta: se / count,
    })
}

/// The means of [`lateral_push`] over the second half of its run.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LateralPush {
    /// Normal force \[N\].
    pub p: f64,
    /// Tangential force on the ball along the travel `x` \[N\].
    pub qx: f64,
    /// Tangential force on the ball across it, `y = n × x` \[N\].
    pub qy: f64,
    /// Lateral creepage `eta` [-].
    pub eta: f64,
}

/// The spin's decay rate of a creep run [1/s] (fitted over `t >= 0.1 s`) and Kalker's linear
/// rate at the run's mean speed [1/s] (module documentation).
pub fn decay_rates(params: &SpinParams) -> Result<(f64, f64), SceneError> {
    let th = params.theory()?;
    let run = run(params, Fidelity::Creep)?;
    let (rate, speed) = run.decay_rate(0.1);
    Ok((rate, th.decay_rate * params.speed / speed))
}
