//! The pair law as LAMMPS sees it: per-pair-type constants built once ([`Model`]), two spheres'
//! state per contact ([`Contact`]), a flat history per contact, `dt` -> forces and torques.
//! [`Model::compute`] evaluates a batch; it is what the C ABI ([`crate::ffi`]) wraps and what the
//! reference driver ([`crate::driver`]) calls.

use creep_law::pair::{
    Cheap, ContactGeometry, ContactHistory, Exact, PairBody, PairConstants, TangentialLaw,
    pair_force,
};
use creep_law::rolling_torque::RollingModel;
use creep_law::{CreepModel, LawError, Material, Surface, Vec3};

/// Tangential tier of the law (both are creep-law's, see [`creep_law::pair`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Tier {
    /// Cattaneo-Mindlin with exact load-history memory and Kuhn's creep ([`Exact`]).
    Exact,
    /// Incremental spring of Mindlin's initial stiffness `8 G* a`, capped at `mu P`, with the
    /// same creep term ([`Cheap`]).
    Spring,
}

impl Tier {
    /// Number of `f64` of one contact's flat history for this tier.
    pub const fn history_len(self) -> usize {
        match self {
            Tier::Exact => ContactHistory::<Exact>::LEN,
            Tier::Spring => ContactHistory::<Cheap>::LEN,
        }
    }
}

/// Coefficients of one pair type, in SI like LAMMPS' `pair_style granular`
/// (`hertz/material E e nu`, `mindlin NULL 0 mu`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Settings {
    /// Young's modulus `E` (Pa) of both spheres; `G = E / (2 (1 + nu))`.
    pub young_modulus: f64,
    /// Poisson's ratio `nu` (-), in (-1, 0.5].
    pub poisson_ratio: f64,
    /// Coefficient of restitution `e` (-) that the Tsuji damping reproduces exactly.
    pub restitution: f64,
    /// Coulomb friction `mu` (-) (>= 0).
    pub friction: f64,
    /// Tangential tier.
    pub tier: Tier,
    /// Kuhn's creep term on (Kalker's `F_ss`) or off (plain Coulomb-Mindlin).
    pub creep: bool,
    /// Optional contact-torque rolling resistance (Ai et al. 2011), `None`: off.
    pub rolling: Option<RollingModel>,
}

