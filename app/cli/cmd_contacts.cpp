// drumlab contacts --particles FILE.csv --method M [--out PAIRS.csv] [--margin GAP]
// Finds every contact among the particles of a CSV file with one search method.
#include <algorithm>
#include <chrono>
#include <string>

#include <fmt/format.h>

#include "app/cli/commands.hpp"
#include "engine/io/atomic_file.hpp"
#include "engine/io/particle_csv.hpp"
#include "engine/search/contact_search.hpp"
#include "engine/search/search_methods.hpp"

namespace drumlab::cli {

namespace {

struct ContactsOptions {
  std::string particles;
  std::string method = "m5";
  std::string out;
  double margin = 0.0;
};

void write_pairs(std::ostream& os, const std::vector<IndexPair>& pairs) {
  os << "i,j\n";
  for (const IndexPair& p : pairs) os << p.i << ',' << p.j << '\n';
}

void run_contacts(const ContactsOptions& opt) {
  auto search = make_search(opt.method);  // unknown method: error before reading the file
  const ParticleTable table = read_particle_csv(opt.particles);
  SearchInput in{table.position, table.radius, opt.margin, std::nullopt, std::nullopt};
  std::vector<IndexPair> pairs;
  const auto t0 = std::chrono::steady_clock::now();
  search->find_pairs(in, pairs);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::sort(pairs.begin(), pairs.end());

  const SearchCounters& c = search->counters();
  const double n = std::max<double>(1.0, static_cast<double>(table.radius.size()));
  const std::string summary = fmt::format(
      "method {}: {} particles, {} contacts; cells visited {} ({:.2f}/particle), pairs tested {} "
      "({:.2f}/particle, {:.2f} per contact); grid cells {}; {:.3f} s\n",
      search->name(), table.radius.size(), pairs.size(), c.cells_visited,
      static_cast<double>(c.cells_visited) / n, c.pairs_tested,
      static_cast<double>(c.pairs_tested) / n,
      pairs.empty() ? 0.0 : static_cast<double>(c.pairs_tested) / static_cast<double>(pairs.size()),
      c.cells_total, seconds);
  if (opt.out.empty()) {
    write_pairs(std::cout, pairs);
    fmt::print(stderr, "{}", summary);
  } else {
    write_file_atomically(opt.out, [&](std::ostream& os) { write_pairs(os, pairs); });
    fmt::print("{}", summary);
  }
}

}  // namespace

void add_contacts_command(CLI::App& app) {
  auto opt = std::make_shared<ContactsOptions>();
  CLI::App* cmd = app.add_subcommand(
      "contacts", "Find all contacts among particles read from a CSV (header x,y,z,r; metres)");
  cmd->add_option("--particles", opt->particles, "CSV file with columns x,y,z,r")->required();
  cmd->add_option("--method", opt->method, "search method: " + search_method_help())
      ->capture_default_str();
  cmd->add_option("--out", opt->out, "write the pairs (i,j rows, 0-based, sorted) to this CSV");
  cmd->add_option("--margin", opt->margin, "count pairs whose surfaces are within this gap (m)")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  cmd->callback([opt] { run_contacts(*opt); });
}

}  // namespace drumlab::cli
