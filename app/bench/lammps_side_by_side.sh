#!/bin/bash
# drumlab against LAMMPS on the same drum, one after the other in one run (one core each, or two):
#
#   PEERS=DIR [CORES=1|2] [LAMMPS_DT=scene|peer] [LMP=EXECUTABLE] \
#     bash app/bench/lammps_side_by_side.sh demo|deep|tilted|periodic [ROUNDS] [LAMMPS_STEPS]
#
# PEERS is the LAMMPS harness of the drum workload (lammps/drum_small.in, lammps/run.sh,
# common/gen_drum.py, common/parse_log.py; default ../shared/peers, as on the development
# machine). The drums, each a drumlab scene and the same spheres, walls and drum for LAMMPS:
#   demo      scenes/drum_demo.toml: the harness's default drum
#   deep      scenes/drum_deep.toml: gen_drum.py --depth-in-rmax 40 --nmin 64800, -var Hdrum 0.6
#   tilted    scenes/tilted_drum.toml: gen_drum.py --drum-radius-in-rmax 10 --depth-in-rmax 20
#             --nmin 3672, -var Rdrum 0.15 -var Hdrum 0.3 -var omega 1.5; the deck's gravity
#             turned into the drum's frame (0, -g cos 20deg, g sin 20deg), as drumlab turns it
#   periodic  the demo drum with periodic ends (its scene made here from drum_demo.toml); the
#             deck's z boundary periodic, its box [0, H] in z and its cylinder's end caps open
# The tilted and periodic scenes are run with search = "auto" (the method `auto` picks, printed);
# demo sets verlet:m2 (auto's pick for it), deep sets auto. LAMMPS
# settles 8000 steps, then its timed stage turns the drum LAMMPS_STEPS steps (default 6000; deep
# 2000); drumlab times 600 steps of its rolling state (bench throughput). Each round runs both,
# LAMMPS first in odd rounds and drumlab first in even ones, and prints the ratio; the last line
# gives every round's ratio and their median. With CORES=1 both run on core PIN (default 0).
# LAMMPS_DT=scene (default) runs LAMMPS at the scene's time step (`drumlab info`),
# LAMMPS_DT=peer at the harness's 1e-4 s. CORES=2: LAMMPS on 2 MPI ranks (mpirun -np 2; the
# input sets `processors * 1 1`) against drumlab on 2 OpenMP threads, whose waits spin
# (OMP_WAIT_POLICY=active, as the MPI ranks poll: both cores are the run's; WAIT=passive runs
# drumlab's default for a shared machine, "Threads on a shared machine"). LMP picks the LAMMPS
# executable: Debian's `lmp` (default; apt-get install lammps), or the one build_lammps.sh builds
# from Debian's source with drumlab's compiler and flags (the fair peer). METHOD=NAME times
# drumlab with that search method instead of the one `auto` resolves to: `auto` times the grids
# on the state and can pick another on a noisy host (the deep drum: verlet:mlgrid or verlet:m5),
# which a comparison of two binaries must not let in.
set -euo pipefail
drum=${1:?demo, deep, tilted or periodic}
rounds=${2:-1}
cores=${CORES:-1}
wait_policy=${WAIT:-active}
case "$wait_policy" in
  active | passive) ;;
  *) echo "lammps_side_by_side: WAIT must be active or passive, not '$wait_policy'" >&2; exit 2 ;;
esac
case "$cores" in
  1) launch=("${LMP:-lmp}") ;;
  2) launch=(mpirun --allow-run-as-root --oversubscribe -np 2 "${LMP:-lmp}") ;;
  *) echo "lammps_side_by_side: CORES must be 1 or 2, not '$cores'" >&2; exit 2 ;;
