//! The case catalogue ([`HardCase`]), what a case measured ([`Outcome`]), and the column,
//! drift and at-rest scenes.

use creep_law::Material;
use creep_rapier::{CreepMaterial, CreepSettings, CreepWorld, Fidelity};
use rapier3d::prelude::*;

use super::*;
use crate::measure::SceneError;

/// One case of the matrix.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum HardCase {
    /// A 0.1 m steel ball on steel, mu = 0.5, theta = 20 deg (Q/(mu P) = 0.208), dt = 1/30 s,
    /// from rest 1 m up the V (max speed 2.2 m/s, 0.7 rad per step).
    LongStep,
    /// Rubber near the friction limit (Q/(mu P) = 0.8) at 1/240 s (4 substeps): the step at
    /// which Rapier's own Coulomb run holds this contact (its slip per rolled distance 2.9e-3,
    /// against a creepage of ~5e-2).
    Rubber240,
    /// The same at 1/60 s: an engine limit ([`HardCase::engine_limit`]).
    Rubber60,
    /// A 32.9 g ball (the steel ball's size and elastic constants, density 7.85 kg/m^3) rolls
    /// on a free 32.9 kg slab (mass ratio 1:1000) resting on the fixed floor; slip is measured
    /// relative to the slab, energy of the ball only (the heavy slab is the ground: its f32
    /// state's energy rounding alone is ~1e-5 of the ball's E0).
    LightBallHeavySlab,
    /// The 32.9 kg steel ball rolls on a free 32.9 g slab that rests on the fixed floor: the
    /// ball's friction force goes through the light slab. An engine limit.
    HeavyBallLightSlab,
    /// The steel ball set down at the V's bottom with 100 rad/s of topspin (surface speed
    /// 10 m/s, 1.7 rad per 1/60 s step): it slides at the Coulomb limit until it rolls (about
    /// 1 s; the V's force pulls it back meanwhile), then oscillates rolling in the V, its
    /// energy decaying at each crossing of the bottom (the engine's loss) until it rests at the
    /// bottom. The creep is measured from step 60 (1 s) on, while the ball's amplitude is at
    /// least 0.1 m: below it the force reverses every few steps (half period 2 sqrt(2 A / a),
    /// 0.6 s at 0.1 m, 3 steps at 1 mm), which no step-lagged law follows and which Kalker's
    /// steady creepage does not describe (over the whole run, rest included: 0.71).
    Spin,
    /// Ten 5 cm steel balls stacked in a vertical column on the fixed floor, translations
    /// locked in x and z (a free column of spheres is unstable), rotations free, each spinning
    /// at up to 30 rad/s about a horizontal axis: the spins slide against each other and the
    /// floor, every contact carries both rolling and a tangential force, and friction brings the
    /// column to rest (no external work: gravity only). Then it must stay at rest: centre
    /// motion and surface motion `R * angle` over 2,000 further steps below 1e-6 m or twice
    /// plain Rapier's own drift of the same column.
    Column,
    /// A 0.1 m steel ball at rest on a steel plane (mu = 0.5), 1/60 s, creep fidelity: after
    /// 120 steps to settle, it must not creep away over 10^4 steps (< 1e-6 m).
    AtRest,
}

impl HardCase {
    /// The matrix, in table order.
    pub const ALL: [HardCase; 8] = [
        HardCase::LongStep,
        HardCase::Rubber240,
        HardCase::Rubber60,
        HardCase::LightBallHeavySlab,
        HardCase::HeavyBallLightSlab,
        HardCase::Spin,
        HardCase::Column,
        HardCase::AtRest,
    ];