/// A bad coefficient or history.
#[derive(Debug, thiserror::Error)]
pub enum ModelError {
    /// A material or law parameter was refused by creep-law.
    #[error("{0}")]
    Law(#[from] LawError),
    /// Young's modulus not finite and > 0.
    #[error("Young's modulus must be finite and > 0 Pa, got {0}")]
    Young(f64),
    /// A history buffer of the wrong length.
    #[error("history stride {got} does not match this tier's {want} doubles per contact")]
    Stride {
        /// Given.
        got: usize,
        /// Needed.
        want: usize,
    },
    /// The models of one batch use different tiers (so different history lengths).
    #[error("all models of one batch must use the same tangential tier")]
    MixedTiers,
    /// A sphere radius or mass that is not finite and > 0.
    #[error(
        "contact {index}: radius and mass must be finite and > 0 (radius {radius} m, mass {mass} kg)"
    )]
    Body {
        /// Index in the batch.
        index: usize,
        /// Radius (m).
        radius: f64,
        /// Mass (kg).
        mass: f64,
    },
    /// No model for a contact (a null pointer from C).
    #[error("contact {0}: no model (pair_coeff not set?)")]
    MissingModel(usize),
    /// The output buffer is shorter than the batch.
    #[error("output buffer holds {got} contacts, the batch has {want}")]
    Output {
        /// Given.
        got: usize,
        /// Needed.
        want: usize,
    },
    /// A wall normal that is not a unit vector.
    #[error("wall contact {0}: the wall normal must be a unit vector")]
    WallNormal(usize),
    /// A history offset whose row does not lie inside the history store.
    #[error(
        "contact {index}: history offset {offset} + stride {stride} exceeds the store's {len} doubles"
    )]
    Offset {
        /// Index in the batch.
        index: usize,
        /// The offset given (doubles).
        offset: usize,
        /// Doubles per contact.
        stride: usize,
        /// Length of the store (doubles).
        len: usize,
    },
    /// The offsets buffer is shorter than the batch.
    #[error("offsets buffer holds {got} entries, the batch has {want}")]
    Offsets {
        /// Given.
        got: usize,
        /// Needed.
        want: usize,
    },
    /// The time step is not finite and >= 0.
    #[error("time step must be finite and >= 0 s, got {0}")]
    TimeStep(f64),
    /// The environment's choice of compiled kernels is not understood
    /// ([`creep_dem::KERNELS_ENV`]).
    #[error("{0}")]
    Kernels(String),
    /// An atom index outside the host's atom arrays.
    #[error("contact {index}: atom index {atom} outside the {nall} atoms of the arrays")]
    AtomIndex {
        /// Index in the batch.
        index: usize,
        /// The atom index given.
        atom: i32,
        /// Atoms in the arrays (owned and ghost).
        nall: usize,
    },
    /// An atom type outside `1..=ntypes`.
    #[error("contact {index}: atom type {kind} outside 1..={ntypes}")]
    AtomType {
        /// Index in the batch.
        index: usize,
        /// The type found.
        kind: i32,
        /// Number of atom types of the model table.
        ntypes: usize,
    },
    /// A history slot outside the store.
    #[error("contact {index}: history slot {slot} outside the store's {len} slots")]
    Slot {
        /// Index in the batch.
        index: usize,
        /// The slot given.
        slot: i32,
        /// Slots in the store.
        len: usize,
    },
    /// The per-atom arrays of one call have different lengths (or more owned atoms than atoms).
    #[error("the per-atom arrays must all hold nall entries, and nlocal <= nall")]
    AtomArrays,
    /// A position, velocity or angular velocity that is NaN or infinite.
    #[error("contact {index}: an atom's position, velocity or angular velocity is not finite")]
    AtomState {
        /// Index in the batch.
        index: usize,
    },
    /// A null atom array where atoms are needed.
    #[error("null per-atom array")]
    NullArray,
    /// An atom of a neighbour list (`ilist`) that is negative or outside the list's per-atom
    /// arrays (`numneigh`, `firstneigh`).
    #[error("neighbour list atom {0} outside the list's per-atom arrays")]
    ListAtom(i32),
    /// The host's per-entry arrays do not have one value per neighbour-list entry.
    #[error("the per-entry arrays hold {got} entries, the neighbour list has {want}")]
    ListEntries {
        /// Given (the shorter of the slot and swap arrays).
        got: usize,
        /// Entries of the list.
        want: usize,
    },
    /// A contact's history could not be read (corrupt or from another build).
    #[error("contact {index}: {source}")]
    History {
        /// Index in the batch.
        index: usize,
        /// Why.
        source: LawError,
    },
}

/// Constants of one pair type, built once by `pair_coeff`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Model {
    tier: Tier,
    constants: PairConstants,
}

/// One sphere of a contact (SI).
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Body {
    /// Centre (m).
    pub x: [f64; 3],
    /// Velocity (m/s).
    pub v: [f64; 3],
    /// Angular velocity (rad/s).
    pub omega: [f64; 3],
    /// Radius (m).
    pub radius: f64,
    /// Mass (kg).
    pub mass: f64,
}

/// One contact: sphere p and sphere q (the normal points from p to q).
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Contact {
    /// Body p.
    pub p: Body,
    /// Body q.
    pub q: Body,
}

/// One sphere against a plane wall (the wall is body p: the normal points from the wall into
/// the domain, towards the sphere).
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct WallContact {
    /// A point on the wall plane (m).
    pub point: [f64; 3],
    /// Unit normal of the wall, pointing into the domain (-).
    pub normal: [f64; 3],
    /// Velocity of the wall (m/s) (it does not rotate).
    pub wall_velocity: [f64; 3],
    /// The sphere (body q).
    pub sphere: Body,
}

