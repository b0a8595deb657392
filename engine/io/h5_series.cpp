#include "engine/io/h5_series.hpp"

#include <chrono>
#include <sstream>
#include <stdexcept>
#include <unordered_map>

#include <fmt/format.h>

#include "engine/io/atomic_file.hpp"
#include "engine/io/h5_file.hpp"
#include "engine/io/h5_journal.hpp"

namespace drumlab {

namespace {

void data_item(std::ostringstream& x, const std::string& h5_name, const std::string& path,
               std::size_t n, int components, const char* number_type, int precision) {
  const std::string dims =
      components > 1 ? fmt::format("{} {}", n, components) : fmt::format("{}", n);
  x << fmt::format(
      "          <DataItem Dimensions=\"{}\" NumberType=\"{}\" Precision=\"{}\" "
      "Format=\"HDF\">{}:{}</DataItem>\n",
      dims, number_type, precision, h5_name, path);
}

void attribute(std::ostringstream& x, const std::string& h5_name, const std::string& group,
               const char* name, const char* dataset, std::size_t n, bool vector,
               const char* number_type, int precision) {
  x << fmt::format("        <Attribute Name=\"{}\" AttributeType=\"{}\" Center=\"Node\">\n", name,
                   vector ? "Vector" : "Scalar");
  data_item(x, h5_name, "/" + group + "/" + dataset, n, vector ? 3 : 1, number_type, precision);
  x << "        </Attribute>\n";
}

constexpr const char* kXdmfHead =
    "<?xml version=\"1.0\" ?>\n<!DOCTYPE Xdmf SYSTEM \"Xdmf.dtd\" []>\n"
    "<Xdmf Version=\"3.0\" xmlns:xi=\"http://www.w3.org/2001/XInclude\">\n  <Domain>\n"
    "    <Grid Name=\"particles\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
constexpr const char* kXdmfTail = "    </Grid>\n  </Domain>\n</Xdmf>\n";

/// The Uniform grid of frame k.
std::string xdmf_frame_grid(const std::string& h5_name, std::size_t k, double time, std::size_t n,
                            bool with_bonds) {
  std::ostringstream x;
  const std::string g = h5_frame_group(k);
  x << fmt::format("      <Grid Name=\"{}\" GridType=\"Uniform\">\n", g);
  x << fmt::format("        <Time Value=\"{:.17g}\"/>\n", time);
  x << fmt::format(
      "        <Topology TopologyType=\"Polyvertex\" NumberOfElements=\"{}\" "
      "NodesPerElement=\"1\"/>\n",
      n);
  x << "        <Geometry GeometryType=\"XYZ\">\n";
  data_item(x, h5_name, "/" + g + "/position", n, 3, "Float", 8);
  x << "        </Geometry>\n";
  attribute(x, h5_name, g, "velocity", "velocity", n, true, "Float", 8);
  attribute(x, h5_name, g, "angular_velocity", "omega", n, true, "Float", 8);
  attribute(x, h5_name, g, "radius", "radius", n, false, "Float", 8);
  attribute(x, h5_name, g, "id", "id", n, false, "UInt", 4);
  attribute(x, h5_name, g, "size_class", "size_class", n, false, "UChar", 1);
  if (with_bonds) {
    attribute(x, h5_name, g, "agglomerate_id", "agglomerate_id", n, false, "UInt", 4);
    attribute(x, h5_name, g, "liquid_volume", "liquid_volume", n, false, "Float", 8);
  }
  x << "      </Grid>\n";
  return x.str();
}

}  // namespace

struct H5Series::Impl {
  h5::Handle file;  ///< open only while a frame is written
  bool created = false;
  Access access;
};

H5Series::Access H5Series::serial_access() {
  Access a;
  a.create = [](const std::filesystem::path& f) { return h5::create_disk_file(f); };
  a.open = [](const std::filesystem::path& f) { return h5::open_file_rw(f); };
  a.close = [](h5::Handle& h, const std::filesystem::path& f) {
    h5::flush(h.get());
    if (!h.reset()) throw InputError(fmt::format("{}: write failed (disk full?)", f.string()));
  };
  return a;
}

void SeriesBondRows::push_back(std::uint32_t a, std::uint32_t b, const Bond& bond) {
  id_a.push_back(a);
  id_b.push_back(b);
  volume.push_back(bond.volume);
  force.push_back(bond.force);
  age.push_back(bond.age);
}

SeriesBondRows series_bond_rows(const Particles& p, std::span<const Bond> bonds) {
  SeriesBondRows r;
  for (const Bond& b : bonds) r.push_back(p.id[b.i], p.id[b.j], b);
  return r;
}

void H5Series::set_rows(h5::Rows rows) {
  impl_->access.rows = std::move(rows);
}

std::string h5_frame_group(std::size_t k) {
  return fmt::format("frame_{:06d}", k);
}

H5Series::H5Series(std::filesystem::path file, Access access)
    : file_(std::move(file)), impl_(std::make_unique<Impl>()) {
  impl_->access = std::move(access);
  if (impl_->access.root) h5::check_writable(file_);  // fail before the run, not at its first frame
}

H5Series::~H5Series() = default;

std::filesystem::path H5Series::xdmf_file() const {
  std::filesystem::path x = file_;
  x.replace_extension(".xdmf");
  return x;
}

void H5Series::discard() noexcept {
  impl_->file.reset();
  if (impl_->access.root) {
    std::error_code ignored;
    std::filesystem::remove(file_, ignored);
    std::filesystem::remove(h5::journal_path(file_), ignored);
    std::filesystem::remove(xdmf_file(), ignored);
  }
  finished_ = true;  // nothing more is written
}

void H5Series::open_for_writing() {
  if (impl_->created) {
    impl_->file = impl_->access.open(file_);
    return;
  }
  impl_->file = impl_->access.create(file_);
  h5::create_growing_doubles(impl_->file.get(), "time");
  h5::create_growing_u64(impl_->file.get(), "step");
  impl_->created = true;
}

void H5Series::close_after_writing() {
  impl_->access.close(impl_->file, file_);
}

void H5Series::write_sidecar() const {
  if (!impl_->access.root) return;
  write_file_atomically(xdmf_file(),
                        [&](std::ostream& out) { out << kXdmfHead << xdmf_grids_ << kXdmfTail; });
}

namespace {

void write_bond_frame(hid_t g, const Particles& p, const SeriesBondFrame& b, const h5::Rows& rows) {
  h5::write_attribute(g, "period_z", b.period);
  h5::write_attribute(g, "drum_omega", b.drum_omega);
  h5::write_attribute(g, "wall_bridge_liquid", b.wall_liquid);
  h5::write_attribute(g, "sprayed_liquid", b.spray.sprayed);
  h5::write_attribute(g, "airborne_liquid", b.spray.airborne);
  h5::write_attribute(g, "lost_liquid", b.spray.lost);
  h5::write_attribute(g, "wall_film_liquid", b.spray.on_wall);
  h5::write(g, "mass", p.mass, {p.size()}, rows);
  const std::vector<double>* film = p.find_array(kLiquidFilmArray);
  const std::vector<double> no_film(film ? 0 : p.size(), 0.0);
  h5::write(g, "liquid_volume", film ? *film : no_film, {p.size()}, rows);
  if (b.agglomerate_id.size() != p.size()) {
    throw std::invalid_argument("H5Series: agglomerate_id does not match the particles");
  }
  h5::write(g, "agglomerate_id", b.agglomerate_id, rows);
  const SeriesBondRows& r = b.bonds;
  const std::size_t n = r.size();
  h5::Handle bonds = h5::create_group(g, "bonds");
  h5::write(bonds.get(), "id_a", std::span<const std::uint32_t>(r.id_a), b.bond_rows);
  h5::write(bonds.get(), "id_b", std::span<const std::uint32_t>(r.id_b), b.bond_rows);
  h5::write(bonds.get(), "volume", r.volume, {n}, b.bond_rows);
  h5::write(bonds.get(), "force", r.force, {n}, b.bond_rows);
  h5::write(bonds.get(), "age", r.age, {n}, b.bond_rows);
}

}  // namespace

void H5Series::write_frame(const Particles& p, double time, std::uint64_t step,
                           const SeriesBondFrame* bonds) {
  if (finished_) throw std::logic_error("H5Series: write after finish");
  try {
    open_for_writing();
    const hid_t f = impl_->file.get();
    const h5::Rows& rows = impl_->access.rows;
    {
      h5::Handle g = h5::create_group(f, h5_frame_group(times_.size()));
      h5::write_attribute(g.get(), "time", time);
      h5::write_attribute(g.get(), "step", step);
      h5::write_vec3(g.get(), "position", p.position, rows);
      h5::write_vec3(g.get(), "velocity", p.velocity, rows);
      h5::write_vec3(g.get(), "omega", p.omega, rows);
      h5::write(g.get(), "radius", p.radius, {p.size()}, rows);
      h5::write(g.get(), "id", std::span<const std::uint32_t>(p.id), rows);
      h5::write(g.get(), "size_class", std::span<const std::uint8_t>(p.size_class), rows);
      if (bonds) write_bond_frame(g.get(), p, *bonds, rows);
    }
    // The frame goes to disk before its time is listed: HDF5 writes a file's metadata in no
    // order a reader can rely on, so a run killed while the listing goes out must not leave a
    // listed frame whose group never reached the disk (seen under load: /time one ahead).
    h5::flush(f);
    // The frame counts once its time is listed; then the listing goes to disk.
    h5::append(h5::open_dataset(f, "time").get(), time, impl_->access.scalar);
    h5::append(h5::open_dataset(f, "step").get(), step, impl_->access.scalar);
    close_after_writing();
    const std::size_t n = rows.all ? p.size() : rows.total;
    xdmf_grids_ +=
        xdmf_frame_grid(file_.filename().string(), times_.size(), time, n, bonds != nullptr);
    times_.push_back(time);
    // The sidecar lists every frame of a short series; past kSidecarEveryFrame frames it is
    // rewritten at most every kSidecarInterval of wall time (its size grows with the frames, so
    // rewriting it after each of thousands of fast frames would cost more than the run).
    const auto now = std::chrono::steady_clock::now();
    if (times_.size() <= kSidecarEveryFrame || now - last_sidecar_ >= kSidecarInterval) {
      write_sidecar();
      last_sidecar_ = now;
    }
  } catch (...) {
    discard();
    throw;
  }
}

void H5Series::finish() {
  if (finished_) return;
  try {
    open_for_writing();  // without a frame: an empty, complete series
    h5::write_attribute(impl_->file.get(), "complete", std::uint64_t{1});
    close_after_writing();
    write_sidecar();
  } catch (...) {
    discard();
    throw;
  }
  finished_ = true;
}

std::string xdmf_for_series(const std::string& h5_name, const std::vector<double>& times,
                            const std::vector<std::size_t>& counts,
                            const std::vector<bool>& with_bonds) {
  std::string x = kXdmfHead;
  for (std::size_t k = 0; k < times.size(); ++k) {
    x += xdmf_frame_grid(h5_name, k, times[k], counts[k], k < with_bonds.size() && with_bonds[k]);
  }
  return x + kXdmfTail;
}

SeriesInfo read_series_info(const std::filesystem::path& file) {
  h5::Handle f = h5::open_file(file);
  SeriesInfo info;
  if (!h5::exists(f.get(), "time")) {
    throw InputError(fmt::format("{}: not a drumlab HDF5 series (no /time)", file.string()));
  }
  info.frames = h5::element_count(f.get(), "time");
  info.complete = H5Aexists(f.get(), "complete") > 0;
  if (info.frames > 0) {
    h5::Handle g = h5::open_group(f.get(), h5_frame_group(0));
    info.has_bonds = h5::exists(g.get(), "bonds");
  }
  return info;
}

SeriesFrame read_series_frame(const std::filesystem::path& file, std::size_t k) {
  h5::Handle f = h5::open_file(file);
  const std::string name = h5_frame_group(k);
  h5::Handle g = h5::open_group(f.get(), name);
  SeriesFrame s;
  s.time = h5::read_double_attribute(g.get(), "time");
  s.step = h5::read_u64_attribute(g.get(), "step");
  for (const char* column : {"id", "radius", "size_class"})
    h5::check_row_shape(g.get(), column, {});
  s.id = h5::read_u32(g.get(), "id", h5::kAnySize);
  const std::size_t n = s.id.size();
  s.position = h5::read_vec3(g.get(), "position", n);
  s.velocity = h5::read_vec3(g.get(), "velocity", n);
  s.omega = h5::read_vec3(g.get(), "omega", n);
  s.radius = h5::read_doubles(g.get(), "radius", n);
  s.size_class = h5::read_u8(g.get(), "size_class", n);
  s.has_bonds = h5::exists(g.get(), "bonds");
  if (!s.has_bonds) return s;
  for (const char* column : {"mass", "liquid_volume", "agglomerate_id"}) {
    h5::check_row_shape(g.get(), column, {});
  }
  s.mass = h5::read_doubles(g.get(), "mass", n);
  s.film = h5::read_doubles(g.get(), "liquid_volume", n);
  s.agglomerate_id = h5::read_u32(g.get(), "agglomerate_id", n);
  s.period = h5::read_double_attribute(g.get(), "period_z");
  s.drum_omega = h5::read_double_attribute(g.get(), "drum_omega");
  if (H5Aexists(g.get(), "wall_bridge_liquid") > 0) {
    s.wall_liquid = h5::read_double_attribute(g.get(), "wall_bridge_liquid");
  }
  for (const auto& [name, value] :
       {std::pair<const char*, double*>{"sprayed_liquid", &s.spray.sprayed},
        {"airborne_liquid", &s.spray.airborne},
        {"lost_liquid", &s.spray.lost},
        {"wall_film_liquid", &s.spray.on_wall}}) {
    if (H5Aexists(g.get(), name) > 0) *value = h5::read_double_attribute(g.get(), name);
  }
  h5::Handle b = h5::open_group(g.get(), "bonds");
  const std::vector<std::uint32_t> id_a = h5::read_u32(b.get(), "id_a", h5::kAnySize);
  const std::size_t m = id_a.size();
  const std::vector<std::uint32_t> id_b = h5::read_u32(b.get(), "id_b", m);
  const std::vector<double> volume = h5::read_doubles(b.get(), "volume", m);
  const std::vector<double> force = h5::read_doubles(b.get(), "force", m);
  const std::vector<double> age = h5::read_doubles(b.get(), "age", m);
  std::unordered_map<std::uint32_t, Index> slot;
  slot.reserve(n);
  for (std::size_t i = 0; i < n; ++i) slot.emplace(s.id[i], static_cast<Index>(i));
  s.bonds.resize(m);
  for (std::size_t k2 = 0; k2 < m; ++k2) {
    const auto a = slot.find(id_a[k2]);
    const auto c = slot.find(id_b[k2]);
    if (a == slot.end() || c == slot.end()) {
      throw InputError(fmt::format("{}: {}/bonds names particle id {} that the frame lacks",
                                   file.string(), name, a == slot.end() ? id_a[k2] : id_b[k2]));
    }
    s.bonds[k2] = {std::min(a->second, c->second), std::max(a->second, c->second), volume[k2],
                   force[k2], age[k2]};
  }
  return s;
}

}  // namespace drumlab
