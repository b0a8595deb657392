#!/bin/bash
# Build the MercuryDPM peer (GitHub kuwt/MercuryDPM_fork) beside drumlab, never inside it:
#
#   bash app/bench/build_mercury.sh SRC_DIR BUILD_DIR [GIT_DIR]
#
# SRC_DIR   the MercuryDPM source tree (its top CMakeLists.txt), outside any repository.
# BUILD_DIR where CMake builds it; the driver ends up as
#           BUILD_DIR/Drivers/Demos/IndustrialMixers/RotatingDrumWet.
# GIT_DIR   optional: a git directory of the fork (the `fetch` tool's snapshot). When given and
#           SRC_DIR has no CMakeLists.txt, the tree is first copied out of it blob by blob
#           (`git ls-tree -r` + `git cat-file --batch`), skipping the blobs the snapshot lacks
#           (documentation images, some driver data; `git archive` stops on them). Kernel/ and
#           the driver are complete. /work/shared/DESIGN.md, "Peers built from source".
#
# Flags: drumlab's own, so that a throughput ratio compares the codes, not the compilers:
# Release with -O3, the -march drumlab's CMakeLists picks on this machine (x86-64-v4 where the
# CPU runs AVX-512, else x86-64-v3 with AVX2 and FMA; MARCH=... overrides), and
# -fno-math-errno -fno-trapping-math (drumlab's add_compile_options). CXX picks the compiler
# (default c++, as drumlab's build). User drivers are off (-DMercuryDPM_BUILD_USER_DIR=OFF).
# Only the one target is built, with JOBS (default 2) jobs under nice: others share the cores.
#
# Needs: cmake, make, a C++ compiler, python3 (the copy only). CI never runs this script.
set -euo pipefail
src=${1:-}
build=${2:-}
git_dir=${3:-}
if [ -z "$src" ] || [ -z "$build" ]; then
  echo "build_mercury: usage: build_mercury.sh SRC_DIR BUILD_DIR [GIT_DIR]" >&2
  exit 2
fi

copy_tree() { # copy_tree GIT_DIR DEST: every blob of HEAD that the git directory holds
  git --git-dir="$1" ls-tree -r HEAD | python3 -c '
import os, subprocess, sys
git_dir, dest = sys.argv[1], sys.argv[2]
cat = subprocess.Popen(["git", "--git-dir", git_dir, "cat-file", "--batch"],
                       stdin=subprocess.PIPE, stdout=subprocess.PIPE)
copied = missing = 0
for line in sys.stdin:
    meta, path = line.rstrip("\n").split("\t", 1)
    mode, _, sha = meta.split()
    if mode == "160000":
        continue
    cat.stdin.write((sha + "\n").encode()); cat.stdin.flush()
    head = cat.stdout.readline().decode().split()
    if len(head) < 3 or head[1] == "missing":
        missing += 1
        continue
    data = cat.stdout.read(int(head[2])); cat.stdout.read(1)
    out = os.path.join(dest, path)
    os.makedirs(os.path.dirname(out), exist_ok=True)
    if mode == "120000":
        if not os.path.lexists(out):
            os.symlink(data.decode(), out)
        continue
    with open(out, "wb") as f:
        f.write(data)
    if mode == "100755":
        os.chmod(out, 0o755)
    copied += 1
print(f"build_mercury: copied {copied} files, {missing} blobs missing from the snapshot")
' "$1" "$2"
}

if [ ! -f "$src/CMakeLists.txt" ] && [ -n "$git_dir" ]; then
  if [ ! -d "$git_dir" ]; then
    echo "build_mercury: GIT_DIR '$git_dir' is not a directory" >&2
    exit 2
  fi
  mkdir -p "$src"
  copy_tree "$git_dir" "$src"
fi
if [ ! -f "$src/CMakeLists.txt" ] || [ ! -f "$src/Drivers/Demos/IndustrialMixers/RotatingDrumWet.cpp" ]; then
  echo "build_mercury: SRC_DIR '$src' is not a MercuryDPM source tree (no CMakeLists.txt or no RotatingDrumWet.cpp)" >&2
  exit 2
