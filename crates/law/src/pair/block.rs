//! Four sphere-sphere contacts at once: [`cheap_sphere_block`] for the [`Cheap`] tier,
//! [`exact_sphere_block`] for the [`Exact`] tier (whose Cattaneo-Mindlin memory, a short list
//! of annuli per contact, runs lane by lane between the shared vector parts described below).
//!
//! The same arithmetic as [`pair_force`](super::pair_force) for two movable spheres with the
//! cheap tier, no rolling resistance and (with creep) Kuhn's steady law, operation for
//! operation, but on lanes of four contacts (`[f64; 4]` arrays the compiler turns into vector
//! instructions: SSE2's two `f64` per instruction on every x86-64, four with AVX), so every
//! lane's result is the same bits as the one-contact kernel's (IEEE 754 operations are
//! correctly rounded lane by lane; no fused multiply-add is introduced). The branches of the
//! one-contact kernel become masks: both sides are evaluated and each lane keeps its own
//! (the Coulomb limit, the creep term, the spin of the basis, the renormalisation of the
//! carried tangent), except that the rare sides with a square root or a division (the
//! rescale onto the Coulomb limit, the creep term's cap at `1/k`, the full renormalisation
//! of a tangent whose length is not within 1e-8 of 1) are evaluated only when some lane of
//! the block takes them; the cube root of the creep term and the sine of a spin beyond 1e-3 rad
//! per step are taken lane by lane with the one-contact kernel's functions. Built for a CPU
//! with AVX (`-C target-cpu=native`), the four lanes fit one register: the same bits. The cases the
//! block does not take, a lane's rare branches (a virgin or opening contact, a normal that
//! turned beyond 45 degrees, a carried tangent of length zero, a non-finite value), leave
//! that lane untouched and clear its bit of the returned mask: the host runs the one-contact
//! kernel on it, so the results are the same whichever way a contact goes (test
//! `block_equals_the_one_contact_kernel`).

use super::kernel::finite;
use super::{Cheap, ContactHistory, Exact, PairConstants, PairDissipation, TangentialLaw};
use crate::kalker;
use crate::material::{PairMaterial, Surface};
use crate::steady_law::SteadyLaw;
use crate::vector::{Vec2, Vec3};

/// Contacts per block.
pub const LANES: usize = 4;

/// One lane's bodies: two spheres p and q (the normal points from p to q).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct SpherePair {
    /// Centre of p \[m\].
    pub xp: Vec3,
    /// Centre of q \[m\].
    pub xq: Vec3,
    /// Radius of p \[m\].
    pub rp: f64,
    /// Radius of q \[m\].
    pub rq: f64,
    /// Velocity of p [m/s].
    pub vp: Vec3,
    /// Velocity of q [m/s].
    pub vq: Vec3,
    /// Angular velocity of p [rad/s].
    pub wp: Vec3,
    /// Angular velocity of q [rad/s].
    pub wq: Vec3,
    /// Mass of p \[kg\].
    pub mp: f64,
    /// Mass of q \[kg\].
    pub mq: f64,
}

/// Stores `v` in lane `l` of a vector's lanes (`l < LANES`, checked by the caller).
#[inline(always)]
fn put_lane(a: &mut [[f64; LANES]; 3], l: usize, v: Vec3) {
    a[0][l] = v.x;
    a[1][l] = v.y;
    a[2][l] = v.z;
}

/// Copies lane `from` into lane `to` of each vector's lanes.
#[inline]
fn copy_lanes<const N: usize>(vectors: [&mut [[f64; LANES]; 3]; N], from: usize, to: usize) {
    for a in vectors {
        for c in a.iter_mut() {
            c[to] = c[from];
        }
    }
}

/// The bodies of [`LANES`] sphere pairs, lane by lane (structure of arrays: each quantity's
/// lanes side by side, as the block loads them).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct SphereLanes {
    xp: [[f64; LANES]; 3],
    xq: [[f64; LANES]; 3],
    vp: [[f64; LANES]; 3],
    vq: [[f64; LANES]; 3],
    wp: [[f64; LANES]; 3],
    wq: [[f64; LANES]; 3],
    rp: [f64; LANES],
    rq: [f64; LANES],
    mp: [f64; LANES],
    mq: [f64; LANES],
}

impl SphereLanes {
    /// Sets lane `l` (< [`LANES`]; panics otherwise) to the pair `s`.
    #[inline(always)]
    pub fn set(&mut self, l: usize, s: &SpherePair) {
        // One check here instead of one per store below.
        assert!(l < LANES, "lane {l} of {LANES}");
        put_lane(&mut self.xp, l, s.xp);
        put_lane(&mut self.xq, l, s.xq);
        put_lane(&mut self.vp, l, s.vp);
        put_lane(&mut self.vq, l, s.vq);
        put_lane(&mut self.wp, l, s.wp);
        put_lane(&mut self.wq, l, s.wq);
        self.rp[l] = s.rp;
        self.rq[l] = s.rq;
        self.mp[l] = s.mp;
        self.mq[l] = s.mq;
    }

    /// Copies lane `from` into lane `to` (to fill the unused lanes of a block).
    #[inline]
    pub fn copy_lane(&mut self, from: usize, to: usize) {
        copy_lanes(
            [
                &mut self.xp,
                &mut self.xq,
                &mut self.vp,
                &mut self.vq,
                &mut self.wp,
                &mut self.wq,
            ],
            from,
            to,
        );
        for a in [&mut self.rp, &mut self.rq, &mut self.mp, &mut self.mq] {
            a[to] = a[from];
        }
    }
}

