#pragma once
// The paper's own estimates, printed beside drumlab's counts: Tables 1 (drum depth 0.15 m) and 2
// (depth 2 m) of Lobovikov D.V., Kharchenko A.V., Matygullina E.V., "Comparison of efficiency of
// contact search algorithms for discrete element method", Bulletin PNRPU. Mechanical engineering,
// materials science, 2021, vol. 23, no. 2, pp. 55-61, DOI 10.15593/2224-9877/2021.2.07. -1 marks
// an empty cell of the paper's table.
#include <array>

namespace drumlab::bench {

struct PaperColumn {
  double cell_side;  ///< m
  double total_cells;
  double particles_per_cell;
  std::array<double, 3> search_cells;  ///< small, medium, large (or the same for all)
  std::array<double, 3> particles_checked;
  double operations_per_particle;
};

struct PaperTable {
  double depth;                     ///< m
  std::array<double, 3> particles;  ///< small, medium, large
  std::array<PaperColumn, 5> methods;
};

inline constexpr std::array<PaperTable, 2> kPaperTables{{
    {0.15,
     {166500, 20813, 6167},
     {{{0.005, 133200, 1.4525, {41, 61, 85}, {60, 89, 123}, 3145},
       {0.005, 133200, 1.4525, {41, 61, 85}, {25, 89, 123}, 2126},
       {0.005, 3996000, 0.0484, {779, 1159, 1615}, {38, 56, 78}, 13542},
       {0.015, 14800, 13.0729, {13, 13, 13}, {170, 170, 170}, 6386},
       {0.015, 148000, 1.3073, {65, 65, 65}, {85, 85, 85}, 4140}}}},
    {2.0,
     {2217780, 277223, 82140},
     {{{0.005, 133200, 19.34, {41, 61, 85}, {793, 1180, 1644}, 31051},
       {0.005, 133200, 19.34, {41, 61, 85}, {793, 1180, 1644}, 17475},
       {0.005, 53280000, 0.0484, {779, 1159, 1615}, {38, 56, 78}, 13540},
       {0.015, 14800, 174.13, {13, 13, 13}, {2264, 2264, 2264}, 79668},
       {0.015, 1973333, 1.31, {65, 65, 65}, {85, 85, 85}, 4137}}}},
}};

}  // namespace drumlab::bench
