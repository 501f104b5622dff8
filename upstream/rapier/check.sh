#!/usr/bin/env bash
# Applies the patch series in this directory to rapier3d 0.36.1's source (from the cargo
# registry) in a scratch directory under target/, runs Rapier's own tests on it, and builds
# and tests the workspace against it without changing Cargo.toml:
#
#   1. copy rapier3d-0.36.1 from the registry (cargo fetch first if absent) into
#      target/rapier-patched/rapier3d-0.36.1, git init, give it a [workspace] of its own (it
#      sits inside ours), `git am` the series;
#   2. Rapier's tests on it: the library's unit tests and the tests/ files the series adds or
#      changes, plus a few of Rapier's contact and snapshot tests (RAPIER_TESTS=all: every
#      test that ships in the crate; see README.md for what ships);
#   3. the workspace against it, via
#      `cargo --config 'patch.crates-io.rapier3d.path="…"'`: creep-rapier's tests with the
#      feature `rapier-patched`, and the fast-rolling CI subset at Rapier's default four
#      substeps, plain Rapier and the plugin (creep-scenes' tests/rapier_substeps.rs;
#      ROLLING_TESTS=plain or =plugin runs one of the two, CREEP_MATRIX=full the 72 cases).
#
# Run time: 6.3 min of CPU on a 2-core x86-64 machine (23 min wall on a busy one), nearly all of it
# building (Rapier's tests: the scratch crate and its dependencies; the workspace: its own target
# directory); the tests themselves take under a minute.
#
# The patched source lives in target/rapier-patched/ (CREEP_RAPIER_SCRATCH overrides). Both
# builds use the workspace's target directory, so every dependency Rapier shares with the
# workspace (nalgebra, parry3d, ...) is built once: the patched rapier3d has another source
# than crates.io's, hence its own fingerprint, and the crates built on it (creep-rapier,
# creep-scenes) get their own too; the crates.io builds beside them are not touched.
# Cargo.lock is restored on exit (the patch rewrites rapier3d's entry while cargo runs).
set -euo pipefail
cd "$(dirname "$0")/../.."
root=$PWD
series_dir=$root/upstream/rapier
scratch=${CREEP_RAPIER_SCRATCH:-$root/target/rapier-patched}
version=0.36.1

registry_src() {
  ls -d "${CARGO_HOME:-$HOME/.cargo}"/registry/src/*/rapier3d-$version 2>/dev/null | head -n 1
}
src=$(registry_src)
if [ -z "$src" ]; then
  echo "== cargo fetch (rapier3d $version is not in the registry cache)"
  cargo fetch --locked
  src=$(registry_src)
fi
[ -n "$src" ] || { echo "rapier3d $version not found in the cargo registry" >&2; exit 1; }

echo "== apply the series to $src"
mkdir -p "$scratch"
rapier=$scratch/rapier3d-$version
rm -rf "$rapier"
cp -r "$src" "$rapier"
git_() { git -C "$rapier" -c user.name=check.sh -c user.email=check@localhost "$@"; }
git_ init -q
git_ add -A
git_ commit -q -m "rapier3d $version (crates.io)"
printf '\n[workspace]\n' >> "$rapier/Cargo.toml"
git_ commit -q -am "scratch: a workspace of its own"
git_ am -q "$series_dir"/0*.patch
git_ log --oneline "HEAD~$(ls "$series_dir"/0*.patch | wc -l)..HEAD"

echo "== Rapier's tests on the patched source"
# Start from the workspace's lockfile: the dependencies Rapier shares with the workspace keep
# the versions CI tests (and their builds are reused); cargo adds Rapier's dev-dependencies.
cp "$root/Cargo.lock" "$rapier/Cargo.lock"
(
  cd "$rapier"
  export CARGO_TARGET_DIR=${CARGO_TARGET_DIR:-$root/target}
  if [ "${RAPIER_TESTS:-}" = all ]; then
    # RAPIER_PROFILE=release: optimised (soft_bodies.rs alone runs 1.4 min so on a quiet 2-core
    # machine, more than half an hour in the debug profile).
    cargo test --no-fail-fast ${RAPIER_PROFILE:+--profile "$RAPIER_PROFILE"}
  else
    cargo test --lib
    cargo test --test ball_rolling_substeps --test speed_cap --test recycled_contact_modification \
      --test empty_manifold_hook --test total_contact_impulse --test contact_clustering --test snapshot_roundtrip \
      --test persistent_islands --test sleep_wake
  fi
)

echo "== the workspace against the patched Rapier"
cp Cargo.lock "$scratch/Cargo.lock.orig"
trap 'cp "$scratch/Cargo.lock.orig" "$root/Cargo.lock"' EXIT
patch_cfg="patch.crates-io.rapier3d.path=\"$rapier\""
cargo --config "$patch_cfg" test -p creep-rapier --features rapier-patched
cargo --config "$patch_cfg" test -p creep-scenes --features creep-rapier/rapier-patched \
  --test rapier_substeps -- --ignored --nocapture "${ROLLING_TESTS-}"
