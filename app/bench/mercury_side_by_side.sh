#!/bin/bash
# The same wet drum in drumlab and in MercuryDPM (its RotatingDrumWet driver), side by side:
# the angle of repose against the Bond number, and both throughputs on one core.
#
#   bash app/bench/mercury_side_by_side.sh MERCURY_BUILD OUT_DIR [options]
#
# MERCURY_BUILD  the build folder of app/bench/build_mercury.sh (it holds
#                Drivers/Demos/IndustrialMixers/RotatingDrumWetSeeded)
# OUT_DIR        where both codes run: OUT_DIR/peer/bo<B>_mur<M>_seed<S>/ (log.txt, time.txt,
#                rc) and OUT_DIR/drumlab_mur<M>/ (a `drumlab sweep`: sweep.csv, sweep.png,
#                runs/). Finished runs are kept and reused: a killed comparison resumes.
# Options:
#   --bond "0 1 2 5 10 20"  Bond numbers Bo = F_bridge / (m g) of a mean particle pair
#   --seeds "1 2 3"         the peer's random seed (placement) and drumlab's fill.seed
#   --rolling "0.5"         rolling friction coefficients (e.g. "0.5 0")
#   --revolutions 3         drum turns of every run (the peer's driver alone always runs 5)
#   --window-from 1         the angle is averaged over revolutions [this, the end]
#   --jobs 2                runs at a time (each code runs its own queue, one after the other)
#   --throughput            also time both codes at Bo = 5 on one core (taskset -c 0):
#                           the peer over its second half revolution with 4 outputs a revolution,
#                           drumlab's stepping over one revolution after settling, one thread
#   --drumlab PATH          the drumlab executable [build/bin/drumlab]
#   --report-only           start no run: print the table from the runs OUT_DIR already holds
#
# The drum is scenes/mercury_wet_drum.toml (the peer's drum in drumlab's keys; read its header
# for the one difference, the periodic width). Bo sets the surface tension in both codes:
# gamma = Bo m g / (2 pi r) = Bo rho (2/3) r^2 g = 0.0392 Bo N/m for r = 2 mm, rho = 1500.
# Both angles are MercuryDPM's: the centre of mass about the axis from straight down,
# atan2(-x_com, -z_com) in the peer's frame (drumlab: DrumObservables::com_angle_deg).
#
# Needs: python3, /usr/bin/time, taskset (util-linux). CI never runs this script.
set -euo pipefail
here=$(cd "$(dirname "$0")/../.." && pwd)
peer_build=${1:-}
out=${2:-}
if [ -z "$peer_build" ] || [ -z "$out" ]; then
  echo "mercury_side_by_side: usage: mercury_side_by_side.sh MERCURY_BUILD OUT_DIR [options]" >&2
  exit 2
fi
shift 2
bonds="0 1 2 5 10 20"
seeds="1 2 3"
rolling="0.5"
revolutions=3
window_from=1
jobs=2
throughput=0
report_only=0
drumlab="$here/build/bin/drumlab"
while [ $# -gt 0 ]; do
  case "$1" in
    --bond) bonds=$2; shift 2 ;;
    --seeds) seeds=$2; shift 2 ;;
    --rolling) rolling=$2; shift 2 ;;
    --revolutions) revolutions=$2; shift 2 ;;
    --window-from) window_from=$2; shift 2 ;;
    --jobs) jobs=$2; shift 2 ;;
    --throughput) throughput=1; shift ;;
    --drumlab) drumlab=$2; shift 2 ;;
    --report-only) report_only=1; shift ;;
    *) echo "mercury_side_by_side: unknown option '$1'" >&2; exit 2 ;;
  esac
done
peer="$peer_build/Drivers/Demos/IndustrialMixers/RotatingDrumWetSeeded"
scene="$here/scenes/mercury_wet_drum.toml"
[ -x "$peer" ] || { echo "mercury_side_by_side: no peer at '$peer' (run app/bench/build_mercury.sh)" >&2; exit 2; }
[ -x "$drumlab" ] || { echo "mercury_side_by_side: no drumlab at '$drumlab' (build it first)" >&2; exit 2; }
for tool in python3 /usr/bin/time taskset; do
  command -v "$tool" > /dev/null || { echo "mercury_side_by_side: needs '$tool'" >&2; exit 2; }
done
mkdir -p "$out/peer"

