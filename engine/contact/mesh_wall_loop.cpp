// The forces of the triangle walls (ContactModel::add_mesh_forces): three passes over each of
// fixed blocks of particles, so that the bits do not depend on the thread count nor on which
// particles share a block. (1) Each particle's contacts with every mesh (mesh_wall_set.hpp) and
// their history slots (mesh_wall_history.hpp). (2) Per mesh, its law's kernel on its contacts, in
// batches as the analytic wall's loop runs them. (3) Each particle adds its contacts' forces in
// the order of their patches and keeps their advanced history.
#include <algorithm>
#include <cmath>

#include "engine/contact/contact_kernel.hpp"
#include "engine/contact/contact_model.hpp"
#include "engine/contact/law_dispatch.hpp"
#include "engine/contact/mesh_wall_history.hpp"
#include "engine/contact/sjkr_cohesion.hpp"
#include "engine/mesh/mesh_wall_set.hpp"

namespace drumlab {
namespace {

constexpr std::size_t kBlock = 256;
constexpr int kNoSlot = -1;

/// A particle's mesh history arrays, by slot.
struct SlotArrays {
  std::array<double*, kMeshSlots> patch{};
  std::array<std::array<double*, 3>, kMeshSlots> xi{};
  std::array<std::array<double*, 3>, kMeshSlots> roll{};  ///< null without the rolling spring
  bool rolling = false;

