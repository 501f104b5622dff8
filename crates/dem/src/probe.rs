//! Per-contact forces for measurements (contact stress, contact shares): the pure kernel
//! re-evaluated on a copy of each touching contact's history, so the engine's state is not
//! changed and the step loop stores nothing more per contact.

use creep_law::pair::{ContactGeometry, PairBody, PairForces, TangentialLaw, pair_force};
use creep_law::{Surface, Vec3};

use crate::Dem;

/// One touching contact with its forces, as reported by [`Dem::for_each_contact_force`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactForce {
    /// Particle id of p, or `None` when p is a wall.
    pub p: Option<usize>,
    /// Wall index when p is a wall.
    pub wall: Option<usize>,
    /// Particle id of q.
    pub q: usize,
    /// Centre of p \[m\] (for a wall: the contact's point on the wall plane).
    pub x_p: Vec3,
    /// Centre of q \[m\] (minimum image of p's partner under periodic axes).
    pub x_q: Vec3,
    /// Overlap \[m\].
    pub overlap: f64,
    /// The kernel's output ([`creep_law::pair::pair_force`]): `force_p` is the force on p
    /// from q \[N\].
    pub forces: PairForces,
}

impl<T: TangentialLaw> Dem<T> {
    /// Calls `f` for every touching contact with the pair kernel evaluated at the current
    /// positions and velocities on a copy of the contact's history, with a step of `dt` \[s\]:
    /// `dt = 0` gives the forces the contacts carry now (no tangential increment, the memory
    /// unchanged: the forces of the last evaluation); `dt > 0` the increments of one more step
    /// at the current velocities (sliding flag, creep displacement, `v_disp`, `v_roll`).
    pub fn for_each_contact_force(&self, dt: f64, mut f: impl FnMut(ContactForce)) {
        for i in 0..self.len() {
            for k in self.nl_start[i] as usize..self.nl_start[i + 1] as usize {
                if self.nl_h[k].is_virgin() {
                    continue;
                }
                let mut h = self.nl_h[k];
                let j = self.nl_j[k] as usize;
                if let Ok((p, q, out)) = self.pair(i, j, &mut h, dt) {
                    let x_p = self.x[p];
                    let x_q = x_p + self.grid.min_image(self.x[q] - x_p);
                    f(ContactForce {
                        p: Some(self.id[p] as usize),
                        wall: None,
                        q: self.id[q] as usize,
                        x_p,
                        x_q,
                        overlap: h.overlap,
                        forces: out,
                    });
                }
            }
        }
        self.for_each_wall_contact_force(dt, f);
    }

    /// [`Dem::for_each_contact_force`] for the particle-wall contacts only.
    pub fn for_each_wall_contact_force(&self, dt: f64, mut f: impl FnMut(ContactForce)) {
        for e in 0..self.wl_i.len() {
            if self.wl_h[e].is_virgin() {
                continue;
            }
            let mut h = self.wl_h[e];
            let k = self.wl_k[e] as usize;
            let i = self.wl_i[e] as usize;
            let wall = self.walls[k];
            let geo = ContactGeometry::plane_sphere(wall.point, wall.normal, self.x[i], self.r[i]);
            if !(geo.overlap > 0.0) {
                continue;
            }
            let c = self.table.pair(wall.material, self.mat[i] as usize);
            let bp = PairBody {
                position: geo.point,
                velocity: wall.velocity,
                angular_velocity: Vec3::ZERO,
                surface: Surface::Plane,
                mass: f64::INFINITY,
            };
            let out = pair_force(c, &bp, &self.body(i, self.x[i]), &geo, &mut h, dt);
            if out.touching {
                f(ContactForce {
                    p: None,
                    wall: Some(k),
                    q: self.id[i] as usize,
                    x_p: geo.point,
                    x_q: self.x[i],
                    overlap: geo.overlap,
                    forces: out,
                });
            }
        }
    }
}
