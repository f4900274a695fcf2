#include "core/sweep_matcher.hpp"

#include <algorithm>
#include <limits>
#include <numeric>

#include "aief/error.hpp"

namespace aief {

// Inserts in `closer` order; the last entry of a full list falls off, and a list that fills up
// stops claiming completeness (see offer for why that keeps the prefix invariant).
void NeighbourList::insert(Neighbour neighbour) {
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

// Dropping elements keeps a prefix a prefix (of the smaller set, ending at the last survivor),
// and a complete list complete. Renumbering keeps the order because the elements that stayed
// keep their relative order (checked by the caller), so ties still break to the lower index.
void NeighbourList::renumber(const std::vector<std::int32_t>& new_index_of_old) {
  int kept = 0;
  for (int k = 0; k < count; ++k) {
    const Neighbour old = entries[static_cast<std::size_t>(k)];
    const std::int32_t index = new_index_of_old[static_cast<std::size_t>(old.index)];
    if (index >= 0) entries[static_cast<std::size_t>(kept++)] = {old.distance, index};
  }
  count = kept;
}

SweepMatcher::SweepMatcher(const MatchOptions& options, const KernelTable& kernels)
    : options_(options), kernels_(&kernels), mutual_(options.kind == MatcherKind::mutual) {
  options_.validate();
}

// Maps the previous set onto the new one. Returns false when two features present at both calls
// swapped order (the lists' tie-breaking would no longer follow the indices).
bool SweepMatcher::renumber(Side& side, const std::vector<std::int32_t>& ids) {
  side.new_index_of_old.assign(side.ids.size(), -1);
  side.is_new.assign(ids.size(), 0);
  side.new_elements.clear();
  const std::int32_t max_id = ids.empty() ? -1 : *std::max_element(ids.begin(), ids.end());
  if (!ids.empty() && *std::min_element(ids.begin(), ids.end()) < 0) throw Error("SweepMatcher: negative feature id");
  if (static_cast<std::size_t>(max_id + 1) > side.index_of_id.size())
    side.index_of_id.resize(static_cast<std::size_t>(max_id + 1), -1);

  bool order_kept = true;
  std::int32_t last_old = -1;
  for (std::size_t i = 0; i < ids.size(); ++i) {
    const std::int32_t old = side.index_of_id[static_cast<std::size_t>(ids[i])];
    if (old >= 0) {
      side.new_index_of_old[static_cast<std::size_t>(old)] = static_cast<std::int32_t>(i);
      order_kept = order_kept && old > last_old;
      last_old = old;
    } else {
      side.is_new[i] = 1;
      side.new_elements.push_back(static_cast<std::int32_t>(i));
    }
  }
  for (std::int32_t id : side.ids) side.index_of_id[static_cast<std::size_t>(id)] = -1;
  for (std::size_t i = 0; i < ids.size(); ++i) side.index_of_id[static_cast<std::size_t>(ids[i])] = static_cast<std::int32_t>(i);
  side.ids = ids;
  return order_kept;
}

// As if the previous call had been empty: every feature is new.
void SweepMatcher::forget_previous(Side& side) {
  std::fill(side.new_index_of_old.begin(), side.new_index_of_old.end(), -1);
  side.is_new.assign(side.ids.size(), 1);
  side.new_elements.resize(side.ids.size());
  std::iota(side.new_elements.begin(), side.new_elements.end(), 0);
}

namespace {

// The lists of the features that stayed move to their new index and forget the neighbours that
// left; a new feature starts with the empty, complete list of an empty set, to be offered the
// whole other set.
void carry_lists(std::vector<NeighbourList>& lists, const std::vector<std::int32_t>& new_index_of_old,
                 std::size_t new_count, const std::vector<std::int32_t>& other_new_index_of_old) {
  std::vector<NeighbourList> carried(new_count);
  for (std::size_t old = 0; old < lists.size(); ++old) {
    const std::int32_t index = new_index_of_old[old];
    if (index < 0) continue;
    NeighbourList& list = carried[static_cast<std::size_t>(index)];
    list = lists[old];
    list.renumber(other_new_index_of_old);
  }
  lists.swap(carried);
}

}  // namespace

// Offers the pairs (query, trains[k]) at distances[k] to the query's list and, for the cross
// check, to the train's list. A pair above both lists' bounds would be refused by both, so it is
// skipped: the row is filtered a chunk at a time with the bounds of the moment (they only shrink).
void SweepMatcher::offer_row(std::int32_t query, const std::uint16_t* distances, const std::vector<std::int32_t>& trains) {
  constexpr int kChunk = 64;
  NeighbourList& list = a_.lists[static_cast<std::size_t>(query)];
  const int n = static_cast<int>(trains.size());
  worth_offering_.resize(kChunk);
  for (int begin = 0; begin < n; begin += kChunk) {
    const int end = std::min(n, begin + kChunk);
    const int query_bound = list.bound();
    int worth = 0;
    for (int k = begin; k < end; ++k) {
      const int distance = distances[k];
      const bool for_b = mutual_ && distance <= b_bounds_[static_cast<std::size_t>(trains[static_cast<std::size_t>(k)])];
      worth_offering_[static_cast<std::size_t>(worth)] = k;
      worth += (distance <= query_bound) | for_b;
    }
    for (int w = 0; w < worth; ++w) {
      const int k = worth_offering_[static_cast<std::size_t>(w)];
      const std::int32_t train = trains[static_cast<std::size_t>(k)];
      list.offer({distances[k], train});
      if (!mutual_) continue;
      NeighbourList& train_list = b_.lists[static_cast<std::size_t>(train)];
      train_list.offer({distances[k], query});
      b_bounds_[static_cast<std::size_t>(train)] = train_list.bound();
    }
  }
}

// Offers each list exactly the pairs it has not seen: an old feature of A the new features of B,
// a new feature of A every feature of B (and the same pairs, read the other way, to B's lists).
// Old-old pairs were offered at an earlier call, when both features were there.
void SweepMatcher::update_lists(const std::vector<Descriptor>& a, const std::vector<Descriptor>& b) {
  carry_lists(a_.lists, a_.new_index_of_old, a.size(), b_.new_index_of_old);
  if (mutual_) {
    carry_lists(b_.lists, b_.new_index_of_old, b.size(), a_.new_index_of_old);
    b_bounds_.resize(b.size());
    for (std::size_t j = 0; j < b.size(); ++j) b_bounds_[j] = b_.lists[j].bound();
  }

  new_b_descriptors_.clear();
  for (std::int32_t j : b_.new_elements) new_b_descriptors_.push_back(b[static_cast<std::size_t>(j)]);
  all_b_.resize(b.size());
  std::iota(all_b_.begin(), all_b_.end(), 0);
  row_.resize(std::max(b.size(), new_b_descriptors_.size()));
  for (std::size_t i = 0; i < a.size(); ++i) {
    const bool all_of_b = a_.is_new[i] != 0;
    const std::vector<Descriptor>& train = all_of_b ? b : new_b_descriptors_;
    if (train.empty()) continue;
    const int n = static_cast<int>(train.size());
    kernels_->hamming_256_many(a[i].data(), train.front().data(), n, row_.data());
    distances_computed_ += n;
    offer_row(static_cast<std::int32_t>(i), row_.data(), all_of_b ? all_b_ : b_.new_elements);
  }
}

void SweepMatcher::recompute(NeighbourList& list, const Descriptor& query, const std::vector<Descriptor>& others) {
  list = NeighbourList{};
  const int n = static_cast<int>(others.size());
  row_.resize(std::max(row_.size(), others.size()));
  kernels_->hamming_256_many(query.data(), others.front().data(), n, row_.data());
  distances_computed_ += n;
  for (int k = 0; k < n; ++k) list.offer({row_[static_cast<std::size_t>(k)], k});
}

const NeighbourList& SweepMatcher::list_knowing(Side& side, int index, int wanted, const std::vector<Descriptor>& own,
                                                const std::vector<Descriptor>& others) {
  NeighbourList& list = side.lists[static_cast<std::size_t>(index)];
  if (!list.knows(wanted)) recompute(list, own[static_cast<std::size_t>(index)], others);
  return list;
}

std::vector<Match> SweepMatcher::match(const std::vector<Descriptor>& a, const std::vector<std::int32_t>& ids_a,
                                       const std::vector<Descriptor>& b, const std::vector<std::int32_t>& ids_b) {
  if (ids_a.size() != a.size() || ids_b.size() != b.size()) throw Error("SweepMatcher: one id per descriptor");
  const bool a_order_kept = renumber(a_, ids_a);
  const bool b_order_kept = renumber(b_, ids_b);
  if (!a_order_kept || !b_order_kept) {
    forget_previous(a_);
    forget_previous(b_);
  }
  update_lists(a, b);

  std::vector<Match> matches;
  if (a.empty() || b.empty()) return matches;
  const int n_a = static_cast<int>(a.size());
  // A list's first entry is match_descriptors' nearest train (ties to the lower index), its
  // second entry's distance the second nearest distance; the ratio test needs both.
  const int wanted = options_.kind == MatcherKind::ratio ? 2 : 1;
  std::vector<Neighbour> best(static_cast<std::size_t>(n_a));
  std::vector<int> second_distance(static_cast<std::size_t>(n_a));
  int min_distance = std::numeric_limits<int>::max();
  for (int i = 0; i < n_a; ++i) {
    const NeighbourList& list = list_knowing(a_, i, wanted, a, b);
    best[static_cast<std::size_t>(i)] = list.entries[0];
    second_distance[static_cast<std::size_t>(i)] = list.count > 1 ? list.entries[1].distance : std::numeric_limits<int>::max();
    min_distance = std::min(min_distance, list.entries[0].distance);
  }
  const int paper_limit = std::max(2 * min_distance, 30);  // as match_descriptors

  for (int i = 0; i < n_a; ++i) {
    const Neighbour nearest = best[static_cast<std::size_t>(i)];
    if (nearest.distance > options_.max_distance) continue;
    bool keep = false;
    switch (options_.kind) {
      // The first entry of B's list is the nearest query of that train, ties to the lower query.
      case MatcherKind::mutual: keep = list_knowing(b_, nearest.index, 1, b, a).entries[0].index == i; break;
      case MatcherKind::ratio:
        keep = static_cast<double>(nearest.distance) < options_.ratio * second_distance[static_cast<std::size_t>(i)];
        break;
      case MatcherKind::paper: keep = nearest.distance <= paper_limit; break;
    }
    if (keep) matches.push_back({i, nearest.index, nearest.distance});
  }
  return matches;
}

}  // namespace aief
