//! The tangential tiers: the [`TangentialLaw`] trait, [`Exact`] (Cattaneo-Mindlin memory with
//! Kuhn's creep) and [`Cheap`] (incremental `8 G* a` spring capped at `mu P`, plus creep).

use super::block::{
    LANES, SphereForceLanes, SphereForces, SphereLanes, cheap_sphere_block_lanes,
    exact_sphere_block_lanes,
};
use super::kernel::finite;
use super::{ContactHistory, PairConstants};
use crate::LawError;
use crate::creep::{CreepInput, CreepLaw, CreepState};
use crate::kalker;
use crate::material::PairMaterial;
use crate::mindlin::{MINDLIN_FLAT_LEN, MindlinState};
use crate::steady_law::{CreepModel, SteadyLaw};
use crate::vector::Vec2;

/// What one tangential update did.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct TangentialStep {
    /// Tangential force on p from q after the step, in the contact's `(t1, t2)` \[N\].
    pub q: Vec2,
    /// Creep displacement of the step \[m\].
    pub creep_displacement: Vec2,
    /// Energy dissipated by micro-slip and gross slip \[J\].
    pub slip: f64,
    /// Energy dissipated by creep \[J\].
    pub creep: f64,
    /// Energy added by the model's simplifications \[J\] (see each tier).
    pub truncation: f64,
}

/// A tangential contact law: the generic parameter of [`pair_force`](super::pair_force).
pub trait TangentialLaw:
    Copy + Clone + Default + std::fmt::Debug + PartialEq + Send + Sync + 'static
{
    /// Per-contact history of the law (flat, `Copy`, all f64).
    type History: Copy + Clone + Default + std::fmt::Debug + PartialEq + Send + Sync;
    /// Name of the tier (`"exact"` or `"cheap"`).
    const NAME: &'static str;
    /// Number of `f64` of the flat history.
    const HISTORY_LEN: usize;
    /// Whether the tier implements the creep model (the cheap tier has no lag state).
    fn supports(model: Option<CreepModel>) -> bool;
    /// One step: elastic normal force `p` \[N\], contact radius `a` \[m\], displacements `du_disp`,
    /// `du_roll` \[m\] in the tangent basis (`du_roll` zero without creep).
    fn step(
        h: &mut Self::History,
        c: &PairConstants,
        pm: &PairMaterial,
        p: f64,
        a: f64,
        du_disp: Vec2,
        du_roll: Vec2,
    ) -> TangentialStep;
    /// The stored tangential force \[N\].
    fn force(h: &Self::History) -> Vec2;
    /// Elastic energy stored in the tangential spring(s) \[J\].
    fn elastic_energy(h: &Self::History, pm: &PairMaterial) -> f64;
    /// Writes the history into `out` (length [`TangentialLaw::HISTORY_LEN`]).
    fn write(h: &Self::History, out: &mut [f64]);
    /// Reads a history written by [`TangentialLaw::write`].
    fn read(v: &[f64]) -> Result<Self::History, LawError>;

    /// Whether the tier has a kernel of [`LANES`] sphere-sphere contacts at once
    /// ([`TangentialLaw::sphere_block`]).
    const HAS_BLOCK: bool = false;

    /// Whether a host that adds the block's lanes to its bodies as they come, without a buffer
    /// of outputs, should run [`TangentialLaw::sphere_block_lanes`] (the same bits either
    /// way). True for the cheap tier.
    const HAS_BLOCK_LANES: bool = false;

    /// Whether the block kernel pays only where four `f64` fit one vector register (AVX): a
    /// host's build for two-lane registers (SSE2) then runs the one-contact kernel (the same
    /// bits). False for both tiers.
    const BLOCK_NEEDS_WIDE: bool = false;

    /// [`LANES`] sphere-sphere contacts at once with constants `c`, bodies `pairs`, histories
    /// `hist[idx[l]]` (none virgin; lanes from `n` on repeat one of the first and are not
    /// written) and step `dt` \[s\]: the mask of the lanes done (their histories updated, their
    /// outputs in `out[idx[l]]`, the same bits as [`pair_force`](super::pair_force)'s); the others are
    /// left for the one-contact kernel. [`TangentialLaw::sphere_block_lanes`]'s lanes written to
    /// `out` (the tiers': [`cheap_sphere_block`](super::cheap_sphere_block) and
    /// [`exact_sphere_block`](super::exact_sphere_block)).
    #[inline(always)]
    fn sphere_block(
        c: &PairConstants,
        pairs: &SphereLanes,
        hist: &mut [ContactHistory<Self>],
        out: &mut [SphereForces],
        idx: [usize; LANES],
        n: usize,
        dt: f64,
    ) -> u32 {
        let mut lanes = SphereForceLanes::default();
        let done = Self::sphere_block_lanes(c, pairs, hist, idx, n, dt, &mut lanes);
        lanes.scatter(done, out, idx, n);
        done
    }

    /// [`TangentialLaw::sphere_block`] with the outputs lane by lane in `out` (lane `l` where
    /// the returned mask sets bit `l`). None by default (every lane left to the one-contact
    /// kernel); the cheap tier's is [`cheap_sphere_block_lanes`](super::cheap_sphere_block_lanes).
    #[inline(always)]
    fn sphere_block_lanes(
        c: &PairConstants,
        pairs: &SphereLanes,
        hist: &mut [ContactHistory<Self>],
        idx: [usize; LANES],
        n: usize,
        dt: f64,
        out: &mut SphereForceLanes,
    ) -> u32 {
        let _ = (c, pairs, hist, out, idx, n, dt);
        0
    }
}

