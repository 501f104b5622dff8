//! Settled piles of glass spheres in a box, for timing Rapier's step with and without the
//! plugin (the `pile` bench of creep-scenes and the scale section of `creep report` call the
//! same builders and the same interleaved timer).
//!
//! Two layouts, both of 5 cm glass spheres (`Material::glass`, density 2,500 kg/m^3) in a box of
//! fixed cuboid walls, every collider registered with the plugin, sleeping off (a sleeping pile
//! costs nothing, with or without hooks), stepped at 1/60 s:
//! * [`dropped`]: an `n^3` lattice spaced 1.1 diameters, with a small deterministic jitter, that
//!   collapses into a random pile in a 1.8 m x 1.8 m box (400 steps to settle: 17 s for 4,096
//!   spheres on this machine, too long for tens of thousands);
//! * [`stacked`]: a face-centred cubic packing that starts at rest, in contact: layers of
//!   `n x n` spheres touching in a square grid alternate with layers of `(n-1) x (n-1)` sitting
//!   in the hollows of the layer below (`R sqrt(2)` higher), the walls touching the full
//!   layers; each sphere has up to 12 neighbours. It settles in a few tens of steps at any
//!   size, so the scale study reaches 64,000 spheres.
//!
//! The copies are made with [`creep_rapier::clone_physics`]: a plain-Rapier copy ([`plain`])
//! and copies with every collider at one fidelity ([`with_fidelity`]) step from the same state.

use std::time::Instant;

use creep_law::Material;
use creep_rapier::{
    CreepHooks, CreepMaterial, CreepSettings, CreepWorld, Fidelity, MaterialRegistry, clone_physics,
};
use rapier3d::prelude::*;

use crate::measure::SceneError;

/// Sphere radius of the piles \[m\].
pub const RADIUS: f32 = 0.05;

/// Time step of the piles \[s\].
pub const DT: f32 = 1.0 / 60.0;

/// The scale study's piles (`creep report`'s scale section and the `pile` bench): stacked
/// packings of [`SCALE_LAYERS`] layers with `n` spheres per side of the full layers, about 1k,
/// 4k, 16k and 64k spheres ([`stacked_count`]: 1,005, 4,184, 16,301, 64,349). One height for
/// every size, so that the piles settle in the same number of steps and differ only in area.
pub const SCALE_SIDES: [usize; 4] = [11, 22, 43, 85];

/// Layers of the scale study's piles.
pub const SCALE_LAYERS: usize = 9;

/// Settling steps of the scale study's piles: after 40 steps at 1/60 s the fastest sphere of
/// the 1,005-sphere pile moves at 1.8e-3 m/s, below the plugin's activation speed (1e-2 m/s).
pub const SCALE_SETTLE_STEPS: usize = 40;

/// Thickness (half) of the walls \[m\].
const WALL: f32 = 0.1;

/// A settled pile and how it settled.
pub struct Pile {
    /// The world, every collider registered (`Fidelity::Auto`, the default).
    pub world: CreepWorld,
    /// Number of spheres.
    pub spheres: usize,
    /// Steps it was settled for.
    pub settle_steps: usize,
    /// Wall-clock time of the settling \[s\].
    pub settle_seconds: f64,
    /// Largest sphere speed after settling [m/s].
    pub max_speed: f64,
}

impl Pile {
    fn settle(mut world: CreepWorld, spheres: usize, steps: usize) -> Result<Self, SceneError> {
        let t0 = Instant::now();
        for _ in 0..steps {
            world.step()?;
        }
        let max_speed = world
            .physics
            .bodies
            .iter()
            .map(|(_, b)| f64::from(b.linvel().length()))
            .fold(0.0f64, f64::max);
        if !max_speed.is_finite() {
            return Err(SceneError::Parameter(
                "the pile became non-finite while settling".into(),
            ));
        }
        Ok(Pile {
            world,
            spheres,
            settle_steps: steps,
            settle_seconds: t0.elapsed().as_secs_f64(),
            max_speed,
        })
    }
}