/// What one lane of [`cheap_sphere_block`] returns: the outputs of
/// [`PairForces`](super::PairForces) a DEM host uses, for a touching contact.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct SphereForces {
    /// Force on p \[N\] (`-force_p` on q).
    pub force_p: Vec3,
    /// Torque on p about its centre [N m].
    pub torque_p: Vec3,
    /// Torque on q about its centre [N m].
    pub torque_q: Vec3,
    /// Whether the contact is at the Coulomb limit.
    pub sliding: bool,
    /// Creep displacement of the step in `(t1, t2)` \[m\].
    pub creep_displacement: Vec2,
    /// The step's energies.
    pub dissipation: PairDissipation,
}

/// The outputs of a block's [`LANES`] contacts, lane by lane (structure of arrays: each
/// quantity's lanes side by side, as the block computes them); lane `l` is
/// [`SphereForceLanes::lane`].
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct SphereForceLanes {
    /// Force on p \[N\], by component.
    pub force_p: [[f64; LANES]; 3],
    /// Torque on p about its centre [N m], by component.
    pub torque_p: [[f64; LANES]; 3],
    /// Torque on q about its centre [N m], by component.
    pub torque_q: [[f64; LANES]; 3],
    /// Whether the contact is at the Coulomb limit.
    pub sliding: [bool; LANES],
    /// Creep displacement of the step in `(t1, t2)` \[m\], by component.
    pub creep_displacement: [[f64; LANES]; 2],
    /// Energy dissipated by the normal damping \[J\].
    pub damping: [f64; LANES],
    /// Energy dissipated by micro-slip and gross slip \[J\].
    pub slip: [f64; LANES],
    /// Energy dissipated by creep \[J\].
    pub creep: [f64; LANES],
    /// Energy added by the tier's simplifications \[J\].
    pub truncation: [f64; LANES],
}

impl SphereForceLanes {
    /// Writes the lanes `l < used` that `done` sets to `out[idx[l]]` (a block's outputs into a
    /// host's buffer).
    #[inline(always)]
    pub fn scatter(&self, done: u32, out: &mut [SphereForces], idx: [usize; LANES], used: usize) {
        for l in 0..used.min(LANES) {
            if done >> l & 1 == 1 {
                out[idx[l]] = self.lane(l);
            }
        }
    }

    /// Lane `l`'s outputs (`l` < [`LANES`]; panics otherwise).
    #[inline(always)]
    pub fn lane(&self, l: usize) -> SphereForces {
        let v = |a: &[[f64; LANES]; 3]| Vec3::new(a[0][l], a[1][l], a[2][l]);
        SphereForces {
            force_p: v(&self.force_p),
            torque_p: v(&self.torque_p),
            torque_q: v(&self.torque_q),
            sliding: self.sliding[l],
            creep_displacement: Vec2::new(
                self.creep_displacement[0][l],
                self.creep_displacement[1][l],
            ),
            dissipation: PairDissipation {
                damping: self.damping[l],
                slip: self.slip[l],
                creep: self.creep[l],
                rolling: 0.0,
                truncation: self.truncation[l],
            },
        }
    }
}

/// Whether the block takes contacts with constants `c` at all: no rolling resistance, and
/// with creep, Kuhn's steady law (the others go to the one-contact kernel).
#[inline]
pub fn block_supports(c: &PairConstants) -> bool {
    c.rolling.is_none() && (c.creep.is_none() || matches!(c.steady, SteadyLaw::Kuhn { .. }))
}

#[derive(Clone, Copy)]
struct F([f64; LANES]);

/// A lane mask: all ones (true) or all zeros, as the vector compares give them (held as
/// `f64` bit patterns so that they stay in the vector registers).
#[derive(Clone, Copy)]
struct M([f64; LANES]);

#[inline(always)]
fn mask(b: bool) -> f64 {
    f64::from_bits((b as u64).wrapping_neg())
}

/// Lane `l` of a vector stored by components.
#[inline(always)]
fn lane3(a: &[[f64; LANES]; 3], l: usize) -> Vec3 {
    Vec3::new(a[0][l], a[1][l], a[2][l])
}

#[inline(always)]
fn bits(x: f64) -> u64 {
    x.to_bits()
}

/// `f64::MAX` in every lane, passed through [`std::hint::black_box`] once per block, so that
/// the compiler cannot see the value: it would fold the tests of one lane's value (`x > 0`
/// with `x` finite, `x < inf`) into one floating-point class test, which it evaluates lane by
/// lane in integer registers (about 40 instructions per contact), where with an opaque bound
/// each test stays one vector compare. `x <= f64::MAX` for `|x|` is the same test as
/// [`f64::is_finite`], and for `x > 0` as `x < inf`.
#[derive(Clone, Copy)]
struct Big(F);

impl Big {
    #[inline(always)]
    fn new() -> Big {
        Big(F::splat(std::hint::black_box(f64::MAX)))
    }
}

#[derive(Clone, Copy)]
struct V {
    x: F,
    y: F,
    z: F,
}

macro_rules! lanes {
    ($l:ident => $e:expr) => {
        F(std::array::from_fn(|$l| $e))
    };
}

macro_rules! binop {
    ($tr:ident, $f:ident, $op:tt) => {
        impl std::ops::$tr for F {
            type Output = F;
            #[inline(always)]
            fn $f(self, o: F) -> F {
                lanes!(l => self.0[l] $op o.0[l])
            }
        }
        impl std::ops::$tr<f64> for F {
            type Output = F;
            #[inline(always)]
            fn $f(self, o: f64) -> F {
                lanes!(l => self.0[l] $op o)
            }
        }
        impl std::ops::$tr for V {
            type Output = V;
            #[inline(always)]
            fn $f(self, o: V) -> V {
                V { x: self.x $op o.x, y: self.y $op o.y, z: self.z $op o.z }
            }
        }
        impl std::ops::$tr<F> for V {
            type Output = V;
            #[inline(always)]
            fn $f(self, o: F) -> V {
                V { x: self.x $op o, y: self.y $op o, z: self.z $op o }
            }
        }
    };
}
binop!(Add, add, +);
binop!(Sub, sub, -);
binop!(Mul, mul, *);
binop!(Div, div, /);

