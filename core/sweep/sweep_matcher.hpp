#pragma once
// Matching at every threshold of the adaptive sweep without a brute-force matrix per threshold.
//
// The sweep's thresholds select overlapping sets of the same features: from one threshold to the
// next, a few of the 10^3 features of each image leave and a few come (graf: 4 M distances over
// its 21 distinct thresholds instead of 19 M). The distance between two features never changes,
// so each feature keeps a short list of its nearest neighbours in the other image's current set,
// and a new threshold only computes the distances that involve a feature new to it. Every answer
// is the one match_descriptors gives (same matches, same order, same tie-breaking): the lists are
// exact prefixes of the brute-force order, and a list that ran out is recomputed in full.
#include <array>
#include <cstdint>
#include <vector>

#include "aief/match.hpp"
#include "core/kernels/kernel_table.hpp"

namespace aief {

// A feature of the other image, by its index in the other image's current set.
struct Neighbour {
  int distance = 0;
  std::int32_t index = 0;
};

// The order match_descriptors scans in: lower distance first, ties to the lower index.
inline bool closer(Neighbour x, Neighbour y) {
  return x.distance != y.distance ? x.distance < y.distance : x.index < y.index;
}

// The nearest neighbours of one feature, closest first. The entries are exactly the elements of
// the other set that come no later than the last entry in `closer` order (a prefix of that
// order); `complete` says the prefix is the whole set. A full list never claims to be complete
// (it might have cut an element off), which costs at most a recomputation, never exactness.
struct NeighbourList {
  // Shorter lists take fewer offers (a row's passes grow with the length) but run out more often
  // (a full recomputation). Measured on graf 1->2 (cachegrind, whole sweep): length 8 -> 4 takes
  // the offers from 29.8 M to 18.2 M instructions and 512 k to 275 k mispredicted branches, for
  // 274 recomputations; 3 saves no more.
  static constexpr int kLength = 4;
  std::array<Neighbour, kLength> entries{};
  int count = 0;
  bool complete = true;  // an empty list of an empty set is complete

  // Learns one more element of the other set: kept when it ranks within the known prefix, or
  // anywhere while the list is complete.
  void offer(Neighbour neighbour) {
    if (!complete &&
        (count == 0 || !closer(neighbour, entries[static_cast<std::size_t>(count - 1)])))
      return;
    insert(neighbour);
  }
  // Distances above this are never kept (a cheap filter before offer).
  int bound() const {
    return complete ? 256 : count == 0 ? -1 : entries[static_cast<std::size_t>(count - 1)].distance;
  }
  // The other set changed: drops the elements that left it and renumbers the rest
  // (new_index_of_old[i] is the new index of old element i, -1 when it left).
  void renumber(const std::vector<std::int32_t>& new_index_of_old);
  // Whether the list knows the first `wanted` elements of the other set (or all there are).
  bool knows(int wanted) const { return count >= wanted || complete; }

 private:
  void insert(Neighbour neighbour);
};

// Inserts in `closer` order; the last entry of a full list falls off, and a list that fills up
// stops claiming completeness (see offer for why that keeps the prefix invariant). Inline: the
// sweep offers a few hundred thousand pairs.
inline void NeighbourList::insert(Neighbour neighbour) {
  const bool full = count == kLength;
  if (full && !closer(neighbour, entries[static_cast<std::size_t>(kLength - 1)])) return;
  int at = full ? kLength - 1 : count;
  while (at > 0 && closer(neighbour, entries[static_cast<std::size_t>(at - 1)])) {
    entries[static_cast<std::size_t>(at)] = entries[static_cast<std::size_t>(at - 1)];
    --at;
  }
  entries[static_cast<std::size_t>(at)] = neighbour;
  if (!full) ++count;
  if (count == kLength) complete = false;
}

class SweepMatcher {
 public:
  SweepMatcher(const MatchOptions& options, const KernelTable& kernels);

