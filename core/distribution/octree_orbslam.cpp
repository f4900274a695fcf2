#include "core/distribution/octree_orbslam.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <list>
#include <utility>

namespace aief {

namespace {

struct OctreeNode {
  int ul_x = 0, ul_y = 0, ur_x = 0, br_y = 0;  // UL, UR.x, BR.y of ExtractorNode
  std::vector<std::int32_t> keys;
  bool no_more = false;
  std::list<OctreeNode>::iterator self;
};

using NodeList = std::list<OctreeNode>;

// ExtractorNode::DivideNode: halves rounded up (ceil of a float half), a key goes left when
// x < the split, up when y < the split; keys keep their order.
void divide(const OctreeNode& node, const std::vector<Candidate>& candidates, int min_x, int min_y,
            OctreeNode children[4]) {
  const int half_x = static_cast<int>(std::ceil(static_cast<float>(node.ur_x - node.ul_x) / 2));
  const int half_y = static_cast<int>(std::ceil(static_cast<float>(node.br_y - node.ul_y) / 2));
  const int split_x = node.ul_x + half_x, split_y = node.ul_y + half_y;
  children[0] = {node.ul_x, node.ul_y, split_x, split_y, {}, false, {}};
  children[1] = {split_x, node.ul_y, node.ur_x, split_y, {}, false, {}};
  children[2] = {node.ul_x, split_y, split_x, node.br_y, {}, false, {}};
  children[3] = {split_x, split_y, node.ur_x, node.br_y, {}, false, {}};
  for (std::int32_t key : node.keys) {
    const Candidate& c = candidates[static_cast<std::size_t>(key)];
    const int x = c.x - min_x, y = c.y - min_y;
    const int q = (x < split_x ? 0 : 1) + (y < split_y ? 0 : 2);
    children[q].keys.push_back(key);
  }
  for (int q = 0; q < 4; ++q) children[q].no_more = children[q].keys.size() == 1;
}

// ORB-SLAM3's compareNodes: by size, then by the left edge; otherwise "not less".
bool compare_nodes(const std::pair<int, OctreeNode*>& a, const std::pair<int, OctreeNode*>& b) {
  if (a.first < b.first) return true;
  if (a.first > b.first) return false;
  return a.second->ul_x < b.second->ul_x;
}

}  // namespace

void distribute_octree_orbslam(const std::vector<Candidate>& candidates, int min_x, int max_x,
                               int min_y, int max_y, int n_wanted,
                               std::vector<std::int32_t>& selected) {
  if (candidates.empty() || n_wanted <= 0) return;
  const int initial = static_cast<int>(
      std::round(static_cast<float>(max_x - min_x) / static_cast<float>(max_y - min_y)));
  if (initial <= 0) return;  // ORB-SLAM divides by zero here (a portrait level)
  const float node_width = static_cast<float>(max_x - min_x) / static_cast<float>(initial);

  NodeList nodes;
  std::vector<OctreeNode*> initial_nodes(static_cast<std::size_t>(initial));
  for (int i = 0; i < initial; ++i) {
    OctreeNode node;
    node.ul_x = static_cast<int>(node_width * static_cast<float>(i));
    node.ur_x = static_cast<int>(node_width * static_cast<float>(i + 1));
    node.ul_y = 0;
    node.br_y = max_y - min_y;
    nodes.push_back(std::move(node));
    initial_nodes[static_cast<std::size_t>(i)] = &nodes.back();
  }
  for (std::size_t k = 0; k < candidates.size(); ++k) {
    const float x = static_cast<float>(candidates[k].x - min_x);
    const int index = std::min(initial - 1, static_cast<int>(x / node_width));
    initial_nodes[static_cast<std::size_t>(index)]->keys.push_back(static_cast<std::int32_t>(k));
  }
  for (auto it = nodes.begin(); it != nodes.end();) {
    if (it->keys.size() == 1) {
      it->no_more = true;
      ++it;
    } else if (it->keys.empty()) {
      it = nodes.erase(it);
    } else {
      ++it;
    }
  }

  std::vector<std::pair<int, OctreeNode*>> to_expand;
  // Pushes the non-empty children to the front; those with more than one key also to to_expand.
  const auto push_children = [&](OctreeNode children[4], int* expand_count) {
    for (int q = 0; q < 4; ++q) {
      if (children[q].keys.empty()) continue;
      nodes.push_front(std::move(children[q]));
      if (nodes.front().keys.size() > 1) {
        if (expand_count) ++*expand_count;
        to_expand.emplace_back(static_cast<int>(nodes.front().keys.size()), &nodes.front());
        nodes.front().self = nodes.begin();
      }
    }
  };

  bool finished = false;
  while (!finished) {
    const std::size_t previous_size = nodes.size();
    int expand_count = 0;
    to_expand.clear();
    for (auto it = nodes.begin(); it != nodes.end();) {
      if (it->no_more) {
        ++it;
        continue;
      }
      OctreeNode children[4];
      divide(*it, candidates, min_x, min_y, children);
      push_children(children, &expand_count);
      it = nodes.erase(it);
    }
    if (static_cast<int>(nodes.size()) >= n_wanted || nodes.size() == previous_size) {
      finished = true;
    } else if (static_cast<int>(nodes.size()) + expand_count * 3 > n_wanted) {
      while (!finished) {
        const std::size_t size_before = nodes.size();
        std::vector<std::pair<int, OctreeNode*>> previous = to_expand;
        to_expand.clear();
        std::sort(previous.begin(), previous.end(), compare_nodes);
        for (auto j = static_cast<std::ptrdiff_t>(previous.size()) - 1; j >= 0; --j) {
          OctreeNode* node = previous[static_cast<std::size_t>(j)].second;
          OctreeNode children[4];
          divide(*node, candidates, min_x, min_y, children);
          push_children(children, nullptr);
          nodes.erase(node->self);
          if (static_cast<int>(nodes.size()) >= n_wanted) break;
        }
        if (static_cast<int>(nodes.size()) >= n_wanted || nodes.size() == size_before)
          finished = true;
      }
    }
  }

  for (const OctreeNode& node : nodes) {
    std::int32_t best = node.keys.front();
    for (std::size_t k = 1; k < node.keys.size(); ++k)
      if (candidates[static_cast<std::size_t>(node.keys[k])].score >
          candidates[static_cast<std::size_t>(best)].score)
        best = node.keys[k];
    selected.push_back(best);
  }
}

}  // namespace aief
