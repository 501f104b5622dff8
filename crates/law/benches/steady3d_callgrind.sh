#!/bin/bash
# Load-free cost of one variant of the steady3d bench: instructions per evaluation under
# callgrind (the bench's `--count CASE [--blend]` mode, 5 passes over its 4096 inputs in
# `count_batch`): the total per evaluation (with about 25 instructions of the bench's loop
# and closure) and `Steady3d::loads` inclusive (docs/CREEP3D.md, "Cost").
#
# usage: crates/law/benches/steady3d_callgrind.sh BENCH_BINARY CASE [--blend]
#   CASE: 0-4 (the bench's table cases) or fss
set -e
B=$1; shift
out=$(mktemp -d)
valgrind --tool=callgrind --callgrind-out-file="$out/cg.out" --toggle-collect='*count_batch*' \
  "$B" --count "$@" --passes 5 > "$out/log" 2>&1
n=$(grep -o '^[0-9]* evaluations' "$out/log" | cut -d' ' -f1)
ir=$(grep -E '^summary:|^totals:' "$out/cg.out" | head -1 | awk '{print $2}')
ld=$(callgrind_annotate --auto=yes "$out/cg.out" 2>/dev/null \
  | grep -E "=> .*Steady3d::loads \(" | head -1 | awk '{gsub(",","",$1); print $1}')
python3 -c "print('$*'.ljust(12), round($ir/$n, 1), round(${ld:-0}/$n, 1) if ${ld:-0} else '-')"
rm -rf "$out"
