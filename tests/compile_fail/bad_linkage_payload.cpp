// EXPECT: STREAMCLUST_LINKAGE_PAYLOAD_INVALID
// SPDX-License-Identifier: MIT
// A linkage declaring a compact payload wider than 32 bytes must be rejected
// where the engine starts (the payload ring is meant to be denser than the
// 40-byte Samples).
#include <streamclust/presets.hpp>
#include <streamclust/stream_clusterer.hpp>

struct WidePayloadLinkage {
  struct Params {};
  struct Payload {
    float v[9];  // 36 bytes: too wide
  };
  explicit WidePayloadLinkage(const Params&) {}
  static Payload make_payload(const streamclust::Sample& s) { return Payload{{s.range}}; }
  bool operator()(const Payload& a, const Payload& b) const { return a.v[0] == b.v[0]; }
  bool operator()(const streamclust::Sample& a, const streamclust::Sample& b) const {
    return (*this)(make_payload(a), make_payload(b));
  }
};

struct Cfg : streamclust::CArcConfig {
  using linkage = WidePayloadLinkage;
};

void instantiate() {
  streamclust::StreamClusterer<Cfg> c;
  (void)c;
}
