//! The fast-rolling matrix in Avian: a 0.1 m ball of steel, glass or rubber rolling freely at
//! 2, 5, 10 and 20 m/s, at dt = 1/30, 1/60 and 1/120 s, on a half-space and a flat triangle
//! mesh, at Avian's default 6 substeps (or `--substeps N`), with the plugin, the plugin with its
//! rotation-gap removal and plain Avian side by side: energy gained and lost (of E0), rise
//! and sinking of the centre from rest.
//!
//! `cargo run --release -p creep-avian --example fast_rolling --ignore-rust-version -- [--duration S] [--substeps N]`

use creep_avian::scenes::{DEFAULT_SUBSTEPS, fast_case, fast_matrix};

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let arg = |name: &str| {
        args.iter()
            .position(|a| a == name)
            .and_then(|i| args.get(i + 1))
            .and_then(|v| v.parse::<f64>().ok())
    };
    let duration = arg("--duration").unwrap_or(10.0);
    let substeps = arg("--substeps").map_or(DEFAULT_SUBSTEPS, |s| s as u32);
    println!(
        "fast rolling in Avian, {duration} s, {substeps} substeps; gain, loss of E0; rise, sink in mm"
    );
    println!(
        "| ground | material | v m/s | dt | plugin: gain, loss, rise, sink | gap removed | plain |"
    );
    println!("|---|---|---|---|---|---|---|");
    let (mut ok_plugin, mut ok_removed, mut ok_plain, mut n) = (0, 0, 0, 0);
    for case in fast_matrix() {
        let Some(o) = fast_case(case, duration, substeps) else {
            continue;
        };
        n += 1;
        ok_plugin += usize::from(o.plugin.within_bounds());
        ok_plain += usize::from(o.plain.within_bounds());
        ok_removed += usize::from(o.removed.within_bounds());
        let f = |s: &creep_avian::scenes::Summary| {
            format!(
                "{:.1e}, {:.1e}, {:.3}, {:.3}",
                s.max_gain,
                s.loss,
                1e3 * s.max_rise,
                1e3 * s.max_sink
            )
        };
        println!(
            "| {} | {} | {} | 1/{:.0} | {} | {} | {} |",
            case.ground.label(),
            case.material,
            case.speed,
            1.0 / case.dt,
            f(&o.plugin),
            f(&o.removed),
            f(&o.plain)
        );
    }
    println!(
        "within all bounds: plugin {ok_plugin} of {n}, gap removed {ok_removed} of {n}, plain Avian {ok_plain} of {n}"
    );
}