/// Cattaneo-Mindlin with load-history memory (Popov & Heß's method of dimensionality reduction,
/// creep-law [`MindlinState`]) and Kuhn's (2011) creep term ([`CreepState`]): the exact tier.
/// `truncation` is [`crate::CreepStep::truncation_energy`] (>= 0).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Exact;

impl TangentialLaw for Exact {
    type History = CreepState;
    const NAME: &'static str = "exact";
    const HISTORY_LEN: usize = MINDLIN_FLAT_LEN + 4;

    #[inline]
    fn supports(_: Option<CreepModel>) -> bool {
        true
    }

    /// Always inlined (down to the Cattaneo-Mindlin update), so that a host's loop compiled
    /// for a wider instruction set compiles the memory update for it too (the same bits).
    #[inline(always)]
    fn step(
        h: &mut CreepState,
        c: &PairConstants,
        pm: &PairMaterial,
        p: f64,
        a: f64,
        du_disp: Vec2,
        du_roll: Vec2,
    ) -> TangentialStep {
        // The one call into CreepState.
        let model = c.creep.unwrap_or(CreepModel::Kuhn);
        let law = CreepLaw::from_parts(*pm, model, c.steady);
        let s = h.update(&law, CreepInput::new(p, du_disp, du_roll).with_radius(a));
        TangentialStep {
            q: s.q,
            creep_displacement: s.creep_displacement,
            slip: s.slip_dissipation,
            creep: s.creep_dissipation,
            truncation: s.truncation_energy,
        }
    }

    #[inline]
    fn force(h: &CreepState) -> Vec2 {
        h.force()
    }

    fn elastic_energy(h: &CreepState, pm: &PairMaterial) -> f64 {
        h.mindlin().elastic_energy(pm)
    }

    /// The block ([`exact_sphere_block`](super::exact_sphere_block)) exists and gives the
    /// one-contact kernel's bits, but hosts' loops that buffer its outputs do not take it: a
    /// contact's time is in its memory update, lane by lane, and gathering the lanes and
    /// buffering the outputs cost more than the shared vector front saves (measured in creep-dem's triaxial test with a buffer: 5 %
    /// slower with the block, with four-lane registers too).
    const HAS_BLOCK: bool = false;

    /// Without a buffer of outputs the block saves about 3 % of the instructions per contact of
    /// creep-dem's serial loop on a dense packing (the shared vector front), but no time that
    /// could be measured beside the one-contact loop: hosts keep the one-contact kernel.
    const HAS_BLOCK_LANES: bool = false;

    #[inline(always)]
    fn sphere_block_lanes(
        c: &PairConstants,
        pairs: &SphereLanes,
        hist: &mut [ContactHistory<Self>],
        idx: [usize; LANES],
        n: usize,
        dt: f64,
        out: &mut SphereForceLanes,
    ) -> u32 {
        exact_sphere_block_lanes(c, pairs, hist, idx, n, dt, out)
    }

