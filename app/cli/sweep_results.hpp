#pragma once
// What `drumlab sweep` keeps of a run: the mean and spread (sample standard deviation over the
// frames of the window) of each drum observable (run --observables) and, for a scene with
// bonds, of the agglomerate statistics (run --agglomerates), and the largest drift of the
// liquid's total over the run, and the window's flow regime; and sweep.csv, one row per finished
// run, rewritten atomically after each so that a killed sweep keeps its rows and resumes.
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "app/cli/sweep_plan.hpp"
#include "engine/analysis/flow_regime.hpp"

namespace drumlab::cli {

/// The observables a row reports, as (column in sweep.csv, column in the run's table, table).
struct SweptQuantity {
  const char* name;
  const char* column;
  bool agglomerates;  ///< from agglomerates.csv (scenes with bonds), else observables.csv
};
inline constexpr SweptQuantity kSweptQuantities[] = {
    {"angle_fit_deg", "angle_fit_deg", false},
    {"angle_com_deg", "angle_com_deg", false},
    {"flowing_layer", "flowing_layer", false},
    {"bridges", "bridges", false},
    {"agglomerates", "agglomerates", true},
    {"largest", "largest", true},
    {"d50", "d50", true},
    {"airborne_fraction", "airborne_fraction", false},
    {"relative_speed", "relative_speed", false},
    {"wall_speed", "wall_speed", false},
    {"upper_fraction", "upper_fraction", false},
    {"com_offset", "com_offset", false}};

struct RunResult {
  std::string name;
  std::vector<std::string> values;
  std::int64_t seed = -1;
  std::size_t frames = 0;        ///< frames in the window
  double window_from = 0.0;      ///< revolutions (turns either way) at the window's first frame
  std::vector<double> mean, sd;  ///< per kSweptQuantities (nan: not measured)
  double liquid_drift = 0.0;     ///< max |total - first total| / first total (0: dry)
  std::string criterion;         ///< the granule criterion of agglomerates.csv ("" without bonds)
  RegimeEvidence regime;         ///< the window's flow regime (engine/analysis/flow_regime.hpp)
};

/// Reads a run's tables in `dir` (observables.csv, agglomerates.csv when `run.has_bonds`) and
/// keeps the frames from `window_from` revolutions (either way) on (< 0: the second half of the
/// run's time); classifies the window's regime. Throws
/// InputError naming the file if a table is missing or damaged, or the window has no frame.
RunResult summarise_run(const SweepRun& run, const std::filesystem::path& dir, double window_from);

/// sweep.csv's header for these sets.
std::string sweep_header(const std::vector<SweepSet>& sets);
std::string sweep_row(const RunResult& r);

/// The rows of an existing sweep.csv by run name (none if there is no file). Throws InputError
/// if its header is not `header` (another sweep's folder).
std::map<std::string, std::string> read_sweep_rows(const std::filesystem::path& file,
                                                   const std::string& header);

/// A CSV table with a header, every cell a number (nan allowed; `text_columns` kept apart).
struct CsvTable {
  std::vector<std::string> columns;
  std::vector<std::vector<double>> rows;
  std::size_t column(const std::string& name, const std::filesystem::path& file) const;
};
CsvTable read_numeric_csv(const std::filesystem::path& file);

/// The flow regime of a window of observables.csv's rows (`in_window`), by the rules of
/// engine/analysis/flow_regime.hpp; the rows carry no surface profiles, so the curvature is the
/// samples' median. Throws InputError naming the file if a column is missing.
RegimeEvidence table_regime(const CsvTable& table, const std::vector<bool>& in_window,
                            const std::filesystem::path& file);

}  // namespace drumlab::cli
