//! The virtual rows of creep-law's fast 3-D steady law between the rows of its table
//! (`creep_law::steady3d`, "Between rows"): for the validation table's axis and Poisson
//! ratios (and any given as `AB NU` pairs), the construction time of `Steady3d::new` and the
//! largest deviation of the one-row law from the two-row blend (`Steady3d::two_row_blend`)
//! over pure spin (`phi_n = 0.01 ... 30`) and over combined creepage (`|xi_n|, |eta_n| <= 0.6`,
//! `phi_n = 0.05 ... 3`, grids that are not the fit's), force over `mu P`, moment over `mu P c`.
//!
//! `cargo run --release -p creep-reference --example steady3d_virtual [-- AB NU ...]`
use std::time::Instant;

use creep_law::steady3d::Steady3d;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<f64> = std::env::args()
        .skip(1)
        .map(|a| a.parse::<f64>())
        .collect::<Result<_, _>>()?;
    let cases: Vec<(f64, f64)> = if args.is_empty() {
        vec![
            (0.35, 0.125),
            (0.7, 0.375),
            (0.27, 0.375),
            (0.85, 0.125),
            (1.4, 0.125),
            (3.0, 0.375),
        ]
    } else {
        args.chunks(2).map(|c| (c[0], c[1])).collect()
    };
    println!(
        "| a/b | nu | new [ms] | pure spin F | pure spin M | combined F (at) | combined M (at) |"
    );
    println!("|---|---|---|---|---|---|---|");
    for (ab, nu) in cases {
        let t = Instant::now();
        let law = Steady3d::new(ab, nu)?;
        let ms = t.elapsed().as_secs_f64() * 1e3;
        let blend = Steady3d::two_row_blend(ab, nu)?;
        let dev = |x: [f64; 3]| {
            let (a, b) = (law.loads(x[0], x[1], x[2]), blend.loads(x[0], x[1], x[2]));
            ((a.fx - b.fx).hypot(a.fy - b.fy), (a.mz - b.mz).abs())
        };
        let (mut sf, mut sm) = (0.0f64, 0.0f64);
        for k in 0..=70 {
            let phi = 0.01 * 3000f64.powf(k as f64 / 70.0);
            let (f, m) = dev([0.0, 0.0, phi]);
            sf = sf.max(f);
            sm = sm.max(m);
        }
        let (mut cf, mut cm) = ((0.0f64, [0.0; 3]), (0.0f64, [0.0; 3]));
        for i in -6..=6 {
            for j in -6..=6 {
                for k in 0..=12 {
                    let x = [
                        0.1 * i as f64,
                        0.1 * j as f64,
                        0.05 * 60f64.powf(k as f64 / 12.0),
                    ];
                    let (f, m) = dev(x);
                    if f > cf.0 {
                        cf = (f, x);
                    }
                    if m > cm.0 {
                        cm = (m, x);
                    }
                }
            }
        }
        let pct = |v: f64| format!("{:.2} %", 100.0 * v);
        let at = |x: [f64; 3]| format!("{:.2}, {:.2}, {:.3}", x[0], x[1], x[2]);
        println!(
            "| {ab} | {nu} | {ms:.1} | {} | {} | {} ({}) | {} ({}) |",
            pct(sf),
            pct(sm),
            pct(cf.0),
            at(cf.1),
            pct(cm.0),
            at(cm.1)
        );
    }
    Ok(())
}
