#pragma once
// `drumlab paper-table`: the paper's operation-count estimates (paper_reference.hpp) beside the
// counts of m1..m5 on the paper's packing.
#include <string>

namespace drumlab::bench {

/// Prints the table `table` (1 or 2) and, if `csv_path` is not empty, writes it as CSV (long
/// format). Throws if the five methods disagree on the contact set.
void run_paper_table(int table, const std::string& csv_path);

}  // namespace drumlab::bench