impl F {
    #[inline(always)]
    fn splat(x: f64) -> F {
        F([x; LANES])
    }
    #[inline(always)]
    fn sqrt(self) -> F {
        lanes!(l => self.0[l].sqrt())
    }
    #[inline(always)]
    fn neg(self) -> F {
        lanes!(l => -self.0[l])
    }
    #[inline(always)]
    fn gt(self, o: F) -> M {
        M(std::array::from_fn(|l| mask(self.0[l] > o.0[l])))
    }
    #[inline(always)]
    fn lt(self, o: F) -> M {
        M(std::array::from_fn(|l| mask(self.0[l] < o.0[l])))
    }
    #[inline(always)]
    fn ge(self, o: F) -> M {
        M(std::array::from_fn(|l| mask(self.0[l] >= o.0[l])))
    }
    #[inline(always)]
    fn le(self, o: F) -> M {
        M(std::array::from_fn(|l| mask(self.0[l] <= o.0[l])))
    }
    /// Whether each lane is finite, as [`f64::is_finite`]: `|x| <= big` with `big` the largest
    /// finite `f64` ([`Big`]).
    #[inline(always)]
    fn finite(self, big: Big) -> M {
        M(std::array::from_fn(|l| mask(self.0[l].abs() <= big.0.0[l])))
    }
}

impl M {
    /// Whether some lane is set.
    #[inline(always)]
    fn any(self) -> bool {
        self.0.iter().any(|&m| bits(m) != 0)
    }
    /// The lanes of `self` not set in `o`.
    #[inline(always)]
    fn and_not(self, o: M) -> M {
        M(std::array::from_fn(|l| {
            f64::from_bits(bits(self.0[l]) & !bits(o.0[l]))
        }))
    }
    #[inline(always)]
    fn and(self, o: M) -> M {
        M(std::array::from_fn(|l| {
            f64::from_bits(bits(self.0[l]) & bits(o.0[l]))
        }))
    }
    #[inline(always)]
    fn sel(self, a: F, b: F) -> F {
        lanes!(l => f64::from_bits((bits(a.0[l]) & bits(self.0[l])) | (bits(b.0[l]) & !bits(self.0[l]))))
    }
    #[inline(always)]
    fn sel_v(self, a: V, b: V) -> V {
        V {
            x: self.sel(a.x, b.x),
            y: self.sel(a.y, b.y),
            z: self.sel(a.z, b.z),
        }
    }
}

impl V {
    #[inline(always)]
    fn load(a: &[[f64; LANES]; 3]) -> V {
        V {
            x: F(a[0]),
            y: F(a[1]),
            z: F(a[2]),
        }
    }
    #[inline(always)]
    fn gather(f: impl Fn(usize) -> Vec3) -> V {
        V {
            x: lanes!(l => f(l).x),
            y: lanes!(l => f(l).y),
            z: lanes!(l => f(l).z),
        }
    }
    /// As `Vec3::dot`: `x x' + y y' + z z'`, left to right.
    #[inline(always)]
    fn dot(self, o: V) -> F {
        self.x * o.x + self.y * o.y + self.z * o.z
    }
    /// As `Vec3::cross`.
    #[inline(always)]
    fn cross(self, o: V) -> V {
        V {
            x: self.y * o.z - self.z * o.y,
            y: self.z * o.x - self.x * o.z,
            z: self.x * o.y - self.y * o.x,
        }
    }
    #[inline(always)]
    fn store(self) -> [[f64; LANES]; 3] {
        [self.x.0, self.y.0, self.z.0]
    }
}

/// The part of [`pair_force`](super::pair_force) before the tangential law, on [`LANES`]
/// sphere pairs (either tier): geometry, `R*` and `m*`, Kuhn & Bagi's rates, the carried
/// basis, Hertz + Tsuji, the displacements in the basis.
struct Front {
    /// The lanes the block can take so far.
    ok: M,
    /// The opaque `f64::MAX` of the block's finiteness tests.
    big: Big,
    n: V,
    t1: V,
    t2: V,
    delta: F,
    a: F,
    p_el: F,
    p_tot: F,
    damping: F,
    dux: F,
    duy: F,
    drx: F,
    dry: F,
    rho_p: F,
    rho_q: F,
    r_star: F,
}

