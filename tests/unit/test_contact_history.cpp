// CSR contact list and the transfer of tangential history between steps.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <vector>

#include "engine/contact/contact_history.hpp"
#include "engine/threads.hpp"

namespace drumlab {
namespace {

void set_history(ContactList& c, Index i, Index j, const Vec3& v) {
  const Vec3* h = c.find(i, j);
  ASSERT_NE(h, nullptr);
  c.history()[static_cast<std::size_t>(h - c.history().data())] = v;
}

TEST(ContactList, BuildsRowsSortedByIAndJ) {
  ContactList c;
  const std::vector<IndexPair> pairs{{3, 7}, {0, 5}, {3, 4}, {0, 2}, {1, 6}, {3, 5}};
  c.update(pairs, 8);
  EXPECT_EQ(c.size(), 6u);
  EXPECT_EQ(c.rows(), 8u);
  const std::vector<std::size_t> rows(c.row_start().begin(), c.row_start().end());
  EXPECT_EQ(rows, (std::vector<std::size_t>{0, 2, 3, 3, 6, 6, 6, 6, 6}));
  const std::vector<Index> cols(c.col().begin(), c.col().end());
  EXPECT_EQ(cols, (std::vector<Index>{2, 5, 6, 4, 5, 7}));
  for (const auto& p : pairs) {
    ASSERT_NE(c.find(p.i, p.j), nullptr);
    EXPECT_EQ(*c.find(p.i, p.j), Vec3::Zero());
  }
  EXPECT_EQ(c.find(0, 3), nullptr);
  EXPECT_EQ(c.find(7, 3), nullptr);
  EXPECT_EQ(c.find(20, 21), nullptr);
  // The same pairs already sorted (as a Verlet list gives them; empty first, middle and last
  // rows): the same rows.
  std::vector<IndexPair> sorted = pairs;
  std::sort(sorted.begin(), sorted.end());
  ContactList d;
  d.update(std::vector<IndexPair>{{2, 4}}, 8);  // a different list before
  d.update(sorted, 8);
  EXPECT_EQ(std::vector<std::size_t>(d.row_start().begin(), d.row_start().end()), rows);
  EXPECT_EQ(std::vector<Index>(d.col().begin(), d.col().end()), cols);
  const std::vector<IndexPair> late{{5, 6}, {5, 7}};  // rows 0-4 empty
  d.update(late, 8);
  EXPECT_EQ(std::vector<std::size_t>(d.row_start().begin(), d.row_start().end()),
            (std::vector<std::size_t>{0, 0, 0, 0, 0, 0, 2, 2, 2}));
}

TEST(ContactList, HistoryFollowsPersistingContactsOnly) {
  ContactList c;
  c.update(std::vector<IndexPair>{{0, 1}, {1, 2}, {0, 3}}, 4);
  set_history(c, 0, 1, Vec3(1, 0, 0));
  set_history(c, 1, 2, Vec3(0, 2, 0));
  set_history(c, 0, 3, Vec3(0, 0, 3));
  // (1,2) ends, (2,3) and (0,2) appear, the order of the search output changes.
  c.update(std::vector<IndexPair>{{2, 3}, {0, 3}, {0, 2}, {0, 1}}, 4);
  EXPECT_EQ(c.size(), 4u);
  EXPECT_EQ(*c.find(0, 1), Vec3(1, 0, 0));
  EXPECT_EQ(*c.find(0, 3), Vec3(0, 0, 3));
  EXPECT_EQ(*c.find(0, 2), Vec3::Zero());
  EXPECT_EQ(*c.find(2, 3), Vec3::Zero());
  EXPECT_EQ(c.find(1, 2), nullptr);
  // A contact that ended and comes back starts from zero.
  c.update(std::vector<IndexPair>{{1, 2}, {0, 1}}, 4);
  EXPECT_EQ(*c.find(1, 2), Vec3::Zero());
  EXPECT_EQ(*c.find(0, 1), Vec3(1, 0, 0));
  c.update(std::vector<IndexPair>{}, 4);
  EXPECT_EQ(c.size(), 0u);
  c.update(std::vector<IndexPair>{{0, 1}}, 4);
  EXPECT_EQ(*c.find(0, 1), Vec3::Zero());
}

TEST(ContactList, ParticleCountMayChange) {
  ContactList c;
  c.update(std::vector<IndexPair>{{0, 1}}, 2);
  set_history(c, 0, 1, Vec3(1, 2, 3));
  c.update(std::vector<IndexPair>{{0, 1}, {4, 5}}, 6);
  EXPECT_EQ(*c.find(0, 1), Vec3(1, 2, 3));
  EXPECT_EQ(*c.find(4, 5), Vec3::Zero());
  c.clear();
  EXPECT_EQ(c.size(), 0u);
  c.update(std::vector<IndexPair>{{0, 1}}, 2);
  EXPECT_EQ(*c.find(0, 1), Vec3::Zero());
}

TEST(ContactList, LongRowsAreSortedAndMatched) {
  ContactList c;
  std::vector<IndexPair> pairs;
  for (Index j = 40; j > 0; --j) pairs.push_back({0, j});
  c.update(pairs, 41);
  for (Index j = 1; j <= 40; j += 3) set_history(c, 0, j, Vec3(j, 0, 0));
  std::vector<IndexPair> next;
  for (Index j = 1; j <= 40; j += 2) next.push_back({0, j});
  c.update(next, 41);
  for (Index j = 1; j <= 40; j += 2) {
    const double expected = (j - 1) % 3 == 0 ? j : 0.0;
    EXPECT_EQ(c.find(0, j)->x(), expected) << j;
  }
}

// entry_rows()[k] is row i of every entry k, after the list is built, replaced, renumbered and
// re-indexed: the pair loop splits its chunks across row ends by it.
void expect_entry_rows(ContactList& c) {
  c.index_cross_block(4);
  ASSERT_EQ(c.entry_rows().size(), c.size());
  for (std::size_t i = 0; i < c.rows(); ++i) {
    for (std::size_t k = c.row_start()[i]; k < c.row_start()[i + 1]; ++k) {
      ASSERT_EQ(c.entry_rows()[k], i) << "entry " << k;
    }
  }
}

TEST(ContactList, EntryRowsFollowTheListThroughUpdateAndRenumber) {
  ContactList c;
  // Rows of 0 to 4 entries, empty rows between, and an empty row at the end.
  const std::vector<IndexPair> pairs{{0, 1}, {0, 5}, {0, 9}, {2, 3}, {2, 4}, {2, 6},
                                     {2, 8}, {5, 6}, {7, 8}, {7, 9}, {8, 9}};
  c.update(pairs, 11);
  expect_entry_rows(c);
  c.update(std::vector<IndexPair>{{1, 2}, {3, 10}, {4, 5}, {4, 6}}, 11);
  expect_entry_rows(c);
  std::vector<Index> new_index{10, 9, 8, 7, 6, 5, 4, 3, 2, 1, 0};
  c.renumber(new_index);
  expect_entry_rows(c);
  c.update(pairs, 11);
  c.index_cross_block(2);  // another block size: rebuilt as well
  ASSERT_EQ(c.entry_rows().size(), pairs.size());
  EXPECT_EQ(c.entry_rows()[3], 2u);
  c.update(std::vector<IndexPair>{}, 11);
  expect_entry_rows(c);
}

// The cross-block index against its definition, on a list long enough for the parallel counting
// sort to cut it in shares (at least 32,768 contacts a share), on teams of 1 to 3 threads, and
// with row keys (an MPI rank's blocks).
void expect_cross_block_index(const ContactList& c) {
  std::vector<std::vector<std::size_t>> by_receiver(c.rows());
  for (std::size_t i = 0; i < c.rows(); ++i) {
    for (std::size_t k = c.row_start()[i]; k < c.row_start()[i + 1]; ++k) {
      if (c.col()[k] >= c.row_block_end()[i]) by_receiver[c.col()[k]].push_back(k);
    }
  }
  std::vector<Index> receivers;
  std::vector<std::size_t> start{0}, contacts;
  for (std::size_t j = 0; j < c.rows(); ++j) {
    if (by_receiver[j].empty()) continue;
    receivers.push_back(static_cast<Index>(j));
    contacts.insert(contacts.end(), by_receiver[j].begin(), by_receiver[j].end());
    start.push_back(contacts.size());
  }
  EXPECT_TRUE(std::ranges::equal(c.cross_receivers(), receivers));
  EXPECT_TRUE(std::ranges::equal(c.cross_start(), start));
  EXPECT_TRUE(std::ranges::equal(c.cross_contacts(), contacts));
}

TEST(ContactList, CrossBlockIndexIsItsDefinitionOnAnyTeam) {
  const std::size_t n = 30000;
  std::vector<IndexPair> pairs;
  std::uint64_t state = 12345;
  for (Index i = 0; i + 1 < n; ++i) {
    for (int q = 0; q < 6; ++q) {  // partners near (most in the row's block) and far
      state = state * 6364136223846793005ULL + 1442695040888963407ULL;
      const std::uint64_t reach = q < 4 ? 40 : 3000;
      const auto j =
          static_cast<Index>(std::min<std::uint64_t>(n - 1, i + 1 + (state >> 33) % reach));
      pairs.push_back({i, j});
    }
  }
  std::ranges::sort(pairs);
  pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
  ASSERT_GT(pairs.size(), 2u * 32768u);
  std::vector<std::uint64_t> keys(n);
  for (std::size_t i = 0; i < n; ++i) keys[i] = 3 * i + 100;
  const int before = max_threads();
  for (int threads = 1; threads <= 3; ++threads) {
    set_thread_count(threads);
    ContactList c;
    c.update(pairs, n);
    c.index_cross_block(512);
    expect_cross_block_index(c);
    EXPECT_GT(c.cross_contacts().size(), 1000u);
    c.set_row_keys(keys);
    c.index_cross_block(512);
    expect_cross_block_index(c);
  }
  set_thread_count(before);
}

}  // namespace
}  // namespace drumlab