  explicit SlotArrays(Particles& p) {
    const auto find = [&](std::string_view name) {
      std::vector<double>* a = p.find_array(name);
      if (a == nullptr) throw std::logic_error("mesh walls without their history arrays");
      return a->data();
    };
    rolling = p.find_array(kMeshRollingArrays[0][0]) != nullptr;
    for (std::size_t k = 0; k < kMeshSlots; ++k) {
      patch[k] = find(kMeshPatchArrays[k]);
      for (std::size_t c = 0; c < 3; ++c) {
        xi[k][c] = find(kMeshSpringArrays[k][c]);
        if (rolling) roll[k][c] = find(kMeshRollingArrays[k][c]);
      }
    }
  }
  static Vec3 get(const std::array<double*, 3>& a, Index i) { return {a[0][i], a[1][i], a[2][i]}; }
  static void set(const std::array<double*, 3>& a, Index i, const Vec3& v) {
    for (std::size_t c = 0; c < 3; ++c) a[c][i] = v[static_cast<Eigen::Index>(c)];
  }
  void clear(std::size_t k, Index i) const {
    patch[k][i] = 0.0;
    set(xi[k], i, Vec3::Zero());
    if (rolling) set(roll[k], i, Vec3::Zero());
  }
};

/// One contact of pass (1), completed by pass (2).
struct Record {
  Index i = 0;
  int slot = kNoSlot;
  MeshContact contact;
  Vec3 xi = Vec3::Zero();  ///< in: the stored spring; out: the advanced one
  Vec3 xi_r = Vec3::Zero();
  Vec3 force = Vec3::Zero();
  Vec3 torque = Vec3::Zero();
};

/// Pass (1) for the particles [begin, end): their contacts, each with the history its patch had
/// (zero for a new contact). A particle's slots are kept packed in the order of its contacts'
/// patches (slot k: its k-th contact), so a particle whose slot 0 is free has no history at all
/// and one touching no mesh costs one load.
void find_contacts(Particles& p, const MeshWallSet& walls, const SlotArrays& slots, double c,
                   double s, std::size_t begin, std::size_t end, MeshWallSet::Scratch& scratch,
                   std::vector<MeshContact>& hits, std::vector<Record>& out) {
  out.clear();
  for (std::size_t q = begin; q < end; ++q) {
    const auto i = static_cast<Index>(q);
    walls.contacts(p.position[i], p.radius[i], c, s, scratch, hits);
    if (hits.empty()) {
      for (std::size_t k = 0; k < kMeshSlots && slots.patch[k][i] != 0.0; ++k) slots.clear(k, i);
      continue;
    }
    for (std::size_t n = 0; n < hits.size(); ++n) {
      Record r;
      r.i = i;
      r.slot = n < kMeshSlots ? static_cast<int>(n) : kNoSlot;
      r.contact = hits[n];
      const double key = static_cast<double>(hits[n].patch) + 1.0;
      for (std::size_t k = 0; k < kMeshSlots && slots.patch[k][i] != 0.0; ++k) {
        if (slots.patch[k][i] != key) continue;
        r.xi = SlotArrays::get(slots.xi[k], i);
        if (slots.rolling) r.xi_r = SlotArrays::get(slots.roll[k], i);
      }
      out.push_back(r);
    }
    // The new keys, packed; the advanced springs follow in pass (3).
    for (std::size_t k = 0; k < kMeshSlots; ++k) {
      if (k < hits.size()) {
        slots.patch[k][i] = static_cast<double>(hits[k].patch) + 1.0;
      } else if (slots.patch[k][i] != 0.0) {
        slots.clear(k, i);
      }
    }
  }
}

/// Pass (2) for one mesh's contacts among `records`.
template <class Normal, bool Tangential, RollingKind Rolling>
void evaluate(const ContactLaw<Normal>& law, const Particles& p, std::uint32_t wall, bool turns,
              double omega, double dt, double history_dt, std::vector<Record>& records,
              WallBatch& batch) {
  const Vec3 spin(0.0, 0.0, turns ? omega : 0.0);
  const auto flush = [&] {
    batch.evaluate<Normal, Tangential, Rolling>(law, spin, history_dt);
    for (std::size_t l = 0; l < batch.count; ++l) {
      Record& r = records[batch.part[l]];
      r.force = batch.force.vec3(l);
      r.torque = batch.torque_i.vec3(l);
      r.xi = batch.xi.vec3(l);
      if constexpr (Rolling == RollingKind::spring) r.xi_r = batch.xi_r.vec3(l);
    }
    batch.count = 0;
  };
  batch.count = 0;
  for (std::size_t n = 0; n < records.size(); ++n) {
    const Record& r = records[n];
    if (r.contact.wall != wall) continue;
    const Index i = r.i;
    const Vec3 v_wall = turns ? Drum::wall_velocity(r.contact.point, omega) : Vec3::Zero();
    batch.add(i, n, r.contact.normal, r.contact.overlap, p.radius[i], p.mass[i],
              dt * p.inv_inertia[i], p.velocity[i] - v_wall, p.omega[i], r.xi);
    if constexpr (Rolling == RollingKind::spring) batch.set_rolling(r.xi_r);
    if (batch.full()) flush();
  }
  if (batch.count > 0) flush();
}

}  // namespace

std::size_t ContactModel::add_mesh_forces(Particles& p, const MeshWallSet& walls, double angle,
                                          double omega, double dt, double history_dt) const {
  if (walls.empty()) return 0;
  const SlotArrays slots(p);
  const double c = std::cos(angle), s = std::sin(angle);
  const std::size_t n = p.size();
  const auto blocks = static_cast<std::int64_t>((n + kBlock - 1) / kBlock);
  const bool torque = uses_rotation();
  // Dry adhesion ([cohesion], sjkr) pulls a particle onto a mesh as onto the analytic wall:
  // k_c times the overlap's lens area, along the normal, while they overlap.
  const SjkrCohesion* sjkr = part<SjkrCohesion>();
  std::size_t contacts = 0;
#pragma omp parallel reduction(+ : contacts)
  {
    // Each thread's buffers, kept from step to step: the step allocates nothing once warm.
    static thread_local MeshWallSet::Scratch scratch;
    static thread_local std::vector<MeshContact> hits;
    static thread_local std::vector<Record> records;
    WallBatch batch;
#pragma omp for schedule(static)
    for (std::int64_t b = 0; b < blocks; ++b) {
      const std::size_t begin = static_cast<std::size_t>(b) * kBlock;
      find_contacts(p, walls, slots, c, s, begin, std::min(n, begin + kBlock), scratch, hits,
                    records);
      if (records.empty()) continue;
      for (std::size_t w = 0; w < walls.size(); ++w) {
        const MeshLaw& m = mesh_laws_[w];
        const bool turns = walls.wall(w).attach == MeshAttach::drum;
        with_law(m.law, m.tangential, rolling_kind(m.rolling, spring_),
                 [&]<class N, bool Tangential, RollingKind Rolling>(const ContactLaw<N>& law) {
                   evaluate<N, Tangential, Rolling>(law, p, static_cast<std::uint32_t>(w), turns,
                                                    omega, dt, history_dt, records, batch);
                 });
      }
      for (const Record& r : records) {  // pass (3)
        p.force[r.i] += r.force;
        if (sjkr != nullptr) {
          p.force[r.i] -=
              sjkr->force(SjkrCohesion::wall_lens_area(r.contact.overlap, p.radius[r.i])) *
              r.contact.normal;
        }
        if (torque) p.torque[r.i] += r.torque;
        if (r.slot == kNoSlot) continue;
        const auto k = static_cast<std::size_t>(r.slot);
        SlotArrays::set(slots.xi[k], r.i, r.xi);
        if (slots.rolling) SlotArrays::set(slots.roll[k], r.i, r.xi_r);
      }
      contacts += records.size();
    }
  }
  return contacts;
}

}  // namespace drumlab