    fn write(h: &CreepState, out: &mut [f64]) {
        out[..MINDLIN_FLAT_LEN].copy_from_slice(&h.mindlin().to_array());
        let [l0, l1] = h.lag();
        out[MINDLIN_FLAT_LEN..MINDLIN_FLAT_LEN + 4].copy_from_slice(&[l0.x, l0.y, l1.x, l1.y]);
    }

    fn read(v: &[f64]) -> Result<CreepState, LawError> {
        let mut m = [0.0; MINDLIN_FLAT_LEN];
        m.copy_from_slice(&v[..MINDLIN_FLAT_LEN]);
        let mindlin = MindlinState::from_array(&m)?;
        let l = &v[MINDLIN_FLAT_LEN..MINDLIN_FLAT_LEN + 4];
        if !l.iter().all(|x| x.is_finite()) {
            return Err(LawError::OutOfRange {
                name: "creep lag state",
                value: f64::NAN,
                range: "finite",
            });
        }
        Ok(CreepState::from_parts(
            mindlin,
            [Vec2::new(l[0], l[1]), Vec2::new(l[2], l[3])],
        ))
    }
}

/// History of the [`Cheap`] tier.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct CheapHistory {
    /// Tangential force on p from q \[N\], in the contact's `(t1, t2)`.
    pub q: Vec2,
    /// Spring stiffness `8 G* a` of the last step [N/m] (0: virgin).
    pub k: f64,
}

/// The cheap tier: an incremental no-slip spring of Mindlin's (1949) initial stiffness
/// `k_t = 8 G* a`, `Q += k_t du_eff`, scaled back onto `mu P_e` when it exceeds it (LAMMPS
/// `granular` `tangential mindlin/force`, Thornton et al. 2013's incremental form), with Kuhn's
/// creep term `du_eff = du_disp - F_ss(|Q|/(mu P)) Q/|Q| |du_roll|` (the explicit creep step is
/// capped at `|Q|/k_t`, the displacement that unloads the linear spring to zero, so creep relaxes
/// a force and never reverses it). Stored energy `|Q|^2 / (2 k_t)`; slip dissipation
/// `Q . (du_eff - dQ/k_t)` (>= 0); `truncation` books the change of the stored energy when `k_t`
/// changes at fixed `Q`, `|Q|^2 (1/k_t - 1/k_t,old) / 2` (signed: positive when the contact
/// shrinks). Refuses [`CreepModel::FittedTransient`] (no lag state).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Cheap;

impl TangentialLaw for Cheap {
    type History = CheapHistory;
    const NAME: &'static str = "cheap";
    const HISTORY_LEN: usize = 3;

    #[inline]
    fn supports(model: Option<CreepModel>) -> bool {
        model != Some(CreepModel::FittedTransient)
    }

    #[inline(always)]
    fn step(
        h: &mut CheapHistory,
        c: &PairConstants,
        pm: &PairMaterial,
        p: f64,
        a: f64,
        du_disp: Vec2,
        du_roll: Vec2,
    ) -> TangentialStep {
        if !(p > 0.0 && a > 0.0 && finite(p) && finite(a)) {
            let slip = Self::elastic_energy(h, pm);
            *h = CheapHistory::default();
            return TangentialStep {
                slip,
                ..TangentialStep::default()
            };
        }
        let k = pm.tangential_stiffness(a);
        let mu_p = pm.mu * p;
        let q_old = h.q;
        let q2 = q_old.length_squared();
        let truncation = if q2 > 0.0 && h.k > 0.0 {
            // `|Q|^2 (1/k - 1/k_old) / 2` with one division.
            0.5 * q2 * ((h.k - k) / (k * h.k))
        } else {
            0.0
        };
        let roll2 = du_roll.length_squared();
        let mut creep_vec = Vec2::ZERO;
        let mut creep_e = 0.0;
        if roll2 > 0.0 && q2 > 0.0 && finite(roll2) {
            // The creep displacement over |Q|, so that Q/|Q| needs no division of its own.
            let f = creep_per_force(&c.steady, q2, roll2.sqrt(), mu_p, pm.g, a, k);
            if f > 0.0 && finite(f) {
                creep_vec = q_old * f;
                creep_e = q2 * f;
            }
        }
        let du_eff = if finite(du_disp.x) && finite(du_disp.y) {
            du_disp - creep_vec
        } else {
            -creep_vec
        };
        let trial = q_old + du_eff * k;
        // `|trial| > mu P`, squared (both sides >= 0): the square root and the division only
        // for a sliding contact, in a function kept out of line so that the compiler does not
        // evaluate them for every contact and select (it did: 8 % of the plugin's run).
        let t2 = trial.length_squared();
        let (q, slip) = if t2 > mu_p * mu_p && finite(mu_p) {
            if mu_p == 0.0 {
                // A frictionless contact (e.g. a wall) slides at every step: with `t2 > 0`,
                // `mu_p / sqrt(t2)` is `mu_p` itself (a zero of its sign), so the same bits
                // without the call, whose spills cost more than the rest of the law.
                let q = trial * mu_p;
                (q, q.dot(trial - q) / k)
            } else {
                onto_coulomb_limit(trial, t2, mu_p, k)
            }
        } else {
            (trial, 0.0)
        };
        h.q = q;
        h.k = k;
        TangentialStep {
            q,
            creep_displacement: creep_vec,
            slip,
            creep: creep_e,
            truncation,
        }
    }

