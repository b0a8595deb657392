// drumlab convert SERIES.h5 --vtu DIR
// An HDF5 series (`drumlab run --h5`, or one written on several MPI ranks) as the VTU/PVD series
// ParaView users expect: particles_NNNNNN.vtu + particles.pvd, and for a scene with bonds
// bonds_NNNNNN.vtp + bonds.pvd. Serial; reads one frame at a time.
#include <fmt/format.h>

#include "app/cli/commands.hpp"
#include "engine/io/h5_series.hpp"
#include "render/vtu_series_writer.hpp"

namespace drumlab::cli {
namespace {

struct ConvertOptions {
  std::string series;
  std::string vtu;
};

void convert(const ConvertOptions& o) {
  const SeriesInfo info = read_series_info(o.series);
  if (info.frames == 0) throw InputError(fmt::format("{}: the series has no frames", o.series));
  render::VtuSeriesWriter writer(o.vtu, {});
  std::size_t particles = 0;
  for (std::size_t k = 0; k < info.frames; ++k) {
    const SeriesFrame frame = read_series_frame(o.series, k);
    writer.write_frame(frame);
    particles = frame.id.size();
  }
  fmt::print("series    {}: {} frames{}, {} particles in the last\n", o.series, info.frames,
             info.complete ? "" : " (unfinished: the run was stopped; its complete frames)",
             particles);
  fmt::print("vtu       {}/particles.pvd{}\n", writer.directory().string(),
             info.has_bonds ? fmt::format(", {}/bonds.pvd", writer.directory().string()) : "");
}

}  // namespace

void add_convert_command(CLI::App& app) {
  auto o = std::make_shared<ConvertOptions>();
  CLI::App* cmd =
      app.add_subcommand("convert", "An HDF5 series (run --h5) as a VTU/PVD series for ParaView");
  cmd->add_option("series", o->series, "HDF5 series written by run --h5")->required();
  cmd->add_option("--vtu", o->vtu, "output directory (particles.pvd, bonds.pvd)")->required();
  cmd->callback([o] { convert(*o); });
}

}  // namespace drumlab::cli