/// [`Front`] of the pairs `pairs` with constants `c`, histories `h` and step `dt` \[s\]: the
/// one-contact kernel's arithmetic, operation for operation.
#[inline(always)]
fn sphere_front<T: TangentialLaw>(
    c: &PairConstants,
    pairs: &SphereLanes,
    h: &[&ContactHistory<T>; LANES],
    dt: f64,
) -> Front {
    let pm = &c.material;
    let creep_on = c.creep.is_some();
    let big = Big::new();
    let xp = V::load(&pairs.xp);
    let xq = V::load(&pairs.xq);
    let (rp, rq, mp, mq) = (F(pairs.rp), F(pairs.rq), F(pairs.mp), F(pairs.mq));

    // Geometry (`ContactGeometry::sphere_sphere`).
    let d = xq - xp;
    let dist = d.dot(d).sqrt();
    let mut ok = dist.gt(F::splat(f64::MIN_POSITIVE)).and(dist.finite(big));
    let n = d * (F::splat(1.0) / dist);
    let delta = rp + rq - dist;

    // `R*` and `m*` with one reciprocal (the kernel's `reduced_mass_and_material`).
    let (sr, sm) = (rp + rq, mp + mq);
    let inv = F::splat(1.0) / (sr * sm);
    ok = ok
        .and(mp.gt(F::splat(0.0)))
        .and(mq.gt(F::splat(0.0)))
        .and(inv.gt(F::splat(0.0)))
        .and(inv.finite(big))
        .and(sm.finite(big));
    let r_star = rp * rq * sm * inv;
    let m_star = mp * mq * sr * inv;
    ok = ok
        .and(delta.gt(F::splat(0.0)))
        .and(m_star.gt(F::splat(0.0)))
        .and(r_star.finite(big));

    // Kuhn & Bagi's rates for two spheres (`sphere_rates_and_approach`).
    let rho_p = rp - delta * 0.5;
    let rho_q = rq - delta * 0.5;
    let wp = V::load(&pairs.wp);
    let wq = V::load(&pairs.wq);
    let a_w = wp.cross(n);
    let b_w = wq.cross(n);
    let dv = V::load(&pairs.vq) - V::load(&pairs.vp);
    let dvn = dv.dot(n);
    let dv_t = dv - n * dvn;
    let dd = rho_p + rho_q;
    ok = ok.and(dd.gt(F::splat(0.0))).and(dd.finite(big));
    let v_roll =
        dv_t * ((rho_q - rho_p) / (dd * 2.0)) + (a_w * rho_p - b_w * rho_q) * F::splat(0.5);
    let v_disp = dv_t - a_w * rho_p - b_w * rho_q;
    let delta_dot = dvn.neg();

    // The carried basis (`carry_tangent`, the projection branch); the kernel's spin `0.5 * s`
    // is the same product as `s * 0.5`.
    let (t1, mut ok) = carried_t1(h, n, (wp + wq).dot(n) * 0.5, dt, ok);
    let t2 = n.cross(t1);

    // Normal force: Hertz + Tsuji, never attractive.
    let a = (r_star * delta).sqrt();
    let e43 = 4.0 / 3.0 * pm.e_star;
    let p_el = F::splat(e43) * a * delta;
    let damp = F::splat(c.alpha) * (F::splat(e43) * m_star * a).sqrt();
    let p_try = p_el + damp * delta_dot;
    let p_tot = p_try.gt(F::splat(0.0)).sel(p_try, F::splat(0.0));
    let damping = (p_tot - p_el) * delta_dot * dt;

    // Tangential displacements in the basis.
    let ud = v_disp * F::splat(dt);
    let (dux, duy) = (ud.dot(t1), ud.dot(t2));
    ok = ok.and(dux.finite(big)).and(duy.finite(big));
    let (drx, dry) = if creep_on {
        let ur = v_roll * F::splat(dt);
        (ur.dot(t1), ur.dot(t2))
    } else {
        (F::splat(0.0), F::splat(0.0))
    };

    Front {
        ok,
        big,
        n,
        t1,
        t2,
        delta,
        a,
        p_el,
        p_tot,
        damping,
        dux,
        duy,
        drx,
        dry,
        rho_p,
        rho_q,
        r_star,
    }
}

/// The carried first tangent of the pairs with histories `h` on the new normals `n`, turned by
/// the pairs' mean spins `spin` \[rad/s\] over the step `dt` \[s\]: the one-contact kernel's
/// `carry_tangent` (the projection branch, `spin_without_axial` and `renormalize`), operation
/// for operation, and `ok` without the lanes it does not take (a normal that turned beyond 45
/// degrees, a tangent that degenerates).
#[inline(always)]
fn carried_t1<T: TangentialLaw>(
    h: &[&ContactHistory<T>; LANES],
    n: V,
    spin: F,
    dt: f64,
    ok: M,
) -> (V, M) {
    let mut ok = ok;
    let t1_old = V::gather(|l| h[l].t1);
    let from = V::gather(|l| h[l].normal);
    ok = ok.and(from.dot(n).gt(F::splat(std::f64::consts::FRAC_1_SQRT_2)));
    let angle = spin * dt;
    let a2 = angle * angle;
    let mut s = angle * (F::splat(1.0) - a2 * (1.0 / 6.0));
    let mut cs = F::splat(1.0) - a2 * 0.5 * (F::splat(1.0) - a2 * (1.0 / 12.0));
    // Beyond 1e-3 rad per step (`small_sin_cos`'s series) libm's, lane by lane (one vector
    // test for the block first: the rule is that no lane turns so far).
    let far_turn = M(std::array::from_fn(|l| mask(!(angle.0[l].abs() < 1e-3))));
    if far_turn.any() {
        for l in 0..LANES {
            if !(angle.0[l].abs() < 1e-3) {
                (s.0[l], cs.0[l]) = angle.0[l].sin_cos();
            }
        }
    }
    let spun = t1_old * cs + n.cross(t1_old) * s;
    let zero_angle = M(std::array::from_fn(|l| mask(angle.0[l] == 0.0)));
    let spun = zero_angle.sel_v(t1_old, spun);
    let t = spun - n * spun.dot(n);
    let l2 = t.dot(t);
    // `renormalize`: one Newton step near 1, else `try_normalize`.
    let near = lanes!(l => (l2.0[l] - 1.0).abs()).lt(F::splat(1e-8));
    let newton = t * (F::splat(1.5) - l2 * 0.5);
    // The square root and the division only where some lane needs them (every lane near 1 is
    // the rule): the selects below give the same bits either way.
    let far = M(std::array::from_fn(|l| f64::from_bits(!bits(near.0[l])))).any();
    if far {
        let len = l2.sqrt();
        ok = ok.and(M(std::array::from_fn(|l| {
            f64::from_bits(
                bits(near.0[l]) | bits(mask(len.0[l].is_finite() & (len.0[l] > f64::MIN_POSITIVE))),
            )
        })));
        (near.sel_v(newton, t * (F::splat(1.0) / len)), ok)
    } else {
        (newton, ok)
    }
}

