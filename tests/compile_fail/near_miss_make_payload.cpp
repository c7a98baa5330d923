// EXPECT: STREAMCLUST_LINKAGE_CAPABILITY_INVALID: a linkage with a member named `Payload` or `make_payload`
// SPDX-License-Identifier: MIT
// A linkage whose `make_payload` is neither static nor a const member (a
// bound payload) has no compact payload: the slot check says so instead of
// leaving it on the Sample path.
#include <streamclust/presets.hpp>
#include <streamclust/stream_clusterer.hpp>

struct MemberMakePayload {
  struct Params {
    float max_distance = 0.5f;
  };
  struct Payload {
    float x, y, z;
  };
  explicit MemberMakePayload(const Params& p) : max_distance(p.max_distance) {}
  Payload make_payload(const streamclust::Sample& s) {  // neither static nor const: a near miss
    return Payload{s.position.x(), s.position.y(), s.position.z()};
  }
  bool operator()(const Payload& a, const Payload& b) const {
    const float dx = a.x - b.x, dy = a.y - b.y, dz = a.z - b.z;
    return dx * dx + dy * dy + dz * dz <= max_distance * max_distance;
  }
  bool operator()(const streamclust::Sample& a, const streamclust::Sample& b) const {
    MemberMakePayload self = *this;
    return (*this)(self.make_payload(a), self.make_payload(b));
  }
  float max_distance;
};

struct Cfg : streamclust::CArcConfig {
  using linkage = MemberMakePayload;
};

void instantiate() {
  streamclust::StreamClusterer<Cfg> c;
  (void)c;
}