/// A box of fixed cuboid walls: a floor whose top is `y = 0` and four walls of height `height`
/// \[m\] whose inner faces are at `|x| = half_x`, `|z| = half_z` \[m\].
fn add_box(w: &mut CreepWorld, mat: CreepMaterial, half_x: f32, half_z: f32, height: f32) {
    w.insert(
        RigidBodyBuilder::fixed().translation(Vector::new(0.0, -WALL, 0.0)),
        ColliderBuilder::cuboid(half_x + 2.0 * WALL, WALL, half_z + 2.0 * WALL),
        Some(mat),
    );
    let h = 0.5 * height;
    for (x, z, hx, hz) in [
        (half_x + WALL, 0.0, WALL, half_z),
        (-half_x - WALL, 0.0, WALL, half_z),
        (0.0, half_z + WALL, half_x, WALL),
        (0.0, -half_z - WALL, half_x, WALL),
    ] {
        w.insert(
            RigidBodyBuilder::fixed().translation(Vector::new(x, h, z)),
            ColliderBuilder::cuboid(hx, h, hz),
            Some(mat),
        );
    }
}

fn add_sphere(w: &mut CreepWorld, mat: CreepMaterial, p: Vector) {
    w.insert(
        RigidBodyBuilder::dynamic().translation(p).can_sleep(false),
        ColliderBuilder::ball(RADIUS).density(2500.0),
        Some(mat),
    );
}

/// The `n^3` dropped pile (module docs), settled for 400 steps.
pub fn dropped(n: usize) -> Result<Pile, SceneError> {
    Pile::settle(dropped_lattice(n)?, n * n * n, 400)
}

/// The `n^3` lattice of [`dropped`] before it falls (every sphere at rest in the air).
pub fn dropped_lattice(n: usize) -> Result<CreepWorld, SceneError> {
    if n == 0 {
        return Err(SceneError::Parameter("n must be at least 1".into()));
    }
    let mut w = CreepWorld::new(DT, CreepSettings::default().with_rapier_solver())?;
    let mat = CreepMaterial::new(Material::glass());
    add_box(&mut w, mat, 0.9, 0.9, 4.0);
    for p in pour_lattice(n) {
        add_sphere(&mut w, mat, p);
    }
    Ok(w)
}

/// The centres of an `n x n x n` lattice of spheres of [`RADIUS`] above the floor, 10 % apart,
/// with a small deterministic jitter so that the lattice collapses into a pile.
fn pour_lattice(n: usize) -> impl Iterator<Item = Vector> {
    let spacing = 2.0 * RADIUS * 1.1;
    let offset = -(n as f32 - 1.0) * spacing / 2.0;
    (0..n).flat_map(move |i| {
        (0..n).flat_map(move |j| {
            (0..n).map(move |k| {
                let jit = ((i * 7 + j * 13 + k * 29) % 11) as f32 * 1e-3;
                Vector::new(
                    offset + i as f32 * spacing + jit,
                    RADIUS + 0.01 + j as f32 * spacing,
                    offset + k as f32 * spacing - jit,
                )
            })
        })
    })
}

/// Spheres of the stacked packing with `n` spheres per side of its full layers and `layers`
/// layers: `ceil(layers/2) n^2 + floor(layers/2) (n-1)^2`.
pub fn stacked_count(n: usize, layers: usize) -> usize {
    layers.div_ceil(2) * n * n + layers / 2 * n.saturating_sub(1).pow(2)
}