/// The cheap tier's step on [`LANES`] sphere-sphere contacts with the same constants `c`
/// (which [`block_supports`]), bodies `pairs` and histories `hist[idx[l]]` (none virgin; the
/// first `used` lanes are contacts, the others repeat one of them and are not written), time
/// step `dt` \[s\]: for each lane whose bit the returned mask sets, its history is updated
/// and `out[idx[l]]` holds the contact's outputs, the same bits as [`pair_force`](super::pair_force)
/// gives on that lane; the other lanes (see the module docs) are left as they were for the
/// caller's one-contact kernel.
#[inline(always)]
pub fn cheap_sphere_block(
    c: &PairConstants,
    pairs: &SphereLanes,
    hist: &mut [ContactHistory<Cheap>],
    out: &mut [SphereForces],
    idx: [usize; LANES],
    used: usize,
    dt: f64,
) -> u32 {
    let mut lanes = SphereForceLanes::default();
    let done = cheap_sphere_block_lanes(c, pairs, hist, idx, used, dt, &mut lanes);
    lanes.scatter(done, out, idx, used);
    done
}

/// [`cheap_sphere_block`] with the outputs lane by lane in `out` (lane `l` valid where the
/// returned mask sets bit `l`), for a host that adds them to its bodies itself.
#[inline(always)]
pub fn cheap_sphere_block_lanes(
    c: &PairConstants,
    pairs: &SphereLanes,
    hist: &mut [ContactHistory<Cheap>],
    idx: [usize; LANES],
    used: usize,
    dt: f64,
    out: &mut SphereForceLanes,
) -> u32 {
    let h: [&ContactHistory<Cheap>; LANES] = std::array::from_fn(|l| &hist[idx[l]]);
    let pm = &c.material;
    let creep_on = c.creep.is_some();
    let c11 = match c.steady {
        SteadyLaw::Kuhn { c11 } => c11,
        _ if !creep_on => 0.0,
        _ => return 0,
    };
    if c.rolling.is_some() {
        return 0;
    }
    let Front {
        mut ok,
        big,
        n,
        t1,
        t2,
        delta,
        a,
        p_el,
        p_tot,
        damping,
        dux,
        duy,
        drx,
        dry,
        rho_p,
        rho_q,
        r_star: _,
    } = sphere_front(c, pairs, &h, dt);

    // The cheap tier (`Cheap::step`).
    ok = ok
        .and(p_el.gt(F::splat(0.0)))
        .and(a.gt(F::splat(0.0)))
        .and(p_el.finite(big))
        .and(a.finite(big));
    let k = F::splat(8.0 * pm.g_star) * a;
    let mu_p = F::splat(pm.mu) * p_el;
    ok = ok.and(mu_p.finite(big));
    let qx = lanes!(l => h[l].tangential.q.x);
    let qy = lanes!(l => h[l].tangential.q.y);
    let hk = lanes!(l => h[l].tangential.k);
    let q2 = qx * qx + qy * qy;
    let zero = F::splat(0.0);
    let trunc_on = q2.gt(zero).and(hk.gt(zero));
    let truncation = trunc_on.sel(q2 * 0.5 * ((hk - k) / (k * hk)), zero);
    let roll2 = drx * drx + dry * dry;
    let creep_in = roll2.gt(zero).and(q2.gt(zero)).and(roll2.finite(big));
    // `creep_per_force`, Kuhn's branch; a creeping lane outside it goes to the kernel.
    let ga2 = F::splat(pm.g) * a * a;
    let kuhn = mu_p
        .gt(zero)
        .and(mu_p.le(big.0))
        .and(ga2.gt(zero))
        .and(ga2.le(big.0));
    ok = M(std::array::from_fn(|l| {
        f64::from_bits(bits(ok.0[l]) & (!bits(creep_in.0[l]) | bits(kuhn.0[l])))
    }));
    let roll = roll2.sqrt();
    let q_abs = q2.sqrt();
    let gc = ga2 * c11;
    let below = q_abs.lt(mu_p);
    let diff = mu_p - q_abs;
    // The cube root's fraction lane by lane (bit operations); lanes not below the limit or
    // not creeping take a harmless argument.
    let use_root = below.and(creep_in).and(kuhn).and(ok);
    let xr = use_root.sel(diff / mu_p, F::splat(1.0));
    let inv_xr = use_root.sel(mu_p / diff, F::splat(1.0));
    let mut tt = F::splat(0.0);
    let mut tn_n = F::splat(0.0);
    let mut td = F::splat(0.0);
    for l in 0..LANES {
        let (t, nn, dd) = kalker::cbrt_fraction(xr.0[l], inv_xr.0[l]);
        tt.0[l] = t;
        tn_n.0[l] = nn;
        td.0[l] = dd;
    }
    let tn = tt * tn_n;
    let num_b = roll * 3.0 * (td * td);
    let den_b = gc * (td * (td + tn) + tn * tn);
    let num_s = roll * 3.0 * mu_p;
    let den_s = gc * q_abs;
    let num = below.sel(num_b, num_s);
    let den = below.sel(den_b, den_s);
    let uncapped = (num * k).lt(den);
    // `1/k` only where a creeping lane is capped by it (the others' `f` is not used).
    let f = if creep_in.and_not(uncapped).any() {
        uncapped.sel(num / den, F::splat(1.0) / k)
    } else {
        num / den
    };
    let creep_use = creep_in.and(f.gt(zero)).and(f.finite(big));
    let fc = creep_use.sel(f, zero);
    let (cx, cy) = (creep_use.sel(qx * fc, zero), creep_use.sel(qy * fc, zero));
    let creep_e = creep_use.sel(q2 * fc, zero);
    let trial_x = qx + (dux - cx) * k;
    let trial_y = qy + (duy - cy) * k;
    let tr2 = trial_x * trial_x + trial_y * trial_y;
    let slide = tr2.gt(mu_p * mu_p);
    // The rescale onto the Coulomb limit only where some lane slides.
    let (q_x, q_y, slip) = if slide.any() {
        let scale = mu_p / tr2.sqrt();
        let (sx, sy) = (trial_x * scale, trial_y * scale);
        let slip_s = (sx * (trial_x - sx) + sy * (trial_y - sy)) / k;
        (
            slide.sel(sx, trial_x),
            slide.sel(sy, trial_y),
            slide.sel(slip_s, zero),
        )
    } else {
        (trial_x, trial_y, zero)
    };

    // Outputs.
    let q_world = t1 * q_x + t2 * q_y;
    let limit = F::splat((1.0 - 1e-9) * pm.mu) * p_el;
    let sliding = (q_x * q_x + q_y * q_y).ge(limit * limit);
    let f_p = q_world - n * p_tot;
    let nf = t2 * q_x - t1 * q_y;
    let torque_p = nf * rho_p
        - V {
            x: zero,
            y: zero,
            z: zero,
        };
    let torque_q = nf * rho_q
        + V {
            x: zero,
            y: zero,
            z: zero,
        };
    *out = SphereForceLanes {
        force_p: f_p.store(),
        torque_p: torque_p.store(),
        torque_q: torque_q.store(),
        sliding: std::array::from_fn(|l| bits(sliding.0[l]) != 0),
        creep_displacement: [cx.0, cy.0],
        damping: damping.0,
        slip: slip.0,
        creep: creep_e.0,
        truncation: truncation.0,
    };
    let ok = ok.0;
    let mut done = 0;
    // The basis lane by lane from arrays stored once (extracting a lane from the vectors in the
    // loop stored them again at every lane).
    let (t1a, na) = (t1.store(), n.store());
    for l in 0..used.min(LANES) {
        if bits(ok[l]) == 0 {
            continue;
        }
        done |= 1 << l;
        let hl = &mut hist[idx[l]];
        hl.tangential.q = Vec2::new(q_x.0[l], q_y.0[l]);
        hl.tangential.k = k.0[l];
        hl.t1 = lane3(&t1a, l);
        hl.normal = lane3(&na, l);
        hl.overlap = delta.0[l];
    }
    done
}

