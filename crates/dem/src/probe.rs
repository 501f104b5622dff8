//! Per-contact forces for measurements (contact stress, contact shares): the pure kernel
//! re-evaluated on a copy of each touching contact's history, so the engine's state is not
//! changed and the step loop stores nothing more per contact.

use creep_law::Vec3;
use creep_law::kinematics::{BodyMotion, contact_rates_and_approach};
use creep_law::pair::{
    ContactGeometry, ContactHistory, PairBody, PairForces, TangentialLaw, pair_force,
};

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
            let bp = wall.body_at(geo.point);
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

/// One touching contact's load as the last force evaluation left it, as reported by
/// [`Dem::for_each_contact_load`]: what a stress measurement needs, without the tangential
/// law's update.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactLoad {
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
    /// Contact point \[m\].
    pub point: Vec3,
    /// Overlap \[m\].
    pub overlap: f64,
    /// Normal force on q along the normal \[N\], damping at the current velocities included
    /// (>= 0): the kernel's `normal_force`.
    pub normal_force: f64,
    /// Force on p from q \[N\]: the kernel's `force_p`, `Q - n P`.
    pub force_p: Vec3,
}

/// The load of a touching contact: the kernel's normal force (creep-law's `pair_force`: Hertz
/// `P_e = (4/3) E* a delta` with `a = sqrt(R* delta)`, Johnson 1985 §4.2, plus Tsuji's damping
/// `alpha sqrt((4/3) E* m* a) delta_dot`, never attractive) at the current velocities, and the
/// tangential force the history holds (`T::force`, in the basis the last evaluation stored).
/// Equal to [`pair_force`] with `dt = 0` where the geometry is that of the last evaluation
/// (a test checks it), at the cost of the geometry alone: no copy of the history, no update of
/// the tangential memory. `None` when the contact carries no force.
#[inline]
fn load<T: TangentialLaw>(
    c: &creep_law::pair::PairConstants,
    p: &PairBody,
    q: &PairBody,
    g: &ContactGeometry,
    h: &ContactHistory<T>,
) -> Option<(f64, Vec3)> {
    let delta = g.overlap;
    let inv_mass = |b: &PairBody| {
        if b.mass > 0.0 && b.mass.is_finite() {
            1.0 / b.mass
        } else {
            0.0
        }
    };
    let inv_sum = inv_mass(p) + inv_mass(q);
    let pm = c.pair_material(p.surface, q.surface);
    if !(delta > 0.0 && inv_sum > 0.0 && pm.r_star.is_finite()) || h.is_virgin() {
        return None;
    }
    let motion = |b: &PairBody| BodyMotion {
        position: b.position,
        velocity: b.velocity,
        angular_velocity: b.angular_velocity,
        surface: b.surface,
    };
    let (_, delta_dot) = contact_rates_and_approach(&motion(p), &motion(q), g.point, g.normal);
    let a = (pm.r_star * delta).sqrt();
    let e43 = 4.0 / 3.0 * pm.e_star;
    let p_el = e43 * a * delta;
    let m_star = 1.0 / inv_sum;
    let damp = c.alpha() * (e43 * m_star * a).sqrt();
    let p_tot = (p_el + damp * delta_dot).max(0.0);
    let q_world = T::force(&h.tangential).to_3d(h.t1, h.normal.cross(h.t1));
    Some((p_tot, q_world - g.normal * p_tot))
}

impl<T: TangentialLaw> Dem<T> {
    /// Calls `f` for every touching contact with the load it carries now ([`ContactLoad`]):
    /// the cheap form of [`Dem::for_each_contact_force`] with `dt = 0` for stress measurements
    /// every step (it reads the histories in place and does not run the tangential law).
    pub fn for_each_contact_load(&self, mut f: impl FnMut(ContactLoad)) {
        for i in 0..self.len() {
            for k in self.nl_start[i] as usize..self.nl_start[i + 1] as usize {
                let h = &self.nl_h[k];
                if h.is_virgin() {
                    continue;
                }
                let j = self.nl_j[k] as usize;
                let d = self.grid.min_image(self.x[j] - self.x[i]);
                let (p, q, dpq) = if self.id[i] < self.id[j] {
                    (i, j, d)
                } else {
                    (j, i, -d)
                };
                let xp = self.x[p];
                let xq = xp + dpq;
                let Some(geo) = ContactGeometry::sphere_sphere(xp, self.r[p], xq, self.r[q]) else {
                    continue;
                };
                let c = self.table.pair(self.mat[p] as usize, self.mat[q] as usize);
                if let Some((normal_force, force_p)) =
                    load(c, &self.body(p, xp), &self.body(q, xq), &geo, h)
                {
                    f(ContactLoad {
                        p: Some(self.id[p] as usize),
                        wall: None,
                        q: self.id[q] as usize,
                        x_p: xp,
                        x_q: xq,
                        point: geo.point,
                        overlap: geo.overlap,
                        normal_force,
                        force_p,
                    });
                }
            }
        }
        self.for_each_wall_contact_load(f);
    }

