// SPDX-License-Identifier: MIT
// The policy registry (streamclust/registry): a policy registered from
// outside (its descriptor beside it, the policy unedited) is chosen by name,
// its options parse into its Params with the tool's messages, appear in the
// help and dispatch to its type; and the tool's own registry: every
// registered policy and option, and every preset, is in `cluster --help` and
// `evaluate --help` and parses.

#include <doctest/doctest.h>

#include "cli/main.hpp"
#include "cli/options.hpp"

#include <streamclust/registry/registry.hpp>
#include <streamclust/registry/stock.hpp>

#include "support/cli_run.hpp"
#include "support/contains.hpp"

#include <cstdint>
#include <string>
#include <vector>

namespace sc = streamclust;
namespace reg = streamclust::registry;

namespace test_policies {

/// A researcher's linkage as the registry sees it: a type with Params
/// (the registry needs nothing else of it).
struct GatedLinkage {
  struct Params {
    float gap = 20.0f;           ///< [intensity units]
    std::uint32_t patience = 3;  ///< [points]
  };
};

}  // namespace test_policies

template <>
struct streamclust::registry::PolicyDescriptor<test_policies::GatedLinkage> {
  static constexpr Slot slot = Slot::linkage;
  static constexpr const char* name = "gated";
  static constexpr const char* summary = "link when the intensities differ by at most --gap";
  static std::vector<Option<test_policies::GatedLinkage::Params>> options() {
    using P = test_policies::GatedLinkage::Params;
    return {option("--gap", &P::gap, "I", ValueKind::positive, "largest intensity difference", "gap"),
            option("--patience", &P::patience, "N", ValueKind::count, "points to wait", "patience")
                .at_most(10, "expected 1 to 10 points")};
  }
};

namespace {

using Registry = reg::PolicyRegistry<sc::AngularLinkage, test_policies::GatedLinkage, sc::BucketGrid>;

/// The UsageError message of parsing `option value` into `values`, or "" when it parses.
std::string parse_error(const std::string& option, const std::string& value, Registry::Values& values) {
  bool registered = false;
  try {
    registered = Registry::parse_option(option, [&] { return value; }, values);
  } catch (const reg::UsageError& e) {
    return e.what();
  }
  CHECK(registered);
  return {};
}

using streamclust::test::contains;

}  // namespace

TEST_CASE("registry: a policy registered from outside is chosen, parsed, described and dispatched by name") {
  CHECK(Registry::names(reg::Slot::linkage) == std::vector<std::string>{"angular", "gated"});
  CHECK(Registry::names(reg::Slot::spatial_index) == std::vector<std::string>{"bucket"});
  CHECK(Registry::choose(reg::Slot::linkage, "gated") == "gated");
  CHECK_THROWS_WITH_AS(Registry::choose(reg::Slot::linkage, "intensity"),
                       "--linkage: expected angular|gated, got 'intensity'", reg::UsageError);

  Registry::Values values;
  CHECK(values.get<test_policies::GatedLinkage>().gap == 20.0f);
  CHECK(parse_error("--gap", "7.5", values).empty());
  CHECK(parse_error("--theta", "30", values).empty());
  CHECK(values.get<test_policies::GatedLinkage>().gap == 7.5f);
  CHECK(values.get<sc::AngularLinkage>().theta_deg == 30.0f);
  CHECK(parse_error("--gap", "-1", values) == "--gap: expected a positive number, got '-1'");
  CHECK(parse_error("--gap", "x", values) == "--gap: expected a number, got 'x'");
  CHECK(parse_error("--patience", "2.5", values) == "--patience: expected a whole number >= 1, got '2.5'");
  CHECK(parse_error("--patience", "11", values) == "--patience: expected 1 to 10 points");
  CHECK(values.get<test_policies::GatedLinkage>().patience == 3);  // unchanged by the refused values
  CHECK(values.get<test_policies::GatedLinkage>().gap == 7.5f);
  bool called = false;
  CHECK_FALSE(Registry::parse_option("--cap", [&] { called = true; return std::string("4"); }, values));
  CHECK_FALSE(called);  // an unregistered option takes no value

  const auto name_of = [](auto tag) { return std::string(reg::PolicyDescriptor<typename decltype(tag)::type>::name); };
  CHECK(Registry::with_policy<reg::Slot::linkage>("gated", name_of) == "gated");
  CHECK(Registry::with_policy<reg::Slot::linkage>("angular", name_of) == "angular");
  CHECK(Registry::with_policy<reg::Slot::spatial_index>("bucket", name_of) == "bucket");
  CHECK_THROWS_AS(Registry::with_policy<reg::Slot::linkage>("bucket", name_of), reg::UsageError);

  CHECK(Registry::describe(reg::Slot::linkage, "gated", values) == "gated gap 7.5 patience 3");
  CHECK(Registry::describe(reg::Slot::linkage, "angular", values) == "angular theta 30 deg");
  const std::string help = Registry::help(reg::Slot::linkage);
  CHECK(contains(help, "--linkage angular|gated   (default angular)"));
  CHECK(contains(help, "gated    link when the intensities differ by at most --gap"));
  CHECK(contains(help, "--gap I (default 20)"));
  CHECK(contains(help, "gated: largest intensity difference"));
  CHECK(contains(help, "--patience N (default 3)"));
  CHECK_FALSE(contains(help, "bucket"));  // another slot's policy
  // A tool whose defaults are a preset's prints those.
  const std::string preset_help = Registry::help(reg::Slot::linkage, "gated", values);
  CHECK(contains(preset_help, "(default gated)"));
  CHECK(contains(preset_help, "--gap I (default 7.5)"));
  CHECK(contains(preset_help, "--theta DEG (default 30)"));

  const auto options = Registry::options();
  REQUIRE(options.size() == 4);
  CHECK(options[2].keyword == "gap");
  CHECK(options[3].integral);
  const auto reported = Registry::values_of(values);
  REQUIRE(reported.size() == 4);
  CHECK(reported[0].key == "theta_deg");
  CHECK(reported[0].value == 30.0);
}

