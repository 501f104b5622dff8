//! Stress measurement: walls, Love-Weber contact stress, kinetic energy, contact shares.

use rapier3d::prelude::*;

use super::specimen::Specimen;

/// A contact counts as creeping when its creep displacement in a step is at least this share
/// of its sliding displacement (Kuhn's rule: the creep term then changes the tangential
/// increment by 10 % or more).
pub const CREEPING: f64 = 0.1;

/// A stress measurement.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub(super) struct Stress {
    /// Box dimensions between the walls' inner faces \[m\].
    pub(super) dims: [f64; 3],
    /// Wall stresses per axis \[Pa\].
    pub(super) walls: [f64; 3],
    /// Per-wall stress \[Pa\], index `2 axis + (side > 0)`.
    pub(super) each: [f64; 6],
    /// Love-Weber stress \[Pa\].
    pub(super) love: [[f64; 3]; 3],
    /// Normal contact stiffness summed over each wall's contacts [N/m] (Hertz:
    /// `dP/d delta = 1.5 P / delta`).
    pub(super) stiffness: [f64; 6],
}

impl Specimen {
    /// The stresses from the walls and from the contacts of the last step.
    pub(super) fn stress(&self) -> Stress {
        let dims = self.dims();
        let volume = dims[0] * dims[1] * dims[2];
        let mut each = [0.0; 6];
        let mut stiffness = [0.0; 6];
        let mut love = [[0.0; 3]; 3];
        let wall_of = |c: ColliderHandle| self.walls.iter().position(|w| w.collider == c);
        let bodies = &self.world.physics.bodies;
        let colliders = &self.world.physics.colliders;
        let centre = |c: ColliderHandle| {
            colliders
                .get(c)
                .and_then(|co| co.parent())
                .map(|b| bodies[b].translation())
                .map(|x| [f64::from(x.x), f64::from(x.y), f64::from(x.z)])
                .unwrap_or_default()
        };
        for (&(c1, c2), rec) in self.world.compliant().contacts() {
            // Force on p (collider1) from q.
            let f = rec.tangential_force - rec.normal * rec.normal_force;
            let f = [f.x, f.y, f.z];
            let point = [rec.point.x, rec.point.y, rec.point.z];
            let mut add = |arm: [f64; 3], force: [f64; 3]| {
                for i in 0..3 {
                    for j in 0..3 {
                        love[i][j] -= arm[i] * force[j] / volume;
                    }
                }
            };
            match (wall_of(c1), wall_of(c2)) {
                (None, None) => {
                    let (xp, xq) = (centre(c1), centre(c2));
                    add([xq[0] - xp[0], xq[1] - xp[1], xq[2] - xp[2]], f);
                }
                (Some(w), None) => {
                    // The ball is q and gets -f; the wall gets f.
                    let x = centre(c2);
                    add(
                        [point[0] - x[0], point[1] - x[1], point[2] - x[2]],
                        [-f[0], -f[1], -f[2]],
                    );
                    each[w] += self.walls[w].side * f[self.walls[w].axis];
                    stiffness[w] += 1.5 * rec.normal_force / rec.overlap;
                }
                (None, Some(w)) => {
                    let x = centre(c1);
                    add([point[0] - x[0], point[1] - x[1], point[2] - x[2]], f);
                    each[w] -= self.walls[w].side * f[self.walls[w].axis];
                    stiffness[w] += 1.5 * rec.normal_force / rec.overlap;
                }
                (Some(_), Some(_)) => {}
            }
        }
        let mut walls = [0.0; 3];
        for axis in 0..3 {
            let area = dims[(axis + 1) % 3] * dims[(axis + 2) % 3];
            each[2 * axis] /= area;
            each[2 * axis + 1] /= area;
            walls[axis] = 0.5 * (each[2 * axis] + each[2 * axis + 1]);
        }
        Stress {
            dims,
            walls,
            each,
            love,
            stiffness,
        }
    }

    /// Kinetic energy of the balls \[J\].
    pub(super) fn kinetic_energy(&self) -> f64 {
        self.balls
            .iter()
            .map(|&(b, _)| {
                let rb = &self.world.physics.bodies[b];
                let w = rb.angvel();
                let iw = rb.mass_properties().effective_angular_inertia() * w;
                0.5 * f64::from(rb.mass()) * f64::from(rb.linvel().length_squared())
                    + 0.5 * f64::from(w.dot(iw))
            })
            .sum()
    }

    /// Volume of the balls [m^3].
    pub(super) fn solids(&self) -> f64 {
        self.balls
            .iter()
            .map(|&(_, c)| {
                let r = f64::from(
                    self.world.physics.colliders[c]
                        .shape()
                        .as_ball()
                        .map_or(0.0, |b| b.radius),
                );
                4.0 / 3.0 * std::f64::consts::PI * r * r * r
            })
            .sum()
    }

    /// Contact statistics of the ball-ball contacts: (contacts, sliding, rolling, creeping).
    pub(super) fn contact_shares(&self) -> (usize, usize, usize, usize) {
        let is_wall = |c: ColliderHandle| self.walls.iter().any(|w| w.collider == c);
        let (mut n, mut sliding, mut rolling, mut creeping) = (0, 0, 0, 0);
        for (&(c1, c2), rec) in self.world.compliant().contacts() {
            if is_wall(c1) || is_wall(c2) {
                continue;
            }
            n += 1;
            sliding += usize::from(rec.sliding);
            creeping += usize::from(rec.creep_ratio >= CREEPING);
            rolling += usize::from(rec.v_roll.length() > rec.v_disp.length());
        }
        (n, sliding, rolling, creeping)
    }
}
