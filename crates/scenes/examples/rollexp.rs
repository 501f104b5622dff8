//! Temporary experiment: the fast-rolling matrix, summaries only.
use creep_scenes::hard_cases::fast_rolling::*;
fn main() {
    let substeps: usize = std::env::args()
        .nth(1)
        .map(|s| s.parse().unwrap())
        .unwrap_or(1);
    let filter: Vec<String> = std::env::args().skip(2).collect();
    let (mut pass, mut n) = (0, 0);
    for case in matrix() {
        let l = case.label();
        if !filter.iter().all(|f| l.contains(f.as_str())) {
            continue;
        }
        let o = case.run(substeps).unwrap();
        let (p, q) = (o.plugin, o.plain);
        n += 1;
        if o.passed() {
            pass += 1;
        }
        println!(
            "{} {}: plugin gain {:.1e} loss {:.1e} rise {:.1e} sink {:.1e} | plain gain {:.1e} loss {:.1e} rise {:.1e} sink {:.1e}",
            if o.passed() { "ok  " } else { "FAIL" },
            l,
            p.max_gain,
            p.loss,
            p.max_rise,
            p.max_sink,
            q.max_gain,
            q.loss,
            q.max_rise,
            q.max_sink
        );
    }
    println!("{pass}/{n} pass at {substeps} substeps");
}
