#include "engine/io/h5_series.hpp"

#include <sstream>

#include <fmt/format.h>

#include "engine/io/atomic_file.hpp"
#include "engine/io/h5_file.hpp"

namespace drumlab {

struct H5Series::Impl {
  h5::Handle file;
};

std::string h5_frame_group(std::size_t k) {
  return fmt::format("frame_{:06d}", k);
}

H5Series::H5Series(std::filesystem::path file)
    : file_(std::move(file)), impl_(std::make_unique<Impl>()) {
  h5::check_writable(file_);  // fail before the run, not at its end
  impl_->file = h5::create_memory_file(file_.string());
}

H5Series::~H5Series() = default;

std::filesystem::path H5Series::xdmf_file() const {
  std::filesystem::path x = file_;
  x.replace_extension(".xdmf");
  return x;
}

void H5Series::write_frame(const Particles& p, double time, std::uint64_t step) {
  if (finished_) throw std::logic_error("H5Series: write after finish");
  const hid_t f = impl_->file.get();
  h5::Handle g = h5::create_group(f, h5_frame_group(times_.size()));
  h5::write_attribute(g.get(), "time", time);
  h5::write_attribute(g.get(), "step", step);
  h5::write_vec3(g.get(), "position", p.position);
  h5::write_vec3(g.get(), "velocity", p.velocity);
  h5::write_vec3(g.get(), "omega", p.omega);
  h5::write(g.get(), "radius", p.radius, {p.size()});
  h5::write(g.get(), "id", std::span<const std::uint32_t>(p.id));
  h5::write(g.get(), "size_class", std::span<const std::uint8_t>(p.size_class));
  times_.push_back(time);
  steps_.push_back(step);
  counts_.push_back(p.size());
  if (h5::memory_file_size(f) > kMaxBytes) {
    throw InputError(fmt::format(
        "{}: the HDF5 series passed {} GiB in memory; write fewer frames (a larger --every)",
        file_.string(), kMaxBytes >> 30));
  }
}

void H5Series::finish() {
  if (finished_) return;
  const hid_t f = impl_->file.get();
  h5::write(f, "time", times_, {times_.size()});
  h5::write(f, "step", std::span<const std::uint64_t>(steps_));
  h5::save_memory_file(impl_->file, file_);
  const std::string text = xdmf_for_series(file_.filename().string(), times_, counts_);
  write_file_atomically(xdmf_file(), [&](std::ostream& out) { out << text; });
  finished_ = true;
}

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

}  // namespace

std::string xdmf_for_series(const std::string& h5_name, const std::vector<double>& times,
                            const std::vector<std::size_t>& counts) {
  std::ostringstream x;
  x << "<?xml version=\"1.0\" ?>\n<!DOCTYPE Xdmf SYSTEM \"Xdmf.dtd\" []>\n"
       "<Xdmf Version=\"3.0\" xmlns:xi=\"http://www.w3.org/2001/XInclude\">\n  <Domain>\n"
       "    <Grid Name=\"particles\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
  for (std::size_t k = 0; k < times.size(); ++k) {
    const std::string g = h5_frame_group(k);
    const std::size_t n = counts[k];
    x << fmt::format("      <Grid Name=\"{}\" GridType=\"Uniform\">\n", g);
    x << fmt::format("        <Time Value=\"{:.17g}\"/>\n", times[k]);
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
    x << "      </Grid>\n";
  }
  x << "    </Grid>\n  </Domain>\n</Xdmf>\n";
  return x.str();
}

}  // namespace drumlab
