#include "app/cli/sweep_results.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>

#include <fmt/format.h>

#include "engine/types.hpp"

namespace drumlab::cli {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

std::vector<std::string> cells_of(const std::string& line) {
  std::vector<std::string> out;
  std::stringstream in(line);
  for (std::string c; std::getline(in, c, ',');) out.push_back(c);
  return out;
}

/// Mean and sample standard deviation of the finite values.
std::pair<double, double> mean_sd(const std::vector<double>& v) {
  double n = 0.0, sum = 0.0;
  for (const double x : v) {
    if (std::isfinite(x)) {
      n += 1.0;
      sum += x;
    }
  }
  if (n == 0.0) return {kNaN, kNaN};
  const double mean = sum / n;
  double ss = 0.0;
  for (const double x : v) {
    if (std::isfinite(x)) ss += (x - mean) * (x - mean);
  }
  return {mean, n > 1.0 ? std::sqrt(ss / (n - 1.0)) : 0.0};
}

/// The text of column `name` in the first data row of `file` ("" if the table has no rows).
std::string first_text_cell(const std::filesystem::path& file, const std::string& name) {
  std::ifstream in(file);
  std::string header, line;
  if (!std::getline(in, header) || !std::getline(in, line)) return {};
  const std::vector<std::string> columns = cells_of(header), cells = cells_of(line);
  const auto at = std::find(columns.begin(), columns.end(), name);
  if (at == columns.end()) throw InputError(fmt::format("{}: no column '{}'", file.string(), name));
  const auto k = static_cast<std::size_t>(at - columns.begin());
  return k < cells.size() ? cells[k] : std::string();
}

}  // namespace

std::size_t CsvTable::column(const std::string& name, const std::filesystem::path& file) const {
  const auto at = std::find(columns.begin(), columns.end(), name);
  if (at == columns.end()) {
    throw InputError(fmt::format("{}: no column '{}'", file.string(), name));
  }
  return static_cast<std::size_t>(at - columns.begin());
}

CsvTable read_numeric_csv(const std::filesystem::path& file) {
  std::ifstream in(file);
  std::string line;
  if (!in || !std::getline(in, line)) {
    throw InputError(fmt::format("{}: cannot read (the run wrote no table)", file.string()));
  }
  CsvTable t{cells_of(line), {}};
  for (std::size_t number = 2; std::getline(in, line); ++number) {
    const std::vector<std::string> cells = cells_of(line);
    if (cells.size() != t.columns.size()) {
      throw InputError(fmt::format("{}:{}: {} cells, the header has {}", file.string(), number,
                                   cells.size(), t.columns.size()));
    }
    std::vector<double> row(cells.size(), kNaN);
    for (std::size_t k = 0; k < cells.size(); ++k) {
      char* end = nullptr;
      const double v = std::strtod(cells[k].c_str(), &end);
      if (end != cells[k].c_str() && *end == '\0') row[k] = v;  // text cells stay nan
    }
    t.rows.push_back(std::move(row));
  }
  return t;
}

