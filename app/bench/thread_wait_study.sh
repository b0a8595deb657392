#!/bin/bash
# One against two OpenMP threads of a scene's rolling state under each way an OpenMP thread can
# wait at a barrier, on the machine as it is and with 1 and 2 busy processes beside the run.
#
#   bash app/bench/thread_wait_study.sh [BINARY] [STEPS] [SCENE]
#
# Each row: `drumlab bench throughput --threads 2` (the 1- and 2-thread runs of the same method
# take turns) with the environment shown; "2 / 1" is the 2-thread rate over the 1-thread rate.
# The busy processes are shell loops at the same priority. The settings: libgomp's default
# (spin about 300,000 times, then sleep), OMP_WAIT_POLICY=passive (sleep at once),
# GOMP_SPINCOUNT=N (spin N times, then sleep), OMP_WAIT_POLICY=active (spin without end), and
# what drumlab chooses when none is set (DRUMLAB_OMP_DEFAULT=off turns that choice off).
set -euo pipefail
bin=${1:-build/bin/drumlab}
steps=${2:-300}
scene=${3:-scenes/drum_demo.toml}
cache=${CACHE:-out/bench}
# SETTINGS="A=1 B=2 ..." replaces the list; REPEATS=R keeps the fastest of R runs per row.
read -r -a settings <<<"${SETTINGS:-DRUMLAB_OMP_DEFAULT=off DRUMLAB_OMP_DEFAULT=on OMP_WAIT_POLICY=passive GOMP_SPINCOUNT=10000 GOMP_SPINCOUNT=1000 OMP_WAIT_POLICY=active}"
repeats=${REPEATS:-1}
busy=()
stop_busy() { for p in "${busy[@]}"; do kill "$p" 2>/dev/null || true; done; busy=(); }
trap stop_busy EXIT
printf '%-6s %-26s %12s %12s %7s  %s\n' busy setting "1 thread" "2 threads" "2 / 1" load
for n in 0 1 2; do
  stop_busy
  for ((k = 0; k < n; ++k)); do
    bash -c 'while :; do :; done' &
    busy+=($!)
  done
  for s in "${settings[@]}"; do
    out=$(env "$s" "$bin" bench throughput --scene "$scene" --methods verlet:m2 --threads 2 \
      --steps "$steps" --warmup 20 --repeats "$repeats" --cache "$cache" --out /tmp/thread_wait_study)
    one=$(awk '$1 == "verlet:m2" && $2 == 1 {print $4}' <<<"$out" | tail -1)
    two=$(awk '$1 == "verlet:m2" && $2 == 2 {print $4}' <<<"$out" | tail -1)
    printf '%-6s %-26s %12s %12s %7.2f  %s\n' "$n" "$s" "$one" "$two" \
      "$(awk -v a="$one" -v b="$two" 'BEGIN {print b / a}')" "$(cut -d' ' -f1 /proc/loadavg)"
  done
done
