//! `creep triaxial --quick` stopped (as by Ctrl-C, by SIGINT, by SIGKILL) and resumed with
//! `--resume` gives the same CSVs, byte for byte, as the run that never stopped; a foreign or
//! damaged checkpoint is an error, never a fresh start.

use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};
use std::time::Duration;

fn creep() -> Command {
    Command::new(env!("CARGO_BIN_EXE_creep"))
}

fn dir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("creep-resume-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    d
}

fn run(args: &[&str]) -> Output {
    creep().args(args).output().expect("the creep binary runs")
}

fn text(o: &Output) -> String {
    format!(
        "stdout:\n{}\nstderr:\n{}",
        String::from_utf8_lossy(&o.stdout),
        String::from_utf8_lossy(&o.stderr)
    )
}

/// The results of a run: both shears' CSVs.
fn results(d: &Path) -> [Vec<u8>; 2] {
    ["triaxial_coulomb.csv", "triaxial_creep.csv"].map(|f| {
        std::fs::read(d.join(f)).unwrap_or_else(|e| panic!("{}: {e}", d.join(f).display()))
    })
}

/// Waits (up to ten minutes) until `path` exists.
fn wait_for(path: &Path, child: &mut std::process::Child) {
    for _ in 0..60_000 {
        if path.is_file() {
            return;
        }
        if let Ok(Some(status)) = child.try_wait() {
            panic!("the run ended ({status}) before writing {}", path.display());
        }
        std::thread::sleep(Duration::from_millis(10));
    }
    panic!("no {} after ten minutes", path.display());
}

/// Steps of the compaction and of each shear, from a finished run's SUMMARY.md.
fn steps(d: &Path) -> (u64, u64) {
    let s = std::fs::read_to_string(d.join("SUMMARY.md")).unwrap();
    let after = |key: &str| -> u64 {
        let rest = &s[s.find(key).unwrap_or_else(|| panic!("{key} in {s}")) + key.len()..];
        rest.trim_start()
            .split(|c: char| !c.is_ascii_digit())
            .next()
            .unwrap()
            .parse()
            .unwrap()
    };
    (
        after("Compaction (frictionless):"),
        after("| steps, run time |"),
    )
}