RunResult summarise_run(const SweepRun& run, const std::filesystem::path& dir, double window_from) {
  const auto obs_file = dir / "observables.csv";
  const CsvTable obs = read_numeric_csv(obs_file);
  if (obs.rows.empty()) throw InputError(fmt::format("{}: no frames", obs_file.string()));
  const std::size_t rev = obs.column("revolutions", obs_file), time = obs.column("time", obs_file);
  RunResult r{run.name, run.values, run.seed, 0, window_from, {}, {}, 0.0, {}, {}};
  // Turns counted either way (a drum may turn clockwise); the default window is the second half
  // of the run's time, which also serves a drum that does not turn (a planetary pot at k = -1).
  const double t_half = 0.5 * (obs.rows.front()[time] + obs.rows.back()[time]);
  std::vector<bool> in_window(obs.rows.size());
  for (std::size_t k = 0; k < obs.rows.size(); ++k) {
    in_window[k] =
        window_from < 0.0 ? obs.rows[k][time] >= t_half : std::abs(obs.rows[k][rev]) >= window_from;
    if (in_window[k] && r.frames++ == 0 && window_from < 0.0)
      r.window_from = std::abs(obs.rows[k][rev]);
  }
  if (r.frames == 0) {
    throw InputError(fmt::format("{}: no frame from revolution {:g} on (the run turned {:g})",
                                 obs_file.string(), window_from, std::abs(obs.rows.back()[rev])));
  }
  CsvTable agg;
  const auto agg_file = dir / "agglomerates.csv";
  if (run.has_bonds) agg = read_numeric_csv(agg_file);
  if (run.has_bonds && agg.rows.size() != obs.rows.size()) {
    throw InputError(fmt::format("{}: {} rows, observables.csv has {}", agg_file.string(),
                                 agg.rows.size(), obs.rows.size()));
  }
  if (run.has_bonds) r.criterion = first_text_cell(agg_file, "criterion");
  r.regime = table_regime(obs, in_window, obs_file);
  for (const SweptQuantity& q : kSweptQuantities) {
    std::vector<double> values;
    if (!q.agglomerates || run.has_bonds) {
      const CsvTable& t = q.agglomerates ? agg : obs;
      const std::size_t c = t.column(q.column, q.agglomerates ? agg_file : obs_file);
      for (std::size_t k = 0; k < t.rows.size(); ++k) {
        if (in_window[k]) values.push_back(t.rows[k][c]);
      }
    }
    const auto [m, s] = mean_sd(values);
    r.mean.push_back(m);
    r.sd.push_back(s);
  }
  // The conserved total: the bed's liquid plus what flies or was lost, less what was sprayed.
  const std::size_t f = obs.column("free_liquid", obs_file);
  const std::size_t sprayed = obs.column("sprayed_liquid", obs_file);
  const auto total = [&](const std::vector<double>& row) {
    return row[f] + row[f + 1] + row[f + 2] + row[sprayed + 1] + row[sprayed + 2] - row[sprayed];
  };
  const double first = total(obs.rows.front());
  for (const auto& row : obs.rows) {
    if (first > 0.0)
      r.liquid_drift = std::max(r.liquid_drift, std::abs(total(row) - first) / first);
  }
  return r;
}

RegimeEvidence table_regime(const CsvTable& t, const std::vector<bool>& in_window,
                            const std::filesystem::path& file) {
  const auto at = [&](const char* name) { return t.column(name, file); };
  const std::size_t angle = at("angle_fit_deg"), curvature = at("surface_curvature"),
                    relative = at("relative_speed"), air = at("airborne_fraction"),
                    upper = at("upper_fraction"), com = at("com_offset"), wall = at("wall_speed"),
                    field = at("field"), radius = at("drum_radius");
  std::vector<DrumObservables> window;
  for (std::size_t k = 0; k < t.rows.size(); ++k) {
    if (!in_window[k]) continue;
    const std::vector<double>& row = t.rows[k];
    DrumObservables o;
    o.surface_found = std::isfinite(row[angle]);
    o.angle_of_repose_deg = o.surface_found ? row[angle] : 0.0;
    o.surface_curvature = row[curvature];
    o.relative_speed = row[relative];
    o.airborne_fraction = row[air];
    o.upper_fraction = row[upper];
    o.com_offset = row[com];
    o.wall_speed = row[wall];
    o.field = row[field];
    o.radius = row[radius];
    window.push_back(o);
  }
  return classify_regime(window);
}

std::string sweep_header(const std::vector<SweepSet>& sets) {
  std::string h = "run";
  for (const SweepSet& s : sets) h += "," + s.key;
  h += ",seed,window_from,frames,granule_criterion";
  for (const SweptQuantity& q : kSweptQuantities) h += fmt::format(",{},{}_sd", q.name, q.name);
  return h + ",liquid_drift,regime";
}

std::string sweep_row(const RunResult& r) {
  std::string row = r.name;
  for (const std::string& v : r.values) row += "," + v;
  row += fmt::format(",{},{:.6g},{},{}", r.seed, r.window_from, r.frames, r.criterion);
  for (std::size_t k = 0; k < r.mean.size(); ++k) {
    row += fmt::format(",{:.6g},{:.6g}", r.mean[k], r.sd[k]);
  }
  return row + fmt::format(",{:.3g},{}", r.liquid_drift, regime_name(r.regime.regime));
}

std::map<std::string, std::string> read_sweep_rows(const std::filesystem::path& file,
                                                   const std::string& header) {
  std::map<std::string, std::string> rows;
  std::ifstream in(file);
  if (!in) return rows;
  std::string line;
  if (!std::getline(in, line) || line != header) {
    throw InputError(
        fmt::format("{}: written by another sweep (its columns differ): choose "
                    "another --out or remove it",
                    file.string()));
  }
  while (std::getline(in, line)) {
    if (!line.empty()) rows.emplace(line.substr(0, line.find(',')), line);
  }
  return rows;
}

}  // namespace drumlab::cli