TEST_CASE("registry: every policy, option and preset of the tool is in its help and parses") {
  using Tool = sc::cli::ToolRegistry;
  const std::string cluster = sc::cli::cluster_help();
  const std::string evaluate = sc::cli::evaluate_help();
  for (const reg::OptionInfo& o : Tool::options()) {
    CAPTURE(o.name);
    CHECK(contains(cluster, "  " + o.name + " " + o.metavar + " (default " + o.default_text + ")"));
    if (o.slot == reg::Slot::linkage) CHECK(contains(evaluate, "  " + o.name + " " + o.metavar));
    // The default parses to itself; 3 (valid for every stock option) is what the value becomes.
    const sc::cli::ClusterOptions given = sc::cli::parse_cluster_options({"in.csv", o.name, o.default_text});
    const sc::cli::ClusterOptions three = sc::cli::parse_cluster_options({"in.csv", o.name, "3"});
    bool seen = false;
    for (const reg::OptionValue& v : Tool::values_of(three.params)) {
      if (v.key != o.key) continue;
      seen = true;
      CHECK(v.value == 3.0);
    }
    for (const reg::OptionValue& v : Tool::values_of(given.params)) {
      if (v.key == o.key) CHECK(reg::Option<int>::format_number(v.value) == o.default_text);
    }
    CHECK(seen);
    CHECK(contains(sc::test::run_cli({"cluster", "in.csv", o.name, "abc"}).err, o.name + ": expected"));
  }
  for (const reg::Slot slot : {reg::Slot::projection, reg::Slot::spatial_index, reg::Slot::linkage,
                               reg::Slot::connectivity}) {
    for (const std::string& name : Tool::names(slot)) {
      CAPTURE(name);
      CHECK(contains(cluster, "        " + name + " "));
      const sc::cli::ClusterOptions o = sc::cli::parse_cluster_options({"in.csv", reg::slot_option(slot), name});
      const std::string chosen = slot == reg::Slot::projection      ? o.projection
                                 : slot == reg::Slot::spatial_index ? o.index
                                 : slot == reg::Slot::linkage       ? o.linkage
                                                                    : o.connectivity;
      CHECK(chosen == name);
    }
  }
  for (const auto& preset : sc::cli::preset_catalogue()) {
    const std::string name(preset.first);
    CAPTURE(name);
    CHECK(contains(cluster, "        " + name + " "));
    CHECK_NOTHROW(sc::cli::parse_cluster_options({"in.csv", "--preset", name}));
  }
  for (const char* option : {"--ground", "--no-ground", "--poses FILE", "--mount ROLL,PITCH,YAW", "--sensor-height M",
                             "--ground-tolerance M", "--ground-cell M", "--max-slope DEG", "--no-ceiling"}) {
    CAPTURE(option);
    CHECK(contains(cluster, option));
  }
  // The tool's choices keep their documented messages.
  CHECK(contains(sc::test::run_cli({"cluster", "a.csv", "--linkage", "x"}).err,
                 "--linkage: expected angular|euclidean|range-adaptive|scan-adaptive, got 'x'"));
  CHECK(sc::test::run_cli({"cluster", "a.csv", "--cap", "300"}).err ==
        "streamclust: --cap: expected 1 to 255 points per cell\n");
}
