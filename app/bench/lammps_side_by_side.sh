#!/bin/bash
# drumlab against LAMMPS on the same drum, one after the other in one run (one core each, or two):
#
#   PEERS=DIR [CORES=1|2] bash app/bench/lammps_side_by_side.sh demo|deep [ROUNDS] [LAMMPS_STEPS]
#
# PEERS is the LAMMPS harness of the drum workload (lammps/drum_small.in, lammps/run.sh,
# common/gen_drum.py, common/parse_log.py; default ../shared/peers, as on the development
# machine). `demo` is scenes/drum_demo.toml against the harness's default drum; `deep` is
# scenes/drum_deep.toml against gen_drum.py --depth-in-rmax 40 --nmin 64800 with
# -var Hdrum 0.6. LAMMPS settles 8000 steps, then its timed stage turns the drum LAMMPS_STEPS
# steps (default 6000 demo, 2000 deep); drumlab times 600 steps of its rolling state (bench
# throughput, the method `auto` picks for the scene). Rounds alternate LAMMPS and drumlab.
# CORES=2: LAMMPS on 2 MPI ranks (mpirun -np 2; the input sets `processors * 1 1`) against
# drumlab on 2 OpenMP threads. Needs: apt-get install lammps.
set -euo pipefail
drum=${1:?demo or deep}
rounds=${2:-1}
cores=${CORES:-1}
case "$cores" in
  1) launch=(lmp) ;;
  2) launch=(mpirun --allow-run-as-root --oversubscribe -np 2 lmp) ;;
  *) echo "lammps_side_by_side: CORES must be 1 or 2, not '$cores'" >&2; exit 2 ;;
esac
here=$(cd "$(dirname "$0")/../.." && pwd)
peers=$(cd "${PEERS:-$here/../shared/peers}" && pwd)
bin=${DRUMLAB:-$here/build/bin/drumlab}
cache=${CACHE:-$here/out/bench}
command -v lmp >/dev/null || { echo "lammps_side_by_side: lmp not found (apt-get install lammps)" >&2; exit 2; }
case "$drum" in
  demo) scene=$here/scenes/drum_demo.toml gen=() lvars=() nrot=${3:-6000} ;;
  deep) scene=$here/scenes/drum_deep.toml gen=(--depth-in-rmax 40 --nmin 64800)
        lvars=(-var Hdrum 0.6) nrot=${3:-2000} ;;
  *) echo "lammps_side_by_side: unknown drum '$drum' (demo or deep)" >&2; exit 2 ;;
esac
# The scene's method, `auto` resolved as `drumlab info` resolves it ("search method  auto -> M").
method=$("$bin" info "$scene" | awk '/^search method/ {print ($3 == "auto" ? $5 : $3); exit}')
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
printf '%-6s %-9s %-14s %14s  %s\n' round engine "method ($cores core(s))" "p-steps/s" load
for ((r = 1; r <= rounds; ++r)); do
  (cd "$work" && python3 "$peers/common/gen_drum.py" --prefix drum "${gen[@]}" >/dev/null &&
    "${launch[@]}" -in "$peers/lammps/drum_small.in" -log log.lammps -var datafile drum.lammps.data \
      -var nrot "$nrot" -var dumpevery 0 "${lvars[@]}" >screen.txt)
  rate=$(python3 "$peers/common/parse_log.py" "$work/log.lammps" |
    awk '/run rotate/ {for (k = 1; k < NF; ++k) if ($k == "->") print $(k + 1)}')
  printf '%-6s %-9s %-14s %14s  %s\n' "$r" LAMMPS "granular" "$rate" "$(cut -d' ' -f1 /proc/loadavg)"
  out=$("$bin" bench throughput --scene "$scene" --methods "$method" --steps 600 --repeats 1 \
    --threads "$cores" --cache "$cache" --out "$work/bench")
  rate=$(awk -v m="$method" -v t="$cores" '$1 == m && $2 == t {print $4}' <<<"$out" | tail -1)
  printf '%-6s %-9s %-14s %14s  %s\n' "$r" drumlab "$method" "$rate" "$(cut -d' ' -f1 /proc/loadavg)"
done