/// What one contact gives back.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ContactOutput {
    /// Force on p (N) (`-force_p` on q).
    pub force_p: [f64; 3],
    /// Torque on p about its centre (N m).
    pub torque_p: [f64; 3],
    /// Torque on q about its centre (N m).
    pub torque_q: [f64; 3],
    /// 1 if the spheres overlap (the history is live), 0 if apart (history reset to virgin).
    pub touching: u32,
}

fn v3(a: [f64; 3]) -> Vec3 {
    Vec3::new(a[0], a[1], a[2])
}
fn arr(v: Vec3) -> [f64; 3] {
    [v.x, v.y, v.z]
}

impl Model {
    /// The constants of one pair type (both spheres of the same material). Errors for any
    /// coefficient creep-law refuses (`e` outside `[MIN_RESTITUTION, 1]`, `nu` outside
    /// (-1, 0.5], `mu < 0`, ...).
    pub fn new(s: &Settings) -> Result<Self, ModelError> {
        if !(s.young_modulus.is_finite() && s.young_modulus > 0.0) {
            return Err(ModelError::Young(s.young_modulus));
        }
        // G = E / (2 (1 + nu)) (isotropic elasticity); density plays no part in the pair law.
        let g = s.young_modulus / (2.0 * (1.0 + s.poisson_ratio));
        let m = Material::new(g, s.poisson_ratio, s.friction, 0.0)?;
        let creep = s.creep.then_some(CreepModel::Kuhn);
        let constants = PairConstants::new(&m, &m, s.friction, s.restitution, creep, s.rolling)?;
        Ok(Self {
            tier: s.tier,
            constants,
        })
    }

    /// The tier.
    pub fn tier(&self) -> Tier {
        self.tier
    }

    /// The pair constants (creep-law's), built once per pair type.
    pub(crate) fn constants(&self) -> &PairConstants {
        &self.constants
    }

    /// One contact: reads its `history` (length [`Tier::history_len`]), steps it by `dt` and
    /// writes it back. Apart spheres give zero output and a virgin (all-zero) history.
    pub fn step(
        &self,
        c: &Contact,
        history: &mut [f64],
        dt: f64,
    ) -> Result<ContactOutput, LawError> {
        match self.tier {
            Tier::Exact => self.step_tier::<Exact>(c, history, dt),
            Tier::Spring => self.step_tier::<Cheap>(c, history, dt),
        }
    }

    #[inline]
    fn step_tier<T: TangentialLaw>(
        &self,
        c: &Contact,
        history: &mut [f64],
        dt: f64,
    ) -> Result<ContactOutput, LawError> {
        let body = |b: &Body| PairBody {
            position: v3(b.x),
            velocity: v3(b.v),
            angular_velocity: v3(b.omega),
            surface: Surface::Sphere(b.radius),
            mass: b.mass,
        };
        let (p, q) = (body(&c.p), body(&c.q));
        let mut h = ContactHistory::<T>::read(history)?;
        let Some(g) =
            ContactGeometry::sphere_sphere(p.position, c.p.radius, q.position, c.q.radius)
        else {
            // Coincident centres: no normal; the contact is dropped.
            ContactHistory::<T>::default().write(history)?;
            return Ok(ContactOutput::default());
        };
        let f = pair_force(&self.constants, &p, &q, &g, &mut h, dt);
        h.write(history)?;
        Ok(ContactOutput {
            force_p: arr(f.force_p),
            torque_p: arr(f.torque_p),
            torque_q: arr(f.torque_q),
            touching: u32::from(f.touching),
        })
    }

    /// One sphere-wall contact (the wall is p, immovable for the damping's reduced mass): as
    /// [`Model::step`], with `force_p` the force on the wall and `torque_q` the torque on the
    /// sphere.
    pub fn step_wall(
        &self,
        c: &WallContact,
        history: &mut [f64],
        dt: f64,
    ) -> Result<ContactOutput, LawError> {
        match self.tier {
            Tier::Exact => self.step_wall_tier::<Exact>(c, history, dt),
            Tier::Spring => self.step_wall_tier::<Cheap>(c, history, dt),
        }
    }

