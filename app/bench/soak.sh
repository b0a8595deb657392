#!/bin/bash
# Soak test (issue 38): the wet granulation and the demo drum for HOURS of wall clock, killed and
# restarted at random moments, then four checks per scene.
#
#   nice -n 10 app/bench/soak.sh HOURS [OUTDIR]        (HOURS may be a fraction: 0.1 = 6 minutes)
#
# Environment: DRUMLAB_BIN   the drumlab executable (default: the repo's launcher ./drumlab)
#              SOAK_SEED     the seed of the kill schedule (default: from the clock; printed)
#              SOAK_SCENES   the scenes (default: scenes/granulation.toml scenes/drum_demo.toml)
#              SOAK_WRITE_KILLS  share of the kills that wait for a checkpoint write (default 0.3)
#              SOAK_CORES    cores to plan for (default: nproc)
# OUTDIR (default out/soak/DATE) gets a folder per scene with its logs, checkpoints and results,
# and a copy of the executable (when DRUMLAB_BIN is one, not the launcher) that all runs use.
#
# What it does, per scene (the scenes side by side, every process on one thread):
#  1. init: `drumlab run SCENE --steps 0 --checkpoint init.h5` (fill and settle);
#  2. calibration: a short run from init.h5 gives the scene's steps per second on one core;
#  3. from the time left (HOURS less steps 1-2, less a reserve for the checks) it sizes the run:
#     N turning steps, so that each of the 2 x scenes processes of step 4, sharing the cores,
#     ends within the budget with a fifth to spare; a checkpoint every K steps (about 1/40 of the
#     run: every ~3 minutes for HOURS = 2), frames every N/100 steps;
#  4. two runs of N steps from init.h5 at the same time:
#     - reference: one uninterrupted process, `--restart init.h5 --steps N --checkpoint
#       reference.h5 --h5 series.h5 --observables observables.csv --every N/100`; its VmRSS and
#       RssAnon are sampled from /proc/PID/status into memory.csv;
#     - killed (soak_check.py drive): `--restart last.h5 --steps (what is left) --checkpoint
#       killed.h5 --checkpoint-every K` killed by SIGKILL after a random delay (uniform 0.25-1.75
#       x 4 checkpoint intervals, Python's random seeded by SOAK_SEED); a share of the kills
#       (SOAK_WRITE_KILLS) waits for the checkpoint's temporary file (FILE.tmp-PID) to appear and
#       kills at once, inside the write. After a kill the run goes on from killed.h5, the file
#       under its final name (a left-over .tmp is counted and removed, never read). No kills in
#       the last tenth of the budget, so the run ends.
#  5. checks (soak_check.py check), all must pass, else the exit status is 1:
#     - identical: killed.h5 and reference.h5 hold the same attributes and datasets, bit for bit,
#       the contact lists compared without their empty entries (zero history and state: which
#       pairs of the Verlet list hold one depends on when the list was last built, so on the
#       restarts; seen in the wet drum, 36 such entries after 7 restarts);
#     - liquid: films + bridges + wall bridges (+ the spray's airborne, lost and wall film, less
#       what it sprayed) per frame of observables.csv drift from frame 0 by <= 1e-12 relative
#       (the dry drum: nothing to check, "dry");
#     - energy: the kinetic energy (translation + rotation, from series.h5 with m = rho 4/3 pi r^3)
#       finite and never above M (g D + (omega R)^2 / 2), the bed lifted by a drum diameter plus
#       the bed turning with the wall;
#     - memory: RssAnon (heap and anonymous maps) of the reference process, its peak in the last
#       tenth of the run before the final tenth, against its peak in the tenth before the mark,
#       the mark being hour 1 or half the run if shorter; allowed growth max(1 %, 2 MiB).
#  6. a summary table (soak_check.py table), also in OUTDIR/summary.txt.
set -euo pipefail
hours=${1:?usage: soak.sh HOURS [OUTDIR]}
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
out=${2:-$root/out/soak/$(date +%Y%m%d-%H%M%S)}
mkdir -p "$out"
out=$(cd "$out" && pwd)
bin=${DRUMLAB_BIN:-$root/drumlab}
case "$bin" in /*) ;; *) bin=$(cd "$(dirname "$bin")" && pwd)/$(basename "$bin") ;; esac
# A copy of an executable, so that a rebuild during the hours cannot change the code under test.
if [ "$(head -c 4 "$bin" | tr -d '\177')" = ELF ]; then cp "$bin" "$out/drumlab.bin" && bin=$out/drumlab.bin; fi
py=/usr/bin/python3
check="$py $root/app/bench/soak_check.py"
seed=${SOAK_SEED:-$(date +%s)}
write_kills=${SOAK_WRITE_KILLS:-0.3}
cores=${SOAK_CORES:-$(nproc)}
read -r -a scenes <<<"${SOAK_SCENES:-scenes/granulation.toml scenes/drum_demo.toml}"
cd "$root"
export OMP_NUM_THREADS=1
calc() { awk -v OFMT=%.12g "BEGIN { print ($1) }"; }
trap 'kill $(jobs -p) 2>/dev/null; exit 130' INT TERM
say() { printf '[soak %s] %s\n' "$(date +%H:%M:%S)" "$*" | tee -a "$out/soak.log"; }

budget=$(calc "$hours * 3600")
reserve=$(calc "($budget * 0.02 > 20) ? $budget * 0.02 : 20")
t0=$(date +%s)
say "HOURS=$hours (budget $budget s), seed $seed, binary $bin, scenes ${scenes[*]}, out $out"

names=()
for s in "${scenes[@]}"; do names+=("$(basename "$s" .toml)"); mkdir -p "$out/${names[-1]}"; done

# 1-2. init and calibration, the scenes side by side.
prepare() {  # SCENE DIR
  local s=$1 d=$2 n cal
  "$bin" run "$s" --threads 1 --steps 0 --checkpoint "$d/init.h5" >"$d/init.log" 2>&1 ||
    { echo "init failed: $d/init.log" >&2; return 1; }
  read -r _ n < <($check steps "$d/init.h5")
  # About 1e6 particle-steps x the calibration seconds (5 to 30 s at ~1e6 particle-steps/s).
  cal=$(calc "int(($budget * 0.01 < 5 ? 5 : ($budget * 0.01 > 30 ? 30 : $budget * 0.01)) * 1e6 / $n) + 10")
  "$bin" run "$s" --threads 1 --restart "$d/init.h5" --steps "$cal" >"$d/calibrate.log" 2>&1 ||
    { echo "calibration failed: $d/calibrate.log" >&2; return 1; }
  $check rate "$d/calibrate.log" >"$d/rate"
}
pids=()
for k in "${!scenes[@]}"; do prepare "${scenes[$k]}" "$out/${names[$k]}" & pids+=($!); done
for p in "${pids[@]}"; do wait "$p" || { say "FAIL: init or calibration (see $out/*/init.log, calibrate.log)"; exit 1; }; done