fi
for tool in cmake make "${CXX:-c++}"; do
  command -v "$tool" > /dev/null || { echo "build_mercury: needs '$tool' on PATH" >&2; exit 2; }
done

cxx=${CXX:-c++}
cpu_runs() { # cpu_runs MARCH TEST: the compiler targets MARCH and this CPU runs it (drumlab_cpu_runs)
  local dir
  dir=$(mktemp -d)
  echo "int main() { __builtin_cpu_init(); return ($2) ? 0 : 1; }" > "$dir/t.cpp"
  "$cxx" -march="$1" "$dir/t.cpp" -o "$dir/t" 2> /dev/null && "$dir/t"
  local rc=$?
  rm -rf "$dir"
  return $rc
}
if [ -z "${MARCH:-}" ]; then
  if cpu_runs x86-64-v4 '__builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512vl") && __builtin_cpu_supports("avx512bw") && __builtin_cpu_supports("avx512dq") && __builtin_cpu_supports("avx512cd")'; then
    MARCH=x86-64-v4
  elif cpu_runs x86-64-v3 '__builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma")'; then
    MARCH=x86-64-v3
  else
    MARCH=x86-64
  fi
fi
flags="-march=$MARCH -fno-math-errno -fno-trapping-math"
echo "build_mercury: $cxx, Release -O3 $flags"

# RotatingDrumWetSeeded: the same driver with two command-line options more, so that runs can
# differ by seed and be shortened (the driver itself has neither: it draws every run from the
# same random state and always runs 5 revolutions). Written beside the driver in SRC_DIR, never
# in drumlab's tree; the physics is untouched:
#   -seed S         (>= 0) seeds the random state that places the particles (RNG::setRandomSeed);
#                   without it the run is the driver's own
#   -revolutions R  turns the drum R times instead of 5 (t_max = 2 pi R / omega)
#   -outputsPerRevolution K  writes its files and log line K times a revolution instead of 100
#                   (a throughput run without the output's cost)
demos="$src/Drivers/Demos/IndustrialMixers"
python3 - "$demos/RotatingDrumWet.cpp" "$demos/RotatingDrumWetSeeded.cpp" <<'PY'
import sys
src = open(sys.argv[1]).read()
edits = [
    ("        // dimensional parameters\n",
     '        const double seed = helpers::readFromCommandLine(argc,argv,"-seed",-1.0);\n'
     "        if (seed >= 0) random.setRandomSeed(static_cast<unsigned long>(seed));\n"
     "        // dimensional parameters\n"),
    ("double timeMax = 10.0*constants::pi/angularVelocity;",
     'double timeMax = 2.0*helpers::readFromCommandLine(argc,argv,"-revolutions",5.0)'
     "*constants::pi/angularVelocity;"),
    ('setName("RotatingDrumWet")', 'setName("RotatingDrumWetSeeded")'),
    ("setSaveCount(2.0*constants::pi/angularVelocity/getTimeStep()/100);",
     "setSaveCount(2.0*constants::pi/angularVelocity/getTimeStep()/"
     'helpers::readFromCommandLine(argc,argv,"-outputsPerRevolution",100.0));'),
]
for old, new in edits:
    if src.count(old) != 1:
        sys.exit(f"build_mercury: the driver changed, cannot find: {old.strip()}")
    src = src.replace(old, new, 1)
open(sys.argv[2], "w").write(src)
PY

mkdir -p "$build"
cmake -S "$src" -B "$build" -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_COMPILER="$cxx" \
  -DCMAKE_CXX_FLAGS="$flags" -DCMAKE_C_FLAGS="$flags" \
  -DCMAKE_CXX_FLAGS_RELEASE="-O3 -DNDEBUG" -DCMAKE_C_FLAGS_RELEASE="-O3 -DNDEBUG" \
  -DMercuryDPM_BUILD_USER_DIR=OFF > "$build/build_mercury.cmake.log" 2>&1 ||
  { echo "build_mercury: cmake failed, see $build/build_mercury.cmake.log" >&2; exit 1; }
nice -n 10 make -C "$build" -j"${JOBS:-2}" RotatingDrumWet RotatingDrumWetSeeded
echo "build_mercury: $build/Drivers/Demos/IndustrialMixers/RotatingDrumWet (and ...Seeded)"
