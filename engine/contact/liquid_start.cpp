#include "engine/contact/liquid_start.hpp"

#include <numbers>
#include <stdexcept>

#include "engine/periodic.hpp"

namespace drumlab {

void fill_films(const SceneConfig& scene, Particles& p, std::vector<double>& reserve) {
  const LiquidConfig& liquid = scene.liquid;
  std::vector<double>* film = p.find_array(kLiquidFilmArray);
  if (film == nullptr) throw std::logic_error("fill_films: no film array");
  reserve.assign(p.size(), 0.0);
  for (std::size_t i = 0; i < p.size(); ++i) {
    const std::size_t c = p.size_class[i];
    const double content = c < scene.classes.size()
                               ? scene.classes[c].liquid_content.value_or(liquid.liquid_content)
                               : liquid.liquid_content;
    const double r = liquid.film_radius > 0.0 ? liquid.film_radius : p.radius[i];
    const double v = content * (4.0 / 3.0) * std::numbers::pi * r * r * r;
    (*film)[i] = liquid.film_share * v;
    reserve[i] = v - (*film)[i];
  }
  if (liquid.film_share == 1.0) reserve.clear();
}

void seed_bridges(const CohesiveParts& parts, Particles& p, ContactList& contacts, double period,
                  std::vector<double>& reserve) {
  const LiquidBridge* bridge = parts.get<LiquidBridge>();
  std::vector<double>* films = p.find_array(kLiquidFilmArray);
  if (bridge == nullptr || films == nullptr || reserve.size() != p.size()) {
    throw std::logic_error("no films to seed");
  }
  double* film = films->data();
  const auto row = contacts.row_start();
  const auto col = contacts.col();
  const auto state = contacts.state();
  const std::size_t stride = contacts.state_size();
  const std::size_t offset = parts.offset<LiquidBridge>();
  const auto touching = [&](std::size_t i, Index j) {
    const double dist = nearest_image(p.position[i], p.position[j], period).norm();
    return dist > 0.0 && dist <= p.radius[i] + p.radius[j];
  };
  std::vector<double> share(p.size(), 0.0);
  for (std::size_t i = 0; i < contacts.rows(); ++i) {
    for (std::size_t k = row[i]; k < row[i + 1]; ++k) {
      if (!touching(i, col[k])) continue;
      share[i] += 1.0;
      share[col[k]] += 1.0;
    }
  }
  for (std::size_t i = 0; i < share.size(); ++i) {
    share[i] = share[i] > 0.0 ? reserve[i] / share[i] : 0.0;
  }
  const double v_max = bridge->max_volume;
  for (std::size_t i = 0; i < contacts.rows(); ++i) {
    for (std::size_t k = row[i]; k < row[i + 1]; ++k) {
      const Index j = col[k];
      if (!touching(i, j)) continue;
      double gi = share[i], gj = share[j];
      if (gi + gj > v_max) {
        gi = share[i] * (v_max / (share[i] + share[j]));
        gj = v_max - gi;
      }
      if (!(gi + gj > 0.0)) continue;
      double* s = &state[k * stride + offset];
      s[0] = gi + gj;
      s[1] = 0.0;
      reserve[i] -= gi;
      reserve[j] -= gj;
    }
  }
  for (std::size_t i = 0; i < reserve.size(); ++i) film[i] += reserve[i];
  reserve.clear();
}

}  // namespace drumlab
