#include "core/match/ransac_support.hpp"

namespace aief::ransac {

int first_non_finite(const std::vector<Point2>& a, const std::vector<Point2>& b) {
  for (std::size_t i = 0; i < a.size(); ++i) {
    const Point2 p = a[i], q = b[i];
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(q.x) || !std::isfinite(q.y))
      return static_cast<int>(i);
  }
  return -1;
}

std::vector<int> canonical_order(const std::vector<Point2>& a, const std::vector<Point2>& b) {
  std::vector<int> order(a.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](int i, int j) {
    const Point2 &pi = a[static_cast<std::size_t>(i)], &pj = a[static_cast<std::size_t>(j)];
    const Point2 &qi = b[static_cast<std::size_t>(i)], &qj = b[static_cast<std::size_t>(j)];
    if (pi.x != pj.x) return pi.x < pj.x;
    if (pi.y != pj.y) return pi.y < pj.y;
    if (qi.x != qj.x) return qi.x < qj.x;
    if (qi.y != qj.y) return qi.y < qj.y;
    return i < j;
  });
  return order;
}

}  // namespace aief::ransac