esac
# One core: both engines on the same core (PIN, default 0; PIN= lets the scheduler choose), so
# that a difference between the cores of a shared machine does not enter the ratio.
pin=()
if [ "$cores" = 1 ] && [ -n "${PIN-0}" ]; then pin=(taskset -c "${PIN-0}"); fi
here=$(cd "$(dirname "$0")/../.." && pwd)
peers=$(cd "${PEERS:-$here/../shared/peers}" && pwd)
bin=${DRUMLAB:-$here/build/bin/drumlab}
cache=${CACHE:-$here/out/bench}
command -v "${LMP:-lmp}" >/dev/null ||
  { echo "lammps_side_by_side: ${LMP:-lmp} not found (apt-get install lammps, or LMP=...)" >&2; exit 2; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
deck=$work/drum.in
cp "$peers/lammps/drum_small.in" "$deck"

# edit PATTERN REPLACEMENT: one sed substitution on the deck, which must match exactly once.
edit() {
  local n
  n=$(grep -c -- "$1" "$deck" || true)
  [ "$n" = 1 ] || { echo "lammps_side_by_side: '$1' found $n times in the peer deck" >&2; exit 2; }
  sed -i "s|$1|$2|" "$deck"
}
# scene_from SRC NAME [KEY = VALUE lines]: SRC with search = "auto", the name NAME (its own
# cached rolling state) and each top-level or [drum] key given replaced, written under $cache.
scene_from() {
  local src=$1 name=$2
  shift 2
  mkdir -p "$cache/scenes"
  local out=$cache/scenes/$name.toml
  sed -e "0,/^name = /s|^name = .*|name = \"$name\"|" -e 's|^search = .*|search = "auto"|' "$src" >"$out"
  for kv in "$@"; do sed -i "s|^${kv%% =*} = .*|$kv|" "$out"; done
  echo "$out"
}

nrot=${3:-6000} gen=() lvars=() zperiodic=0
case "$drum" in
  demo) scene=$here/scenes/drum_demo.toml ;;  # sets verlet:m2, the method auto picks for it
  deep) scene=$here/scenes/drum_deep.toml      # sets auto
        gen=(--depth-in-rmax 40 --nmin 64800) lvars=(-var Hdrum 0.6) nrot=${3:-2000} ;;
  tilted)
    scene=$(scene_from "$here/scenes/tilted_drum.toml" tilted_drum_auto)
    gen=(--drum-radius-in-rmax 10 --depth-in-rmax 20 --nmin 3672)
    lvars=(-var Rdrum 0.15 -var Hdrum 0.3 -var omega 1.5)
    tilt=$(awk -F= '/^tilt_deg/ {print $2 + 0}' "$scene")
    edit "vector 0.0 -1.0 0.0" \
      "vector 0.0 $(python3 -c "import math; t = math.radians($tilt); print(-math.cos(t), math.sin(t))")"
    ;;
  periodic)
    scene=$(scene_from "$here/scenes/drum_demo.toml" drum_demo_periodic 'ends = "periodic"')
    zperiodic=1
    edit "^boundary        f f f" "boundary        f f p"
    edit 'side in units box &' 'side in open 1 open 2 units box \&'
    ;;
  *) echo "lammps_side_by_side: unknown drum '$drum' (demo, deep, tilted or periodic)" >&2; exit 2 ;;
esac
info=$("$bin" info "$scene")
# `auto` resolved as `drumlab info` resolves it ("search method  auto -> M").
method=${METHOD:-$(awk '/^search method/ {print ($3 == "auto" ? $5 : $3); exit}' <<<"$info")}
dt=$(awk '/^time step/ {print $3; exit}' <<<"$info")
case "${LAMMPS_DT:-scene}" in
  scene) lvars+=(-var dt "$dt") ;;
  peer) ;;
  *) echo "lammps_side_by_side: LAMMPS_DT must be scene or peer, not '$LAMMPS_DT'" >&2; exit 2 ;;
esac
echo "drumlab: $scene, $(awk '/^particles/ {print $2; exit}' <<<"$info") particles, dt $dt s, $method${METHOD:+ (METHOD)}"
echo "LAMMPS:  ${gen[*]:-(default drum)} ${lvars[*]}"
[ "$cores" = 1 ] || echo "drumlab's threads wait: OMP_WAIT_POLICY=$wait_policy"
printf '%-6s %-9s %-14s %14s  %s\n' round engine "method ($cores core(s))" "p-steps/s" load
lammps_round() {
  (cd "$work" && python3 "$peers/common/gen_drum.py" --prefix drum "${gen[@]}" >/dev/null &&
    if [ "$zperiodic" = 1 ]; then  # the box's z extent is the drum's depth (the period)
      sed -i -E "s|^\S+ \S+ zlo zhi|0.000000 $(awk '/^depth/ {print $3}' "$scene") zlo zhi|" \
        drum.lammps.data
    fi &&
    "${pin[@]}" "${launch[@]}" -in "$deck" -log log.lammps -var datafile drum.lammps.data \
      -var nrot "$nrot" -var dumpevery 0 "${lvars[@]}" >screen.txt)
  lammps_rate=$(python3 "$peers/common/parse_log.py" "$work/log.lammps" |
    awk '/run rotate/ {for (k = 1; k < NF; ++k) if ($k == "->") print $(k + 1)}')
  printf '%-6s %-9s %-14s %14s  %s\n' "$1" LAMMPS "granular" "$lammps_rate" "$(cut -d' ' -f1 /proc/loadavg)"
}
drumlab_round() {
  local out
  out=$(OMP_WAIT_POLICY=$wait_policy "${pin[@]}" "$bin" bench throughput --scene "$scene" --methods "$method" --steps 600 \
    --repeats 1 --threads "$cores" --cache "$cache" --out "$work/bench")
  drumlab_rate=$(awk -v m="$method" -v t="$cores" '$1 == m && $2 == t {print $4}' <<<"$out" | tail -1)
  printf '%-6s %-9s %-14s %14s  %s\n' "$1" drumlab "$method" "$drumlab_rate" "$(cut -d' ' -f1 /proc/loadavg)"
}
ratios=()
for ((r = 1; r <= rounds; ++r)); do
  if ((r % 2 == 1)); then lammps_round "$r"; drumlab_round "$r"; else drumlab_round "$r"; lammps_round "$r"; fi
  ratios+=("$(awk -v d="$drumlab_rate" -v l="$lammps_rate" 'BEGIN {printf "%.2f", d / l}')")
  printf '%-6s %-9s %-14s %14s\n' "$r" ratio "drumlab/LAMMPS" "${ratios[-1]}x"
done
printf 'drumlab / LAMMPS, %d round(s): %s; median %sx\n' "$rounds" "${ratios[*]}" \
  "$(printf '%s\n' "${ratios[@]}" | sort -g | awk '{v[NR] = $1} END {print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2}')"
