// `drumlab info SCENE [--write-mesh DIR]` with triangle walls: a line per mesh (key, triangles,
// patches, attachment, closed or open), and each mesh written as DIR/<key>.stl as built (the
// drum at angle 0), read back to the same triangles; a directory that cannot take them is one
// line, exit 2, and no file.
#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "app/cli/wall_mesh_files.hpp"
#include "engine/mesh/stl_file.hpp"
#include "engine/mesh/wall_meshes.hpp"
#include "engine/scene/scene_config.hpp"
#include "tests/unit/cli_runner.hpp"
#include "tests/unit/mesh_test_shapes.hpp"

namespace drumlab::test {
namespace {

/// The small drum with four straight lifters and a plate fixed in the lab (plate.stl beside it).
std::filesystem::path mesh_scene(const TempDir& dir) {
  const auto plate =
      grid_square(2, Vec3(-0.05, 0.0, 0.025), Vec3::UnitX(), Vec3::UnitY(), 0.01);  // 8 triangles
  write_stl(make_mesh(plate, 0.3, "plate"), dir.path() / "plate.stl");
  SmallDrumText t;
  t.wall =
      "friction = 0.5\n[[wall.mesh]]\nfile = \"plate.stl\"\nattach = \"lab\"\n"
      "[[wall.lifters]]\ncount = 4\nheight = 0.02";
  return dir.write("meshes.toml", t.text());
}

bool one_line(const std::string& s) {
  return !s.empty() && s.find('\n') == s.size() - 1;
}

TEST(MeshFiles, KeysNameTheirFiles) {
  EXPECT_EQ(cli::mesh_file_name("wall.lifters[0]"), "lifters_0.stl");
  EXPECT_EQ(cli::mesh_file_name("wall.mesh[12]"), "mesh_12.stl");
}

TEST(CliInfo, PrintsEachMeshAndWritesItAsTheStlItWasBuiltFrom) {
  TempDir dir("info-mesh");
  const auto scene_file = mesh_scene(dir);
  const auto out = dir.path() / "stl";
  const auto r = run_cli("info " + scene_file.string() + " --write-mesh " + out.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  // Four lifters of 12 triangles; each is its own closed box.
  EXPECT_NE(r.output.find("wall.mesh[0]: 8 triangles, 1 smooth patch, fixed in the lab, open"),
            std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("wall.lifters[0]: 48 triangles, 24 smooth patches, turning with the "
                          "drum, closed"),
            std::string::npos)
      << r.output;
  const std::vector<WallMesh> built = build_wall_meshes(load_scene(scene_file));
  ASSERT_EQ(built.size(), 2u);
  for (const WallMesh& w : built) {
    const auto file = out / cli::mesh_file_name(w.key);
    ASSERT_TRUE(std::filesystem::exists(file)) << file;
    const auto corners = read_stl(file);
    ASSERT_EQ(corners.size(), w.mesh.size()) << w.key;
    for (std::size_t t = 0; t < corners.size(); ++t) {
      for (int k = 0; k < 3; ++k) {  // binary STL holds floats
        EXPECT_LT((corners[t][k] - w.mesh.corner(t, k)).norm(), 1e-7) << w.key << " " << t;
      }
    }
  }
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(out), {}), 2);  // no temporaries
}

TEST(CliInfo, ADirectoryThatCannotTakeTheMeshesIsOneLineAndNoFile) {
  TempDir dir("info-mesh-bad");
  const auto scene_file = mesh_scene(dir);
  // Under a regular file: no directory can be made there.
  const auto bad = scene_file / "stl";
  const auto r = run_cli("info " + scene_file.string() + " --write-mesh " + bad.string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_TRUE(one_line(r.output)) << r.output;
  EXPECT_NE(r.output.find("--write-mesh " + bad.string()), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("scene "), std::string::npos) << "info printed before failing";
  for (const auto& e : std::filesystem::recursive_directory_iterator(dir.path())) {
    if (e.path().filename() == "plate.stl") continue;  // the scene's own
    EXPECT_NE(e.path().extension(), ".stl") << "written: " << e.path();
  }
  // A scene without meshes has nothing to write.
  const auto plain = dir.write("plain.toml", SmallDrumText{}.text());
  const auto none =
      run_cli("info " + plain.string() + " --write-mesh " + (dir.path() / "x").string());
  EXPECT_EQ(none.exit_code, 2) << none.output;
  EXPECT_TRUE(one_line(none.output)) << none.output;
  EXPECT_FALSE(std::filesystem::exists(dir.path() / "x"));
}

}  // namespace
}  // namespace drumlab::test