    /// [`Dem::for_each_contact_load`] for the particle-wall contacts only.
    pub fn for_each_wall_contact_load(&self, mut f: impl FnMut(ContactLoad)) {
        for e in 0..self.wl_i.len() {
            let h = &self.wl_h[e];
            if h.is_virgin() {
                continue;
            }
            let k = self.wl_k[e] as usize;
            let i = self.wl_i[e] as usize;
            let wall = self.walls[k];
            let geo = ContactGeometry::plane_sphere(wall.point, wall.normal, self.x[i], self.r[i]);
            let c = self.table.pair(wall.material, self.mat[i] as usize);
            let bp = wall.body_at(geo.point);
            if let Some((normal_force, force_p)) = load(c, &bp, &self.body(i, self.x[i]), &geo, h) {
                f(ContactLoad {
                    p: None,
                    wall: Some(k),
                    q: self.id[i] as usize,
                    x_p: geo.point,
                    x_q: self.x[i],
                    point: geo.point,
                    overlap: geo.overlap,
                    normal_force,
                    force_p,
                });
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use creep_law::{CreepModel, Material, Vec3};

    use crate::{Cheap, Dem, DemConfig, Exact, MaterialTable, Particle, TangentialLaw, Wall};

    /// A 4 x 4 x 4 cloud with friction and creep settling under a centrifuge's gravity onto a
    /// floor inside four side walls (one periodic axis), stepped until it is a packing with
    /// loaded, partly slipping contacts.
    fn settled<T: TangentialLaw>() -> Dem<T> {
        let glass = Material::new(29e6, 0.23, 0.5, 2500.0).unwrap();
        let r = 1e-3;
        let table = MaterialTable::new(&[glass], 0.5, Some(CreepModel::Kuhn), None).unwrap();
        let t_r = creep_law::hertz::rayleigh_time_step(&glass, 0.8 * r);
        let n = 4;
        let side = n as f64 * 2.2 * r;
        let mut ps = Vec::new();
        let mut s: u64 = 7;
        let mut rnd = || {
            s = s
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (s >> 11) as f64 / (1u64 << 53) as f64
        };
        for i in 0..n {
            for j in 0..n {
                for k in 0..n {
                    ps.push(Particle {
                        position: Vec3::new(
                            (i as f64 + 0.5) * 2.2 * r + 0.1 * r * rnd(),
                            (k as f64 + 0.5) * 2.2 * r + 0.1 * r * rnd(),
                            (j as f64 + 0.5) * 2.2 * r + 0.1 * r * rnd(),
                        ),
                        velocity: Vec3::new(rnd() - 0.5, rnd() - 0.5, rnd() - 0.5) * 0.05,
                        angular_velocity: Vec3::new(rnd() - 0.5, rnd() - 0.5, rnd() - 0.5) * 20.0,
                        radius: r * (0.8 + 0.2 * rnd()),
                        material: 0,
                    });
                }
            }
        }
        let wall = |point: Vec3, normal: Vec3| Wall {
            point,
            normal,
            velocity: Vec3::ZERO,
            material: 0,
        };
        let walls = [
            wall(Vec3::ZERO, Vec3::Y),
            wall(Vec3::ZERO, Vec3::X),
            wall(Vec3::new(side, 0.0, 0.0), -Vec3::X),
        ];
        let cfg = DemConfig {
            dt: 0.2 * t_r,
            skin: 0.2 * r,
            periodic: [None, None, Some((0.0, side))],
            gravity: Vec3::new(0.0, -300.0, 0.0),
            parallel: false,
        };
        let mut d = Dem::<T>::new(cfg, table, &ps, &walls).unwrap();
        for _ in 0..3000 {
            d.step().unwrap();
        }
        d
    }

    /// The cheap load equals the kernel re-evaluated with `dt = 0`, contact by contact.
    fn loads_are_the_kernels_forces<T: TangentialLaw>() {
        let d = settled::<T>();
        let mut forces = Vec::new();
        d.for_each_contact_force(0.0, |c| forces.push(c));
        let mut loads = Vec::new();
        d.for_each_contact_load(|c| loads.push(c));
        assert_eq!(forces.len(), loads.len());
        let walls = loads.iter().filter(|c| c.wall.is_some()).count();
        assert!(
            walls > 0 && loads.len() > walls,
            "{walls} of {}",
            loads.len()
        );
        let mut tangential = 0;
        for (f, l) in forces.iter().zip(&loads) {
            assert_eq!((f.p, f.wall, f.q), (l.p, l.wall, l.q));
            assert_eq!((f.x_p, f.x_q, f.overlap), (l.x_p, l.x_q, l.overlap));
            assert_eq!(f.forces.point, l.point);
            // Rounding: the two evaluate the same formulas, in a different order.
            let scale = f.forces.normal_force + f.forces.force_p.length();
            assert!((f.forces.normal_force - l.normal_force).abs() <= 1e-12 * scale);
            assert!(
                (f.forces.force_p - l.force_p).length() <= 1e-9 * scale,
                "{:?} vs {:?}",
                f.forces.force_p,
                l.force_p
            );
            tangential += usize::from(f.forces.tangential_force.length() > 1e-3 * scale);
        }
        // The packing's contacts carry friction: the tangential part is compared too.
        assert!(
            tangential > loads.len() / 4,
            "{tangential} of {}",
            loads.len()
        );
        let mut wall_loads = 0;
        d.for_each_wall_contact_load(|_| wall_loads += 1);
        assert_eq!(wall_loads, walls);
    }

    #[test]
    fn loads_are_the_kernels_forces_exact() {
        loads_are_the_kernels_forces::<Exact>();
    }

    #[test]
    fn loads_are_the_kernels_forces_cheap() {
        loads_are_the_kernels_forces::<Cheap>();
    }
}