/// The stacked face-centred cubic packing (module docs) with `n >= 2` spheres per side of its
/// full layers and `layers >= 1` layers, settled for `settle_steps` steps of plain Rapier
/// (hooks off), then registered with the plugin (`Fidelity::Auto`). The layers and the square
/// grids start 1e-5 of their spacing apart (no initial overlap).
pub fn stacked(n: usize, layers: usize, settle_steps: usize) -> Result<Pile, SceneError> {
    if n < 2 || layers == 0 {
        return Err(SceneError::Parameter(format!(
            "a stacked pile needs n >= 2 and layers >= 1, got n = {n}, layers = {layers}"
        )));
    }
    let mut w = CreepWorld::new(DT, CreepSettings::default().with_rapier_solver())?;
    let mat = CreepMaterial::new(Material::glass());
    let pitch = 2.0 * RADIUS * (1.0 + 1e-5);
    let rise = RADIUS * std::f32::consts::SQRT_2 * (1.0 + 1e-5);
    let half = 0.5 * pitch * (n as f32 - 1.0) + RADIUS;
    let height = RADIUS + rise * layers as f32 + 0.5;
    add_box(&mut w, mat, half, half, height);
    for j in 0..layers {
        let (count, shift) = if j % 2 == 0 { (n, 0.0) } else { (n - 1, 0.5) };
        let y = RADIUS + rise * j as f32;
        for i in 0..count {
            for k in 0..count {
                let x = -half + RADIUS + pitch * (i as f32 + shift);
                let z = -half + RADIUS + pitch * (k as f32 + shift);
                add_sphere(&mut w, mat, Vector::new(x, y, z));
            }
        }
    }
    // Settled by plain Rapier (its hooks off: while the packing finds its contacts the spheres
    // move faster than the plugin's activation speed, and hooked contacts lose Rapier's
    // recycling), then handed back to the plugin as registered.
    let flags: Vec<(ColliderHandle, ActiveHooks)> = w
        .physics
        .colliders
        .iter()
        .map(|(h, c)| (h, c.active_hooks()))
        .collect();
    for (h, _) in &flags {
        w.physics.colliders[*h].set_active_hooks(ActiveHooks::empty());
    }
    let t0 = Instant::now();
    for _ in 0..settle_steps {
        w.physics.step();
    }
    let plain_seconds = t0.elapsed().as_secs_f64();
    for (h, f) in flags {
        w.physics.colliders[h].set_active_hooks(f);
    }
    let mut pile = Pile::settle(w, stacked_count(n, layers), 0)?;
    pile.settle_steps = settle_steps;
    pile.settle_seconds = plain_seconds;
    Ok(pile)
}

/// A copy of `w` whose colliders are all registered at `fidelity`, with `settings`.
pub fn with_fidelity(
    w: &CreepWorld,
    fidelity: Fidelity,
    settings: CreepSettings,
) -> Result<CreepWorld, SceneError> {
    let mut reg = MaterialRegistry::new();
    for (h, _) in w.physics.colliders.iter() {
        if let Some(m) = w.hooks().registry().get(h) {
            reg.insert(h, m.with_fidelity(fidelity));
        }
    }
    Ok(CreepWorld::from_parts(
        clone_physics(&w.physics),
        CreepHooks::new(reg, settings)?,
    )?)
}

/// A copy of `w` without the plugin: no `MODIFY_SOLVER_CONTACTS` flags, to be stepped without
/// hooks (`PhysicsWorld::step`, with the plugin's integration parameters: Coulomb friction, no
/// clustering).
pub fn plain(w: &CreepWorld) -> PhysicsWorld {
    let mut p = clone_physics(&w.physics);
    let handles: Vec<ColliderHandle> = p.colliders.iter().map(|(h, _)| h).collect();
    for h in handles {
        p.colliders[h].set_active_hooks(ActiveHooks::empty());
    }
    p
}

/// Writes every collider's hook flags back through `ColliderSet::index_mut`, which marks the
/// collider modified: [`plain`] must do this to clear its flags, and a world whose every
/// collider was modified once steps measurably slower afterwards (measured: plain 47.9 ms
/// against 31.3 ms for an untouched copy of the 4,096-sphere dropped pile), so every copy that
/// is compared with a plain one gets the same treatment.
pub fn touch_all(p: &mut PhysicsWorld) {
    let handles: Vec<ColliderHandle> = p.colliders.iter().map(|(h, _)| h).collect();
    for h in handles {
        let flags = p.colliders[h].active_hooks();
        p.colliders[h].set_active_hooks(flags);
    }
}

/// Contact pairs of the narrow phase with at least one active contact point.
pub fn active_contact_pairs(p: &PhysicsWorld) -> usize {
    p.narrow_phase
        .contact_pairs()
        .filter(|c| c.has_any_active_contact())
        .count()
}

/// The plain copy and the plugin copy (`Fidelity::Auto`, default settings) of a pile, both
/// touched ([`touch_all`]) and warmed up by a few steps so that each has rebuilt its
/// workspace (and the plain one its contact recycling).
pub fn plain_and_auto(pile: &Pile) -> Result<(PhysicsWorld, CreepWorld), SceneError> {
    let mut p = plain(&pile.world);
    let mut a = with_fidelity(&pile.world, Fidelity::Auto, CreepSettings::default())?;
    touch_all(&mut a.physics);
    for _ in 0..5 {
        p.step();
        a.step()?;
    }
    Ok((p, a))
}

