#!/bin/bash
# Two drumlab binaries (or one binary under two environments) on the same rolling state, for a
# change of a few per cent on a shared machine whose speed moves by more than that:
#
#   bash app/bench/ab_compare.sh BIN_A BIN_B [ROUNDS] [-- bench throughput options]
#
# MODE=together (default): each round runs A and B at the same time, one on each of cores 0 and
#   1, and swaps the cores in the next round, so both see the same host and a difference
#   between the two cores cancels over an even number of rounds.
# MODE=turns: each round runs A then B on core 0 (B then A in even rounds).
# Each run is `BIN bench throughput --threads 1 --repeats 1` with the options after `--`
# (default: --scene scenes/drum_deep.toml --methods verlet:mlgrid --steps 400); the cached rolling
# state must exist (run one of them once first). Prints each round's A and B in M p-steps/s and
# B/A, then the median of the rounds' B/A and the ratio of the sums. A against itself gave sums
# within 0.1 % over 6 rounds together (2026-12-03).
set -euo pipefail
a=${1:?BIN_A} b=${2:?BIN_B}
rounds=${3:-6}
shift $(($# < 3 ? $# : 3))
[ "${1-}" = -- ] && shift
opts=("$@")
[ ${#opts[@]} -gt 0 ] || opts=(--scene scenes/drum_deep.toml --methods verlet:mlgrid --steps 400)
mode=${MODE:-together}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# one BIN CORE TAG: the run's particle-steps/s into $work/TAG.
one() {
  OMP_NUM_THREADS=1 taskset -c "$2" "$1" bench throughput --threads 1 --repeats 1 "${opts[@]}" \
    --out "$work/out$2" 2>&1 | awk '/^fastest/ {for (k = 1; k < NF; ++k) if ($k ~ /^[0-9.]+e[+]/) {print $k; exit}}' >"$work/$3"
  [ -s "$work/$3" ] || { echo "ab_compare: no figure from $1 (run it alone to see why)" >&2; exit 1; }
}
for ((r = 1; r <= rounds; ++r)); do
  case "$mode" in
    together)
      ca=$((r % 2 ? 0 : 1)) cb=$((r % 2 ? 1 : 0))
      one "$a" "$ca" A & pa=$!
      one "$b" "$cb" B & pb=$!
      wait "$pa" && wait "$pb"
      ;;
    turns)
      if ((r % 2)); then one "$a" 0 A && one "$b" 0 B; else one "$b" 0 B && one "$a" 0 A; fi
      ;;
    *) echo "ab_compare: MODE must be together or turns, not '$mode'" >&2; exit 2 ;;
  esac
  echo "$(cat "$work/A") $(cat "$work/B")" >>"$work/rounds"
done
awk '{a[NR] = $1; b[NR] = $2; r[NR] = $2 / $1; sa += $1; sb += $2
      printf "round %d: A %.2f  B %.2f  B/A %.3f\n", NR, $1 / 1e6, $2 / 1e6, $2 / $1}
     END {n = NR; for (i = 1; i <= n; ++i) for (j = i + 1; j <= n; ++j) if (r[j] < r[i]) {t = r[i]; r[i] = r[j]; r[j] = t}
          med = (n % 2) ? r[(n + 1) / 2] : (r[n / 2] + r[n / 2 + 1]) / 2
          printf "B/A: median %.3f, sums %.3f, rounds %.3f-%.3f\n", med, sb / sa, r[1], r[n]}' "$work/rounds"
