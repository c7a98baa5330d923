// SPDX-License-Identifier: MIT
// Smallest use of an installed streamclust: one point in, one point out.
#include <streamclust/streamclust.hpp>

int main() {
  auto c = streamclust::make_carc();
  streamclust::Point p{1.f, 2.f, 0.5f, 0.f, 0.0};
  c.insert(p);
  c.complete_calibration();  // one point never completes the adaptive grid's first window
  return c.retrieve().points.size() == 1 ? 0 : 1;
}