/// The exact tier's step on [`LANES`] sphere-sphere contacts with the same constants `c`
/// (which [`block_supports`]), bodies `pairs` and histories `hist[idx[l]]` (none virgin; the
/// first `used` lanes are contacts, the others repeat one of them and are not written), time
/// step `dt` \[s\]: [`cheap_sphere_block`]'s contract for [`Exact`]. The part before the
/// tangential law and the outputs run on the lanes at once; the Cattaneo-Mindlin memory with
/// Kuhn's creep ([`Exact`]'s step, the one-contact kernel's call) lane by lane. The same bits
/// as [`pair_force`](super::pair_force) on every lane taken (test
/// `block_equals_the_one_contact_kernel`).
#[inline(always)]
pub fn exact_sphere_block(
    c: &PairConstants,
    pairs: &SphereLanes,
    hist: &mut [ContactHistory<Exact>],
    out: &mut [SphereForces],
    idx: [usize; LANES],
    used: usize,
    dt: f64,
) -> u32 {
    let mut lanes = SphereForceLanes::default();
    let done = exact_sphere_block_lanes(c, pairs, hist, idx, used, dt, &mut lanes);
    lanes.scatter(done, out, idx, used);
    done
}

/// [`exact_sphere_block`] with the outputs lane by lane in `out` (lane `l` valid where the
/// returned mask sets bit `l`), for a host that adds them to its bodies itself.
#[inline(always)]
pub fn exact_sphere_block_lanes(
    c: &PairConstants,
    pairs: &SphereLanes,
    hist: &mut [ContactHistory<Exact>],
    idx: [usize; LANES],
    used: usize,
    dt: f64,
    out: &mut SphereForceLanes,
) -> u32 {
    if c.rolling.is_some() {
        return 0;
    }
    let f = {
        let h: [&ContactHistory<Exact>; LANES] = std::array::from_fn(|l| &hist[idx[l]]);
        sphere_front(c, pairs, &h, dt)
    };
    let pm = &c.material;
    let zero = F::splat(0.0);
    // The lanes the tangential law takes: the front's, with a loaded contact (the one-contact
    // kernel's other cases go to it).
    let ok =
        f.ok.and(f.p_el.gt(zero))
            .and(f.a.gt(zero))
            .and(f.p_el.finite(f.big))
            .and(f.a.finite(f.big))
            .0;
    let (mut q_x, mut q_y) = (zero, zero);
    let (mut cx, mut cy) = (zero, zero);
    let (mut slip, mut creep, mut truncation) = (zero, zero, zero);
    let mut done = 0;
    let (t1a, na) = (f.t1.store(), f.n.store());
    for l in 0..used.min(LANES) {
        if bits(ok[l]) == 0 {
            continue;
        }
        done |= 1 << l;
        // The one-contact kernel's pair material (`reduced_mass_and_material`).
        let lane_pm = PairMaterial {
            r_star: f.r_star.0[l],
            surface_p: Surface::Sphere(pairs.rp[l]),
            surface_q: Surface::Sphere(pairs.rq[l]),
            ..*pm
        };
        let hl = &mut hist[idx[l]];
        let s = Exact::step(
            &mut hl.tangential,
            c,
            &lane_pm,
            f.p_el.0[l],
            f.a.0[l],
            Vec2::new(f.dux.0[l], f.duy.0[l]),
            Vec2::new(f.drx.0[l], f.dry.0[l]),
        );
        (q_x.0[l], q_y.0[l]) = (s.q.x, s.q.y);
        (cx.0[l], cy.0[l]) = (s.creep_displacement.x, s.creep_displacement.y);
        (slip.0[l], creep.0[l], truncation.0[l]) = (s.slip, s.creep, s.truncation);
        hl.t1 = lane3(&t1a, l);
        hl.normal = lane3(&na, l);
        hl.overlap = f.delta.0[l];
    }

    // Outputs (the one-contact kernel's, as `cheap_sphere_block`'s).
    let (t1, t2, n) = (f.t1, f.t2, f.n);
    let q_world = t1 * q_x + t2 * q_y;
    let limit = F::splat((1.0 - 1e-9) * pm.mu) * f.p_el;
    let mu_finite = finite(pm.mu);
    let sliding = (q_x * q_x + q_y * q_y).ge(limit * limit);
    let f_p = q_world - n * f.p_tot;
    let nf = t2 * q_x - t1 * q_y;
    let v0 = V {
        x: zero,
        y: zero,
        z: zero,
    };
    let torque_p = nf * f.rho_p - v0;
    let torque_q = nf * f.rho_q + v0;
    *out = SphereForceLanes {
        force_p: f_p.store(),
        torque_p: torque_p.store(),
        torque_q: torque_q.store(),
        sliding: std::array::from_fn(|l| mu_finite && bits(sliding.0[l]) != 0),
        creep_displacement: [cx.0, cy.0],
        damping: f.damping.0,
        slip: slip.0,
        creep: creep.0,
        truncation: truncation.0,
    };
    done
}