/// Step times of a plain and a plugin copy measured side by side.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Interleaved {
    /// Pairs of steps timed.
    pub pairs: usize,
    /// Median step time of plain Rapier \[s\].
    pub plain: f64,
    /// Median step time with the plugin \[s\].
    pub plugin: f64,
    /// Median of the per-pair ratios plugin / plain [-].
    pub ratio: f64,
    /// Active contact pairs after the last step (plain copy).
    pub contacts: usize,
    /// Registered colliders whose hook was on in the plugin's last step.
    pub hooks_on: usize,
}

/// [`crate::stats::median`] of samples that are never empty here (`pairs` and `steps` are
/// checked to be > 0 before sampling).
fn median(v: &mut [f64]) -> f64 {
    crate::stats::median(v).unwrap_or(f64::NAN)
}

/// Steps `plain` and `plugin` alternately `pairs` times (alternating which goes first), so that
/// the machine's load drifts hit both alike; the medians and the median of the pair ratios.
pub fn interleaved(
    plain: &mut PhysicsWorld,
    plugin: &mut CreepWorld,
    pairs: usize,
) -> Result<Interleaved, SceneError> {
    if pairs == 0 {
        return Err(SceneError::Parameter("pairs must be at least 1".into()));
    }
    let (mut tp, mut ta, mut ratio) = (vec![], vec![], vec![]);
    let mut hooks_on = 0;
    for i in 0..pairs {
        let time_plain = |p: &mut PhysicsWorld| {
            let t0 = Instant::now();
            p.step();
            t0.elapsed().as_secs_f64()
        };
        let mut time_plugin = |a: &mut CreepWorld| -> Result<f64, SceneError> {
            let t0 = Instant::now();
            hooks_on = a.step()?.hooks_on;
            Ok(t0.elapsed().as_secs_f64())
        };
        let (p, a) = if i % 2 == 0 {
            let p = time_plain(plain);
            (p, time_plugin(plugin)?)
        } else {
            let a = time_plugin(plugin)?;
            (time_plain(plain), a)
        };
        tp.push(p);
        ta.push(a);
        ratio.push(a / p);
    }
    Ok(Interleaved {
        pairs,
        plain: median(&mut tp),
        plugin: median(&mut ta),
        ratio: median(&mut ratio),
        contacts: active_contact_pairs(plain),
        hooks_on,
    })
}

/// Per-step cost ratios of a moving pile, plugin over plain Rapier.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MovingRatios {
    /// Spheres.
    pub spheres: usize,
    /// Steps timed (pour and settling).
    pub steps: usize,
    /// Median of the per-step ratios `Fidelity::Auto` / plain [-].
    pub auto: f64,
    /// Median of the per-step ratios `Fidelity::Creep` (every contact) / plain [-].
    pub creep: f64,
    /// Steps of the pour ([`POUR_STEPS`], or all the steps if fewer).
    pub pour_steps: usize,
    /// [`Self::auto`] over the pour's steps only [-].
    pub pour_auto: f64,
    /// [`Self::creep`] over the pour's steps only [-].
    pub pour_creep: f64,
    /// Median step time of plain Rapier \[s\].
    pub plain_step: f64,
    /// Active contact pairs at the end (plain copy).
    pub contacts: usize,
}

/// The first steps of [`moving_ratios`] counted as the pour (2 s of 1/60 s): the lattice's top
/// layer (1.8 m up for 16^3 balls) lands within 0.6 s and the heap collapses over the next
/// second; the steps after are the settling.
pub const POUR_STEPS: usize = 120;

/// The poured pile: the `n^3` lattice of [`dropped`] falls into the box and settles while three
/// copies from the same state step in turn (plain Rapier with the plugin's integration
/// parameters, the plugin at `Fidelity::Auto`, the plugin with creep on every contact), the
/// order rotating every step so that the machine's load drifts hit all alike. Returns the
/// medians of the per-step ratios over `steps` steps (the pour and the settling) and over the
/// pour's ([`POUR_STEPS`]).
pub fn moving_ratios(n: usize, steps: usize) -> Result<MovingRatios, SceneError> {
    moving_ratios_of(n, steps, [true, true])
}

