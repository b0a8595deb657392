// `drumlab paper-table`: the paper's operation-count estimates beside what drumlab counts on the
// paper's packing.
#include "app/bench/paper_table.hpp"

#include <algorithm>
#include <chrono>
#include <sstream>
#include <string>

#include <fmt/format.h>

#include "app/bench/paper_reference.hpp"
#include "engine/fill/paper_packing.hpp"
#include "engine/io/atomic_file.hpp"
#include "engine/search/contact_search.hpp"

namespace drumlab::bench {

namespace {

constexpr const char* kSizeNames[3] = {"small", "medium", "large"};

struct MethodCount {
  std::string name;
  double cell_side = 0;
  std::uint64_t cells_total = 0;
  std::array<double, 3> mean_cells{};  ///< per particle of each size
  std::array<double, 3> mean_tested{};
  double mean_cells_all = 0, mean_tested_all = 0;
  std::uint64_t contacts = 0;
  double seconds = 0;
  std::vector<IndexPair> pairs;
};

MethodCount count_method(const std::string& name, const Particles& p, const Box& box) {
  auto search = make_search(name);
  MethodCount m;
  m.name = name;
  SearchInput in{p.position, p.radius, 0.0, box, std::nullopt};
  const auto t0 = std::chrono::steady_clock::now();
  search->find_pairs(in, m.pairs);
  m.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::sort(m.pairs.begin(), m.pairs.end());
  m.cell_side = search->cell_size();
  m.cells_total = search->counters().cells_total;
  m.contacts = m.pairs.size();
  std::array<double, 3> count{};
  const auto cells = search->cells_visited_per_particle();
  const auto tested = search->pairs_tested_per_particle();
  for (std::size_t i = 0; i < p.size(); ++i) {
    const int c = p.size_class[i];
    count[c] += 1;
    m.mean_cells[c] += cells[i];
    m.mean_tested[c] += tested[i];
  }
  const double n = static_cast<double>(p.size());
  m.mean_cells_all = static_cast<double>(search->counters().cells_visited) / n;
  m.mean_tested_all = static_cast<double>(search->counters().pairs_tested) / n;
  for (int c = 0; c < 3; ++c) {
    m.mean_cells[c] /= std::max(1.0, count[c]);
    m.mean_tested[c] /= std::max(1.0, count[c]);
  }
  return m;
}

std::string number(double v) {
  if (v < 0) return "-";
  if (v == static_cast<double>(static_cast<long long>(v)) && v < 1e12)
    return fmt::format("{}", static_cast<long long>(v));
  return fmt::format("{:.4g}", v);
}

/// Rows of (quantity, paper value per method, drumlab value per method).
struct Row {
  std::string quantity;
  std::array<double, 5> paper;
  std::array<double, 5> ours;
};

/// m1..m5 counted on the packing (progress on stderr).
std::vector<MethodCount> count_methods(const Particles& p, const Box& box) {
  std::vector<MethodCount> counts;
  for (int m = 1; m <= 5; ++m) {
    fmt::print(stderr, "counting m{} on {} particles...\n", m, p.size());
    counts.push_back(count_method(fmt::format("m{}", m), p, box));
  }
  return counts;
}

std::vector<Row> table_rows(const PaperTable& ref, const std::vector<MethodCount>& counts,
                            const Particles& p) {
  std::array<std::size_t, 3> count{};
  for (auto c : p.size_class) ++count[c];
  std::vector<Row> rows;
  auto add = [&](std::string q, auto paper_of, auto ours_of) {
    Row r{std::move(q), {}, {}};
    for (int m = 0; m < 5; ++m) {
      r.paper[m] = paper_of(ref.methods[m], m);
      r.ours[m] = ours_of(counts[m]);
    }
    rows.push_back(std::move(r));
  };
  for (int c = 0; c < 3; ++c) {
    add(
        fmt::format("particles {}", kSizeNames[c]), [&](auto&, int) { return ref.particles[c]; },
        [&](auto&) { return static_cast<double>(count[c]); });
  }
  add(
      "cell side (m)", [](auto& col, int) { return col.cell_side; },
      [](auto& m) { return m.cell_side; });
  add(
      "grid cells", [](auto& col, int) { return col.total_cells; },
      [](auto& m) { return static_cast<double>(m.cells_total); });
  add(
      "particles per cell", [](auto& col, int) { return col.particles_per_cell; },
      [&](auto& m) { return static_cast<double>(p.size()) / static_cast<double>(m.cells_total); });
  for (int c = 0; c < 3; ++c) {
    add(
        fmt::format("cells visited / {}", kSizeNames[c]),
        [&](auto& col, int) { return col.search_cells[c]; },
        [&](auto& m) { return m.mean_cells[c]; });
  }
  for (int c = 0; c < 3; ++c) {
    add(
        fmt::format("pairs tested / {}", kSizeNames[c]),
        [&](auto& col, int) { return col.particles_checked[c]; },
        [&](auto& m) { return m.mean_tested[c]; });
  }
  add(
      "cells visited / particle", [](auto&, int) { return -1.0; },
      [](auto& m) { return m.mean_cells_all; });
  add(
      "pairs tested / particle", [](auto&, int) { return -1.0; },
      [](auto& m) { return m.mean_tested_all; });
  add(
      "operations / particle (paper)", [](auto& col, int) { return col.operations_per_particle; },
      [](auto&) { return -1.0; });
  add(
      "true contacts / particle", [](auto&, int) { return -1.0; },
      [&](auto& m) { return static_cast<double>(m.contacts) / static_cast<double>(p.size()); });
  add(
      "pairs tested / contact", [](auto&, int) { return -1.0; },
      [&](auto& m) {
        return m.mean_tested_all * static_cast<double>(p.size()) /
               std::max(1.0, static_cast<double>(m.contacts));
      });
  add(
      "search time (s)", [](auto&, int) { return -1.0; }, [](auto& m) { return m.seconds; });
  return rows;
}

void print_table(int table, const PaperTable& ref, const std::vector<Row>& rows) {
  fmt::print("Paper Table {} (depth H = {} m): paper's estimate | drumlab's count on the packing\n",
             table, ref.depth);
  fmt::print("{:<30}", "quantity");
  for (int m = 1; m <= 5; ++m) fmt::print("{:>22}", fmt::format("m{} paper | ours", m));
  fmt::print("\n");
  for (const Row& r : rows) {
    fmt::print("{:<30}", r.quantity);
    for (int m = 0; m < 5; ++m)
      fmt::print("{:>22}", fmt::format("{} | {}", number(r.paper[m]), number(r.ours[m])));
    fmt::print("\n");
  }
}

/// The table in long format: one line per quantity and method.
void write_table_csv(const std::string& csv_path, int table, const std::vector<Row>& rows) {
  write_file_atomically(csv_path, [&](std::ostream& os) {
    os << "table,quantity,method,paper,drumlab\n";
    for (const Row& r : rows) {
      for (int m = 0; m < 5; ++m) {
        os << table << ',' << r.quantity << ",m" << (m + 1) << ','
           << (r.paper[m] < 0 ? std::string() : fmt::format("{}", r.paper[m])) << ','
           << (r.ours[m] < 0 ? std::string() : fmt::format("{}", r.ours[m])) << '\n';
      }
    }
  });
}

}  // namespace

void run_paper_table(int table, const std::string& csv_path) {
  const PaperTable& ref = kPaperTables.at(static_cast<std::size_t>(table - 1));
  const Vec3 box_size(1.85, 1.80, ref.depth);
  const Particles p = paper_packing(box_size, 2500.0);
  const Box box{Vec3::Zero(), box_size};
  const std::vector<MethodCount> counts = count_methods(p, box);
  bool identical = true;
  for (const auto& m : counts) identical = identical && m.pairs == counts.front().pairs;
  const std::vector<Row> rows = table_rows(ref, counts, p);
  print_table(table, ref, rows);
  fmt::print("contact sets of m1..m5 identical: {} ({} contacts)\n", identical ? "yes" : "NO",
             counts.front().contacts);
  if (!csv_path.empty()) {
    write_table_csv(csv_path, table, rows);
    fmt::print("wrote {}\n", csv_path);
  }
  if (!identical) throw std::runtime_error("the five methods disagree on the contact set");
}

}  // namespace drumlab::bench
