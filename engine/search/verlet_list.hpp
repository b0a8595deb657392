#pragma once
// Verlet (neighbour) lists with a skin, built by any other method: pairs within margin + skin are
// listed once, and every call only re-tests the listed pairs. The list is rebuilt when the two
// largest displacements since the last build sum to more than the skin (until then no pair
// outside the list can have come within the margin; this is never later than LAMMPS's "one
// particle moved more than half the skin"), or when the particle count, radii, margin or period
// changed. A caller that knows a bound on the motion since its last call (the
// simulation: time step x the fastest speed) passes it, and the per-particle check is skipped
// while the summed bounds prove that no particle moved more than half the skin. Otherwise the
// check runs on every call, so a contact can never be missed ("dangerous" builds: none).
//
// The displacements are measured in the frame of SearchInput::frame_angle (a drum's angle: pair
// distances are the same in any frame turning about the z axis), where the part of a bed that
// turns with its drum does not move. When they call for a new list and fewer than one particle in
// eight moved more than a quarter of the skin in that frame, only those are patched
// (verlet_patch.hpp): they take their current positions as their references and their partners
// within reach are added to the list; a full rebuild follows when more moved, or when the patches
// have grown the list by a quarter. Either way the list holds every pair that can come within the
// margin, sorted: the same forces in the same order.
//
// Two ways to use it: find_pairs() filters the list down to the pairs within the margin (any
// consumer of the ContactSearch interface); a simulation that keeps contact history on the listed
// pairs itself calls refresh() every step and re-reads list() only after a rebuild: its force loop
// then tests the listed pairs once (the filter is fused into the force loop, as in LAMMPS's
// granular pair styles), and it reports the pairs it found with record_found().
#include <limits>
#include <memory>
#include <span>
#include <string>

#include "engine/search/contact_search.hpp"
#include "engine/search/search_input.hpp"
#include "engine/search/verlet_patch.hpp"

namespace drumlab {

class VerletListSearch final : public ContactSearch {
 public:
  /// `builder` finds the listed pairs; skin = skin_factor x the smallest radius (m).
  VerletListSearch(std::unique_ptr<ContactSearch> builder, double skin_factor);

  std::string_view name() const override { return name_; }
  std::string_view description() const override { return description_; }
  void find_pairs(const SearchInput& in, std::vector<IndexPair>& out) override;
  /// Rebuilds the list if needed and counts one call's work (the listed pairs are the pairs
  /// tested); returns true if the list was rebuilt or patched. Does not filter. `moved`: an upper
  /// bound on how far any particle moved (nearest image along a periodic z) since the previous
  /// call, m; infinite if not known.
  bool refresh(const SearchInput& in, double moved = kUnknownMotion);
  static constexpr double kUnknownMotion = std::numeric_limits<double>::infinity();
  /// Pairs within margin + skin at the last build, sorted by (i, j).
  std::span<const IndexPair> list() const { return list_; }
  /// Sets the pairs found in the last refresh() (by the caller's own test of the list).
  void record_found(std::uint64_t pairs) { counters_.pairs_found = pairs; }
  /// Forces a rebuild at the next call.
  void invalidate() { reference_.clear(); }
  /// Follows a re-ordering of the particles (slot k now holds the particle that was at
  /// order[k]; particle i moved to new_index[i]): the list stays valid without a rebuild.
  void renumber(std::span<const Index> order, std::span<const Index> new_index);
  double cell_size() const override { return builder_->cell_size(); }
  /// Candidates: i's listed partners, tested on `in`; grids: the
  /// builder's cells for i at the last rebuild, unless the particles were re-ordered since.
  SearchVisit visit(Index i, const SearchInput& in) const override;

  std::string report() const override;
  const ContactSearch& builder() const { return *builder_; }
  double skin() const { return skin_; }
  /// Rebuilds and calls so far (a rebuild happens on the first call too).
  std::uint64_t rebuilds() const { return rebuilds_; }
  std::uint64_t calls() const { return calls_; }
  /// Patches (the list kept, the particles that moved given new partners; see above).
  std::uint64_t patches() const { return patches_; }
  /// Patches only for at least this many particles (below, a rebuild costs little); 0: never.
  void set_patch_min_particles(std::size_t n) { patch_min_particles_ = n; }
  static constexpr std::size_t kPatchMinParticles = 4096;
  /// Calls that measured every particle's displacement (the others were settled by the bound).
  std::uint64_t checks() const { return checks_; }
  /// Pairs in the current list.
  std::size_t list_size() const { return list_.size(); }

 private:
  enum class Need { nothing, motion, rebuild };
  Need needs_rebuild(const SearchInput& in);
  void rebuild(const SearchInput& in);
  bool patch(const SearchInput& in);
  void filter(const SearchInput& in, std::vector<IndexPair>& out);

  std::unique_ptr<ContactSearch> builder_;
  double skin_factor_;
  double skin_ = 0.0;
  std::string name_, description_;
  std::vector<IndexPair> list_;  ///< pairs within margin + skin at the last build, sorted
  PairSlices slices_;            ///< per-thread output of filter()
  std::vector<std::uint32_t> listed_per_particle_;  ///< list entries with first index i
  std::vector<IndexPair> scratch_pairs_;
  std::vector<std::uint32_t> scratch_counts_;
  std::vector<Vec3> reference_;  ///< positions at the last build or patch, in the turning frame
  std::vector<Vec3> scratch_positions_;
  std::vector<double> scratch_radii_;
  std::vector<double> radius_;  ///< radii at the last build
  double margin_ = -1.0;
  double period_ = 0.0;
  /// Bound on the largest displacement since the last build (m): the measured one after a check,
  /// plus the callers' bounds since.
  double moved_ = kUnknownMotion;
  /// The frame's angle at the last call, and a bound on every particle's distance from the axis.
  double angle_ = 0.0;
  double axis_distance_ = kUnknownMotion;
  bool listed_only_ = false;      ///< the per-particle counters hold the listed pairs alone
  bool builder_current_ = false;  ///< no renumber() since the last rebuild: the builder's cells
                                  ///< still refer to the current storage indices
  VerletPatch patcher_;
  std::vector<Index> patched_;                    ///< the particles of the last patch
  std::vector<std::vector<Index>> moved_shares_;  ///< the patch scan's per-thread finds
  std::vector<std::size_t> splice_cuts_;          ///< the merge's shares (splice_pairs)
  std::vector<std::uint8_t> moved_flag_;          ///< 1 for the particles of a patch, while it runs
  std::vector<IndexPair> patch_pairs_;            ///< their pairs within reach
  std::size_t listed_at_rebuild_ = 0;             ///< the list's size at the last rebuild
  std::size_t patch_min_particles_ = kPatchMinParticles;
  std::uint64_t rebuilds_ = 0, calls_ = 0, checks_ = 0, patches_ = 0;
};

}  // namespace drumlab
