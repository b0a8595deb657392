// The table of search methods (engine/search/search_methods.hpp): every listed name parses and
// makes a search of that name and description; Verlet names parse to their builder; the traits
// agree with the searches they describe.
#include <gtest/gtest.h>

#include "engine/search/cell_grid.hpp"
#include "engine/search/search_methods.hpp"
#include "engine/search/verlet_list.hpp"

namespace drumlab {
namespace {

TEST(SearchRegistry, EveryListedNameParsesAndMakesThatSearch) {
  for (const std::string& name : search_method_names()) {
    const auto parsed = parse_search_method(name);
    ASSERT_TRUE(parsed.has_value()) << name;
    const auto search = make_search(name);
    EXPECT_EQ(search->name(), name);
    EXPECT_EQ(parsed->verlet, dynamic_cast<VerletListSearch*>(search.get()) != nullptr) << name;
    if (!parsed->verlet) {
      EXPECT_EQ(search->description(), parsed->method->description) << name;
    }
  }
}

TEST(SearchRegistry, VerletNamesAndUnknownNames) {
  EXPECT_EQ(parse_search_method("verlet")->method->name, kDefaultVerletBuilder);
  EXPECT_EQ(parse_search_method("verlet:m3")->method->name, "m3");
  EXPECT_TRUE(parse_search_method("verlet:m3")->verlet);
  EXPECT_EQ(verlet_method_name("m5"), "verlet");
  EXPECT_EQ(verlet_method_name("m2"), "verlet:m2");
  for (const char* bad : {"", "m0", "m6", "verlet:", "verlet:brute", "verlet:verlet", "M5"}) {
    EXPECT_FALSE(parse_search_method(bad).has_value()) << bad;
    EXPECT_THROW(make_search(bad), InputError) << bad;
  }
}

TEST(SearchRegistry, TraitsMatchTheSearches) {
  for (const SearchMethodInfo& m : search_methods()) {
    const auto search = make_search(m.name);
    const auto* grid = dynamic_cast<const CellGridSearch*>(search.get());
    EXPECT_EQ(m.draws_cells, grid != nullptr) << m.name;
    EXPECT_EQ(m.grid == SearchGrid::none, m.cell == CellRule::none) << m.name;
    if (grid != nullptr) {
      EXPECT_EQ(grid->config().three_d, m.grid == SearchGrid::three_d) << m.name;
      EXPECT_EQ(grid->config().cell_from_min_radius, m.cell == CellRule::min_radius) << m.name;
    }
  }
  EXPECT_EQ(verlet_builder_names(),
            (std::vector<std::string>{"m1", "m2", "m3", "m4", "m5", "mlgrid"}));
}

}  // namespace
}  // namespace drumlab