#[test]
fn a_stopped_quick_run_resumes_to_the_same_bits() {
    let straight = dir("straight");
    let o = run(&["triaxial", "--quick", "--out", straight.to_str().unwrap()]);
    assert!(o.status.success(), "{}", text(&o));
    let expected = results(&straight);
    let (compaction, shear) = steps(&straight);
    assert!(compaction > 100 && shear > 100, "{compaction} {shear}");
    assert!(!straight.join("checkpoint.ckpt").exists());

    // Stopped as Ctrl-C stops (the checkpoint at the next step boundary) in the compaction,
    // then in the creep shear, then run to the end. Each shear's engine counts on from the
    // compaction's steps.
    let b = dir("stopped");
    let bs = b.to_str().unwrap();
    let o = run(&[
        "triaxial",
        "--quick",
        "--out",
        bs,
        "--stop-at",
        &format!("compaction:{}", compaction / 2),
    ]);
    assert_eq!(o.status.code(), Some(2), "{}", text(&o));
    assert!(text(&o).contains("--resume"), "{}", text(&o));
    assert!(b.join("checkpoint.ckpt").is_file());
    let o = run(&[
        "triaxial",
        "--resume",
        bs,
        "--stop-at",
        &format!("shear_creep:{}", compaction + shear / 2),
    ]);
    assert_eq!(o.status.code(), Some(2), "{}", text(&o));
    assert!(text(&o).contains("shear_creep"), "{}", text(&o));
    // The Coulomb shear finished before the stop: its CSV is there already.
    assert_eq!(
        std::fs::read(b.join("triaxial_coulomb.csv")).unwrap(),
        expected[0]
    );
    let o = run(&["triaxial", "--resume", bs]);
    assert!(o.status.success(), "{}", text(&o));
    assert!(text(&o).contains("resuming"), "{}", text(&o));
    assert_eq!(results(&b), expected, "stopped twice and resumed");
    assert!(
        !b.join("checkpoint.ckpt").exists(),
        "a finished run removes its checkpoint"
    );
    let o = run(&["triaxial", "--resume", bs]);
    assert!(!o.status.success(), "nothing to resume: {}", text(&o));

    // Killed (SIGKILL) after its first periodic checkpoint, wherever it was then.
    let c = dir("killed");
    let mut child = creep()
        .args(["triaxial", "--quick", "--checkpoint-every", "300", "--out"])
        .arg(&c)
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .unwrap();
    wait_for(&c.join("checkpoint.ckpt"), &mut child);
    child.kill().unwrap();
    let status = child.wait().unwrap();
    assert!(!status.success());
    let o = run(&["triaxial", "--resume", c.to_str().unwrap()]);
    assert!(o.status.success(), "{}", text(&o));
    assert_eq!(results(&c), expected, "killed and resumed");

    // Interrupted (SIGINT, the Ctrl-C handler), with snapshots on.
    let d = dir("interrupted");
    let dump = d.join("dump");
    let mut child = creep()
        .args(["triaxial", "--quick", "--checkpoint-every", "200", "--out"])
        .arg(&d)
        .arg("--dump")
        .arg(&dump)
        .args(["--dump-every", "400"])
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    wait_for(&d.join("checkpoint.ckpt"), &mut child);
    let kill = Command::new("kill")
        .args(["-INT", &child.id().to_string()])
        .status()
        .unwrap();
    assert!(kill.success());
    let o = child.wait_with_output().unwrap();
    if o.status.success() {
        // The run ended before the signal came: nothing to resume, and the results stand.
        assert_eq!(results(&d), expected);
    } else {
        assert_eq!(o.status.code(), Some(2), "{}", text(&o));
        assert!(text(&o).contains("--resume"), "{}", text(&o));
        let o = run(&[
            "triaxial",
            "--resume",
            d.to_str().unwrap(),
            "--dump",
            dump.to_str().unwrap(),
            "--dump-every",
            "400",
        ]);
        assert!(o.status.success(), "{}", text(&o));
        assert_eq!(results(&d), expected, "interrupted and resumed");
    }
    for phase in ["compaction", "shear_coulomb", "shear_creep"] {
        let files: Vec<_> = std::fs::read_dir(dump.join(phase))
            .unwrap()
            .map(|e| e.unwrap().file_name().into_string().unwrap())
            .collect();
        assert!(
            files
                .iter()
                .any(|f| f.starts_with("particles.") && f.ends_with(".dump")),
            "{phase}: {files:?}"
        );
        // The .pvd series lists every .vtp frame, those of the stopped session too.
        let pvd = std::fs::read_to_string(dump.join(phase).join("particles.pvd")).unwrap();
        let vtp = files
            .iter()
            .filter(|f| f.starts_with("particles.") && f.ends_with(".vtp"))
            .count();
        assert_eq!(pvd.matches("<DataSet").count(), vtp, "{phase}: {pvd}");
    }
    for d in [straight, b, c, d] {
        std::fs::remove_dir_all(d).unwrap();
    }
}

#[test]
fn foreign_or_damaged_checkpoints_are_errors() {
    let e = dir("foreign");
    std::fs::create_dir_all(&e).unwrap();
    let es = e.to_str().unwrap();
    let ckpt = e.join("checkpoint.ckpt");
    std::fs::write(&ckpt, "ITEM: TIMESTEP\n0\n").unwrap();
    let o = run(&["triaxial", "--resume", es]);
    assert_eq!(o.status.code(), Some(2), "{}", text(&o));
    assert!(text(&o).contains("not a creep checkpoint"), "{}", text(&o));

    // A real checkpoint, then cut short and with a flipped byte.
    let o = run(&[
        "triaxial",
        "--quick",
        "--out",
        es,
        "--stop-at",
        "compaction:50",
    ]);
    assert_eq!(o.status.code(), Some(2), "{}", text(&o));
    let good = std::fs::read(&ckpt).unwrap();
    std::fs::write(&ckpt, &good[..good.len() / 2]).unwrap();
    let o = run(&["triaxial", "--resume", es]);
    assert!(text(&o).contains("damaged checkpoint"), "{}", text(&o));
    let mut flipped = good.clone();
    let k = flipped.len() / 3;
    flipped[k] ^= 1;
    std::fs::write(&ckpt, &flipped).unwrap();
    let o = run(&["triaxial", "--resume", es]);
    assert!(text(&o).contains("damaged checkpoint"), "{}", text(&o));
    // Flags that would change the run are refused with --resume.
    std::fs::write(&ckpt, &good).unwrap();
    let o = run(&["triaxial", "--resume", es, "--quick"]);
    assert!(!o.status.success(), "{}", text(&o));
    std::fs::remove_dir_all(&e).unwrap();
}