    /// A short label (also the prefix of its lines).
    pub fn label(self) -> &'static str {
        match self {
            HardCase::LongStep => "dt 1/30",
            HardCase::Rubber240 => "rubber 1/240",
            HardCase::Rubber60 => "rubber 1/60",
            HardCase::LightBallHeavySlab => "mass ratio 1:1000",
            HardCase::HeavyBallLightSlab => "mass ratio 1000:1",
            HardCase::Spin => "spin 100 rad/s",
            HardCase::Column => "column of 10",
            HardCase::AtRest => "at rest",
        }
    }

    /// What the case is, for a table.
    pub fn description(self) -> &'static str {
        match self {
            HardCase::LongStep => "steel ball in a V-incline, Q/(mu P) = 0.21",
            HardCase::Rubber240 | HardCase::Rubber60 => {
                "rubber (G = 1 MPa) at Q/(mu P) = 0.8, creepage 5e-2"
            }
            HardCase::LightBallHeavySlab => "light ball on a 1000x heavier free slab",
            HardCase::HeavyBallLightSlab => "heavy ball on a 1000x lighter free slab",
            HardCase::Spin => "100 rad/s topspin, then rolling",
            HardCase::Column => "column of 10 spinning spheres",
            HardCase::AtRest => "sphere at rest on a plane",
        }
    }

    /// The time step \[s\].
    pub fn dt(self) -> f64 {
        match self {
            HardCase::LongStep => 1.0 / 30.0,
            HardCase::Rubber240 => 1.0 / 240.0,
            _ => 1.0 / 60.0,
        }
    }

    /// Why the case is beyond the engine (it fails, and the test is ignored), if it is.
    pub fn engine_limit(self) -> Option<&'static str> {
        match self {
            HardCase::Rubber60 => Some(
                "engine limit: at 1/60 s Rapier's own Coulomb run already slips on this contact \
                 (10 % of the rolled distance on the plain incline, `creep run incline \
                 --material rubber --theta-deg 68.4 --dt 0.0166667`), so run against run the \
                 creep run's energy is not held below plain Rapier's (8.3e-3 of E0 above it; \
                 one substep: 1.1e-2; at 1/120 s still 2.1e-3, one substep 3.1e-3); 1/240 s \
                 passes",
            ),
            HardCase::HeavyBallLightSlab => Some(
                "engine limit: Rapier's Gauss-Seidel does not converge for a 32.9 kg ball on a \
                 32.9 g slab on the floor: the slab takes up the slip target (creep realised \
                 0.02 of Kalker's even at 16 substeps; at 1/240 s and 1/960 s the energy \
                 bounds hold but creep is 0.064 and 0.088 of Kalker's; one substep at 1/60 s: \
                 -0.008, and 1.5e-3 of E0 net); |Q| <= mu P and finiteness hold",
            ),
            _ => None,
        }
    }

    /// Runs the case ([`STEPS`] steps per run).
    pub fn run(self) -> Result<Outcome, SceneError> {
        self.run_steps(STEPS)
    }

    /// Runs the case with `steps` steps per run (the matrix's verdicts are calibrated at
    /// [`STEPS`]).
    pub fn run_steps(self, steps: usize) -> Result<Outcome, SceneError> {
        if steps == 0 {
            return Err(SceneError::Parameter("steps must be at least 1".into()));
        }
        let label = self.label();
        match self {
            HardCase::LongStep => Vee {
                dt: 1.0 / 30.0,
                ..steel_vee()
            }
            .case(label, steps, 0),
            HardCase::Rubber240 => rubber_vee(1.0 / 240.0).case(label, steps, 0),
            HardCase::Rubber60 => rubber_vee(1.0 / 60.0).case(label, steps, 0),
            HardCase::LightBallHeavySlab => Vee {
                slab: Some(steel_ball_mass()),
                ball_density: Some(7.85),
                count_slab: false,
                ..steel_vee()
            }
            .case(label, steps, 0),
            HardCase::HeavyBallLightSlab => Vee {
                slab: Some(steel_ball_mass() / 1000.0),
                ..steel_vee()
            }
            .case(label, steps, 0),
            HardCase::Spin => {
                let mut o = Vee {
                    x_start: 0.0,
                    w0: Vector::new(0.0, 0.0, -100.0),
                    min_amplitude: 0.1,
                    ..steel_vee()
                }
                .case(label, steps, 60)?;
                // The spin set it moving, and the speed stays bounded by the spin's energy.
                let v = o.creep.max_speed;
                o.verdicts.push(Verdict::new(
                    "max speed [m/s], set moving by the spin",
                    v,
                    Bound::Above(0.5),
                ));
                o.verdicts.push(Verdict::new(
                    "max speed [m/s], bounded by the spin's energy",
                    v,
                    Bound::Below(10.0),
                ));
                Ok(o)
            }
            HardCase::Column => column(label, steps),
            HardCase::AtRest => at_rest(steps),
        }
    }
}

