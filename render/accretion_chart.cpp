#include "render/accretion_chart.hpp"

#include <fmt/format.h>

#include "render/xy_chart.hpp"

namespace drumlab::render {

void write_accretion_chart(const std::vector<double>& t, const std::vector<double>& n,
                           const SaturatingFit& fit, const std::string& criterion,
                           const std::filesystem::path& file) {
  std::vector<double> fitted;
  for (const double time : t) fitted.push_back(saturating_value(fit, time));
  XYPanel panel{
      fmt::format("accretion onto the seed ({})", criterion), "time (s)", "primaries held", {}};
  panel.series = {{"accreted", t, n, false, true},
                  {fmt::format("fit: N_inf {:.3g}, tau {:.3g} s, R^2 {:.3f}", fit.n_inf, fit.tau,
                               fit.r_squared),
                   t, fitted, true}};
  write_xy_charts({panel}, file, 1200, 600);
}

}  // namespace drumlab::render
