// drumlab analyze SERIES.h5 --agglomerates FILE.csv [--granule-criterion C] [--granule-age T]
//                                                  [--granule-resolution R]
// The agglomerate table of `run --agglomerates` computed afterwards from an HDF5 series (which
// stores the bond graph of every frame of a scene with bonds), with its chart FILE.png.
// drumlab analyze TABLE.csv
// The chart TABLE.png of a finished table (drumlab-mpi writes the table, and has this drawn: an
// MPI executable links no VTK).
// --growth FILE.png (with a series or a table): the phases of granulation
// (engine/analysis/growth_phases.hpp) printed, and d50 and the granule count against the liquid
// sprayed drawn.
// --accretion FILE.csv --seed-class K (a series): the primaries held in the granules of class K's
// particles per frame (engine/analysis/accretion.hpp), the saturating exponential fitted to them,
// and the chart FILE.png.
#include <fmt/format.h>

#include <algorithm>
#include <optional>

#include "app/cli/commands.hpp"
#include "app/run/granule_flags.hpp"
#include "app/run/output_schedule.hpp"
#include "engine/analysis/accretion.hpp"
#include "engine/analysis/agglomerate_table.hpp"
#include "engine/analysis/growth_phases.hpp"
#include "engine/io/atomic_file.hpp"
#include "engine/io/h5_series.hpp"
#ifdef DRUMLAB_WITH_RENDER
#include "render/accretion_chart.hpp"
#include "render/agglomerate_chart.hpp"
#include "render/growth_chart.hpp"
#endif