  // match_descriptors(a, b, options), to the byte. ids_a[i] is the identity of a[i] (distinct,
  // >= 0): a feature keeps its id and its descriptor at every call, so that distances computed at
  // an earlier call stay valid. Features present at the previous call too are expected in the
  // same relative order (the sweep's are: level, then raster order); if not, the lists are
  // rebuilt from scratch, so the answer is exact either way.
  std::vector<Match> match(const std::vector<Descriptor>& a, const std::vector<std::int32_t>& ids_a,
                           const std::vector<Descriptor>& b,
                           const std::vector<std::int32_t>& ids_b);

  // match() in pieces, for a caller that spreads one threshold's matching over frames
  // (core/sweep/spread_sweep.hpp): begin(a, ids_a, b, ids_b), then offer_rows() until rows_left()
  // is 0, then finish(). The descriptors must stay in place until finish(). The same answer as
  // match().
  void begin(const std::vector<Descriptor>& a, const std::vector<std::int32_t>& ids_a,
             const std::vector<Descriptor>& b, const std::vector<std::int32_t>& ids_b);
  // Rows of new distances left to offer, and the distances of the next one.
  int rows_left() const { return static_cast<int>(rows_.size() - next_row_); }
  int next_row_length() const;
  void offer_rows(int count);
  std::vector<Match> finish();

  // Forgets the previous calls (a new pair of images), keeping the buffers.
  void reset();

  // Descriptor distances computed by the calls so far (for tests and benchmarks).
  long long distances_computed() const { return distances_computed_; }

 private:
  // One image's current set: its ids, its features' lists of neighbours in the other set with
  // each list's bound() beside it (the filter's input), and this call's descriptors blocked.
  struct Side {
    std::vector<std::int32_t> ids;
    std::vector<std::int32_t> index_of_id;  // index in the current set, -1 when absent
    std::vector<NeighbourList> lists;
    std::vector<std::int16_t> bounds;  // lists[i].bound(), or -1 where no list is kept
    std::vector<std::uint32_t>
        blocked;  // this call's descriptors (core/kernels/hamming_256_blocked.hpp)
    std::vector<std::int32_t> new_index_of_old;  // this call: where each previous element went
    std::vector<std::uint8_t> is_new;            // this call: per element, new to the set
    std::vector<std::int32_t> new_elements;      // this call: their indices, ascending
  };

  static bool renumber(Side& side, const std::vector<std::int32_t>& ids);
  static void forget_previous(Side& side);
  bool keeps_lists(const Side& side) const { return &side == &a_ || mutual_; }
  void update_lists();
  void offer_new_row(std::int32_t row);
  void offer_row(Side& query_side, std::int32_t query, Side& train_side, int n_train);
  void recompute(NeighbourList& list, const Descriptor& query,
                 const std::vector<Descriptor>& others);
  const NeighbourList& list_knowing(Side& side, int index, int wanted,
                                    const std::vector<Descriptor>& own,
                                    const std::vector<Descriptor>& others);

  MatchOptions options_;
  const KernelTable* kernels_;
  bool mutual_;  // the cross check needs the lists of B too
  Side a_, b_;
  // The call under way: its descriptors, and its rows of new distances, in order: each new
  // feature of B (against all of A), then, unless every feature of B is new, each new feature of
  // A (against the old ones of B); a row is j >= 0 for B's feature j, -1 - i for A's feature i.
  const std::vector<Descriptor>* a_descriptors_ = nullptr;
  const std::vector<Descriptor>* b_descriptors_ = nullptr;
  std::vector<std::int32_t> rows_;
  std::size_t next_row_ = 0;
  std::vector<std::uint16_t> row_;       // one query's distances to the other set
  std::vector<std::int32_t> positions_;  // the filter's output for one chunk of row_
  std::vector<std::int16_t> no_bounds_;  // -1s: train bounds that take nothing (recompute)
  long long distances_computed_ = 0;
};

}  // namespace aief