/// One lane's bodies of a wall contact: the wall p (a plane through `point` with unit
/// `normal` towards the sphere, moving at `velocity`, not turning, immovable) and the sphere q.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct WallSphere {
    /// A point of the wall's plane \[m\].
    pub point: Vec3,
    /// The wall's unit normal, towards the sphere [-].
    pub normal: Vec3,
    /// Velocity of the wall [m/s].
    pub velocity: Vec3,
    /// Centre of q \[m\].
    pub xq: Vec3,
    /// Velocity of q [m/s].
    pub vq: Vec3,
    /// Angular velocity of q [rad/s].
    pub wq: Vec3,
    /// Radius of q \[m\].
    pub rq: f64,
    /// Mass of q \[kg\].
    pub mq: f64,
}

/// The bodies of [`LANES`] wall contacts, lane by lane (structure of arrays).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct WallLanes {
    point: [[f64; LANES]; 3],
    normal: [[f64; LANES]; 3],
    velocity: [[f64; LANES]; 3],
    xq: [[f64; LANES]; 3],
    vq: [[f64; LANES]; 3],
    wq: [[f64; LANES]; 3],
    rq: [f64; LANES],
    mq: [f64; LANES],
}

impl WallLanes {
    /// Sets lane `l` (< [`LANES`]; panics otherwise) to the contact `s`.
    #[inline(always)]
    pub fn set(&mut self, l: usize, s: &WallSphere) {
        assert!(l < LANES, "lane {l} of {LANES}");
        put_lane(&mut self.point, l, s.point);
        put_lane(&mut self.normal, l, s.normal);
        put_lane(&mut self.velocity, l, s.velocity);
        put_lane(&mut self.xq, l, s.xq);
        put_lane(&mut self.vq, l, s.vq);
        put_lane(&mut self.wq, l, s.wq);
        self.rq[l] = s.rq;
        self.mq[l] = s.mq;
    }

    /// Copies lane `from` into lane `to` (to fill the unused lanes of a block).
    #[inline]
    pub fn copy_lane(&mut self, from: usize, to: usize) {
        copy_lanes(
            [
                &mut self.point,
                &mut self.normal,
                &mut self.velocity,
                &mut self.xq,
                &mut self.vq,
                &mut self.wq,
            ],
            from,
            to,
        );
        for a in [&mut self.rq, &mut self.mq] {
            a[to] = a[from];
        }
    }
}

/// The outputs of [`wall_block_lanes`], lane by lane: those of
/// [`PairForces`](super::PairForces) a DEM host uses for a wall contact.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct WallForceLanes {
    /// Force on the wall \[N\] (`-force_p` on the sphere), by component.
    pub force_p: [[f64; LANES]; 3],
    /// Torque on the sphere about its centre [N m], by component.
    pub torque_q: [[f64; LANES]; 3],
    /// Whether the contact is at the Coulomb limit.
    pub sliding: [bool; LANES],
    /// Whether the contact crept (a creep displacement not zero).
    pub creeping: [bool; LANES],
    /// Energy dissipated by the normal damping \[J\].
    pub damping: [f64; LANES],
    /// Energy dissipated by micro-slip and gross slip \[J\].
    pub slip: [f64; LANES],
    /// Energy dissipated by creep \[J\].
    pub creep: [f64; LANES],
    /// Energy added by the tier's simplifications \[J\].
    pub truncation: [f64; LANES],
}

impl WallForceLanes {
    /// Lane `l`'s dissipation (`rolling` zero: the block takes no rolling resistance).
    #[inline(always)]
    pub fn dissipation(&self, l: usize) -> PairDissipation {
        PairDissipation {
            damping: self.damping[l],
            slip: self.slip[l],
            creep: self.creep[l],
            rolling: 0.0,
            truncation: self.truncation[l],
        }
    }
}

