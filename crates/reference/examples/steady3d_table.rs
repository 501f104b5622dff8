//! How closely creep-law's fast 3-D steady law between the rows of its table
//! (`creep_law::steady3d`, "Between rows": one translation on tabulated spin terms) follows
//! the law it tabulates, measured against the two rows' blended loads
//! (`Steady3d::two_row_blend`) on fine grids: pure spin `phi_n = 1e-4 ... 1e4` (3001 points,
//! lateral force over `mu P` and moment over `mu P c`), and combined creepage `|xi_n|, |eta_n|
//! <= 0.6`, `phi_n = 0.01 ... 8` (force and moment); largest and mean deviation per case.
//! For comparing table layouts (run it on each and diff the output).
//!
//! `cargo run --release -p creep-reference --example steady3d_table [-- AB NU ...]`
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
            (0.3, 0.5),
            (4.0, 0.0),
        ]
    } else {
        args.chunks(2).map(|c| (c[0], c[1])).collect()
    };
    println!(
        "| a/b | nu | pure spin Fy max (at phi_n) | mean | pure spin Mz max | combined F max | mean | combined M max |"
    );
    println!("|---|---|---|---|---|---|---|---|");
    for (ab, nu) in cases {
        let law = Steady3d::new(ab, nu)?;
        let blend = Steady3d::two_row_blend(ab, nu)?;
        let dev = |x: [f64; 3]| {
            let (a, b) = (law.loads(x[0], x[1], x[2]), blend.loads(x[0], x[1], x[2]));
            ((a.fx - b.fx).hypot(a.fy - b.fy), (a.mz - b.mz).abs())
        };
        let (mut sf, mut sat, mut smean, mut sm) = (0.0f64, 0.0, 0.0, 0.0f64);
        let n = 3000;
        for k in 0..=n {
            let phi = 1e-4 * 1e8f64.powf(k as f64 / n as f64);
            let (f, m) = dev([0.0, 0.0, phi]);
            if f > sf {
                (sf, sat) = (f, phi);
            }
            smean += f / (n + 1) as f64;
            sm = sm.max(m);
        }
        let (mut cf, mut cmean, mut cm, mut count) = (0.0f64, 0.0, 0.0f64, 0);
        for i in -12..=12 {
            for j in -12..=12 {
                for k in 0..=40 {
                    let x = [
                        0.05 * i as f64,
                        0.05 * j as f64,
                        0.01 * 800f64.powf(k as f64 / 40.0),
                    ];
                    let (f, m) = dev(x);
                    cf = cf.max(f);
                    cmean += f;
                    cm = cm.max(m);
                    count += 1;
                }
            }
        }
        println!(
            "| {ab} | {nu} | {:.3} % ({sat:.3}) | {:.4} % | {:.4} % | {:.3} % | {:.4} % | {:.4} % |",
            100.0 * sf,
            100.0 * smean,
            100.0 * sm,
            100.0 * cf,
            100.0 * cmean / count as f64,
            100.0 * cm
        );
    }
    Ok(())
}
