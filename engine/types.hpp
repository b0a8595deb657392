#pragma once
// Basic numeric types shared by the whole engine. SI units everywhere.
#include <Eigen/Core>
#include <cstdint>
#include <stdexcept>
#include <string>

namespace drumlab {

using Vec3 = Eigen::Vector3d;
using Index = std::uint32_t;

/// Thrown for invalid user input (scene files, CSVs, command-line values). The message is one line
/// that names the file/key and the reason; the CLI prints it and exits non-zero.
class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Thrown when a run becomes numerically unstable (non-finite values, runaway overlaps).
class UnstableError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace drumlab
