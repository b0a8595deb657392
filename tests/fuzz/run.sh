#!/usr/bin/env bash
# tests/fuzz/run.sh SECONDS [READER...]: fuzzes each reader's harness (default: all) for SECONDS
# with libFuzzer under ASan and UBSan, in a clang build of its own (build-fuzz/, or
# $DRUMLAB_FUZZ_BUILD). The working corpus grows in build-fuzz/corpus/READER, seeded from
# tests/data/fuzz/READER (and scenes/ for the scene reader); a crash, hang or abort is written
# to build-fuzz/artifacts/READER/. Once fixed, copy the input into tests/data/fuzz/READER/: ctest
# replays that folder on every build (fuzz.replay_READER). Needs clang and libfuzzer-14-dev.
# READERs: scene, particle_csv, stl (the readers), and cli_drumlab, cli_mpi, cli_gui: the command
# lines of drumlab, drumlab-mpi and drumlab-gui, parsed with every subcommand's callback replaced
# (nothing runs), one argument a line (or NUL-separated) in an input. A harness this build does
# not make (cli_mpi without MPI) is skipped with a line saying so.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
seconds="${1:?usage: tests/fuzz/run.sh SECONDS [READER...]}"
shift
build="${DRUMLAB_FUZZ_BUILD:-$root/build-fuzz}"
readers=("$@")
if [ ${#readers[@]} -eq 0 ]; then
  for f in "$root"/tests/fuzz/fuzz_*.cpp; do
    name="$(basename "$f" .cpp)"
    readers+=("${name#fuzz_}")
  done
fi
cmake -S "$root" -B "$build" -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ \
  -DCMAKE_BUILD_TYPE=RelWithDebInfo -DDRUMLAB_FUZZ=ON >/dev/null
cmake --build "$build" -j "$(nproc)" >"$build/build.log" 2>&1 || {
  tail -n 40 "$build/build.log"
  exit 1
}
# Leaks allocated inside libhdf5 (HDF5 1.10.8 leaks an object header that fails to decode,
# HDFGroup/hdf5#2599) or OpenMPI's runtime are not drumlab's: tests/sanitize/lsan.supp.
export LSAN_OPTIONS="suppressions=$root/tests/sanitize/lsan.supp:print_suppressions=0"
status=0
for reader in "${readers[@]}"; do
  if [ ! -x "$build/bin/fuzz_$reader" ]; then
    echo "== $reader: skipped (fuzz_$reader is not built in $build)"
    continue
  fi
  corpus="$build/corpus/$reader"
  mkdir -p "$corpus" "$build/artifacts/$reader"
  seeds=("$root/tests/data/fuzz/$reader")
  if [ "$reader" = scene ]; then seeds+=("$root/scenes"); fi
  # A command line's harness builds the whole CLI11 app for each input, ~29,000 features an
  # execution: libFuzzer's entropic schedule spends most of its time weighing them (perf: 45 % in
  # InputCorpus::UpdateFeatureFrequency); without it, 3 -> 27 inputs/s (drumlab), 62 -> 117 (mpi).
  extra=()
  case "$reader" in cli_*) extra+=(-entropic=0) ;; esac
  echo "== $reader: ${seconds} s"
  if ! "$build/bin/fuzz_$reader" "$corpus" "${seeds[@]}" -max_total_time="$seconds" \
      -timeout=10 -rss_limit_mb=4096 -print_final_stats=1 ${extra[@]+"${extra[@]}"} \
      -artifact_prefix="$build/artifacts/$reader/" >"$build/fuzz_$reader.log" 2>&1; then
    status=1
    echo "   FINDING: see $build/fuzz_$reader.log and $build/artifacts/$reader/"
  fi
  grep -E "^#[0-9]+.*DONE|stat::number_of_executed_units|stat::peak_rss|cov:" \
    "$build/fuzz_$reader.log" | tail -n 3
done
exit "$status"