# One peer run in its own folder; `rc` is written last, so a folder without it is redone.
peer_run() { # peer_run BO MU SEED
  local d="$out/peer/bo$1_mur$2_seed$3"
  [ -f "$d/rc" ] && [ "$(cat "$d/rc")" = 0 ] && return 0
  rm -rf "$d" && mkdir -p "$d"
  (cd "$d" && /usr/bin/time -v -o time.txt "$peer" -bond "$1" -rollingFriction "$2" -seed "$3" \
    -revolutions "$revolutions" > log.txt 2>&1; echo $? > rc.tmp)
  rm -f "$d"/*.vtu "$d"/*.data "$d"/*.fstat  # 2 x 100 VTU files a revolution: only the log counts
  mv "$d/rc.tmp" "$d/rc"
  echo "peer: Bo $1, mu_r $2, seed $3: exit $(cat "$d/rc")"
}
export -f peer_run
export out peer revolutions
gammas=$(python3 -c "import sys; print(','.join(f'{0.0392*float(b):.6g}' for b in sys.argv[1:]))" $bonds)
seed_list=$(echo $seeds | tr ' ' ',')

for mu in $rolling; do
  [ "$report_only" = 1 ] && break
  for b in $bonds; do for s in $seeds; do echo "$b $mu $s"; done; done
done | xargs -r -P "$jobs" -L 1 bash -c 'peer_run "$0" "$1" "$2"'

for mu in $rolling; do
  [ "$report_only" = 1 ] && break
  "$drumlab" sweep "$scene" --set "liquid.surface_tension=$gammas" \
    --set "material.rolling_friction=$mu" --set "wall.rolling_friction=$mu" \
    --seeds "$seed_list" --out "$out/drumlab_mur$mu" --jobs "$jobs" \
    --revolutions "$revolutions" --window-from "$window_from" > "$out/drumlab_mur$mu.log" 2>&1 ||
    { echo "mercury_side_by_side: drumlab sweep failed, see $out/drumlab_mur$mu.log" >&2; exit 1; }
done

python3 - "$out" "$window_from" "$revolutions" "$bonds" "$rolling" "$here" <<'PY'
import csv, math, os, re, statistics, sys
out, window_from, revolutions = sys.argv[1], float(sys.argv[2]), float(sys.argv[3])
bonds, rolling = sys.argv[4].split(), sys.argv[5].split()
line = re.compile(r"^t (\S+)\s+N (\S+)\s+Nc \S+\s+Nl (\S+)\s+o \S+\s+AoR (\S+)")
scene = open(os.path.join(sys.argv[6], "scenes", "mercury_wet_drum.toml")).read()
n_drumlab = int(re.search(r"^count = (\d+)", scene, re.M).group(1))

def peer_runs(bo, mu):
    runs = []
    folder = os.path.join(out, "peer")
    for d in sorted(os.listdir(folder)):
        m = re.fullmatch(rf"bo{re.escape(bo)}_mur{re.escape(mu)}_seed(\d+)", d)
        rc = os.path.join(folder, d, "rc")
        if not m or not os.path.exists(rc) or open(rc).read().strip() != "0":
            continue
        angles, bridges = [], []
        for text in open(os.path.join(folder, d, "log.txt"), errors="replace"):
            hit = line.match(text)
            if hit and float(hit.group(1)) * revolutions >= window_from - 1e-9:
                angles.append(float(hit.group(4)))
                bridges.append(float(hit.group(3)) / float(hit.group(2)))
        if angles:
            runs.append((angles, statistics.fmean(bridges)))
    return runs

def drumlab_runs(bo, mu):
    path = os.path.join(out, f"drumlab_mur{mu}", "sweep.csv")
    runs, drift = [], 0.0
    if not os.path.exists(path):
        return runs, drift
    gamma = 0.0392 * float(bo)
    for row in csv.DictReader(open(path)):
        if abs(float(row["liquid.surface_tension"]) - gamma) <= 1e-6 * max(gamma, 1e-12):
            runs.append((float(row["angle_com_deg"]), float(row["angle_com_deg_sd"]),
                         int(row["frames"]), float(row["bridges"]) / n_drumlab))
            drift = max(drift, float(row["liquid_drift"]))
    return runs, drift

def summary(means, pooled_sd):
    m = statistics.fmean(means)
    sd = statistics.stdev(means) if len(means) > 1 else float("nan")
    return m, sd, pooled_sd

print(f"angle of repose (centre of mass, deg), revolutions {window_from:g}-{revolutions:g}, "
      "mean over seeds; 'seeds' = sd of the seeds' means, 'all' = sd of every frame of every seed")
print(f"{'mu_r':>5} {'Bo':>4} | {'peer':>6} {'seeds':>6} {'all':>6} {'n':>2} | "
      f"{'drumlab':>7} {'seeds':>6} {'all':>6} {'n':>2} | {'diff':>6} {'verdict':>18} | "
      f"bridges/particle peer, drumlab")
worst_drift = 0.0
for mu in rolling:
    for bo in bonds:
        p = peer_runs(bo, mu)
        d, drift = drumlab_runs(bo, mu)
        worst_drift = max(worst_drift, drift)
        if not p or not d:
            print(f"{mu:>5} {bo:>4} | runs missing (peer {len(p)}, drumlab {len(d)})")
            continue
        pm, ps, pall = summary([statistics.fmean(a) for a, _ in p],
                               statistics.pstdev([x for a, _ in p for x in a]))
        pb = statistics.fmean([b for _, b in p])
        db = statistics.fmean([b for _, _, _, b in d])
        # drumlab's pooled sd from each run's mean and sd over its frames (law of total variance)
        dmeans = [m for m, _, _, _ in d]
        dm = statistics.fmean(dmeans)
        n_all = sum(f for _, _, f, _ in d)
        dall = math.sqrt(sum(f * (s * s + (m - dm) ** 2) for m, s, f, _ in d) / n_all)
        ds = statistics.stdev(dmeans) if len(dmeans) > 1 else float("nan")
        diff = dm - pm
        verdict = "inside peer +-2 sd" if abs(diff) <= 2.0 * pall else "OUTSIDE"
        print(f"{mu:>5} {bo:>4} | {pm:6.2f} {ps:6.2f} {pall:6.2f} {len(p):2d} | "
              f"{dm:7.2f} {ds:6.2f} {dall:6.2f} {len(d):2d} | {diff:+6.2f} {verdict:>18} | "
              f"{pb:.3f}, {db:.3f}")
print(f"drumlab liquid accounting: films + bridges (+ wall bridges) drift at most "
      f"{worst_drift:.3g} of the scene's liquid over every frame of every run")
PY

if [ "$throughput" = 1 ]; then
  d="$out/throughput"
  mkdir -p "$d/peer"
  (cd "$d/peer" && taskset -c 0 "$peer" -bond 5 -seed 1 -revolutions 1 -outputsPerRevolution 4 |
    while IFS= read -r l; do printf '%s %s\n' "$(date +%s.%N)" "$l"; done > stamped.log)
  rm -f "$d/peer"/*.vtu "$d/peer"/*.data "$d/peer"/*.fstat
  taskset -c 0 "$drumlab" run "$scene" --revolutions 1 --threads 1 > "$d/drumlab.txt" 2>&1
  python3 - "$d" <<'PY'
import re, sys
d = sys.argv[1]
stamps = []
for text in open(f"{d}/peer/stamped.log"):
    m = re.match(r"^(\S+) t (\S+)\s+N (\d+)", text)
    if m:
        stamps.append((float(m.group(1)), float(m.group(2)), int(m.group(3))))
dt = 0.05 * 0.1 * (2e-3 / 9.8) ** 0.5
omega = (0.01 * 9.8 / 0.04) ** 0.5
steps_per_rev = 2 * 3.141592653589793 / omega / dt
half = [s for s in stamps if s[1] >= 0.5 - 1e-3]  # its log's fractions round below 0.5
(t0, f0, n), (t1, f1, _) = half[0], half[-1]
peer = n * (f1 - f0) * steps_per_rev / (t1 - t0)
parts = [n * (b[1] - a[1]) * steps_per_rev / (b[0] - a[0]) for a, b in zip(half, half[1:])
         if b[1] - a[1] > 0.1]
ours = float(re.search(r"throughput\s+(\S+) particle-steps/s", open(f"{d}/drumlab.txt").read()).group(1))
n_ours = int(re.search(r"particles\s+(\d+)", open(f"{d}/drumlab.txt").read()).group(1))
print(f"throughput, Bo = 5, one core (taskset -c 0), one thread:")
print(f"  peer     {peer:.4g} particle-steps/s ({n} particles, revolution {f0:.2f}-{f1:.2f} of 1, "
      f"4 outputs a revolution; its quarters {min(parts):.3g}-{max(parts):.3g})")
print(f"  drumlab  {ours:.4g} particle-steps/s ({n_ours} particles, stepping of revolution 0-1 "
      f"after settling)")
print(f"  ratio    {ours / peer:.2f}")
PY
fi