/// [`moving_ratios`] with only some of the plugin copies stepped (`[auto, creep]`; a copy left
/// out has a NaN ratio): for profiling one fidelity at a time (`creep bench pile --only`).
pub fn moving_ratios_of(
    n: usize,
    steps: usize,
    worlds: [bool; 2],
) -> Result<MovingRatios, SceneError> {
    if steps == 0 {
        return Err(SceneError::Parameter("steps must be at least 1".into()));
    }
    let w = dropped_lattice(n)?;
    let mut p = plain(&w);
    let mut a = with_fidelity(&w, Fidelity::Auto, CreepSettings::default())?;
    let mut c = with_fidelity(&w, Fidelity::Creep, CreepSettings::default())?;
    touch_all(&mut a.physics);
    touch_all(&mut c.physics);
    let (mut ra, mut rc, mut tp) = (vec![], vec![], vec![]);
    for i in 0..steps {
        let mut t = [f64::NAN; 3];
        for k in 0..3 {
            let which = (i + k) % 3;
            if which > 0 && !worlds[which - 1] {
                continue;
            }
            let t0 = Instant::now();
            match which {
                0 => p.step(),
                1 => {
                    a.step()?;
                }
                _ => {
                    c.step()?;
                }
            }
            t[which] = t0.elapsed().as_secs_f64();
        }
        tp.push(t[0]);
        ra.push(t[1] / t[0]);
        rc.push(t[2] / t[0]);
    }
    let pour = steps.min(POUR_STEPS);
    let (pour_auto, pour_creep) = (
        median(&mut ra[..pour].to_vec()),
        median(&mut rc[..pour].to_vec()),
    );
    Ok(MovingRatios {
        spheres: n * n * n,
        steps,
        pour_steps: pour,
        pour_auto,
        pour_creep,
        auto: median(&mut ra),
        creep: median(&mut rc),
        plain_step: median(&mut tp),
        contacts: active_contact_pairs(&p),
    })
}

/// The pile of [`sleeping_pile`]: `n^3` 5 cm steel balls (`Material::steel`, its density)
/// released from the lattice of [`dropped`] into its box (steel walls), sleeping on (Rapier's
/// defaults), `CreepWorld::new`'s default settings (one solver substep), every collider
/// registered at `fidelity`, or none with `None` (plain Rapier, stepped without the plugin:
/// [`step_sleeping`]).
pub fn sleeping_lattice(n: usize, fidelity: Option<Fidelity>) -> Result<CreepWorld, SceneError> {
    if n == 0 {
        return Err(SceneError::Parameter("n must be at least 1".into()));
    }
    let mut w = CreepWorld::new(DT, CreepSettings::default())?;
    let steel = Material::steel();
    let mu = steel.friction() as f32;
    let mat = fidelity.map(|f| CreepMaterial::new(steel).with_fidelity(f));
    let (half, height) = (0.9f32, 4.0f32);
    w.insert(
        RigidBodyBuilder::fixed().translation(Vector::new(0.0, -WALL, 0.0)),
        ColliderBuilder::cuboid(half + 2.0 * WALL, WALL, half + 2.0 * WALL).friction(mu),
        mat,
    );
    let h = 0.5 * height;
    for (x, z, hx, hz) in [
        (half + WALL, 0.0, WALL, half),
        (-half - WALL, 0.0, WALL, half),
        (0.0, half + WALL, half, WALL),
        (0.0, -half - WALL, half, WALL),
    ] {
        w.insert(
            RigidBodyBuilder::fixed().translation(Vector::new(x, h, z)),
            ColliderBuilder::cuboid(hx, h, hz).friction(mu),
            mat,
        );
    }
    for p in pour_lattice(n) {
        w.insert(
            RigidBodyBuilder::dynamic().translation(p),
            ColliderBuilder::ball(RADIUS)
                .density(steel.density() as f32)
                .friction(mu),
            mat,
        );
    }
    Ok(w)
}

/// One step of a [`sleeping_lattice`] world: through the plugin if any collider is
/// registered, else plain Rapier's `PhysicsWorld::step`.
pub fn step_sleeping(w: &mut CreepWorld) -> Result<(), SceneError> {
    if w.registry().is_empty() {
        w.physics.step();
    } else {
        w.step()?;
    }
    Ok(())
}

