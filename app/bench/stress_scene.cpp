#include "app/bench/stress_scene.hpp"

#include <cctype>
#include <cmath>
#include <fstream>

#include <fmt/format.h>

#include "engine/types.hpp"

namespace drumlab::bench {

namespace {
constexpr double kGravity = 9.81;
}

double StressScene::omega() const {
  return std::sqrt(froude * kGravity / (0.5 * diameter));
}

std::string StressScene::toml() const {
  std::string text = fmt::format("search = \"{}\"\ngravity = [0.0, {}, 0.0]\n", search,
                                 zero_gravity ? 0.0 : -kGravity);
  text += fmt::format(
      "[drum]\ndiameter = {}\ndepth = {}\nomega = {:.17g}\ntilt_deg = {}\nends = \"{}\"\n",
      diameter, depth, omega(), tilt_deg, periodic ? "periodic" : "caps");
  if (large_radius > 0.0) {
    text += fmt::format("[[particles]]\nradius = {}\nvolume_fraction = {}\n", radius,
                        1.0 - large_fraction);
    text += fmt::format("[[particles]]\nradius = {}\nvolume_fraction = {}\n", large_radius,
                        large_fraction);
  } else {
    text += fmt::format("[[particles]]\nradius = {}\n", radius);
  }
  text += fmt::format(
      "[material]\ndensity = 2500.0\nyoungs_modulus = {}\npoisson_ratio = 0.3\nrestitution = "
      "{}\nfriction = {}\nrolling_friction = {}\n",
      youngs_modulus, restitution, friction, rolling_friction);
  if (fill_file.empty()) {
    text += fmt::format("[fill]\ncount = {}\nsettle_time = {}\n", count, settle_time);
  } else {
    text += fmt::format("[fill]\nkind = \"file\"\nfile = \"{}\"\nsettle_time = {}\n", fill_file,
                        settle_time);
  }
  text += fmt::format("[time]\ndt_factor = {}\nduration = {}\n", dt_factor, duration);
  text += fmt::format("[output]\ndiagnostics_every = {}\n", diagnostics_every);
  return text;
}

std::string StressScene::summary() const {
  const std::string radii = large_radius > 0.0
                                ? fmt::format("{:g}/{:g}", radius * 1000.0, large_radius * 1000.0)
                                : fmt::format("{:g}", radius * 1000.0);
  const std::string particles =
      fill_file.empty() ? fmt::format("{} p", count) : fmt::format("file {}", fill_file);
  std::string drum = periodic ? ", periodic" : "";
  if (tilt_deg > 0.0) drum += fmt::format(", tilt {:g} deg", tilt_deg);
  return fmt::format("{}, r {} mm, D {:g} m{}, Fr {:g}, E {:g} Pa, mu {:g}, {}", particles, radii,
                     diameter, drum, froude, youngs_modulus, friction, search);
}

std::string file_stem(const std::string& name) {
  std::string stem = name;
  for (char& c : stem) {
    const bool keep = std::isalnum(static_cast<unsigned char>(c)) != 0 || c == '.' || c == '-';
    if (!keep) c = '_';
  }
  return stem;
}

std::filesystem::path write_text(const std::filesystem::path& file, const std::string& text) {
  std::ofstream out(file, std::ios::binary);
  out << text;
  if (!out) throw std::runtime_error(fmt::format("cannot write {}", file.string()));
  return file;
}

std::string lattice_csv(const StressScene& scene, double r, double overlap, std::size_t max_count,
                        double wall_gap) {
  const double spacing = 2.0 * r * (1.0 - 0.5 * overlap);
  const double reach = 0.5 * scene.diameter - wall_gap * r;
  std::string csv = "x,y,z,r\n";
  std::size_t n = 0;
  for (double y = -reach; y <= 0.2 * reach && n < max_count; y += spacing) {
    for (double x = -reach; x <= reach && n < max_count; x += spacing) {
      if (x * x + y * y > reach * reach) continue;
      for (double z = wall_gap * r; z <= scene.depth - wall_gap * r && n < max_count;
           z += spacing) {
        csv += fmt::format("{:.17g},{:.17g},{:.17g},{}\n", x, y, z, r);
        ++n;
      }
    }
  }
  return csv;
}

}  // namespace drumlab::bench
