#!/bin/bash
# Deep-drum scaling rounds for app/bench/README.md ("MPI scaling"): in each round, one after the
# other on the same rolling state, `drumlab run` (1 thread), `drumlab-mpi` on 1 and 2 ranks (1
# thread each) and `drumlab run` with 2 threads; prints each run's particle-steps/s (the MPI runs'
# "turning" figure and their share of time inside MPI).
#
#   [ROUNDS=4] [METHOD=verlet:m2] [SCENE=scenes/drum_deep.toml] [STATE=out/bench/drum_deep_rolling.h5] \
#     [SKIN=S] bash app/bench/mpi_scaling_rounds.sh
#
# SKIN: the Verlet skin in smallest radii for every run (`--skin`); unset: the scene's.
#
# STATE is the scene's cached rolling state (`drumlab bench throughput --scene SCENE` makes it).
set -euo pipefail
cd "$(dirname "$0")/../.."
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
scene=${SCENE:-scenes/drum_deep.toml}
state=${STATE:-out/bench/drum_deep_rolling.h5}
method=${METHOD:-verlet:m2}
skin=()
[ -n "${SKIN:-}" ] && skin=(--skin "$SKIN")
[ -f "$state" ] || { echo "mpi_scaling_rounds: no rolling state '$state' (run drumlab bench throughput --scene $scene first)" >&2; exit 2; }
serial() {
  build/bin/drumlab run "$scene" --restart "$state" --steps 600 --threads "$1" --method "$method" "${skin[@]}" |
    awk '/^throughput/ {print $2}'
}
ranks() {
  mpirun --oversubscribe --mca mpi_yield_when_idle 1 -np "$1" build/bin/drumlab-mpi run "$scene" \
    --restart "$state" --steps 600 --threads 1 --method "$method" "${skin[@]}" </dev/null |
    awk '/^communication/ {c = $2} /^steps/ {r = $0; sub(/.*\(/, "", r); sub(/ particle-steps.*/, "", r)}
         END {printf "%s (%s %% in MPI)", r, c}'
}
printf '%-6s %-6s %-12s %-26s %-26s %-12s\n' round load "run, 1 thr" "mpi, 1 rank" "mpi, 2 ranks" "run, 2 thr"
for ((r = 1; r <= ${ROUNDS:-4}; ++r)); do
  load=$(cut -d' ' -f1 /proc/loadavg)
  a=$(serial 1) b=$(ranks 1) c=$(ranks 2) d=$(serial 2)
  printf '%-6s %-6s %-12s %-26s %-26s %-12s\n' "$r" "$load" "$a" "$b" "$c" "$d"
done
