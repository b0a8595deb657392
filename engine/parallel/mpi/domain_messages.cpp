#include "engine/parallel/mpi/domain_messages.hpp"

#include <algorithm>

namespace drumlab::domain_messages {

bool same_arrays(const Particles& a, const Particles& b) {
  if (a.extra.size() != b.extra.size()) return false;
  for (std::size_t k = 0; k < a.extra.size(); ++k) {
    if (a.extra[k].name != b.extra[k].name) return false;
  }
  return true;
}

std::vector<PackedPiece> sorted_pieces(std::span<const std::byte> bytes, std::size_t count,
                                       std::size_t size) {
  std::vector<PackedPiece> out(count);
  for (std::size_t k = 0; k < count; ++k) {
    const std::byte* at = bytes.data() + k * size;
    out[k] = {packed_slot({at, size}), at, -1};
  }
  std::sort(out.begin(), out.end(),
            [](const PackedPiece& a, const PackedPiece& b) { return a.slot < b.slot; });
  return out;
}

OwnedSet unpack_owned(const Particles& like, std::span<const std::byte> bytes, std::size_t count) {
  const std::size_t size = packed_size(like);
  OwnedSet o{empty_like(like), {}, {}};
  o.p.reserve(count);
  for (const PackedPiece& piece : sorted_pieces(bytes, count, size)) {
    std::size_t pos = 0;
    o.slot.push_back(unpack_particle({piece.at, size}, pos, o.p, o.wall));
  }
  return o;
}

void put_count(std::vector<std::byte>& out, std::size_t n) {
  put_bytes(out, static_cast<std::uint64_t>(n));
}

std::size_t read_message(std::span<const std::byte> msg, const Particles& like,
                         std::vector<std::byte>& owned, ContactRecords& records) {
  std::size_t pos = 0;
  const auto n = get_bytes<std::uint64_t>(msg, pos);
  const std::size_t begin = pos;
  pos += static_cast<std::size_t>(n) * packed_size(like);
  owned.insert(owned.end(), msg.begin() + static_cast<std::ptrdiff_t>(begin),
               msg.begin() + static_cast<std::ptrdiff_t>(pos));
  const auto m = get_bytes<std::uint64_t>(msg, pos);
  for (std::uint64_t k = 0; k < m; ++k) records.unpack(msg, pos);
  return static_cast<std::size_t>(n);
}

}  // namespace drumlab::domain_messages