# 3. sizes.
now=$(date +%s)
main_s=$(calc "$budget - ($now - $t0) - $reserve")
if awk "BEGIN { exit !($main_s < 30) }"; then say "FAIL: $main_s s left after init and calibration"; exit 1; fi
share=$(calc "($cores / (2 * ${#scenes[@]}) > 1) ? 1 : $cores / (2 * ${#scenes[@]})")
ckpt_s=$(calc "($main_s / 40 < 5) ? 5 : (($main_s / 40 > 300) ? 300 : $main_s / 40)")
kill_mean=$(calc "4 * $ckpt_s")
deadline=$(calc "$t0 + $budget - $reserve - 0.1 * $main_s")
mem_every=$(calc "($main_s / 500 < 0.5) ? 0.5 : (($main_s / 500 > 10) ? 10 : $main_s / 500)")
steps=() every=() frames=()
for k in "${!scenes[@]}"; do
  d=$out/${names[$k]} rate=$(cat "$out/${names[$k]}/rate")
  steps+=("$(calc "int($rate * $share * $main_s * 0.8)")")
  every+=("$(calc "int($rate * $share * $ckpt_s) > 1 ? int($rate * $share * $ckpt_s) : 1")")
  frames+=("$(calc "int(${steps[$k]} / 100) > 1 ? int(${steps[$k]} / 100) : 1")")
  say "${names[$k]}: $rate steps/s on one core; $main_s s left: $((steps[k])) steps, checkpoint every ${every[$k]} (~$ckpt_s s), frames every ${frames[$k]}, kills every ~$kill_mean s"
done

# 4. the reference and the killed run of each scene, all at once.
pids=()
for k in "${!scenes[@]}"; do
  d=$out/${names[$k]}
  "$bin" run "${scenes[$k]}" --threads 1 --restart "$d/init.h5" --steps "${steps[$k]}" \
    --checkpoint "$d/reference.h5" --h5 "$d/series.h5" --observables "$d/observables.csv" \
    --every "${frames[$k]}" >"$d/reference.log" 2>&1 &
  ref=$!
  pids+=($ref)
  $check memwatch --pid "$ref" --out "$d/memory.csv" --interval "$mem_every" &
  $check drive --bin "$bin" --scene "${scenes[$k]}" --init "$d/init.h5" --ckpt "$d/killed.h5" \
    --log "$d/killed.log" --out "$d/drive.json" --steps "${steps[$k]}" --every "${every[$k]}" \
    --kill-mean "$kill_mean" --write-kills "$write_kills" --seed "$((seed + k))" \
    --deadline "$deadline" &
  pids+=($!)
done
failed=0
for p in "${pids[@]}"; do wait "$p" || failed=1; done
wait  # the memory watchers
[ "$failed" = 0 ] || say "a run failed (see $out/*/reference.log, killed.log)"

# 5-6. checks and the table.
for k in "${!scenes[@]}"; do
  $check check --name "${names[$k]}" --scene "${scenes[$k]}" --dir "$out/${names[$k]}" \
    --steps "${steps[$k]}" | tee -a "$out/soak.log"
done
say "done after $(($(date +%s) - t0)) s of $budget; seed $seed"
dirs=()
for n in "${names[@]}"; do dirs+=("$out/$n"); done
status=0
$check table "${dirs[@]}" >"$out/summary.txt" || status=1
cat "$out/summary.txt" | tee -a "$out/soak.log"
exit "$status"
