#include "tests/gui/gui_test_helpers.hpp"

#include <unistd.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <system_error>
#include <vector>

#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPNGReader.h>

#include "tests/small_drum_text.hpp"

namespace drumlab::test {

bool have_xvfb() {
  return std::string(DRUMLAB_XVFB_RUN).size() > 0;
}

void expect_one_line_error(const GuiRun& r, const std::string& names) {
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
  EXPECT_NE(r.output.find(names), std::string::npos) << r.output;
}

GuiRun run_gui(const std::string& args, bool window) {
  std::string cmd;
  if (window) cmd = std::string(DRUMLAB_XVFB_RUN) + " -a -s \"-screen 0 1600x1000x24\" ";
  cmd += std::string(DRUMLAB_GUI) + " " + args + " 2>&1";
  GuiRun r;
  FILE* pipe = popen(cmd.c_str(), "r");
  if (pipe == nullptr) return r;
  std::array<char, 4096> buf{};
  while (fgets(buf.data(), static_cast<int>(buf.size()), pipe) != nullptr) r.output += buf.data();
  const int status = pclose(pipe);
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

namespace {

/// The directories fresh_dir made in this process, removed when it exits.
struct MadeDirs {
  std::vector<std::filesystem::path> dirs;
  ~MadeDirs() {
    std::error_code ignored;
    for (const auto& d : dirs) std::filesystem::remove_all(d, ignored);
  }
};
MadeDirs made_dirs;

}  // namespace

std::filesystem::path fresh_dir(const std::string& name) {
  // The process id in the name: two checkouts running the suite at once do not share it.
  const auto dir = std::filesystem::temp_directory_path() /
                   ("drumlab-gui-test-" + name + "-" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  made_dirs.dirs.push_back(dir);
  return dir;
}

std::size_t differing_motion(const Particles& a, const Particles& b) {
  std::map<Index, std::size_t> slot;
  for (std::size_t i = 0; i < b.size(); ++i) slot[b.id[i]] = i;
  std::size_t differing = 0;
  for (std::size_t k = 0; k < a.size(); ++k) {
    const std::size_t i = slot.at(a.id[k]);
    for (int c = 0; c < 3; ++c) {
      differing += a.position[k][c] != b.position[i][c];
      differing += a.velocity[k][c] != b.velocity[i][c];
      differing += a.omega[k][c] != b.omega[i][c];
    }
  }
  return differing;
}

std::filesystem::path write_small_drum(const std::filesystem::path& dir,
                                       const std::string& search) {
  SmallDrumText t;
  t.header = "name = \"gui_small\"\n";
  t.search = search;
  const auto file = dir / "gui_small.toml";
  std::ofstream(file) << t.text();
  return file;
}

render::Image read_png(const std::filesystem::path& file) {
  render::Image img;
  if (!std::filesystem::exists(file)) return img;
  vtkNew<vtkPNGReader> reader;
  reader->SetFileName(file.string().c_str());
  reader->Update();
  vtkImageData* data = reader->GetOutput();
  int dims[3] = {0, 0, 0};
  data->GetDimensions(dims);
  const int comps = data->GetNumberOfScalarComponents();
  if (comps < 3) return img;
  img.width = dims[0];
  img.height = dims[1];
  img.rgb.resize(3 * static_cast<std::size_t>(img.width) * img.height);
  for (int y = 0; y < img.height; ++y) {
    for (int x = 0; x < img.width; ++x) {
      // VTK's rows run bottom to top.
      const auto* px =
          static_cast<unsigned char*>(data->GetScalarPointer(x, img.height - 1 - y, 0));
      for (int c = 0; c < 3; ++c) {
        img.rgb[3 * (static_cast<std::size_t>(y) * img.width + x) + c] = px[c];
      }
    }
  }
  return img;
}

std::size_t pixels_near(const render::Image& img, const double* rgb, int tolerance) {
  std::size_t n = 0;
  for (int y = 0; y < img.height; ++y) {
    for (int x = 0; x < img.width; ++x) {
      const auto px = img.pixel(x, y);
      int d = 0;
      for (int c = 0; c < 3; ++c) {
        d = std::max(
            d, std::abs(static_cast<int>(px[c]) - static_cast<int>(std::lround(255.0 * rgb[c]))));
      }
      n += d <= tolerance;
    }
  }
  return n;
}

}  // namespace drumlab::test
