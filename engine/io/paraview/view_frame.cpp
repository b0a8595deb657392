#include "engine/io/paraview/view_frame.hpp"

#include <cmath>

#include <fmt/format.h>

namespace drumlab::paraview {
namespace {

Vec3 turned(const Vec3& v, double c, double s) {
  return Vec3(c * v.x() - s * v.y(), s * v.x() + c * v.y(), v.z());
}

}  // namespace

ViewFrame parse_view_frame(std::string_view name, std::string_view option) {
  if (name == "drum") return ViewFrame::drum;
  if (name == "lab") return ViewFrame::lab;
  if (name == "carrier") return ViewFrame::carrier;
  throw InputError(fmt::format("{}: unknown frame '{}' (valid: drum, lab, carrier)", option, name));
}

const char* view_frame_name(ViewFrame frame) {
  switch (frame) {
    case ViewFrame::lab:
      return "lab";
    case ViewFrame::carrier:
      return "carrier";
    case ViewFrame::drum:
      break;
  }
  return "drum";
}

FrameMotion frame_motion(const Simulation& sim, ViewFrame frame) {
  const bool orbit = sim.scene().drum.orbit.active();
  if (frame == ViewFrame::carrier && !orbit) {
    throw InputError(
        "--frame carrier: the scene has no [drum.orbit] (no carrier arm to turn with)");
  }
  FrameMotion m;
  if (frame == ViewFrame::drum || !orbit) return m;
  m.offset = sim.carrier_offset();
  m.velocity_offset = sim.carrier_velocity();
  if (frame == ViewFrame::carrier) {
    m.turn = -sim.carrier_angle();
    m.spin = sim.carrier_omega();
    // v + c' - Omega z x (x + c) = v - Omega z x x: the arm's own motion taken out.
  }
  return m;
}

void to_frame(DataSet& d, const FrameMotion& m) {
  if (m.identity()) return;
  const double c = std::cos(m.turn), s = std::sin(m.turn);
  // The vectors first: a point velocity's spin term needs the point's drum-frame position.
  const auto vectors = [&](std::vector<DataArray>& arrays, bool points) {
    std::vector<double>* speed = nullptr;
    std::vector<double>* velocity = nullptr;
    for (DataArray& a : arrays) {
      auto* values = std::get_if<std::vector<double>>(&a.values);
      if (values == nullptr) continue;
      if (a.name == "speed") speed = values;
      if (a.components != 3) continue;
      for (std::size_t k = 0; 3 * k + 2 < values->size(); ++k) {
        Vec3 v((*values)[3 * k], (*values)[3 * k + 1], (*values)[3 * k + 2]);
        if (a.name == "velocity") {
          v += m.velocity_offset;
          if (points && m.spin != 0.0) {
            const Vec3 r = d.points[k] + m.offset;
            v -= m.spin * Vec3(-r.y(), r.x(), 0.0);
          }
          velocity = values;
        } else if (a.name == "angular_velocity") {
          v.z() -= m.spin;
        }
        v = turned(v, c, s);
        for (int j = 0; j < 3; ++j) (*values)[3 * k + j] = v[j];
      }
    }
    if (speed != nullptr && velocity != nullptr && velocity->size() == 3 * speed->size()) {
      for (std::size_t k = 0; k < speed->size(); ++k) {
        (*speed)[k] =
            std::hypot((*velocity)[3 * k], (*velocity)[3 * k + 1], (*velocity)[3 * k + 2]);
      }
    }
  };
  vectors(d.point_data, true);
  vectors(d.cell_data, false);
  for (Vec3& x : d.points) x = turned(x + m.offset, c, s);
}

DataSet carrier_arm(const Simulation& sim, ViewFrame frame) {
  DataSet d;
  d.cells = CellKind::lines;
  if (!sim.scene().drum.orbit.active()) return d;
  const double h = sim.scene().drum.depth;
  const Vec3 c = sim.carrier_offset();
  // In the drum frame: the central axis at -c, the drum's axis at the origin.
  d.points = {-c, Vec3(-c.x(), -c.y(), h), Vec3::Zero(), Vec3(0.0, 0.0, h)};
  d.add_cell({0, 1});  // the central axis
  d.add_cell({0, 2});  // the arm at z = 0
  d.add_cell({1, 3});  // the arm at z = H
  d.cell_data.push_back(make_array("part", std::vector<std::uint8_t>{0, 1, 1}));
  d.field_data.push_back(make_array("carrier_angle", std::vector<double>{sim.carrier_angle()}));
  to_frame(d, frame_motion(sim, frame));
  return d;
}

}  // namespace drumlab::paraview
