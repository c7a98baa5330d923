// SPDX-License-Identifier: MIT
// The kit's linkage laws for UprightLinkage; the objects preset with it stays exact.
#define DOCTEST_CONFIG_IMPLEMENT_WITH_MAIN
#include "upright_linkage.hpp"

#include <streamclust/streamclust.hpp>
#include <streamclust/testing/doctest.hpp>
#include <streamclust/testing/testing.hpp>

namespace kit = streamclust::testing;
using upright::UprightLinkage;

struct UprightObjects : streamclust::ObjectsConfig {
  using linkage = UprightLinkage;
};

streamclust::Sample at(const Eigen::Vector3f& p) { return streamclust::make_sample(p, p.norm(), 0.0f, 0.0); }

TEST_CASE("UprightLinkage keeps the linkage laws") {
  kit::LinkageLawOptions<UprightLinkage> options;
  options.params = {{}, {0.1f, 0.0f, 1.0f}, {0.3f, 0.02f, 5.0f}};
  options.invalid_params = {{0.0f, 0.05f, 2.0f}, {0.2f, -0.1f, 2.0f}, {0.2f, 0.05f, 0.5f}};
  // 5 m away the radius is 0.4 m (the floor): 0.45 m apart vertically links, horizontally does not.
  options.must_link = {{at({5.0f, 0.0f, 0.0f}), at({5.0f, 0.0f, 0.45f})}};
  options.must_split = {{at({5.0f, 0.0f, 0.0f}), at({5.0f, 0.45f, 0.0f})}};
  STREAMCLUST_CHECK_LAW(kit::check_linkage<UprightLinkage>(options));
}

TEST_CASE("the objects preset with UprightLinkage: continuous = batch") {
  auto params = streamclust::rebind_params<UprightObjects>(streamclust::objects_mid360_params(),
                                                           UprightLinkage::Params{});  // the rest: the preset's
  params.window.duration = 0.05;  // [s]: the kit's short streams turn the window over
  const kit::ExactnessReport report = kit::check_exactness<UprightObjects>(params);
  STREAMCLUST_CHECK_LAW(report);
  CHECK(report.comparisons > 80);
}
