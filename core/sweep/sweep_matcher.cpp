#include "core/sweep/sweep_matcher.hpp"

#include <algorithm>
#include <limits>
#include <numeric>

#include "aief/error.hpp"
#include "core/kernels/hamming_256_blocked.hpp"
#include "core/options/sweepable_matcher.hpp"

namespace aief {

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
    : options_(options),
      kernels_(&kernels),
      mutual_(options.kind == MatcherKind::mutual || options.kind == MatcherKind::mutual_ratio) {
  require_sweepable(options_);
}

void SweepMatcher::reset() {
  for (Side* side : {&a_, &b_}) {
    for (std::int32_t id : side->ids) side->index_of_id[static_cast<std::size_t>(id)] = -1;
    side->ids.clear();
    side->lists.clear();
  }
}

// Maps the previous set onto the new one. Returns false when two features present at both calls
// swapped order (the lists' tie-breaking would no longer follow the indices).
bool SweepMatcher::renumber(Side& side, const std::vector<std::int32_t>& ids) {
  side.new_index_of_old.assign(side.ids.size(), -1);
  side.is_new.assign(ids.size(), 0);
  side.new_elements.clear();
  const std::int32_t max_id = ids.empty() ? -1 : *std::max_element(ids.begin(), ids.end());
  if (!ids.empty() && *std::min_element(ids.begin(), ids.end()) < 0)
    throw Error("SweepMatcher: negative feature id");
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
  for (std::size_t i = 0; i < ids.size(); ++i)
    side.index_of_id[static_cast<std::size_t>(ids[i])] = static_cast<std::int32_t>(i);
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

// A row goes through the bound filter a chunk at a time. The first chunk is short: a new query's
// list accepts everything until it fills. Its bound then shrinks slowly, so the chunks double
// (fewer filter calls for a few more refused offers; graf 1->2: the matcher's instructions
// 88.2 M -> 80.8 M against fixed chunks of 32).
constexpr int kFirstChunk = 32, kLastChunk = 512;

// The lists of the features that stayed move to their new index and forget the neighbours that
// left; a new feature starts with the empty, complete list of an empty set, to be offered the
// whole other set.
void carry_lists(std::vector<NeighbourList>& lists,
                 const std::vector<std::int32_t>& new_index_of_old, std::size_t new_count,
                 const std::vector<std::int32_t>& other_new_index_of_old) {
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

// Offers the pairs (query, k) at row_[k], k < n_train, to the query's list and to train k's list,
// where those lists are kept. A pair above both lists' bounds would be refused by both, so the
// row goes through the filter a chunk at a time, with the query's bound of the moment (bounds
// only shrink: a stale one lets a few more through, which offer() refuses).
void SweepMatcher::offer_row(Side& query_side, std::int32_t query, Side& train_side, int n_train) {
  NeighbourList* query_list =
      keeps_lists(query_side) ? &query_side.lists[static_cast<std::size_t>(query)] : nullptr;
  positions_.resize(kLastChunk);
  int chunk = kFirstChunk;
  for (int begin = 0; begin < n_train; begin += chunk, chunk = std::min(2 * chunk, kLastChunk)) {
    const int length = std::min(chunk, n_train - begin);
    const int query_bound = query_list != nullptr ? query_list->bound() : -1;
    const int worth =
        kernels_->positions_within_bounds(row_.data() + begin, train_side.bounds.data() + begin,
                                          length, query_bound, positions_.data());
    // Each list is touched only when the pair is within its own bound (most pairs pass one).
    for (int w = 0; w < worth; ++w) {
      const std::int32_t train = begin + positions_[static_cast<std::size_t>(w)];
      const int distance = row_[static_cast<std::size_t>(train)];
      if (distance <= query_bound) query_list->offer({distance, train});
      std::int16_t& train_bound = train_side.bounds[static_cast<std::size_t>(train)];
      if (distance > train_bound) continue;  // also where no train list is kept (bound -1)
      NeighbourList& train_list = train_side.lists[static_cast<std::size_t>(train)];
      train_list.offer({distance, query});
      train_bound = static_cast<std::int16_t>(train_list.bound());
    }
  }
  if (query_list != nullptr)
    query_side.bounds[static_cast<std::size_t>(query)] =
        static_cast<std::int16_t>(query_list->bound());
}

// Offers each list exactly the pairs it has not seen: every pair with a new feature of B (rows of
// the new features of B against all of A), then every pair of a new feature of A with an old one
// of B (rows of the new features of A against all of B, the new ones of B excluded: offered
// already). Old-old pairs were offered at an earlier call, when both features were there.
// update_lists() prepares the lists and the row order; offer_new_row() offers one row.
void SweepMatcher::update_lists() {
  const std::vector<Descriptor>& a = *a_descriptors_;
  const std::vector<Descriptor>& b = *b_descriptors_;
  carry_lists(a_.lists, a_.new_index_of_old, a.size(), b_.new_index_of_old);
  if (mutual_) carry_lists(b_.lists, b_.new_index_of_old, b.size(), a_.new_index_of_old);
  for (Side* side : {&a_, &b_}) {
    side->bounds.resize(side->ids.size());
    for (std::size_t i = 0; i < side->ids.size(); ++i)
      side->bounds[i] = static_cast<std::int16_t>(keeps_lists(*side) ? side->lists[i].bound() : -1);
  }
  rows_.clear();
  next_row_ = 0;
  if (a.empty() || b.empty()) return;
  block_descriptors(a.front().data(), static_cast<int>(a.size()), a_.blocked);
  block_descriptors(b.front().data(), static_cast<int>(b.size()), b_.blocked);
  const int blocks_a = hamming_block_count(static_cast<int>(a.size()));
  const int blocks_b = hamming_block_count(static_cast<int>(b.size()));
  row_.resize(static_cast<std::size_t>(std::max(blocks_a, blocks_b) * kHammingBlock));
  rows_.assign(b_.new_elements.begin(), b_.new_elements.end());
  if (b_.new_elements.size() == b.size()) return;  // every pair seen in those rows
  for (std::int32_t i : a_.new_elements) rows_.push_back(-1 - i);
}

int SweepMatcher::next_row_length() const {
  const std::int32_t row = rows_[next_row_];
  return static_cast<int>(row >= 0 ? a_descriptors_->size()
                                   : b_descriptors_->size() - b_.new_elements.size());
}

void SweepMatcher::offer_new_row(std::int32_t row) {
  const std::vector<Descriptor>& a = *a_descriptors_;
  const std::vector<Descriptor>& b = *b_descriptors_;
  if (row >= 0) {
    const std::int32_t j = row;
    kernels_->hamming_256_blocked(b[static_cast<std::size_t>(j)].data(), a_.blocked.data(),
                                  hamming_block_count(static_cast<int>(a.size())), row_.data());
    distances_computed_ += static_cast<long long>(a.size());
    offer_row(b_, j, a_, static_cast<int>(a.size()));
    return;
  }
  constexpr std::uint16_t kExcluded =
      0x7fff;  // above every bound (core/kernels/positions_within_bounds.hpp)
  const std::int32_t i = -1 - row;
  kernels_->hamming_256_blocked(a[static_cast<std::size_t>(i)].data(), b_.blocked.data(),
                                hamming_block_count(static_cast<int>(b.size())), row_.data());
  distances_computed_ += static_cast<long long>(b.size() - b_.new_elements.size());
  for (std::int32_t j : b_.new_elements) row_[static_cast<std::size_t>(j)] = kExcluded;
  offer_row(a_, i, b_, static_cast<int>(b.size()));
}

void SweepMatcher::offer_rows(int count) {
  for (; count > 0 && next_row_ < rows_.size(); --count) offer_new_row(rows_[next_row_++]);
}

void SweepMatcher::recompute(NeighbourList& list, const Descriptor& query,
                             const std::vector<Descriptor>& others) {
  list = NeighbourList{};
  const int n = static_cast<int>(others.size());
  row_.resize(std::max(row_.size(), others.size()));
  kernels_->hamming_256_many(query.data(), others.front().data(), n, row_.data());
  distances_computed_ += n;
  // Only the list's own bound filters: the chunks of offer_row against bounds that take nothing.
  if (no_bounds_.size() < others.size()) no_bounds_.resize(others.size(), -1);
  positions_.resize(kLastChunk);
  int chunk = kFirstChunk;
  for (int begin = 0; begin < n; begin += chunk, chunk = std::min(2 * chunk, kLastChunk)) {
    const int worth = kernels_->positions_within_bounds(
        row_.data() + begin, no_bounds_.data() + begin, std::min(chunk, n - begin), list.bound(),
        positions_.data());
    for (int w = 0; w < worth; ++w) {
      const std::int32_t k = begin + positions_[static_cast<std::size_t>(w)];
      list.offer({row_[static_cast<std::size_t>(k)], k});
    }
  }
}

const NeighbourList& SweepMatcher::list_knowing(Side& side, int index, int wanted,
                                                const std::vector<Descriptor>& own,
                                                const std::vector<Descriptor>& others) {
  NeighbourList& list = side.lists[static_cast<std::size_t>(index)];
  if (!list.knows(wanted)) recompute(list, own[static_cast<std::size_t>(index)], others);
  return list;
}

std::vector<Match> SweepMatcher::match(const std::vector<Descriptor>& a,
                                       const std::vector<std::int32_t>& ids_a,
                                       const std::vector<Descriptor>& b,
                                       const std::vector<std::int32_t>& ids_b) {
  begin(a, ids_a, b, ids_b);
  offer_rows(rows_left());
  return finish();
}

void SweepMatcher::begin(const std::vector<Descriptor>& a, const std::vector<std::int32_t>& ids_a,
                         const std::vector<Descriptor>& b, const std::vector<std::int32_t>& ids_b) {
  if (ids_a.size() != a.size() || ids_b.size() != b.size())
    throw Error("SweepMatcher: one id per descriptor");
  const bool a_order_kept = renumber(a_, ids_a);
  const bool b_order_kept = renumber(b_, ids_b);
  if (!a_order_kept || !b_order_kept) {
    forget_previous(a_);
    forget_previous(b_);
  }
  a_descriptors_ = &a;
  b_descriptors_ = &b;
  update_lists();
}

std::vector<Match> SweepMatcher::finish() {
  const std::vector<Descriptor>& a = *a_descriptors_;
  const std::vector<Descriptor>& b = *b_descriptors_;
  std::vector<Match> matches;
  if (a.empty() || b.empty()) return matches;
  const int n_a = static_cast<int>(a.size());
  // A list's first entry is match_descriptors' nearest train (ties to the lower index), its
  // second entry's distance the second nearest distance; the ratio test needs both.
  const bool ratio_test =
      options_.kind == MatcherKind::ratio || options_.kind == MatcherKind::mutual_ratio;
  const int wanted = ratio_test ? 2 : 1;
  std::vector<Neighbour> best(static_cast<std::size_t>(n_a));
  std::vector<int> second_distance(static_cast<std::size_t>(n_a));
  int min_distance = std::numeric_limits<int>::max();
  for (int i = 0; i < n_a; ++i) {
    const NeighbourList& list = list_knowing(a_, i, wanted, a, b);
    best[static_cast<std::size_t>(i)] = list.entries[0];
    second_distance[static_cast<std::size_t>(i)] =
        list.count > 1 ? list.entries[1].distance : std::numeric_limits<int>::max();
    min_distance = std::min(min_distance, list.entries[0].distance);
  }
  const int paper_limit = std::max(2 * min_distance, 30);  // as match_descriptors

  for (int i = 0; i < n_a; ++i) {
    const Neighbour nearest = best[static_cast<std::size_t>(i)];
    if (nearest.distance > options_.max_distance) continue;
    // The first entry of B's list is the nearest query of that train, ties to the lower query.
    const auto is_mutual = [&] {
      return list_knowing(b_, nearest.index, 1, b, a).entries[0].index == i;
    };
    const bool passes_ratio = static_cast<double>(nearest.distance) <
                              options_.ratio * second_distance[static_cast<std::size_t>(i)];
    bool keep = false;
    switch (options_.kind) {
      case MatcherKind::mutual: keep = is_mutual(); break;
      case MatcherKind::ratio: keep = passes_ratio; break;
      case MatcherKind::paper: keep = nearest.distance <= paper_limit; break;
      case MatcherKind::mutual_ratio: keep = passes_ratio && is_mutual(); break;
      case MatcherKind::guided: break;  // refused by require_sweepable
    }
    if (keep) matches.push_back({i, nearest.index, nearest.distance});
  }
  return matches;
}

}  // namespace aief