    #[inline]
    fn step_wall_tier<T: TangentialLaw>(
        &self,
        c: &WallContact,
        history: &mut [f64],
        dt: f64,
    ) -> Result<ContactOutput, LawError> {
        let b = &c.sphere;
        let p = PairBody {
            position: v3(c.point),
            velocity: v3(c.wall_velocity),
            angular_velocity: Vec3::ZERO,
            surface: Surface::Plane,
            mass: f64::INFINITY,
        };
        let q = PairBody {
            position: v3(b.x),
            velocity: v3(b.v),
            angular_velocity: v3(b.omega),
            surface: Surface::Sphere(b.radius),
            mass: b.mass,
        };
        let mut h = ContactHistory::<T>::read(history)?;
        let g = ContactGeometry::plane_sphere(p.position, v3(c.normal), q.position, b.radius);
        let f = pair_force(&self.constants, &p, &q, &g, &mut h, dt);
        h.write(history)?;
        Ok(ContactOutput {
            force_p: arr(f.force_p),
            torque_p: arr(f.torque_p),
            torque_q: arr(f.torque_q),
            touching: u32::from(f.touching),
        })
    }

    /// A batch of sphere-wall contacts, as [`Model::compute`]; wall normals must be unit
    /// vectors (within 1e-9).
    pub fn compute_walls(
        models: &[&Model],
        dt: f64,
        contacts: &[WallContact],
        history: &mut [f64],
        stride: usize,
        out: &mut [ContactOutput],
    ) -> Result<(), ModelError> {
        Self::compute_walls_by(
            |k| models.get(k).copied(),
            dt,
            contacts,
            history,
            stride,
            out,
        )
    }