/// What a case measured and how it was judged.
#[derive(Debug, Clone)]
pub struct Outcome {
    /// The creep increment over Kalker's prediction (V-incline cases; judged as [`Check`]
    /// says).
    pub creep_ratio: Option<f64>,
    /// The creep run.
    pub creep: Trace,
    /// The Coulomb run.
    pub coulomb: Trace,
    /// Every check, in order.
    pub verdicts: Vec<Verdict>,
    /// The numbers, as lines of text (what the test prints).
    pub lines: Vec<String>,
}

impl Outcome {
    /// Whether every verdict passed.
    pub fn passed(&self) -> bool {
        self.verdicts.iter().all(Verdict::passed)
    }

    /// The verdicts that failed.
    pub fn failures(&self) -> impl Iterator<Item = &Verdict> {
        self.verdicts.iter().filter(|v| !v.passed())
    }

    /// The verdict closest to (or furthest beyond) its bound, by [`Verdict::relative_margin`]
    /// (among the failures if any fail). Of a passing case only the verdicts with room to
    /// measure count: the creep against Kalker's, the energy, the drift at rest and the speed
    /// bounds; not the bookkeeping (finite state, same scene, creep engaged) nor the friction
    /// cone, which a sliding contact reaches by construction (Rapier clamps at `mu P`, so its
    /// margin there is the rounding allowance).
    pub fn tightest(&self) -> Option<&Verdict> {
        const MEASURED: [&str; 4] = ["creep /", "energy", "drift", "max speed"];
        let candidates: Vec<&Verdict> = if self.passed() {
            self.verdicts
                .iter()
                .filter(|v| MEASURED.iter().any(|p| v.name.starts_with(p)))
                .collect()
        } else {
            self.failures().collect()
        };
        candidates
            .into_iter()
            .min_by(|a, b| a.relative_margin().total_cmp(&b.relative_margin()))
    }

    /// The verdict named `prefix...`, if any.
    pub fn verdict(&self, prefix: &str) -> Option<&Verdict> {
        self.verdicts.iter().find(|v| v.name.starts_with(prefix))
    }
}

