#!/usr/bin/env bash
# Side-by-side (interleaved) throughput of two plugin builds (issue #16) and LAMMPS' granular,
# on the exported 4,096-sphere packing with LAMMPS' walls, 1 rank. Each creepplugin.so is
# self-contained (the Rust kernel is linked in statically), so OLD may be any earlier build:
# e.g. the in-place shim of 2c0955e (creep_lammps_compute_at, a 22-double contact record
# gathered and the output scattered by the shim, each history read and written in its flat
# form per contact) against NEW, the store path (creep_lammps_compute_pairs).
#   crates/lammps/bench-ab.sh OLD.so NEW.so EXPORT_DIR [ROUNDS=5] [STEPS=300]
set -euo pipefail
OLD=$1 NEW=$2 PK=$3 ROUNDS=${4:-5} STEPS=${5:-300}
V=${CREEP_LAMMPS_VENV:?}
IN=$(cd "$(dirname "$0")" && pwd)/tests/lammps/in.bench
export OMP_NUM_THREADS=1
TSV=$(mktemp)
for r in $(seq "$ROUNDS"); do
  for v in "granular exact $NEW" "creep exact $OLD" "creep exact $NEW" "creep spring $OLD" "creep spring $NEW"; do
    set -- $v
    out=$("$V/bin/lmp" -var plugin "$3" -var params "$PK/params.lmp" -var data "$PK/packing.data" -var steps "$STEPS" \
      -var style "$1" -var tier "$2" -var walls 1 -in "$IN" -log none)
    t=$(grep -m1 -oE "Loop time of [0-9.e+-]+" <<< "$out" | awk '{print $4}')
    name=$1/$2/$([ "$3" = "$OLD" ] && echo old || echo new)
    [ "$1" = granular ] && name=granular
    echo -e "$r\t$name\t$t" | tee -a "$TSV"
  done
done
python3 - "$TSV" <<'PYEOF'
import sys, statistics
rows = [l.split() for l in open(sys.argv[1])]
names = list(dict.fromkeys(r[1] for r in rows))
med = {n: statistics.median(float(r[2]) for r in rows if r[1] == n) for n in names}
g = med["granular"]
for n in names:
    print(f"{n:20s} median loop {med[n]:.3f} s over {sum(r[1] == n for r in rows)} rounds, vs LAMMPS granular {g / med[n]:.3f}")
for t in ("exact", "spring"):
    print(f"tier {t}: new shim speed-up over old {med['creep/' + t + '/old'] / med['creep/' + t + '/new']:.2f}x")
PYEOF
