/// Mindlin's no-slip law (mu -> infinity) for a sphere of mass `m`, radius `r` meeting a fixed
/// wall with normal speed `v_n` and tangential speed `v_t`, integrated here independently of
/// the plugin: Hertz normal motion, and the tangential force of the springs that entered the
/// contact while it grew, `Q = 8 G* (a U - integral_0^a U_in(x) dx)` (U: tangential displacement
/// of the contact point since first touch; `U_in(x)`: its value when the contact radius passed
/// x; Mindlin & Deresiewicz 1953 as mapped by Popov & Hess 2015, ch. 5). The force acts at the
/// middle of the overlap, `R - delta/2` below the centre. Returns the final tangential velocity
/// of the centre and the spin about z.
fn no_slip_reference(
    m: f64,
    r: f64,
    e_star: f64,
    g_star: f64,
    v_n: f64,
    v_t: f64,
    t_c: f64,
) -> (f64, f64) {
    let inertia = 0.4 * m * r * r;
    let k_h = 4.0 / 3.0 * e_star * r.sqrt();
    let h = t_c / 200_000.0;
    let (mut delta, mut dd) = (0.0f64, v_n);
    let (mut v, mut w) = (v_t, 0.0f64);
    let (mut u, mut integral, mut a_prev) = (0.0f64, 0.0f64, 0.0f64);
    let mut table: Vec<(f64, f64)> = vec![(0.0, 0.0)];
    let mut loading = true;
    for _ in 0..2_000_000 {
        let a = (r * delta.max(0.0)).sqrt();
        if loading && a >= a_prev {
            integral += u * (a - a_prev);
            table.push((a, integral));
        } else {
            loading = false;
            // Interpolate the loading table at a (the springs still attached).
            let i = table
                .partition_point(|&(x, _)| x < a)
                .clamp(1, table.len() - 1);
            let (x0, i0) = table[i - 1];
            let (x1, i1) = table[i];
            integral = if x1 > x0 {
                i0 + (i1 - i0) * (a - x0) / (x1 - x0)
            } else {
                i0
            };
        }
        a_prev = a;
        let q = -8.0 * g_star * (a * u - integral);
        let p = k_h * delta.max(0.0).powf(1.5);
        let arm = r - 0.5 * delta;
        // Symplectic Euler, forces at the start of the step.
        dd -= p / m * h;
        v += q / m * h;
        w += arm * q / inertia * h;
        delta += dd * h;
        u += (v + w * arm) * h;
        if delta <= 0.0 && dd < 0.0 {
            return (v, w);
        }
    }
    panic!("reference impact did not end");
}