/// The column case ([`HardCase::Column`]).
pub(super) fn column(label: &str, steps: usize) -> Result<Outcome, SceneError> {
    let build = |fidelity: Fidelity| -> Result<Scene, SceneError> {
        let mut w = CreepWorld::new(1.0 / 60.0, CreepSettings::default().with_rapier_solver())?;
        let mat = CreepMaterial::new(Material::steel()).with_fidelity(fidelity);
        w.insert(
            RigidBodyBuilder::fixed().translation(Vector::new(0.0, -0.5, 0.0)),
            ColliderBuilder::cuboid(10.0, 0.5, 10.0).friction(0.5),
            Some(mat),
        );
        let r = 0.05;
        let mut dynamic = vec![];
        for i in 0..10 {
            let k = i as f32;
            let spin = Vector::new((1.7 * k).sin(), 0.0, (2.3 * k + 0.5).cos()) * 30.0;
            let (b, _) = w.insert(
                RigidBodyBuilder::dynamic()
                    .translation(Vector::new(0.0, r + 2.0 * r * k, 0.0))
                    .enabled_translations(false, true, false)
                    .angvel(spin)
                    .can_sleep(false),
                ColliderBuilder::ball(r).density(7850.0).friction(0.5),
                Some(mat),
            );
            dynamic.push(b);
        }
        Ok(Scene {
            w,
            dynamic,
            vee: None,
            f_ss: None,
            support: None,
            radius: f64::from(r),
            min_amplitude: 0.0,
        })
    };
    let (tc, mut sc) = run(build(Fidelity::Coulomb)?, steps, 0)?;
    let (tk, mut sk) = run(build(Fidelity::Creep)?, steps, 0)?;
    let mut lines = Vec::new();
    let mut verdicts = common_verdicts(label, &tk, &tc, Check::Paired, &mut lines);
    // Settled: it has come to rest, and stays there without creeping drift (the issue's
    // at-rest criterion, 1e-6 m, for the column: centre motion and surface motion R * angle
    // over 2,000 further steps), compared with plain Rapier's own drift of the same column.
    let (drift, drift_c) = (drift(&mut sk, 2000)?, drift(&mut sc, 2000)?);
    let e_end = |t: &Trace| t.energy.last().copied().unwrap_or(f64::NAN) / t.e0;
    lines.push(format!(
        "{label}: E_end/E0 creep {:.3e}, coulomb {:.3e}; drift over 2000 further steps: creep {drift:.3e} m, coulomb {drift_c:.3e} m",
        e_end(&tk),
        e_end(&tc)
    ));
    verdicts.push(Verdict::new(
        "drift at rest over 2,000 steps [m] (limit: 1e-6 m or twice plain Rapier's)",
        drift,
        Bound::Below(1e-6_f64.max(2.0 * drift_c)),
    ));
    Ok(Outcome {
        creep_ratio: None,
        creep: tk,
        coulomb: tc,
        verdicts,
        lines,
    })
}

/// The largest motion of the scene's dynamic bodies over `steps` further steps: centre motion
/// and surface motion `R * angle` \[m\].
pub(super) fn drift(sk: &mut Scene, steps: usize) -> Result<f64, SceneError> {
    let snap = |sk: &Scene| -> Vec<(Vector, Rotation)> {
        sk.dynamic
            .iter()
            .map(|&b| {
                let rb = &sk.w.physics.bodies[b];
                (rb.translation(), *rb.rotation())
            })
            .collect()
    };
    let before = snap(sk);
    for _ in 0..steps {
        sk.w.step()?;
    }
    let mut d = 0f64;
    for ((x0, q0), (x1, q1)) in before.iter().zip(snap(sk)) {
        let turn = f((q1 * q0.inverse()).to_scaled_axis().length()) * sk.radius;
        d = d.max(f((x1 - *x0).length())).max(turn);
    }
    // A NaN must not pass as "no drift".
    Ok(if d.is_finite() { d } else { f64::INFINITY })
}

/// The at-rest case ([`HardCase::AtRest`]): the centre's displacement over `steps` steps after
/// 120 settling steps (creep fidelity; no Coulomb run is needed: it must not move at all).
pub(super) fn at_rest(steps: usize) -> Result<Outcome, SceneError> {
    // The incline scene's world, flat: a 0.1 m steel ball (mu = 0.5) on a steel plane.
    let p = crate::incline::InclineParams {
        theta: 0.0,
        dt: 1.0 / 60.0,
        ..Default::default()
    };
    let steel = CreepMaterial::new(p.material).with_fidelity(Fidelity::Creep);
    let (mut w, ball) = crate::incline::world(&p, Some(steel))?;
    for _ in 0..120 {
        w.step()?;
    }
    let x0 = w.physics.bodies[ball].translation();
    for _ in 0..steps {
        w.step()?;
    }
    let d = f((w.physics.bodies[ball].translation() - x0).length());
    let d = if d.is_finite() { d } else { f64::INFINITY };
    let label = HardCase::AtRest.label();
    Ok(Outcome {
        creep_ratio: None,
        creep: Trace::default(),
        coulomb: Trace::default(),
        verdicts: vec![Verdict::new(
            format!("drift at rest over {steps} steps [m]"),
            d,
            Bound::Below(1e-6),
        )],
        lines: vec![format!("{label}: drift over {steps} steps {d:.3e} m")],
    })
}
