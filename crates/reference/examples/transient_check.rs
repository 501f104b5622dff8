//! Checks of the transient solver: Mindlin's loading curve, convergence to steady rolling.
use creep_reference::bem::{
    Creepage, SolverOptions, SteadySolver, TransientInput, mindlin_loading,
    transient_hold_creepage, transient_hold_force,
};
use creep_reference::contact::CircularContact;
use creep_reference::mindlin::Mindlin;
use std::time::Instant;

fn main() {
    let n: usize = std::env::args()
        .nth(1)
        .and_then(|s| s.parse().ok())
        .unwrap_or(16);
    for nu in [0.0, 0.3] {
        let c = CircularContact::normalised(nu).unwrap();
        let t0 = Instant::now();
        let ratios: Vec<f64> = (1..=9).map(|i| i as f64 / 10.0).collect();
        let d = mindlin_loading(c, SolverOptions::with_grid(n), &ratios).unwrap();
        let g_star = c.g() / (2.0 * (2.0 - nu));
        let m = Mindlin::new(c.mu_p(), g_star, c.a()).unwrap();
        let errs: Vec<String> = ratios
            .iter()
            .zip(&d)
            .map(|(r, d)| format!("{:+.4}", d / m.loading_shift(*r).unwrap() - 1.0))
            .collect();
        println!(
            "nu={nu} N={n} mindlin rel err {:?} t={:.3}s",
            errs,
            t0.elapsed().as_secs_f64()
        );

        let opts = SolverOptions::with_grid(n);
        let mut st = SteadySolver::new(c, opts).unwrap();
        let h = st.grid().h();
        let xi = 0.3;
        let steady = st.solve(Creepage::longitudinal(xi)).unwrap();
        let t1 = Instant::now();
        let inp = TransientInput {
            contact: c,
            options: opts,
            step: h,
            steps: 3 * n,
        };
        let rec = transient_hold_creepage(&inp, Creepage::longitudinal(xi)).unwrap();
        let last = rec.last().unwrap();
        println!(
            "  hold creepage: steady {:.6}, transient after {} steps {:.6} (rolled {:.3} a) t={:.3}s; first steps {:?}",
            steady.fx,
            rec.len(),
            last.fx,
            last.rolled,
            t1.elapsed().as_secs_f64(),
            rec.iter()
                .take(6)
                .map(|r| format!("{:.3}", r.fx_over_mu_p))
                .collect::<Vec<_>>()
        );
        let t2 = Instant::now();
        let rec = transient_hold_force(&inp, steady.fx).unwrap();
        let last = rec.last().unwrap();
        println!(
            "  hold force {:.4}: steady creepage {xi}, transient {:.6} t={:.3}s; first {:?}",
            steady.fx,
            last.creepage,
            t2.elapsed().as_secs_f64(),
            rec.iter()
                .take(6)
                .map(|r| format!("{:.3}", r.creepage))
                .collect::<Vec<_>>()
        );
    }
}
