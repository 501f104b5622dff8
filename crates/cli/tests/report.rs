//! `creep report --quick` through the built binary: the report, its CSVs and plots are written,
//! every number is finite, and the graded errors agree with the values the reference crate
//! documents (`crates/reference/README.md`, tables of `cargo run --release -p creep-reference
//! --example tier_errors`).

use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::process::Command;

fn creep() -> Command {
    Command::new(env!("CARGO_BIN_EXE_creep"))
}

/// A fresh directory under the system's temporary directory.
fn temp_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("creep-report-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// Rows of a CSV with a header, as maps from column name to field.
fn read_csv(path: &Path) -> Vec<HashMap<String, String>> {
    let text = std::fs::read_to_string(path).unwrap();
    let mut lines = text.lines();
    let header: Vec<String> = lines.next().unwrap().split(',').map(String::from).collect();
    lines
        .map(|l| {
            let f: Vec<&str> = l.split(',').collect();
            assert_eq!(f.len(), header.len(), "{}: {l}", path.display());
            header
                .iter()
                .cloned()
                .zip(f.into_iter().map(String::from))
                .collect()
        })
        .collect()
}

fn num(row: &HashMap<String, String>, col: &str) -> f64 {
    row[col]
        .parse()
        .unwrap_or_else(|_| panic!("{col}: {:?}", row[col]))
}

#[test]
fn quick_report_writes_finite_numbers_within_the_documented_bounds() {
    let dir = temp_dir("quick");
    let out = creep()
        .args(["report", "--quick", "--out"])
        .arg(&dir)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    for f in [
        "REPORT.md",
        "tiers_cost.csv",
        "tiers_errors.csv",
        "frontier.csv",
        "frontier.svg",
        "frontier.png",
    ] {
        assert!(dir.join(f).is_file(), "{f} missing");
    }
    let png = std::fs::read(dir.join("frontier.png")).unwrap();
    assert_eq!(&png[1..4], b"PNG");
    let md = std::fs::read_to_string(dir.join("REPORT.md")).unwrap();
    assert!(md.contains("| tier | cost per update |") && md.contains("frontier.png"));
    assert!(md.contains("Which tier for which scene"));

    // Seven tiers, each with a positive finite cost.
    let cost = read_csv(&dir.join("tiers_cost.csv"));
    assert_eq!(cost.len(), 7);
    for r in &cost {
        let c = num(r, "cost_ns_per_update");
        assert!(c.is_finite() && c > 0.0, "{r:?}");
    }

    // Every graded error is finite; a tier without a version of a case has empty fields.
    let errors = read_csv(&dir.join("tiers_errors.csv"));
    for r in &errors {
        if r["max_error"].is_empty() {
            assert!(r["rms_error"].is_empty());
            continue;
        }
        let (m, s) = (num(r, "max_error"), num(r, "rms_error"));
        assert!(
            m.is_finite() && s.is_finite() && s <= m * (1.0 + 1e-12),
            "{r:?}"
        );
    }
    let frontier = read_csv(&dir.join("frontier.csv"));
    let find = |tier: &str, case: &str| {
        let r = frontier
            .iter()
            .find(|r| r["tier"] == tier && r["case"] == case)
            .unwrap_or_else(|| panic!("{tier} / {case}"));
        let v = (num(r, "max_error"), num(r, "rms_error"));
        assert!(v.0.is_finite() && v.1.is_finite());
        v
    };
    // Kuhn's F_ss against the boundary elements at nu = 0.25: 9.8 % max, 4.4 % RMS
    // (crates/reference/README.md).
    let (m, s) = find("rigid-kuhn", "steady nu=0.25");
    assert!(m > 0.05 && m < 0.15, "Kuhn steady max {m}");
    assert!(s > 0.02 && s < 0.07, "Kuhn steady RMS {s}");
    // In steady rolling the compliant Kuhn update creeps at F_ss too.
    let (mc, _) = find("compliant-kuhn", "steady nu=0.25");
    assert!((mc - m).abs() < 1e-3 * m, "{mc} vs {m}");
    // The fitted law: within 1 % for Q/(mu P) <= 0.98 at every nu (creep-law's steady_law docs).
    for nu in ["0", "0.25", "0.3", "0.5"] {
        let (m, _) = find("rigid-fitted", &format!("steady nu={nu}"));
        assert!(m < 0.01, "fitted nu={nu}: {m}");
    }
    // Coulomb predicts no creep: the whole creepage is its error.
    assert_eq!(find("coulomb", "Carter line contact").0, 1.0);
    // The compliant tiers reproduce Mindlin & Deresiewicz's cycle (closed form of
    // creep-reference) to rounding.
    for t in ["compliant-kuhn", "fitted-transient"] {
        let (m, _) = find(t, "Mindlin load/unload/reload");
        assert!(m < 1e-9, "{t}: {m}");
    }
    // Held force: Kuhn's rule about 45 %, the transient tier 10-16 % (reference README).
    let (k, _) = find("compliant-kuhn", "transient held force");
    let (f, _) = find("fitted-transient", "transient held force");
    assert!(k > 0.35 && k < 0.55 && f < 0.2 && f < 0.5 * k, "{k} {f}");
    time_step_and_stability_sections(&dir, &md);
    scale_section(&dir, &md);
    // No line-contact version: not in the frontier.
    assert!(
        !frontier
            .iter()
            .any(|r| r["tier"] == "fastsim" && r["case"] == "Carter line contact")
    );
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn unwritable_output_is_an_error_not_a_panic() {
    let dir = temp_dir("bad");
    let file = dir.join("a-file");
    std::fs::write(&file, "x").unwrap();
    let out = creep()
        .args(["report", "--quick", "--out"])
        .arg(file.join("sub"))
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("error:") && !err.contains("panicked"), "{err}");
    std::fs::remove_dir_all(&dir).ok();
}

/// The time-step and stability sections of a `--quick` report in `dir` (`md`: its REPORT.md).
fn time_step_and_stability_sections(dir: &Path, md: &str) {
    assert!(md.contains("## Time step") && md.contains("## Stability"));
    for f in [
        "timestep.csv",
        "timestep_orders.csv",
        "timestep_rigid.png",
        "timestep_compliant.svg",
        "stability.csv",
    ] {
        assert!(dir.join(f).is_file(), "{f} missing");
    }
    // Six rigid steps and five compliant ones per quantity, every error finite.
    let points = read_csv(&dir.join("timestep.csv"));
    for r in &points {
        assert!(num(r, "relative_error").is_finite(), "{r:?}");
    }
    let count = |regime: &str| points.iter().filter(|r| r["regime"] == regime).count();
    assert_eq!(count("rigid") % 6, 0);
    assert_eq!(count("compliant") % 5, 0);
    // Observed orders: every fit finite; the elastic impact converges at second order
    // (symplectic Euler is a leap-frog in positions), the rigid incline's acceleration with a
    // positive order.
    let orders = read_csv(&dir.join("timestep_orders.csv"));
    assert_eq!(orders.len(), 8);
    for r in &orders {
        assert!(
            num(r, "observed_order").is_finite() && num(r, "r2") >= 0.0,
            "{r:?}"
        );
    }
    let order = |prefix: &str| {
        let r = orders
            .iter()
            .find(|r| r["quantity"].starts_with(prefix))
            .unwrap_or_else(|| panic!("{prefix}"));
        num(r, "observed_order")
    };
    for q in [
        "impact (e = 1): contact duration",
        "impact (e = 1): peak force",
        "impact (e = 1): rebound",
    ] {
        let k = order(q);
        assert!(k > 1.5 && k < 3.0, "{q}: {k}");
    }
    assert!(order("incline: acceleration") > 0.5);
    // The hard cases: each passes every check but the two engine limits, which fail one.
    let verdicts = read_csv(&dir.join("stability.csv"));
    let limits = ["rubber 1/60", "mass ratio 1000:1"];
    let mut cases: Vec<&str> = verdicts.iter().map(|r| r["case"].as_str()).collect();
    cases.dedup();
    assert_eq!(cases.len(), 8, "{cases:?}");
    for case in cases {
        let fails = verdicts
            .iter()
            .filter(|r| r["case"] == case && r["passed"] == "false")
            .count();
        assert_eq!(
            fails > 0,
            limits.contains(&case),
            "{case}: {fails} failing checks"
        );
    }
    assert!(md.contains("fail (engine limit)"));
}

/// The scale section of a `--quick` report in `dir`: the 1k and 4k piles, every time positive,
/// the settled piles' hooks off, and a finite positive growth exponent.
fn scale_section(dir: &Path, md: &str) {
    assert!(md.contains("## Scale") && md.contains("scale.png"));
    let rows = read_csv(&dir.join("scale.csv"));
    assert_eq!(rows.len(), 2);
    for r in &rows {
        for col in ["plain_step_s", "plugin_step_s", "ratio_median_of_pairs"] {
            let v = num(r, col);
            assert!(v.is_finite() && v > 0.0, "{col}: {r:?}");
        }
        // Settled below the activation speed: the plugin keeps every hook off.
        assert!(num(r, "max_speed_m_s") < 1e-2, "{r:?}");
        assert_eq!(num(r, "hooks_on"), 0.0, "{r:?}");
    }
    assert!(num(&rows[1], "active_contact_pairs") > 3.0 * num(&rows[0], "active_contact_pairs"));
    let fits = read_csv(&dir.join("scale_fit.csv"));
    assert_eq!(fits.len(), 2);
    for r in &fits {
        let k = num(r, "exponent_vs_contacts");
        assert!(k.is_finite() && k > 0.0, "{r:?}");
    }
    assert!(dir.join("scale.png").is_file());
}
