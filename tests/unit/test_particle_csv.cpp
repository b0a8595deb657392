#include <gtest/gtest.h>

#include "engine/io/particle_csv.hpp"

namespace drumlab {
namespace {

std::string error_of(std::string_view text) {
  try {
    parse_particle_csv(text, "p.csv");
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(ParticleCsv, ReadsColumnsInAnyOrderWithExtras) {
  const auto t = parse_particle_csv("id,r,x,y,z\n7,0.5,1,2,3\n\n8, 0.25 ,-1e3,0,4.5\n", "p.csv");
  ASSERT_EQ(t.radius.size(), 2u);
  EXPECT_EQ(t.position[0], Vec3(1, 2, 3));
  EXPECT_DOUBLE_EQ(t.radius[0], 0.5);
  EXPECT_EQ(t.position[1], Vec3(-1e3, 0, 4.5));
  EXPECT_DOUBLE_EQ(t.radius[1], 0.25);
}

TEST(ParticleCsv, HeaderOnlyIsZeroParticles) {
  EXPECT_TRUE(parse_particle_csv("x,y,z,r\n", "p.csv").radius.empty());
}

TEST(ParticleCsv, ErrorsNameFileLineAndColumn) {
  EXPECT_EQ(error_of(""), "p.csv: empty file (expected header x,y,z,r)");
  EXPECT_EQ(error_of("x,y,r\n"), "p.csv:1: header has no column 'z' (expected x,y,z,r)");
  EXPECT_EQ(error_of("x,y,z,r\n1,2,3\n"), "p.csv:2: 3 fields, the header has 4");
  EXPECT_EQ(error_of("x,y,z,r\n1,2,3,abc\n"), "p.csv:2: column 'r': 'abc' is not a number");
  EXPECT_EQ(error_of("x,y,z,r\n1,2,3,1\n1,nan,3,1\n"),
            "p.csv:3: column 'y': value nan is not finite");
  EXPECT_EQ(error_of("x,y,z,r\n1,2,3,-0.1\n"), "p.csv:2: column 'r': radius -0.1 must be positive");
  EXPECT_EQ(error_of("x,y,z,r\n1,2,3,0\n"), "p.csv:2: column 'r': radius 0 must be positive");
  EXPECT_EQ(error_of("x,y,z,r\n1e999,2,3,1\n"), "p.csv:2: column 'x': '1e999' is not a number");
}

TEST(ParticleCsv, MissingFile) {
  EXPECT_THROW(read_particle_csv("/nonexistent/particles.csv"), InputError);
}

}  // namespace
}  // namespace drumlab
