#pragma once
// How OpenMP threads wait at a barrier, chosen for a shared machine before the runtime starts.
//
// libgomp's default is to spin about 300,000 times before a waiting thread sleeps. On a machine
// where other processes compete for the cores, the partner a thread waits for is often
// descheduled, and the spinning thread burns the core the partner needs: two threads then ran
// 2-10x slower than one (app/bench/README.md, "Threads on a shared machine").
// OMP_WAIT_POLICY=passive makes a waiting thread sleep at once; measured, it keeps two threads
// at or above one thread's speed on a busy machine and costs little on a quiet one.
//
// libgomp reads its environment when it is loaded, before main, so the choice is made by setting
// the variable and executing the program again (/proc/self/exe, the same arguments). That happens
// only when the user asked for more than one thread (`--threads N`, N > 1) and set neither
// OMP_WAIT_POLICY nor GOMP_SPINCOUNT (their choice wins); DRUMLAB_OMP_DEFAULT=off turns it off.
// Without OpenMP, or if the exec fails, the program simply goes on.
#include <unistd.h>

#include <cstdlib>
#include <cstring>
#include <string_view>

namespace drumlab {

/// True if argv asks for more than one thread ("--threads N" or "--threads=N", N > 1).
inline bool asks_for_threads(int argc, char** argv) {
  for (int k = 1; k < argc; ++k) {
    const std::string_view a = argv[k];
    const char* value = nullptr;
    if (a == "--threads" && k + 1 < argc) value = argv[k + 1];
    if (a.starts_with("--threads=")) value = argv[k] + std::strlen("--threads=");
    if (value != nullptr && std::atoi(value) > 1) return true;
  }
  return false;
}

/// Call first in main(): see the file comment. Returns only if no exec was done (or it failed).
inline void choose_openmp_waiting(int argc, char** argv) {
#ifdef _OPENMP
  if (std::getenv("OMP_WAIT_POLICY") != nullptr || std::getenv("GOMP_SPINCOUNT") != nullptr) {
    return;
  }
  const char* opt = std::getenv("DRUMLAB_OMP_DEFAULT");
  if (opt != nullptr && std::string_view(opt) == "off") return;
  if (!asks_for_threads(argc, argv)) return;
  if (setenv("OMP_WAIT_POLICY", "passive", 0) != 0) return;
  execv("/proc/self/exe", argv);
  unsetenv("OMP_WAIT_POLICY");  // the exec failed: go on as we are
#else
  (void)argc;
  (void)argv;
#endif
}

/// How waiting threads wait, in words, for run summaries: the variable that decides it.
inline const char* openmp_waiting_description() {
  if (const char* p = std::getenv("OMP_WAIT_POLICY")) {
    return std::string_view(p) == "passive" || std::string_view(p) == "PASSIVE"
               ? "sleep at once (OMP_WAIT_POLICY=passive)"
               : "spin (OMP_WAIT_POLICY set, not passive)";
  }
  if (std::getenv("GOMP_SPINCOUNT") != nullptr) return "spin, then sleep (GOMP_SPINCOUNT set)";
  return "the OpenMP runtime's default (spin, then sleep)";
}

}  // namespace drumlab
