#!/bin/bash
# Alternates builds of the steady3d bench (their `--time CASE` mode: one variant's CPU ns per
# evaluation, the median of 3 measurements of 1000 passes) in one script, ROUNDS rounds of
# CASE = fss, 1-4 (the bench's table cases) for each binary in turn; prints the medians per
# binary and case, and the load. For comparing two builds (e.g. main's and a branch's) on a
# loaded machine (docs/CREEP3D.md, "Cost").
#
# usage: crates/law/benches/steady3d_alternate.sh ROUNDS BENCH_BINARY_1 BENCH_BINARY_2 ...
# (the binaries: `cargo bench -p creep-law --bench steady3d --no-run` prints the path; copy
# each build's binary aside first)
set -e
R=$1; shift
out=$(mktemp)
for r in $(seq "$R"); do
  for b in "$@"; do
    for c in fss 1 2 3 4; do
      echo "$b $c $("$b" --time $c)" >> "$out"
    done
  done
done
python3 - "$out" "$@" <<'PY'
import sys, statistics as st
lines = [l.split() for l in open(sys.argv[1])]
cases = ["fss", "1", "2", "3", "4"]
print("binary".ljust(40), *[c.rjust(8) for c in cases])
for b in sys.argv[2:]:
    med = [st.median([float(l[2]) for l in lines if l[0] == b and l[1] == c]) for c in cases]
    print(b.ljust(40), *[("%.2f" % m).rjust(8) for m in med])
PY
uptime
rm "$out"