/// The step of [`LANES`] sphere-wall contacts, either tier, with the same constants `c` (which
/// [`block_supports`]), bodies `walls` and histories `hist[idx[l]]` (none virgin; the first
/// `used` lanes are contacts, the others repeat one of them and are not written), time step
/// `dt` \[s\]: [`pair_force`](super::pair_force) with the wall as p (a
/// [`Surface::Plane`] at the contact point, moving at the wall's velocity, not turning, of
/// infinite mass) and the sphere as q, on the geometry
/// [`ContactGeometry::plane_sphere`](super::ContactGeometry::plane_sphere), operation for
/// operation (the terms of the wall's zero angular velocity included, so that the signs of
/// zeros are the kernel's). The geometry, the rates, the carried basis, Hertz + Tsuji and the
/// outputs run on the lanes at once, the tangential law lane by lane (the tier's own step: a
/// frictionless wall's is a few operations). For each lane whose bit the returned mask sets,
/// its history is updated and `out` holds its outputs, the same bits as the one-contact kernel
/// (test `wall_block_equals_the_one_contact_kernel`); the others (apart, a normal that
/// turned far, an unloaded contact, a non-finite value) are left as they were, for the
/// caller's one-contact kernel.
#[inline(always)]
pub fn wall_block_lanes<T: TangentialLaw>(
    c: &PairConstants,
    walls: &WallLanes,
    hist: &mut [ContactHistory<T>],
    idx: [usize; LANES],
    used: usize,
    dt: f64,
    out: &mut WallForceLanes,
) -> u32 {
    if c.rolling.is_some() {
        return 0;
    }
    let pm = &c.material;
    let creep_on = c.creep.is_some();
    let big = Big::new();
    let zero = F::splat(0.0);
    let v0 = V {
        x: zero,
        y: zero,
        z: zero,
    };
    let x0 = V::load(&walls.point);
    let n = V::load(&walls.normal);
    let xq = V::load(&walls.xq);
    let vq = V::load(&walls.vq);
    let wq = V::load(&walls.wq);
    let (rq, mq) = (F(walls.rq), F(walls.mq));

    // Geometry (`ContactGeometry::plane_sphere`).
    let dist = (xq - x0).dot(n);
    let delta = rq - dist;
    let closest = xq - n * dist;
    let cp = closest - n * (delta * 0.5);
    // `m*` is the sphere's mass where it can move (the wall cannot), `R*` its radius
    // (`PairBody::reduced_mass`, `PairConstants::pair_material`).
    let ok = delta
        .gt(zero)
        .and(mq.gt(zero))
        .and(mq.finite(big))
        .and(rq.finite(big));

    // Kuhn & Bagi's rates, the general form (`contact_rates_and_approach`, plane p).
    // The wall's arm to the contact point: the point less the wall body's position, which is
    // the contact point itself (zero where finite, as the kernel computes it).
    #[allow(clippy::eq_op)]
    let arm_p = cp - cp;
    let up = V::load(&walls.velocity) + v0.cross(arm_p);
    let uq = vq + wq.cross(cp - xq);
    let du = uq - up;
    let v_disp = du - n * du.dot(n);
    let rho_q = (xq - cp).dot(n);
    let c_dot = vq - v0.cross(n) * rho_q;
    let mid = (up + uq) * F::splat(0.5) - c_dot;
    let v_roll = mid - n * mid.dot(n);
    let delta_dot = du.dot(n).neg();

    // The carried basis.
    let (t1, ok) = {
        let h: [&ContactHistory<T>; LANES] = std::array::from_fn(|l| &hist[idx[l]]);
        carried_t1(&h, n, (v0 + wq).dot(n) * 0.5, dt, ok)
    };
    let t2 = n.cross(t1);

    // Normal force: Hertz + Tsuji, never attractive.
    let a = (rq * delta).sqrt();
    let e43 = 4.0 / 3.0 * pm.e_star;
    let p_el = F::splat(e43) * a * delta;
    let damp = F::splat(c.alpha) * (F::splat(e43) * mq * a).sqrt();
    let p_try = p_el + damp * delta_dot;
    let p_tot = p_try.gt(zero).sel(p_try, zero);
    let damping = (p_tot - p_el) * delta_dot * dt;

    // Tangential displacements in the basis.
    let ud = v_disp * F::splat(dt);
    let (dux, duy) = (ud.dot(t1), ud.dot(t2));
    let (drx, dry) = if creep_on {
        let ur = v_roll * F::splat(dt);
        (ur.dot(t1), ur.dot(t2))
    } else {
        (zero, zero)
    };
    let ok = ok
        .and(dux.finite(big))
        .and(duy.finite(big))
        .and(p_el.gt(zero))
        .and(a.gt(zero))
        .and(p_el.finite(big))
        .and(a.finite(big))
        .0;

    // The tangential law, lane by lane.
    let (mut q_x, mut q_y) = (zero, zero);
    let mut creeping = [false; LANES];
    let (mut slip, mut creep, mut truncation) = (zero, zero, zero);
    let mut done = 0;
    // The basis lane by lane from arrays stored once (extracting a lane from the vectors in the
    // loop stored them again at every lane).
    let (t1a, na) = (t1.store(), n.store());
    for l in 0..used.min(LANES) {
        if bits(ok[l]) == 0 {
            continue;
        }
        done |= 1 << l;
        let lane_pm = c.pair_material(Surface::Plane, Surface::Sphere(walls.rq[l]));
        let hl = &mut hist[idx[l]];
        let s = T::step(
            &mut hl.tangential,
            c,
            &lane_pm,
            p_el.0[l],
            a.0[l],
            Vec2::new(dux.0[l], duy.0[l]),
            Vec2::new(drx.0[l], dry.0[l]),
        );
        (q_x.0[l], q_y.0[l]) = (s.q.x, s.q.y);
        creeping[l] = s.creep_displacement != Vec2::ZERO;
        (slip.0[l], creep.0[l], truncation.0[l]) = (s.slip, s.creep, s.truncation);
        hl.t1 = lane3(&t1a, l);
        hl.normal = lane3(&na, l);
        hl.overlap = delta.0[l];
    }

    // Outputs (the one-contact kernel's general forms: the wall's arm is not along the normal
    // through a centre).
    let q_world = t1 * q_x + t2 * q_y;
    let limit = F::splat((1.0 - 1e-9) * pm.mu) * p_el;
    let mu_finite = finite(pm.mu);
    let sliding = (q_x * q_x + q_y * q_y).ge(limit * limit);
    let f_p = q_world - n * p_tot;
    let f_q = V {
        x: f_p.x.neg(),
        y: f_p.y.neg(),
        z: f_p.z.neg(),
    };
    let torque_q = (cp - xq).cross(f_q) + v0;
    *out = WallForceLanes {
        force_p: f_p.store(),
        torque_q: torque_q.store(),
        sliding: std::array::from_fn(|l| mu_finite && bits(sliding.0[l]) != 0),
        creeping,
        damping: damping.0,
        slip: slip.0,
        creep: creep.0,
        truncation: truncation.0,
    };
    done
}
