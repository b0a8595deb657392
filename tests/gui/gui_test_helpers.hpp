#pragma once
// Shared by the GUI tests: running drumlab-gui (under xvfb-run where a window is needed) and
// reading its screenshot back.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "engine/particles.hpp"
#include "render/image.hpp"

namespace drumlab::test {

struct GuiRun {
  int exit_code = -1;
  std::string output;  ///< stdout and stderr together
};

/// Runs drumlab-gui with `args`; `window`: under xvfb-run (the caller skips where it is absent).
GuiRun run_gui(const std::string& args, bool window);
/// Expects bad input: exit code 2, one line of output, and `names` (the flag, key or file) in it.
void expect_one_line_error(const GuiRun& r, const std::string& names);
/// True where ctest found xvfb-run at configure time.
bool have_xvfb();
/// A fresh empty directory under the temporary directory, unique to this process and removed when
/// it exits.
std::filesystem::path fresh_dir(const std::string& name);
/// Writes the small two-size test drum (tests/small_drum_text.hpp) with `search` to DIR/NAME.
std::filesystem::path write_small_drum(const std::filesystem::path& dir, const std::string& search);
/// Position, velocity and angular velocity components of `a` that differ in any bit from those of
/// the particle with the same id in `b` (the same particles, in any order).
std::size_t differing_motion(const Particles& a, const Particles& b);
/// Reads a PNG (RGB rows top to bottom); an empty image if it cannot.
render::Image read_png(const std::filesystem::path& file);
/// Pixels within `tolerance` levels of `rgb` (components in [0, 1]) in every channel.
std::size_t pixels_near(const render::Image& img, const double* rgb, int tolerance);

}  // namespace drumlab::test
