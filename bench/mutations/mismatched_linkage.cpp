// SPDX-License-Identifier: MIT
// A planted mutation for the benchmark kit's path check: a Euclidean
// linkage whose payload path uses a 10 % larger threshold than its Sample
// path. The kit must refuse to time it (an error naming both counts) and
// STREAMCLUST_BENCHMARK_MAIN() must exit with 1 (CTest bench_kit_mutation).

#include <streamclust/benchmarking/linkage_benchmarks.hpp>
#include <streamclust/benchmarking/main.hpp>
#include <streamclust/linkage/euclidean.hpp>
#include <streamclust/types.hpp>

#include <Eigen/Core>

namespace sc = streamclust;
namespace bk = streamclust::benchmarking;

namespace {

struct MismatchedLinkage {
  struct Params {
    float max_distance = 0.5f;  ///< [m]
  };
  struct Payload {
    Eigen::Vector3f position;
  };
  explicit MismatchedLinkage(const Params& params) : params_(params) {}
  static Payload make_payload(const sc::Sample& s) { return Payload{s.position}; }
  bool operator()(const sc::Sample& a, const sc::Sample& b) const {
    return (a.position - b.position).squaredNorm() <= params_.max_distance * params_.max_distance;
  }
  bool operator()(const Payload& a, const Payload& b) const {  // the planted slip: 1.1 x the threshold
    const float d = 1.1f * params_.max_distance;
    return (a.position - b.position).squaredNorm() <= d * d;
  }

 private:
  Params params_;
};

[[maybe_unused]] const bool registered = [] {
  static_assert(sc::has_linkage_payload_v<MismatchedLinkage>, "the mutation must have the payload path");
  bk::register_linkage<MismatchedLinkage>("MismatchedLinkage", {},
                                          {bk::PairSource{"mid360_office_back16", []() -> const bk::CandidatePairs& {
                                                            return bk::firing_order_candidates(
                                                                {bk::Sensor::mid360, "office"});
                                                          }}});
  return true;
}();

}  // namespace

STREAMCLUST_BENCHMARK_MAIN();
