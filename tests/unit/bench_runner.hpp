#pragma once
// Runs a benchmark of app/bench in-process and captures what it prints (stdout), as the CLI tests
// capture the output of the `drumlab` executable; plus reading a CSV file's lines.
#include <gtest/gtest.h>

#include <exception>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace drumlab::test {

struct BenchRun {
  bool ok = false;     ///< returned without throwing
  std::string output;  ///< stdout, then the exception's message if it threw
};

template <class F>
BenchRun run_bench(F&& f) {
  BenchRun r;
  testing::internal::CaptureStdout();
  try {
    f();
    r.ok = true;
  } catch (const std::exception& e) {
    r.output = testing::internal::GetCapturedStdout() + "threw: " + e.what() + "\n";
    return r;
  }
  r.output = testing::internal::GetCapturedStdout();
  return r;
}

/// A bench's options (any of app/bench's *Options) for `scene`, with the cached rolling state in
/// DIR/cache and the CSV and chart in DIR/out.
template <class Options>
Options bench_options(const std::string& scene, const std::filesystem::path& dir) {
  Options opt;
  opt.scene = scene;
  opt.plan.cache_dir = dir / "cache";
  opt.out = (dir / "out").string();
  return opt;
}

/// The lines of a text file (none if it cannot be read).
inline std::vector<std::string> read_lines(const std::filesystem::path& file) {
  std::ifstream in(file);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

}  // namespace drumlab::test