namespace drumlab::cli {
namespace {

struct AnalyzeOptions {
  std::string series;
  std::string agglomerates;
  GranuleFlags granule;
  std::string growth;             ///< --growth FILE.png
  std::string accretion;          ///< --accretion FILE.csv
  std::optional<int> seed_class;  ///< --seed-class K
};

/// The accretion curve: its CSV (time, count, the fit's value), the fit printed and its chart.
void accretion(const std::vector<double>& t, const std::vector<double>& n, int seed_class,
               const std::string& csv, const std::string& criterion) {
  if (t.size() < 3) {
    throw InputError(
        fmt::format("--accretion: the series has {} frames, the fit needs 3", t.size()));
  }
  const SaturatingFit fit = fit_saturating_exponential(t, n);
  write_file_atomically(csv, [&](std::ostream& out) {
    out << "time,accreted,fit\n";
    for (std::size_t k = 0; k < t.size(); ++k) {
      out << fmt::format("{:.12g},{:.0f},{:.12g}\n", t[k], n[k], saturating_value(fit, t[k]));
    }
  });
  fmt::print(
      "accretion         {} (class {}, {}): {} -> {} primaries held over t = {:.4g}-{:.4g} s\n",
      csv, seed_class, criterion, n.front(), n.back(), t.front(), t.back());
  fmt::print(
      "accretion fit     N(t) = N_inf - (N_inf - N_0) exp(-(t - {:.4g} s) / tau): N_0 = {:.4g}, "
      "N_inf = {:.4g}, tau = {:.4g} s{}; rms {:.3g}, R^2 {:.4f} (a straight line: R^2 {:.4f})\n",
      fit.t0, fit.n0, fit.n_inf, fit.tau,
      fit.tau_at_grid_edge ? " (the longest tried: the curve has not bent)" : "", fit.rms,
      fit.r_squared, fit.line_r_squared);
#ifdef DRUMLAB_WITH_RENDER
  std::filesystem::path png = csv;
  png.replace_extension(".png");
  render::write_accretion_chart(t, n, fit, criterion, png);
  fmt::print("accretion chart   {}\n", png.string());
#endif
}

/// The phases of granulation in `rows`, one line each, and their chart.
void growth(const std::vector<AgglomerateStats>& rows, const std::string& png) {
  const std::vector<GrowthPhase> phases = growth_phases(rows);
  const bool sprayed = !rows.empty() && rows.back().spray.sprayed > 0.0;
  const auto at = [&](std::size_t k) {
    return sprayed ? fmt::format("{:.4g} m^3 sprayed", rows[k].spray.sprayed)
                   : fmt::format("t = {:.4g} s", rows[k].time);
  };
  if (phases.empty()) fmt::print("growth            no granule (size >= 2) in any frame\n");
  for (const GrowthPhase& p : phases) {
    fmt::print(
        "growth            {:<13} frames {}-{} ({} to {}): granules {} -> {}, d50 {:.3g} -> {:.3g} "
        "mm\n",
        p.name, p.first, p.last, at(p.first), at(p.last), rows[p.first].count, rows[p.last].count,
        1e3 * rows[p.first].d50, 1e3 * rows[p.last].d50);
    if (p.name != "growth" || p.last == p.first) continue;
    // The growth rate: d50's rise over the phase per second and per liquid added.
    const AgglomerateStats &a = rows[p.first], &b = rows[p.last];
    const double rise = 1e3 * (b.d50 - a.d50);
    const double added = b.spray.sprayed - a.spray.sprayed;
    fmt::print("growth rate       {:.4g} mm/s{}\n", rise / (b.time - a.time),
               added > 0.0 ? fmt::format(", {:.4g} mm per 1e-8 m^3 sprayed", rise / added * 1e-8)
                           : std::string());
  }
#ifdef DRUMLAB_WITH_RENDER
  render::write_growth_chart(rows, phases, png);
  fmt::print("growth chart      {}\n", png);
#else
  throw InputError(fmt::format("--growth {}: this build has no VTK to draw the chart", png));
#endif
}

void chart(const std::filesystem::path& table) {
  const std::vector<AgglomerateStats> rows = read_agglomerate_table(table);
#ifdef DRUMLAB_WITH_RENDER
  std::filesystem::path png = table;
  png.replace_extension(".png");
  render::write_agglomerate_chart(rows, png);
  fmt::print("agglomerate chart {} ({} frames)\n", png.string(), rows.size());
#else
  throw InputError(fmt::format("{}: this build has no VTK to draw the chart", table.string()));
#endif
}

void analyze(const AnalyzeOptions& o) {
  check_granule_flags(o.granule);
  if (!o.growth.empty()) check_parent_directory(o.growth, "--growth");
  if (!o.accretion.empty()) check_parent_directory(o.accretion, "--accretion");
  if (o.accretion.empty() != !o.seed_class) {
    throw InputError("--accretion FILE.csv and --seed-class K go together");
  }
  if (o.seed_class && !(*o.seed_class >= 0 && *o.seed_class < 256)) {
    throw InputError(
        fmt::format("--seed-class {}: a [[particles]] index, 0 to 255", *o.seed_class));
  }
  if (o.series.ends_with(".csv")) {
    if (!o.agglomerates.empty()) {
      throw InputError(fmt::format("--agglomerates: {} is already a table", o.series));
    }
    if (!o.accretion.empty()) {
      throw InputError(
          fmt::format("--accretion: needs a series (a table has no particles), got {}", o.series));
    }
    if (!o.growth.empty()) {
      growth(read_agglomerate_table(o.series), o.growth);
    } else {
      chart(o.series);
    }
    return;
  }
  if (o.agglomerates.empty() && o.growth.empty() && o.accretion.empty()) {
    throw InputError(
        "--agglomerates FILE.csv, --growth FILE.png or --accretion FILE.csv: what to make of the "
        "series (one is required)");
  }
  const SeriesInfo info = read_series_info(o.series);
  if (info.frames == 0) throw InputError(fmt::format("{}: the series has no frames", o.series));
  if (!info.has_bonds) {
    throw InputError(fmt::format(
        "{}: the series has no bond graph (written for a scene without bonds)", o.series));
  }
  std::optional<AgglomerateTable> table;
  if (!o.agglomerates.empty()) table.emplace(o.agglomerates);
  std::vector<AgglomerateStats> rows;
  std::vector<double> times, accreted;
  bool seed_found = false;
  for (std::size_t k = 0; k < info.frames; ++k) {
    const SeriesFrame f = read_series_frame(o.series, k);
    if (!f.has_bonds) {
      throw InputError(fmt::format("{}: {} has no bond graph", o.series, h5_frame_group(k)));
    }
    AgglomerateInput in;
    in.position = f.position;
    in.radius = f.radius;
    in.mass = f.mass;
    in.id = f.id;
    in.film = f.film;
    in.bonds = f.bonds;
    in.wall_liquid = f.wall_liquid;
    in.spray = f.spray;
    in.period = f.period;
    in.time = f.time;
    const AgglomerateFrame frame =
        find_agglomerates(in, granule_options(f.drum_omega, o.granule.criterion));
    rows.push_back(frame.stats);
    if (table) table->add(rows.back());
    if (o.seed_class) {
      const auto seed = static_cast<std::uint8_t>(*o.seed_class);
      seed_found = seed_found || std::ranges::find(f.size_class, seed) != f.size_class.end();
      times.push_back(f.time);
      accreted.push_back(static_cast<double>(accreted_count(frame, f.size_class, seed)));
    }
  }
  const AgglomerateStats& last = rows.back();
  fmt::print("series            {}: {} frames{}\n", o.series, info.frames,
             info.complete ? "" : " (unfinished: the run was stopped; its complete frames)");
  if (table) {
    table->finish();
    fmt::print(
        "agglomerates      {} ({}); last frame: {} of size >= 2, largest {}, d50 {:.3g} mm; "
        "largest plain component {:.1f} % of the bed\n",
        table->file().string(), last.criterion, last.count, last.largest, 1000.0 * last.d50,
        100.0 * last.largest_plain_share);
#ifdef DRUMLAB_WITH_RENDER
    render::write_agglomerate_chart(table->rows(), table->chart_file());
    fmt::print("agglomerate chart {}\n", table->chart_file().string());
#endif
  }
  if (!o.growth.empty()) growth(rows, o.growth);
  if (o.seed_class) {
    if (!seed_found) {
      throw InputError(
          fmt::format("--seed-class {}: no particle of that class in {}", *o.seed_class, o.series));
    }
    accretion(times, accreted, *o.seed_class, o.accretion, last.criterion);
  }
}

}  // namespace

void add_analyze_command(CLI::App& app) {
  auto o = std::make_shared<AnalyzeOptions>();
  CLI::App* cmd = app.add_subcommand(
      "analyze", "Agglomerate statistics per frame of an HDF5 series (drumlab run --h5)");
  cmd->add_option("series", o->series,
                  "HDF5 series written by run --h5, or an agglomerate table FILE.csv to chart")
      ->required();
  cmd->add_option("--agglomerates", o->agglomerates,
                  "write the statistics to FILE.csv and their chart to FILE.png");
  add_granule_flags(cmd, o->granule);
  cmd->add_option("--growth", o->growth,
                  "the phases of granulation (nucleation, growth, consolidation) and the chart "
                  "FILE.png of d50 and the granule count against the liquid sprayed");
  cmd->add_option("--accretion", o->accretion,
                  "with --seed-class: the primaries held in the seeds' granules per frame to "
                  "FILE.csv, the saturating exponential fitted to them, and the chart FILE.png");
  cmd->add_option("--seed-class", o->seed_class,
                  "the seeds of --accretion: the [[particles]] class index K (0 = the first)");
  cmd->callback([o] { analyze(*o); });
}

}  // namespace drumlab::cli
