// EXPECT: STREAMCLUST_LINKAGE_CAPABILITY_INVALID: `restore_ray` is not the optional ray payload
// SPDX-License-Identifier: MIT
// A child of a combinator with a `restore_ray` that is not static: the
// combinator checks its children, so the near miss is named even when the
// linkage slot holds AllOf.
#include <streamclust/linkage/combinators.hpp>
#include <streamclust/presets.hpp>
#include <streamclust/stream_clusterer.hpp>

struct MemberRestoreRay : streamclust::AngularLinkage {
  using AngularLinkage::AngularLinkage;
  void restore_ray(const Payload& p, streamclust::Sample& s) const {  // not static: a near miss
    AngularLinkage::restore_ray(p, s);
  }
};

struct Cfg : streamclust::CArcConfig {
  using linkage = streamclust::AllOf<streamclust::EuclideanLinkage, MemberRestoreRay>;
};

void instantiate() {
  streamclust::StreamClusterer<Cfg> c;
  (void)c;
}