/// Dynamic bodies of `p` that sleep.
pub fn asleep(p: &PhysicsWorld) -> usize {
    p.bodies
        .iter()
        .filter(|(_, b)| b.is_dynamic() && b.is_sleeping())
        .count()
}

/// [`sleeping_lattice`] stepped `steps` steps of 1/60 s: the pile poured and, at rest, asleep.
pub fn sleeping_pile(
    n: usize,
    fidelity: Option<Fidelity>,
    steps: usize,
) -> Result<CreepWorld, SceneError> {
    let mut w = sleeping_lattice(n, fidelity)?;
    for _ in 0..steps {
        step_sleeping(&mut w)?;
    }
    Ok(w)
}

/// The settled piles' costs ([`settled_costs`]): plain Rapier, the plugin at
/// `Fidelity::Coulomb`, `Auto` and `Creep`, in that order.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SettledCosts {
    /// Spheres per pile.
    pub spheres: usize,
    /// Steps each pile was settled for.
    pub settle_steps: usize,
    /// Steps timed.
    pub timed_steps: usize,
    /// Sleeping spheres at the end of the settling.
    pub asleep: [usize; 4],
    /// Median wall-clock time of one step of the settled pile \[s\].
    pub step: [f64; 4],
    /// Mean wall-clock time of one step of the settled pile \[s\].
    pub mean: [f64; 4],
}

/// Pours the four piles of [`SettledCosts`] (each its own, from the same lattice), settles each
/// for `settle_steps` steps, then times `timed_steps` more steps of each, interleaved (one step
/// of each world in turn, the order rotating), and returns the medians.
pub fn settled_costs(
    n: usize,
    settle_steps: usize,
    timed_steps: usize,
) -> Result<SettledCosts, SceneError> {
    if timed_steps == 0 {
        return Err(SceneError::Parameter(
            "timed steps must be at least 1".into(),
        ));
    }
    let fidelities = [
        None,
        Some(Fidelity::Coulomb),
        Some(Fidelity::Auto),
        Some(Fidelity::Creep),
    ];
    let mut worlds = Vec::with_capacity(4);
    for f in fidelities {
        worlds.push(sleeping_pile(n, f, settle_steps)?);
    }
    let asleep = [0, 1, 2, 3].map(|k| asleep(&worlds[k].physics));
    let mut times: [Vec<f64>; 4] = Default::default();
    for i in 0..timed_steps {
        for k in 0..4 {
            let which = (i + k) % 4;
            let t0 = Instant::now();
            step_sleeping(&mut worlds[which])?;
            times[which].push(t0.elapsed().as_secs_f64());
        }
    }
    Ok(SettledCosts {
        spheres: n * n * n,
        settle_steps,
        timed_steps,
        asleep,
        mean: times
            .each_ref()
            .map(|t| t.iter().sum::<f64>() / t.len() as f64),
        step: times.map(|mut t| median(&mut t)),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn stacked_packing_settles_at_rest_with_fcc_contacts() {
        assert_eq!(stacked_count(10, 11), 1005);
        let sizes = SCALE_SIDES.map(|n| stacked_count(n, SCALE_LAYERS));
        assert_eq!(sizes, [1005, 4184, 16_301, 64_349]);
        let pile = stacked(4, 5, 30).unwrap();
        assert_eq!(pile.spheres, 3 * 16 + 2 * 9);
        assert_eq!(
            pile.world
                .physics
                .bodies
                .iter()
                .filter(|(_, b)| b.is_dynamic())
                .count(),
            pile.spheres
        );
        // At rest: below the plugin's activation speed, so every Auto hook is off.
        assert!(pile.max_speed < 1e-2, "{}", pile.max_speed);
        let (mut p, mut a) = plain_and_auto(&pile).unwrap();
        let t = interleaved(&mut p, &mut a, 3).unwrap();
        assert_eq!(t.hooks_on, 0);
        assert!(t.plain > 0.0 && t.plugin > 0.0 && t.ratio.is_finite());
        // Each hollow sphere rests on four below; the full layers touch the walls and floor.
        assert!(t.contacts > 4 * 2 * 9, "{}", t.contacts);
        assert!(stacked(1, 3, 1).is_err() && dropped(0).is_err());
        assert!(interleaved(&mut p, &mut a, 0).is_err());
    }
}
