#include "app/run/granule_flags.hpp"

#include <fmt/format.h>

#include "engine/types.hpp"

namespace drumlab::cli {

void add_granule_flags(CLI::App* cmd, GranuleFlags& flags) {
  cmd->add_option_function<std::string>(
         "--granule-criterion",
         [&flags](const std::string& name) {
           // The check below has refused any other name.
           flags.criterion.method = parse_granule_method(name).value_or(GranuleMethod::age);
         },
         "what a granule is: age (bonds older than --granule-age join), community (communities "
         "of the force-weighted bond network, Leiden) or components (every bond joins); "
         "default: age")
      ->check(CLI::IsMember({"age", "community", "components"}));
  cmd->add_option_function<double>(
         "--granule-age",
         [&flags](double t) {
           flags.criterion.age = t;
           flags.age_given = true;
         },
         "with the age criterion: bonds older than T s join (0: plain components; default: one "
         "drum revolution)")
      ->check(CLI::NonNegativeNumber);
  cmd->add_option_function<double>(
         "--granule-resolution",
         [&flags](double r) {
           flags.criterion.resolution = r;
           flags.resolution_given = true;
         },
         "with the community criterion: the modularity's resolution (default 1; larger: "
         "smaller granules)")
      ->check(CLI::PositiveNumber);
}

void check_granule_flags(const GranuleFlags& flags) {
  const GranuleMethod m = flags.criterion.method;
  if (flags.age_given && m != GranuleMethod::age) {
    throw InputError(fmt::format("--granule-age applies to --granule-criterion age, not {}",
                                 granule_method_name(m)));
  }
  if (flags.resolution_given && m != GranuleMethod::community) {
    throw InputError(
        fmt::format("--granule-resolution applies to --granule-criterion community, not {}",
                    granule_method_name(m)));
  }
}

}  // namespace drumlab::cli
