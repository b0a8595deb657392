// drumlab-mpi run --vtu against drumlab run --vtu: on 2 and 3 ranks, the VTU/PVD series of a wet
// drum (particles with force, coordination, agglomerate ids and films; the drum wall; contacts
// with their bridges) has the serial run's files, and each reads back in VTK as the serial file
// does, every array bit for bit, although drumlab-mpi writes them without VTK (gathered on rank 0,
// engine/io/paraview/xml_writer.hpp). (--grid-vtk, which needs one search grid, is refused:
// test_mpi_options.)
#include <gtest/gtest.h>

#include <filesystem>
#include <set>
#include <string>

#include "tests/mpi/mpi_runner.hpp"
#include "tests/mpi/wet_drum_text.hpp"
#include "tests/render/vtk_compare.hpp"

namespace drumlab::test {
namespace {

std::set<std::string> files_in(const std::filesystem::path& dir) {
  std::set<std::string> names;
  for (const auto& e : std::filesystem::directory_iterator(dir)) {
    names.insert(e.path().filename().string());
  }
  return names;
}

class MpiVtu : public MpiCase {};

TEST_F(MpiVtu, SeriesOnTwoAndThreeRanksIsTheSerialRuns) {
  const std::string scene = dir.write("wet.toml", scene_text(wet_law()));
  const std::string args = " --steps 400 --every 100 --granule-age 0 --contacts-vtk --vtu ";
  serial(scene, args + dir.file("serial"), "serial.h5");
  const std::set<std::string> expected = files_in(dir.file("serial"));
  ASSERT_EQ(expected.size(), 3u * 5u + 3u);  // particles, drum, contacts: 5 frames and a .pvd
  // The wet arrays are there to compare: agglomerate ids and films, bridges on the contacts.
  const auto last = std::filesystem::path(dir.file("serial"));
  EXPECT_NE(read_back(last / "particles_000004.vtu")->GetPointData()->GetArray("liquid_volume"),
            nullptr);
  EXPECT_NE(read_back(last / "contacts_000004.vtp")->GetCellData()->GetArray("bridge_volume"),
            nullptr);
  for (const int ranks : {2, 3}) {
    SCOPED_TRACE(std::to_string(ranks) + " ranks");
    const std::string out = dir.file("ranks" + std::to_string(ranks));
    parallel(ranks, scene, args + out, "parallel.h5");
    EXPECT_NE(last_output.find("vtu               5 frames in " + out), std::string::npos)
        << last_output;
    ASSERT_EQ(files_in(out), expected);
    for (const std::string& name : expected) {
      SCOPED_TRACE(name);
      const auto a = std::filesystem::path(dir.file("serial")) / name;
      const auto b = std::filesystem::path(out) / name;
      if (name.ends_with(".pvd")) {
        EXPECT_EQ(read_text(a.string()), read_text(b.string()));
      } else {
        expect_same_datasets(read_back(a), read_back(b));
      }
    }
  }
}

}  // namespace
}  // namespace drumlab::test