    /// [`Model::compute_walls`] with the model of contact `k` given by `model_of(k)`.
    pub(crate) fn compute_walls_by<'a>(
        model_of: impl Fn(usize) -> Option<&'a Model>,
        dt: f64,
        contacts: &[WallContact],
        history: &mut [f64],
        stride: usize,
        out: &mut [ContactOutput],
    ) -> Result<(), ModelError> {
        Self::batch(
            model_of,
            dt,
            contacts,
            history,
            stride,
            |k| k * stride,
            out,
            |k, m, c, h| {
                check_body(k, &c.sphere)?;
                let unit = (v3(c.normal).length() - 1.0).abs() <= 1e-9; // false for NaN too
                if !unit {
                    return Err(ModelError::WallNormal(k));
                }
                m.step_wall(c, h, dt)
                    .map_err(|source| ModelError::History { index: k, source })
            },
        )
    }

    /// A batch: contact `k` uses `models[k]`, its history is `history[k * stride ..][..stride]`
    /// and its result goes to `out[k]`. All models must share one tier and `stride` must be its
    /// [`Tier::history_len`]. Radii and masses must be finite and > 0. On error nothing after
    /// the failing contact is evaluated.
    pub fn compute(
        models: &[&Model],
        dt: f64,
        contacts: &[Contact],
        history: &mut [f64],
        stride: usize,
        out: &mut [ContactOutput],
    ) -> Result<(), ModelError> {
        Self::compute_by(
            |k| models.get(k).copied(),
            dt,
            contacts,
            history,
            stride,
            out,
        )
    }

    /// [`Model::compute`] with the model of contact `k` given by `model_of(k)` (`None`: a missing
    /// model, an error).
    pub(crate) fn compute_by<'a>(
        model_of: impl Fn(usize) -> Option<&'a Model>,
        dt: f64,
        contacts: &[Contact],
        history: &mut [f64],
        stride: usize,
        out: &mut [ContactOutput],
    ) -> Result<(), ModelError> {
        Self::batch(
            model_of,
            dt,
            contacts,
            history,
            stride,
            |k| k * stride,
            out,
            |k, m, c, h| {
                check_body(k, &c.p)?;
                check_body(k, &c.q)?;
                m.step(c, h, dt)
                    .map_err(|source| ModelError::History { index: k, source })
            },
        )
    }

    /// [`Model::compute`] with each contact's history in place in a store: contact `k` reads
    /// and rewrites `history[offsets[k]..][..stride]` (so a host keeps every history once, in
    /// its own order, and passes where each one is; LAMMPS' plugin passes its per-neighbour
    /// slots). Offsets are checked against the store (an error, not a panic); two contacts with
    /// the same offset step the same history one after the other.
    pub fn compute_at(
        models: &[&Model],
        dt: f64,
        contacts: &[Contact],
        history: &mut [f64],
        offsets: &[usize],
        stride: usize,
        out: &mut [ContactOutput],
    ) -> Result<(), ModelError> {
        Self::compute_at_by(
            |k| models.get(k).copied(),
            dt,
            contacts,
            history,
            offsets,
            stride,
            out,
        )
    }

    /// [`Model::compute_at`] with the model of contact `k` given by `model_of(k)`.
    pub(crate) fn compute_at_by<'a>(
        model_of: impl Fn(usize) -> Option<&'a Model>,
        dt: f64,
        contacts: &[Contact],
        history: &mut [f64],
        offsets: &[usize],
        stride: usize,
        out: &mut [ContactOutput],
    ) -> Result<(), ModelError> {
        if offsets.len() < contacts.len() {
            return Err(ModelError::Offsets {
                got: offsets.len(),
                want: contacts.len(),
            });
        }
        Self::batch(
            model_of,
            dt,
            contacts,
            history,
            stride,
            |k| offsets[k],
            out,
            |k, m, c, h| {
                check_body(k, &c.p)?;
                check_body(k, &c.q)?;
                m.step(c, h, dt)
                    .map_err(|source| ModelError::History { index: k, source })
            },
        )
    }

    /// The checks and the loop every batch shares: `dt`, the output size, one tier for all
    /// models, each history row inside the store; then `step(k, model, contact, history row)`
    /// for each contact in order, stopping at the first error. Contact `k`'s row starts at
    /// `offset(k)` (doubles).
    #[allow(clippy::too_many_arguments)]
    fn batch<'a, C>(
        model_of: impl Fn(usize) -> Option<&'a Model>,
        dt: f64,
        contacts: &[C],
        history: &mut [f64],
        stride: usize,
        offset: impl Fn(usize) -> usize,
        out: &mut [ContactOutput],
        mut step: impl FnMut(usize, &Model, &C, &mut [f64]) -> Result<ContactOutput, ModelError>,
    ) -> Result<(), ModelError> {
        if !(dt.is_finite() && dt >= 0.0) {
            return Err(ModelError::TimeStep(dt));
        }
        if contacts.is_empty() {
            return Ok(());
        }
        if out.len() < contacts.len() {
            return Err(ModelError::Output {
                got: out.len(),
                want: contacts.len(),
            });
        }
        let first = model_of(0).ok_or(ModelError::MissingModel(0))?;
        let want = first.tier.history_len();
        if stride != want {
            return Err(ModelError::Stride { got: stride, want });
        }
        let len = history.len();
        for (k, (c, o)) in contacts.iter().zip(out.iter_mut()).enumerate() {
            let m = model_of(k).ok_or(ModelError::MissingModel(k))?;
            if m.tier != first.tier {
                return Err(ModelError::MixedTiers);
            }
            let at = offset(k);
            let row = at
                .checked_add(stride)
                .and_then(|end| history.get_mut(at..end))
                .ok_or(ModelError::Offset {
                    index: k,
                    offset: at,
                    stride,
                    len,
                })?;
            *o = step(k, m, c, row)?;
        }
        Ok(())
    }
}

/// A body's radius and mass must be finite and > 0 (contact `k` of a batch).
fn check_body(k: usize, b: &Body) -> Result<(), ModelError> {
    if b.radius.is_finite() && b.radius > 0.0 && b.mass.is_finite() && b.mass > 0.0 {
        Ok(())
    } else {
        Err(ModelError::Body {
            index: k,
            radius: b.radius,
            mass: b.mass,
        })
    }
}
