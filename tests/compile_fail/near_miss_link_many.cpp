// EXPECT: STREAMCLUST_LINKAGE_CAPABILITY_INVALID: `link_many` is not the optional one-against-many test
// SPDX-License-Identifier: MIT
// A linkage whose `link_many` is not const is not the one-against-many
// capability: instead of running one pair at a time without a word, the
// engine's slot check names the expected signature.
#include <streamclust/linkage/range_adaptive.hpp>
#include <streamclust/presets.hpp>
#include <streamclust/stream_clusterer.hpp>

struct NonConstLinkMany : streamclust::RangeAdaptiveLinkage {
  using RangeAdaptiveLinkage::RangeAdaptiveLinkage;
  void link_many(const Payload& a, const Payload* ring, const std::uint32_t* slots, std::size_t count,
                 std::uint8_t* linked) {  // not const: a near miss
    for (std::size_t k = 0; k < count; ++k) linked[k] = (*this)(a, ring[slots[k]]) ? 1 : 0;
  }
};

struct Cfg : streamclust::CArcConfig {
  using linkage = NonConstLinkMany;
};

void instantiate() {
  streamclust::StreamClusterer<Cfg> c;
  (void)c;
}
