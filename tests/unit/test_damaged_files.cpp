// Damaged files: a checkpoint or series cut at any byte, a flipped bit anywhere, a dataset of the
// wrong shape or type, a checkpoint of another scene. Each is refused with one line (an
// InputError naming the file and, where there is one, the dataset), never a crash and never a run
// that starts from other data than was written: every dataset with values carries HDF5's
// Fletcher32 checksum and all metadata is checksummed (HDF5 1.10's format), so a flipped bit
// that a read meets is found. Each case prints its message (`damage | message`), the table the
// hardening note reports.
#include <fmt/format.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <hdf5.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <limits>

#include "engine/contact/bond.hpp"
#include "engine/io/checkpoint.hpp"
#include "engine/io/h5_file.hpp"
#include "engine/io/h5_series.hpp"
#include "engine/session/run_session.hpp"
#include "tests/same_bits.hpp"
#include "tests/unit/cli_runner.hpp"
#include "tests/unit/output_test_scene.hpp"

namespace drumlab::test {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

std::string bytes_of(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void put_bytes(const fs::path& p, const std::string& bytes) {
  std::ofstream out(p, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

/// Every array of two states, bit for bit.
bool same_state(const SimulationState& a, const SimulationState& b) {
  const Particles &p = a.particles, &q = b.particles;
  return same_bits(p.position, q.position) && same_bits(p.velocity, q.velocity) &&
         same_bits(p.omega, q.omega) && same_bits(p.force, q.force) &&
         same_bits(p.torque, q.torque) && same_bits(p.radius, q.radius) &&
         same_bits(p.mass, q.mass) && same_bits(p.inv_mass, q.inv_mass) &&
         same_bits(p.inv_inertia, q.inv_inertia) && p.size_class == q.size_class && p.id == q.id &&
         same_bits(a.time, b.time) && same_bits(a.dt, b.dt) &&
         same_bits(a.drum_angle, b.drum_angle) && same_bits(a.drum_omega, b.drum_omega) &&
         a.steps == b.steps && a.search_method == b.search_method &&
         a.contact_row_start == b.contact_row_start && a.contact_col == b.contact_col &&
         same_bits(a.contact_history, b.contact_history) &&
         same_bits(a.contact_state, b.contact_state) &&
         a.wall_history.size() == b.wall_history.size() &&
         std::memcmp(a.wall_history.data(), b.wall_history.data(),
                     a.wall_history.size() * sizeof(a.wall_history[0])) == 0;
}

/// The message of the InputError that `f` throws, "" if it throws none (any other exception
/// fails the test through gtest).
std::string refusal(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

void print_row(const std::string& damage, const std::string& message) {
  std::printf("damage | %s | %s\n", damage.c_str(), message.c_str());
}

/// The byte offsets a cut is tried at: the first bytes (the signature and superblock), every
/// 61st byte, the middle and the last byte.
std::vector<std::size_t> cut_offsets(std::size_t size) {
  std::vector<std::size_t> at = {0, 1, 8, 9, 47, 48, 100, 512, size / 2, size - 1};
  for (std::size_t k = 61; k < size; k += size / 61) at.push_back(k);
  return at;
}

/// The small drum of output_scene() settled onto the wall and turning (3,000 steps, 0.3 s): a
/// state with contact and wall history. Made once for every test.
const SimulationState& settled_state() {
  static const SimulationState state = settled_simulation(output_scene(), 3000)->state();
  return state;
}

class DamagedFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    scene_ = output_scene();
    sim_ = std::make_unique<Simulation>(scene_, settled_state());
    good_ = dir_.path() / "good.h5";
    write_checkpoint(good_, sim_->state(), scene_.name);
    bytes_ = bytes_of(good_);
  }

  /// A copy of the good checkpoint, changed by `edit` through HDF5 (opened for writing).
  fs::path edited(const std::string& name, const std::function<void(hid_t)>& edit) {
    const fs::path p = dir_.path() / name;
    fs::copy_file(good_, p, fs::copy_options::overwrite_existing);
    const hid_t f = H5Fopen(p.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
    EXPECT_GE(f, 0);
    edit(f);
    H5Fclose(f);
    return p;
  }

  TempDir dir_{"damaged-files"};
  SceneConfig scene_;
  std::unique_ptr<Simulation> sim_;
  fs::path good_;
  std::string bytes_;
};

/// Replaces dataset `path` of `f` by one of file type `type` and shape `dims`, holding `values`
/// (converted by HDF5).
void replace(hid_t f, const std::string& path, hid_t type, std::vector<hsize_t> dims,
             const std::vector<double>& values) {
  ASSERT_GE(H5Ldelete(f, path.c_str(), H5P_DEFAULT), 0) << path;
  const hid_t space = H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr);
  const hid_t set = H5Dcreate2(f, path.c_str(), type, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  ASSERT_GE(set, 0) << path;
  ASSERT_GE(H5Dwrite(set, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()), 0);
  H5Dclose(set);
  H5Sclose(space);
}

std::vector<double> doubles(std::size_t n, double v = 0.001) {
  return std::vector<double>(n, v);
}

/// Copies the attributes of `from` onto `to`, each with its own type.
void copy_attributes(hid_t from, hid_t to) {
  hsize_t idx = 0;
  H5Aiterate2(
      from, H5_INDEX_NAME, H5_ITER_INC, &idx,
      [](hid_t loc, const char* name, const H5A_info_t*, void* out) -> herr_t {
        const hid_t a = H5Aopen(loc, name, H5P_DEFAULT);
        const hid_t type = H5Aget_type(a), space = H5Aget_space(a);
        std::vector<char> value(H5Tget_size(type));
        H5Aread(a, type, value.data());
        const hid_t b =
            H5Acreate2(*static_cast<hid_t*>(out), name, type, space, H5P_DEFAULT, H5P_DEFAULT);
        H5Awrite(b, type, value.data());
        H5Aclose(b);
        H5Sclose(space);
        H5Tclose(type);
        H5Aclose(a);
        return 0;
      },
      &to);
}

/// Copies group `from` into group `to`: subgroups, datasets (contiguous, no filter) and
/// attributes.
herr_t copy_group(hid_t from, hid_t to) {
  copy_attributes(from, to);
  return H5Literate(
      from, H5_INDEX_NAME, H5_ITER_INC, nullptr,
      [](hid_t loc, const char* name, const H5L_info_t*, void* out) -> herr_t {
        const hid_t dst = *static_cast<hid_t*>(out);
        H5O_info_t info;
        H5Oget_info_by_name(loc, name, &info, H5P_DEFAULT);
        if (info.type == H5O_TYPE_GROUP) {
          const hid_t g = H5Gopen2(loc, name, H5P_DEFAULT);
          const hid_t h = H5Gcreate2(dst, name, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
          copy_group(g, h);
          H5Gclose(h);
          H5Gclose(g);
          return 0;
        }
        const hid_t set = H5Dopen2(loc, name, H5P_DEFAULT);
        const hid_t type = H5Dget_type(set), space = H5Dget_space(set);
        const auto n = static_cast<std::size_t>(H5Sget_simple_extent_npoints(space));
        std::vector<char> values(std::max<std::size_t>(n, 1) * H5Tget_size(type));
        H5Dread(set, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data());
        const hid_t copy =
            H5Dcreate2(dst, name, type, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
        H5Dwrite(copy, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data());
        copy_attributes(set, copy);
        H5Dclose(copy);
        H5Sclose(space);
        H5Tclose(type);
        H5Dclose(set);
        return 0;
      },
      &to);
}

TEST_F(DamagedFiles, CheckpointsOfTheEarlierFormatStillLoad) {
  // drumlab wrote HDF5's default format (superblock 0, no checksums) with contiguous datasets
  // before: the same checkpoint in that form reads back to the same state.
  const fs::path old = dir_.path() / "old.h5";
  {
    const hid_t from = H5Fopen(good_.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
    const hid_t to = H5Fcreate(old.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
    ASSERT_GE(copy_group(from, to), 0);
    H5Fclose(to);
    H5Fclose(from);
  }
  unsigned super = 99;
  {
    const hid_t f = H5Fopen(old.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
    const hid_t fcpl = H5Fget_create_plist(f);
    H5Pget_version(fcpl, &super, nullptr, nullptr, nullptr);
    H5Pclose(fcpl);
    H5Fclose(f);
  }
  EXPECT_EQ(super, 0u);  // the unchecksummed superblock
  EXPECT_TRUE(same_state(read_checkpoint(old).state, read_checkpoint(good_).state));
  EXPECT_TRUE(same_state(read_checkpoint(good_).state, sim_->state()));
}

TEST_F(DamagedFiles, CheckpointCutAtAnyByteIsRefused) {
  std::size_t tried = 0;
  for (const std::size_t at : cut_offsets(bytes_.size())) {
    const fs::path cut = dir_.path() / "cut.h5";
    put_bytes(cut, bytes_.substr(0, at));
    const std::string message = refusal([&] { read_checkpoint(cut); });
    ASSERT_THAT(message, HasSubstr("cut.h5: ")) << "cut at " << at << " of " << bytes_.size();
    if (at == bytes_.size() / 2) print_row("checkpoint cut at half its bytes", message);
    if (at == 0) print_row("checkpoint of 0 bytes", message);
    ++tried;
  }
  std::printf("checkpoint of %zu bytes cut at %zu offsets: all refused\n", bytes_.size(), tried);
}

TEST_F(DamagedFiles, SeriesCutAtAnyByteIsRefused) {
  const fs::path file = dir_.path() / "s.h5";
  {
    H5Series series(file);
    for (int k = 0; k < 3; ++k) {
      series.write_frame(sim_->particles(), sim_->time(), sim_->steps());
      sim_->advance(5);
    }
    series.finish();
  }
  const std::string bytes = bytes_of(file);
  for (const std::size_t at : cut_offsets(bytes.size())) {
    const fs::path cut = dir_.path() / "s_cut.h5";
    put_bytes(cut, bytes.substr(0, at));
    const std::string message = refusal([&] {
      const SeriesInfo info = read_series_info(cut);
      for (std::size_t k = 0; k < info.frames; ++k) read_series_frame(cut, k);
    });
    ASSERT_THAT(message, HasSubstr("s_cut.h5")) << "cut at " << at << " of " << bytes.size();
    if (at == bytes.size() / 2) print_row("series cut at half its bytes", message);
  }
}

TEST_F(DamagedFiles, AFlippedBitInAnyDatasetIsFoundByItsChecksum) {
  // Each dataset with values is chunked with Fletcher32: flip one bit in its first chunk.
  const std::vector<std::string> sets = {
      "particles/position",    "particles/velocity",   "particles/omega", "particles/force",
      "particles/torque",      "particles/radius",     "particles/mass",  "particles/inv_mass",
      "particles/inv_inertia", "particles/size_class", "particles/id",    "contacts/row_start",
      "contacts/col",          "contacts/history",     "walls/history"};
  for (const std::string& name : sets) {
    haddr_t address = HADDR_UNDEF;
    {
      const h5::Handle f = h5::open_file(good_);
      const h5::Handle set = h5::open_dataset(f.get(), name);
      hsize_t offset[3] = {0, 0, 0};
      unsigned mask = 0;
      hsize_t size = 0;
      ASSERT_GE(H5Dget_chunk_info_by_coord(set.get(), offset, &mask, &address, &size), 0) << name;
      ASSERT_GT(size, 8u) << name;
      address += size / 2;
    }
    std::string bytes = bytes_;
    bytes[address] = static_cast<char>(bytes[address] ^ 0x10);
    const fs::path bad = dir_.path() / "bad.h5";
    put_bytes(bad, bytes);
    const std::string message = refusal([&] { read_checkpoint(bad); });
    EXPECT_THAT(message, HasSubstr("Fletcher32")) << name;
    if (name == "particles/position") print_row("a flipped bit in the data of " + name, message);
  }
}

TEST_F(DamagedFiles, AFlippedBitAnywhereIsRefusedOrChangesNothing) {
  const SimulationState original = read_checkpoint(good_).state;
  std::size_t refused = 0, unchanged = 0, wrong = 0;
  const fs::path bad = dir_.path() / "bit.h5";
  for (std::size_t at = 0; at < bytes_.size(); at += 61) {
    std::string bytes = bytes_;
    bytes[at] = static_cast<char>(bytes[at] ^ (1 << (at % 8)));
    put_bytes(bad, bytes);
    try {
      const Checkpoint c = read_checkpoint(bad);
      if (same_state(c.state, original)) {
        ++unchanged;  // a byte HDF5 never reads (free space, padding)
      } else {
        ++wrong;
        ADD_FAILURE() << "a flipped bit at byte " << at << " was read as other data";
      }
    } catch (const InputError&) {
      ++refused;
    }
  }
  std::printf("flipped bit at every 61st byte of %zu: %zu refused, %zu unchanged, %zu wrong\n",
              bytes_.size(), refused, unchanged, wrong);
  EXPECT_EQ(wrong, 0u);
  EXPECT_GT(refused, unchanged);
}

TEST_F(DamagedFiles, DatasetsOfAnotherShapeOrTypeAreRefused) {
  const std::size_t n = sim_->particles().size();
  struct Case {
    std::string file;
    std::function<void(hid_t)> edit;
    std::string expected;
  };
  const Case cases[] = {
      {"position_3xN.h5",
       [&](hid_t f) {
         replace(f, "particles/position", H5T_IEEE_F64LE, {3, n}, doubles(3 * n));
       },
       "dataset 'position' has shape (3 x 250), expected (N x 3)"},
      {"walls_Nx9.h5",
       [&](hid_t f) {
         replace(f, "walls/history", H5T_IEEE_F64LE, {n, 9}, doubles(9 * n));
       },
       "dataset 'history' has shape (250 x 9), expected (N x 3 x 3)"},
      {"radius_short.h5",
       [&](hid_t f) { replace(f, "particles/radius", H5T_IEEE_F64LE, {n - 1}, doubles(n - 1)); },
       "particles/position has 250 rows, particles/radius 249"},
      {"radius_2d.h5",
       [&](hid_t f) {
         replace(f, "particles/radius", H5T_IEEE_F64LE, {n, 1}, doubles(n));
       },
       "dataset 'radius' has shape (250 x 1), expected (N)"},
      {"radius_int.h5",
       [&](hid_t f) { replace(f, "particles/radius", H5T_STD_I32LE, {n}, doubles(n, 1.0)); },
       "unexpected element type in dataset 'radius'"},
      {"position_f32.h5",
       [&](hid_t f) {
         replace(f, "particles/position", H5T_IEEE_F32LE, {n, 3}, doubles(3 * n));
       },
       "unexpected element type in dataset 'position'"},
      {"id_u64.h5",
       [&](hid_t f) { replace(f, "particles/id", H5T_STD_U64LE, {n}, doubles(n, 1.0)); },
       "unexpected element type in dataset 'id'"},
      {"size_class_i8.h5",
       [&](hid_t f) { replace(f, "particles/size_class", H5T_STD_I8LE, {n}, doubles(n, 0.0)); },
       "unexpected element type in dataset 'size_class'"},
      {"no_contacts.h5", [](hid_t f) { H5Ldelete(f, "contacts", H5P_DEFAULT); },
       "missing group 'contacts'"},
      {"no_velocity.h5", [](hid_t f) { H5Ldelete(f, "particles/velocity", H5P_DEFAULT); },
       "missing dataset 'velocity'"},
      {"no_dt.h5", [](hid_t f) { H5Adelete(f, "dt"); }, "missing attribute 'dt'"},
      {"no_format.h5", [](hid_t f) { H5Adelete(f, "format"); }, "not a drumlab checkpoint"},
  };
  for (const Case& c : cases) {
    const fs::path p = edited(c.file, c.edit);
    const std::string message = refusal([&] { read_checkpoint(p); });
    EXPECT_THAT(message, HasSubstr(c.file + ": ")) << c.file;
    EXPECT_THAT(message, HasSubstr(c.expected)) << c.file;
    print_row(c.file, message);
  }
}

TEST_F(DamagedFiles, ADatasetLargerThanTheFileIsRefusedBeforeAllocating) {
  // contacts/col declared with 1e11 rows in chunks never written: the file stays small, and a
  // reader that trusted the header would allocate 400 GB.
  const fs::path p = edited("huge.h5", [](hid_t f) {
    H5Ldelete(f, "contacts/col", H5P_DEFAULT);
    const hsize_t rows = 100'000'000'000ull, chunk = 1024;
    const hid_t space = H5Screate_simple(1, &rows, nullptr);
    const hid_t dcpl = H5Pcreate(H5P_DATASET_CREATE);
    H5Pset_chunk(dcpl, 1, &chunk);
    const hid_t set =
        H5Dcreate2(f, "contacts/col", H5T_STD_U32LE, space, H5P_DEFAULT, dcpl, H5P_DEFAULT);
    EXPECT_GE(set, 0);
    H5Dclose(set);
    H5Pclose(dcpl);
    H5Sclose(space);
  });
  const std::string message = refusal([&] { read_checkpoint(p); });
  EXPECT_THAT(message, HasSubstr("dataset 'col' claims 100000000000 values"));
  print_row("contacts/col declared with 1e11 rows", message);
}

/// A restart of `scene_text` from `file` through a run session (what `drumlab run --restart`
/// does), refused with the returned message.
std::string restart_refusal(const std::string& scene_text, const fs::path& file) {
  return refusal([&] {
    SessionOptions o;
    o.restart = file.string();
    RunSession session(parse_scene(scene_text, "other.toml"), o);
  });
}

std::string with(std::string text, const std::string& from, const std::string& to) {
  const std::size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

TEST_F(DamagedFiles, ACheckpointOfAnotherSceneIsRefused) {
  const std::string text = output_scene_text();
  const struct {
    std::string damage, scene, expected;
  } cases[] = {
      {"another scene: fill.count 200", with(text, "count = 250", "count = 200"),
       "particles: 250 in the checkpoint, the scene's fill.count is 200"},
      {"another scene: a class radius 0.0041", with(text, "radius = 0.004", "radius = 0.0041"),
       "the scene's class"},
      {"another scene: density 2600", with(text, "density = 2500.0", "density = 2600.0"),
       "material.density 2600 kg/m^3"},
      {"a wet scene from a dry checkpoint", wet_output_scene_text(),
       "good.h5: restart state: 0 scalars per contact"},
  };
  for (const auto& c : cases) {
    const std::string message = restart_refusal(c.scene, good_);
    EXPECT_THAT(message, HasSubstr("good.h5: ")) << c.damage;
    EXPECT_THAT(message, HasSubstr(c.expected)) << c.damage;
    print_row(c.damage, message);
  }
  EXPECT_EQ(restart_refusal(text, good_), "");  // the scene itself restarts
}

TEST_F(DamagedFiles, NonFiniteHistoryIsRefused) {
  const std::size_t n = sim_->particles().size();
  const std::size_t m = sim_->state().contact_col.size();
  ASSERT_GT(m, 100u);
  const fs::path nan = edited("nan.h5", [&](hid_t f) {
    std::vector<double> h = doubles(3 * m);
    h[3 * 1 + 2] = std::numeric_limits<double>::quiet_NaN();
    replace(f, "contacts/history", H5T_IEEE_F64LE, {m, 3}, h);
  });
  std::string message = restart_refusal(output_scene_text(), nan);
  EXPECT_THAT(message, HasSubstr("nan.h5: restart state: contacts/history: row 1: not finite"));
  print_row("NaN in contacts/history", message);
  const fs::path inf = edited("inf.h5", [&](hid_t f) {
    std::vector<double> h = doubles(9 * n, 0.0);
    h[9 * 7 + 4] = std::numeric_limits<double>::infinity();
    replace(f, "walls/history", H5T_IEEE_F64LE, {n, 3, 3}, h);
  });
  message = restart_refusal(output_scene_text(), inf);
  EXPECT_THAT(message, HasSubstr("inf.h5: restart state: walls/history: row 7: not finite"));
  print_row("inf in walls/history", message);
}

TEST_F(DamagedFiles, ANonFiniteOrNegativeLiquidArrayIsRefused) {
  // The law parts' per-particle arrays are checked like the fixed ones: a NaN film would spread
  // through the bridges it forms into the liquid totals, a negative one form a bridge of negative
  // volume. The small drum wet, with films (migration) and wall bridges.
  const std::string text =
      output_scene_text() +
      "[liquid]\nsurface_tension = 0.072\ncontact_angle_deg = 0\n"
      "liquid_content = 0.05\nmax_bridge_volume = 5e-11\nwall_bridges = true\n";
  const SceneConfig wet = parse_scene(text, "wet-films");
  const SimulationState state = settled_simulation(wet, 200)->state();
  const fs::path wet_file = dir_.path() / "wet.h5";
  write_checkpoint(wet_file, state, wet.name);
  ASSERT_EQ(restart_refusal(text, wet_file), "");  // the undamaged file restarts
  const std::size_t n = state.particles.size();
  const std::vector<double>* film = state.particles.find_array(kLiquidFilmArray);
  ASSERT_NE(film, nullptr);
  const struct {
    std::string file, array;
    std::size_t row;
    double value;
    std::string expected;
  } cases[] = {
      {"film_nan.h5", "liquid_film", 4, std::numeric_limits<double>::quiet_NaN(),
       "particles/extra_liquid_film: row 4: not finite"},
      {"film_negative.h5", "liquid_film", 5, -1e-12,
       "particles/extra_liquid_film: row 5: -1e-12, below zero"},
      {"wall_age_inf.h5", "wall_bridge_age_mantle", 6, std::numeric_limits<double>::infinity(),
       "particles/extra_wall_bridge_age_mantle: row 6: not finite"},
  };
  for (const auto& c : cases) {
    const fs::path p = dir_.path() / c.file;
    fs::copy_file(wet_file, p, fs::copy_options::overwrite_existing);
    std::vector<double> values = c.array == "liquid_film" ? *film : std::vector<double>(n, 0.0);
    values[c.row] = c.value;
    const hid_t f = H5Fopen(p.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
    ASSERT_GE(f, 0);
    replace(f, "particles/extra_" + c.array, H5T_IEEE_F64LE, {n}, values);
    H5Fclose(f);
    const std::string message = restart_refusal(text, p);
    EXPECT_THAT(message, HasSubstr(c.file + ": ")) << c.file;
    EXPECT_THAT(message, HasSubstr(c.expected)) << c.file;
    print_row(c.array + " " + (std::isnan(c.value) ? "NaN" : fmt::format("{}", c.value)), message);
  }
}

TEST_F(DamagedFiles, ARowStartPastThePartnersIsRefusedBeforeAnyPartnerIsRead) {
  // Found by fuzzing: row 0 claimed more partners than the list holds, and the check read them
  // (a heap-buffer-overflow) before it saw the next row start fall back.
  SimulationState s = sim_->state();
  ASSERT_GT(s.contact_col.size(), 100u);
  s.contact_row_start[1] = s.contact_col.size() + 5;
  const std::string message = refusal([&] { Simulation(scene_, std::move(s)); });
  EXPECT_THAT(message, HasSubstr("contact list: row starts decrease or pass the partners"));
  print_row("contacts/row_start with a row start past the partners", message);
}

TEST_F(DamagedFiles, TheCommandLineSaysOneLineAndExitsTwo) {
  const fs::path scene = dir_.write("scene.toml", output_scene_text());
  put_bytes(dir_.path() / "cut.h5", bytes_.substr(0, bytes_.size() / 3));
  std::string flipped = bytes_;
  {
    const h5::Handle f = h5::open_file(good_);
    const h5::Handle set = h5::open_dataset(f.get(), "particles/velocity");
    hsize_t offset[2] = {0, 0}, size = 0;
    unsigned mask = 0;
    haddr_t address = HADDR_UNDEF;
    ASSERT_GE(H5Dget_chunk_info_by_coord(set.get(), offset, &mask, &address, &size), 0);
    flipped[address + 17] = static_cast<char>(flipped[address + 17] ^ 1);
  }
  put_bytes(dir_.path() / "bit.h5", flipped);
  for (const char* file : {"cut.h5", "bit.h5", "none.h5"}) {
    const CliResult r =
        run_cli("run " + scene.string() + " --steps 5 --restart " + (dir_.path() / file).string());
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
    EXPECT_THAT(r.output, HasSubstr(std::string("drumlab: error: ")));
    EXPECT_THAT(r.output, HasSubstr(file));
    print_row(std::string("CLI restart from ") + file, r.output.substr(0, r.output.size() - 1));
  }
}

}  // namespace
}  // namespace drumlab::test
