#!/usr/bin/env bash
# Side-by-side (interleaved) throughput of two plugin builds (issue #16) and LAMMPS' granular,
# on the exported 4,096-sphere packing with LAMMPS' walls, 1 rank. Each creepplugin.so is
# self-contained (the Rust kernel is linked in statically), so OLD may be any earlier build:
# e.g. the plugin before a change against the plugin after it. Each variant's loop time and
# LAMMPS' "CPU use" are recorded; the summary gives medians of both the wall loop time and the
# loop's CPU time (on a shared machine the latter is the steadier measure).
#   crates/lammps/bench-ab.sh OLD.so NEW.so EXPORT_DIR [ROUNDS=5] [STEPS=300]
# TIERS (default "exact spring") chooses the plugin's tiers, e.g. TIERS=spring for the quick
# comparison (the exact tier's runs take 5x longer).
# With OLD_REF and NEW_REF set (two builds of target/release/creep-lammps-ref, e.g. before and
# after a change of creep-law's kernel), each round also times creep-dem's cheap tier
# (`creep-lammps-ref dem ... spring`: the DEM engine, one thread, on the same packing made
# periodic, since the driver has no side walls) by its process CPU time, old against new.
set -euo pipefail
OLD=$1 NEW=$2 PK=$3 ROUNDS=${4:-5} STEPS=${5:-300}
V=${CREEP_LAMMPS_VENV:?}
IN=$(cd "$(dirname "$0")" && pwd)/tests/lammps/in.bench
export OMP_NUM_THREADS=1
TSV=$(mktemp)
PERIODIC=$(mktemp)
(cat "$PK/params.lmp"; echo "variable periodic equal 1") > "$PERIODIC"
for r in $(seq "$ROUNDS"); do
  if [ -n "${OLD_REF:-}" ] && [ -n "${NEW_REF:-}" ]; then
    for b in old new; do
      ref=$OLD_REF; [ $b = new ] && ref=$NEW_REF
      # "loop" = the process's user CPU time (the driver's set-up, the same for both, included).
      u=$( { /usr/bin/time -f "%U" "$ref" dem "$PK/packing.data" "$PERIODIC" "$STEPS" spring > /dev/null; } 2>&1 | tail -1)
      echo -e "$r\tdem/spring/$b\t$u\t100" | tee -a "$TSV"
    done
  fi
  variants=("granular exact $NEW")
  for tier in ${TIERS:-exact spring}; do variants+=("creep $tier $OLD" "creep $tier $NEW"); done
  for v in "${variants[@]}"; do
    set -- $v
    out=$("$V/bin/lmp" -var plugin "$3" -var params "$PK/params.lmp" -var data "$PK/packing.data" -var steps "$STEPS" \
      -var style "$1" -var tier "$2" -var walls 1 -in "$IN" -log none)
    t=$(grep -m1 -oE "Loop time of [0-9.e+-]+" <<< "$out" | awk '{print $4}')
    cpu=$(grep -m1 -oE "^[0-9.]+% CPU use" <<< "$out" | awk '{print $1}' | tr -d %)
    name=$1/$2/$([ "$3" = "$OLD" ] && echo old || echo new)
    [ "$1" = granular ] && name=granular
    echo -e "$r\t$name\t$t\t$cpu" | tee -a "$TSV"
  done
done
python3 - "$TSV" <<'PYEOF'
import sys, statistics
rows = [l.split() for l in open(sys.argv[1])]
names = list(dict.fromkeys(r[1] for r in rows))
med = {n: statistics.median(float(r[2]) for r in rows if r[1] == n) for n in names}
# The loop's CPU time (LAMMPS' "CPU use" x loop time): on a machine shared with other jobs the
# wall time mostly measures the competition for the cores, the CPU time much less so.
cpu = {n: statistics.median(float(r[2]) * float(r[3]) / 100 for r in rows if r[1] == n) for n in names}
g, gc = med["granular"], cpu["granular"]
for n in names:
    print(f"{n:20s} median loop {med[n]:.3f} s (CPU {cpu[n]:.3f} s) over {sum(r[1] == n for r in rows)} rounds, "
          f"vs LAMMPS granular {g / med[n]:.3f} (CPU time {gc / cpu[n]:.3f})")
for o, w in [("creep/exact/old", "creep/exact/new"), ("creep/spring/old", "creep/spring/new"),
             ("dem/spring/old", "dem/spring/new")]:
    if o in med:
        print(f"{o[:-4]}: new over old {med[o] / med[w]:.2f}x (CPU time {cpu[o] / cpu[w]:.2f}x)")
PYEOF
rm -f "$TSV" "$PERIODIC"
