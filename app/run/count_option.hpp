#pragma once
// A validator for options read into unsigned integers (step and frame counts): CLI11 2.1 reads
// "-3" into an unsigned as 2^64 - 3, which would run for ever; CLI::NonNegativeNumber would say
// so against a range up to 1.8e308. This one wants digits only.
#include <string>

#include <CLI/CLI.hpp>

namespace drumlab::cli {

inline CLI::Validator whole_count() {
  return CLI::Validator(
      [](std::string& value) -> std::string {
        if (!value.empty() && value.find_first_not_of("0123456789") == std::string::npos) {
          return {};
        }
        return "expected a whole number >= 0, got '" + value + "'";
      },
      "COUNT");
}

}  // namespace drumlab::cli