    #[inline]
    fn force(h: &CheapHistory) -> Vec2 {
        h.q
    }

    #[inline]
    fn elastic_energy(h: &CheapHistory, _: &PairMaterial) -> f64 {
        if h.k > 0.0 {
            0.5 * h.q.length_squared() / h.k
        } else {
            0.0
        }
    }

    const HAS_BLOCK: bool = true;

    const HAS_BLOCK_LANES: bool = true;

    #[inline(always)]
    fn sphere_block_lanes(
        c: &PairConstants,
        pairs: &SphereLanes,
        hist: &mut [ContactHistory<Self>],
        idx: [usize; LANES],
        n: usize,
        dt: f64,
        out: &mut SphereForceLanes,
    ) -> u32 {
        cheap_sphere_block_lanes(c, pairs, hist, idx, n, dt, out)
    }

    fn write(h: &CheapHistory, out: &mut [f64]) {
        out[..3].copy_from_slice(&[h.q.x, h.q.y, h.k]);
    }

    fn read(v: &[f64]) -> Result<CheapHistory, LawError> {
        if !(v[..3].iter().all(|x| x.is_finite()) && v[2] >= 0.0) {
            return Err(LawError::OutOfRange {
                name: "cheap tangential history",
                value: v[2],
                range: "finite, stiffness >= 0",
            });
        }
        Ok(CheapHistory {
            q: Vec2::new(v[0], v[1]),
            k: v[2],
        })
    }
}

/// The trial force `trial` (`|trial|^2 = t2 > mu_p^2`) scaled back onto the Coulomb limit
/// `mu_p` \[N\], and the slip dissipation of the step, `Q . (trial - Q) / k` \[J\] (stiffness `k`
/// \[N/m\]): the cheap tier's sliding case.
#[cold]
#[inline(never)]
fn onto_coulomb_limit(trial: Vec2, t2: f64, mu_p: f64, k: f64) -> (Vec2, f64) {
    let q = trial * (mu_p / t2.sqrt());
    (q, q.dot(trial - q) / k)
}

