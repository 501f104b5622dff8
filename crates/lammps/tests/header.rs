//! The checked-in C header `include/creep_lammps.h` is what cbindgen generates from the crate
//! now (so the C++ shim compiles against the real ABI). `CREEP_LAMMPS_BLESS=1` rewrites it.

use std::path::Path;

#[test]
fn c_header_is_current() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR"));
    let config = cbindgen::Config::from_file(dir.join("cbindgen.toml")).expect("cbindgen.toml");
    let mut generated = Vec::new();
    cbindgen::Builder::new()
        .with_crate(dir)
        .with_config(config)
        .generate()
        .expect("cbindgen generates the header")
        .write(&mut generated);
    let generated = String::from_utf8(generated).expect("utf-8");
    let path = dir.join("include/creep_lammps.h");
    if std::env::var_os("CREEP_LAMMPS_BLESS").is_some() {
        std::fs::write(&path, &generated).expect("write the header");
    }
    let current = std::fs::read_to_string(&path).unwrap_or_default();
    assert!(
        current == generated,
        "include/creep_lammps.h is stale: run `CREEP_LAMMPS_BLESS=1 cargo test -p creep-lammps --test header`"
    );
    for f in [
        "creep_lammps_model_new",
        "creep_lammps_model_free",
        "creep_lammps_history_len",
        "creep_lammps_compute",
        "CreepLammpsContact",
        "CreepLammpsOutput",
    ] {
        assert!(generated.contains(f), "{f} missing from the header");
    }
}
