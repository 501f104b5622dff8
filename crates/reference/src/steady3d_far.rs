//! Rays of creepage beyond creep-law's steady 3-D law's box (`|xi_n|, |eta_n| <= 2`, `|phi_n|
//! <= 4`), where the law blends the loads at the box's edge into full slip's: the directions
//! and cases of the checked-in boundary-element table `data/steady3d_far.csv` (example
//! `steady3d_far`).

/// Directions `(xi_n, eta_n, phi_n)` of the rays (scaled onto the box's surface by
/// [`ray_point`]): spin-dominated ones, whose pole lies inside the patch and keeps a sticking
/// zone far beyond the box, translation-dominated ones, and both signs of spin against a
/// lateral creepage.
pub const DIRS: [[f64; 3]; 10] = [
    [0.0, 0.1, 1.0],
    [0.0, 0.6, 1.0],
    [0.0, 0.6, -1.0],
    [0.3, 0.2, 1.0],
    [1.0, 0.0, 1.0],
    [0.0, 1.0, -0.5],
    [0.5, 0.5, -1.0],
    [0.2, -0.4, 1.0],
    [1.0, 1.0, 0.3],
    [0.05, 0.05, 1.0],
];

/// Multiples of the box's surface along each ray (`s = 1` on the surface).
pub const RAYS: [f64; 6] = [1.0, 1.5, 2.0, 3.0, 4.0, 8.0];

/// `(a/b, nu)` of the table: three where creep-law's boundary-element table covers the
/// contact, one where its fitted law answers.
pub const CASES: [(f64, f64); 4] = [(1.0, 0.3), (0.5, 0.25), (2.0, 0.5), (3.0, 0.3)];

/// The creepage at `s` times the direction `dir` scaled onto the box's surface.
pub fn ray_point(dir: [f64; 3], s: f64) -> [f64; 3] {
    let s0 = (dir[0].abs().max(dir[1].abs()) / 2.0).max(dir[2].abs() / 4.0);
    let k = s / s0;
    [dir[0] * k, dir[1] * k, dir[2] * k]
}
