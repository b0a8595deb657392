#!/bin/bash
# Build LAMMPS from Debian's source package with drumlab's compiler and flags, beside drumlab,
# never inside it: the fair peer of the speed ratios (lammps_side_by_side.sh with LMP=...).
#
#   bash app/bench/build_lammps.sh WORK_DIR          ->  WORK_DIR/build/lmp
#
# WORK_DIR  outside the repository; gets the unpacked source (`apt-get source lammps`: Debian 12's
#           20220106 release, the version of Debian's `lmp`) and the build folder.
# Flags: drumlab's own, so that a ratio compares the codes, not the compilers: the same GCC
# (CXX, default c++), Release with -O3, the -march drumlab's CMakeLists picks on this machine
# (x86-64-v4 where the CPU runs AVX-512, else x86-64-v3; MARCH=... overrides, e.g. MARCH=x86-64-v3
# for the baseline build) and -fno-math-errno -fno-trapping-math. Packages: GRANULAR only (the
# drum deck's pair, wall and integrator styles), with MPI (OpenMPI, for CORES=2) and OpenMP as
# Debian's; a static executable (Debian's links a shared liblammps with every package).
# Needs: a deb-src line for bookworm (added to /etc/apt/sources.list.d/ if no source line names
# bookworm: root), dpkg-dev, cmake, make, libopenmpi-dev. Builds with JOBS (default 2) jobs under
# nice. CI never runs this script.
set -euo pipefail
work=${1:?usage: build_lammps.sh WORK_DIR}
mkdir -p "$work"
work=$(cd "$work" && pwd)
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
case "$work/" in "$root"/*) echo "build_lammps: WORK_DIR must be outside the repository" >&2; exit 2 ;; esac
jobs=${JOBS:-2}
cxx=${CXX:-c++}

if ! grep -rqsE '^(Types:.*deb-src|deb-src .*bookworm)' /etc/apt/sources.list /etc/apt/sources.list.d/; then
  echo "build_lammps: adding a deb-src line for bookworm (/etc/apt/sources.list.d/drumlab-deb-src.sources)"
  cat >/etc/apt/sources.list.d/drumlab-deb-src.sources <<'SRC'
Types: deb-src
URIs: http://deb.debian.org/debian
Suites: bookworm
Components: main
Signed-By: /usr/share/keyrings/debian-archive-keyring.gpg
SRC
  apt-get update -qq
fi
src=$(find "$work" -mindepth 1 -maxdepth 1 -type d -name 'lammps-*' | head -n 1)
if [ -z "$src" ]; then
  (cd "$work" && apt-get source -q lammps)
  src=$(find "$work" -mindepth 1 -maxdepth 1 -type d -name 'lammps-*' | head -n 1)
fi
[ -f "$src/cmake/CMakeLists.txt" ] || { echo "build_lammps: no LAMMPS source in $work" >&2; exit 1; }

# The -march of drumlab's CMakeLists: x86-64-v4 when this CPU runs AVX-512, else x86-64-v3.
if [ -z "${MARCH:-}" ]; then
  if grep -qw avx512f /proc/cpuinfo && grep -qw avx512vl /proc/cpuinfo; then MARCH=x86-64-v4; else MARCH=x86-64-v3; fi
fi
flags="-O3 -DNDEBUG -march=$MARCH -fno-math-errno -fno-trapping-math"
build=$work/build
echo "build_lammps: $src -> $build/lmp ($cxx $flags)"
cmake -S "$src/cmake" -B "$build" -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_COMPILER="$cxx" \
  -DCMAKE_CXX_FLAGS_RELEASE="$flags" -DBUILD_SHARED_LIBS=OFF -DBUILD_MPI=ON -DBUILD_OMP=ON \
  -DPKG_GRANULAR=ON -DLAMMPS_MACHINE= >"$work/configure.log"
nice -n 10 cmake --build "$build" -j "$jobs" --target lmp >"$work/build.log" 2>&1 ||
  { tail -n 30 "$work/build.log"; echo "build_lammps: build failed ($work/build.log)" >&2; exit 1; }
"$build/lmp" -h | sed -n '/^Compiler:/,/^$/p' && "$build/lmp" -h | grep -A2 '^Installed packages:'
echo "build_lammps: $build/lmp"