/// The cheap tier's creep displacement of one step divided by the stored force, `min(F_ss
/// |du_roll|, |Q|/k) / |Q|` \[1/N\] (`q2 = |Q|^2 > 0` \[N^2\], `roll = |du_roll| > 0` \[m\], Coulomb
/// limit `mu_p` \[N\], combined shear modulus `g` \[Pa\], contact radius `a` \[m\], spring stiffness
/// `k` \[N/m\]): the creep term subtracts `Q * creep_per_force(..)` from the displacement.
///
/// For Kuhn's law (Kalker 2000's closed form `F_ss = 3 mu P (1 - c)/(G a^2 C11)`,
/// `c = (1 - s)^(1/3)`, `s = |Q|/(mu P)`) with `0 < s <= 1` the identity `(1 - c)(1 + c + c^2) =
/// 1 - c^3 = s` gives `F_ss/|Q| = 3/(G a^2 C11 (1 + c + c^2))`: no cancellation in `1 - c`
/// (at small `s` this is closer to Kalker's linear limit `1/(G a^2 C11)` than `1 - c`,
/// which rounds to 0 below `s ~ 1e-16`) and, with the cap `|Q|/k` compared by a product, one
/// division for the result. The cube root is left as the fraction of its Halley step,
/// `c = t n/d` ([`kalker::cbrt_fraction`]), so that `1 + c + c^2 = (d^2 + t n d + (t n)^2)/d^2`
/// and the result's division is the step's too; `1 - s` is `(mu P - |Q|)/(mu P)` and the
/// reciprocal the cube root's polynomial needs is `mu P/(mu P - |Q|)`, two divisions that run
/// side by side: the chain from `mu P` to the result holds two divisions where it held four
/// (`1/(mu P)`, the cube root's `t/x` and Halley division, the result's; measured in the LAMMPS
/// plugin's profile, the samples piled up after the last two). Past the Coulomb limit
/// (`|Q| >= mu P`, `s` clamped to 1, `c = 0`)
/// `F_ss/|Q| = 3 mu P/(G a^2 C11 |Q|)`. Every other case (another steady law, `mu P` or `G
/// a^2` not finite and > 0) is [`kuhn_creepage`]'s, divided by `|Q|`. Test
/// `creep_per_force_equals_the_steady_law`.
#[inline(always)]
pub(super) fn creep_per_force(
    law: &SteadyLaw,
    q2: f64,
    roll: f64,
    mu_p: f64,
    g: f64,
    a: f64,
    k: f64,
) -> f64 {
    let ga2 = g * a * a;
    if let SteadyLaw::Kuhn { c11 } = *law
        && mu_p > 0.0
        && mu_p < f64::INFINITY
        && ga2 > 0.0
        && ga2 < f64::INFINITY
    {
        let q_abs = q2.sqrt();
        let gc = ga2 * c11;
        let (num, den) = if q_abs < mu_p {
            // `1 - s = (mu P - |Q|)/(mu P)` (the difference exact where `s >= 1/2`, Sterbenz)
            // and its reciprocal for the cube root's polynomial, two divisions side by side;
            // `c = t n/d` (the cube root's Halley step as a fraction), so `1 + c + c^2 =
            // (d^2 + t n d + (t n)^2)/d^2` and the creep term's one division takes the step's
            // too (all terms > 0: no cancellation).
            let diff = mu_p - q_abs;
            let (t, n, d) = kalker::cbrt_fraction(diff / mu_p, mu_p / diff);
            let tn = t * n;
            (3.0 * roll * (d * d), gc * (d * (d + tn) + tn * tn))
        } else {
            (3.0 * roll * mu_p, gc * q_abs)
        };
        // min(num/den, 1/k) with one division: num/den < 1/k <=> num k < den (all > 0).
        return if num * k < den { num / den } else { 1.0 / k };
    }
    let q_abs = q2.sqrt();
    (kuhn_creepage(law, q_abs, mu_p, g, a) * roll).min(q_abs / k) / q_abs
}

/// [`SteadyLaw::creepage_for_force`] inlined into the cheap tier: for Kuhn's law (Kalker's
/// closed form, Kalker 2000) with a finite Coulomb limit `mu_p > 0` \[N\] and a finite contact
/// `G a^2 > 0`, the same arithmetic, `3 mu P (1 - (1 - s)^(1/3)) / (G a^2 C11)` with
/// `s = |Q|/(mu P)` clamped to `[0, 1]` (bit for bit: test
/// `inlined_kuhn_creepage_equals_the_steady_law`), without the call and its checks on the hot
/// path; every other case goes to the steady law.
#[inline(always)]
pub(crate) fn kuhn_creepage(law: &SteadyLaw, q_abs: f64, mu_p: f64, g: f64, a: f64) -> f64 {
    let denom = g * a * a;
    if let SteadyLaw::Kuhn { c11 } = *law
        && mu_p > 0.0
        && mu_p < f64::INFINITY
        && denom > 0.0
        && denom < f64::INFINITY
        && q_abs >= 0.0
    {
        let q = q_abs.min(mu_p);
        let c = kalker::cbrt(1.0 - q / mu_p);
        return 3.0 * mu_p * (1.0 - c) / (denom * c11);
    }
    law.creepage_for_force(q_abs, mu_p, g, a)
}
