// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// The laws the engine relies on for a linkage (concepts/linkage.hpp), as a
/// check that returns a LawResult:
///   - Params: default Params construct; each of `invalid_params` throws
///     std::invalid_argument (and nothing else);
///   - symmetric bit for bit: link(a, b) == link(b, a);
///   - stateless: the same decisions again, in reverse order, and from a
///     fresh instance and a copy;
///   - the compact payload (when present) decides as the Sample operator,
///     both ways, and restore_ray gives back direction and range bit for bit;
///   - link_many (when present) gives the pairwise decisions, writes 0 or 1
///     and nothing past `count`;
///   - not vacuous: the pairs contain linked and split ones;
///   - `must_link` / `must_split` pairs decide so at the default parameters.
/// The pairs: random candidates (candidate_pairs.hpp), realistic ones from
/// simulated Livox scans (livox_streams.hpp), and for each parameter set the
/// pairs on its decision boundary found by bisection.
///
/// \code
/// streamclust::testing::LinkageLawOptions<MyLinkage> options;
/// options.invalid_params = {{-1.0f}, {std::nanf("")}};
/// const streamclust::testing::LawResult r = streamclust::testing::check_linkage<MyLinkage>(options);
/// \endcode
/// Cost: O(parameter sets x pairs) predicate calls (about 0.1 s for the
/// defaults in an optimised build). Not thread-safe (one call per thread).

#include <streamclust/concepts/linkage.hpp>
#include <streamclust/testing/candidate_pairs.hpp>
#include <streamclust/testing/law_result.hpp>
#include <streamclust/testing/livox_streams.hpp>
#include <streamclust/testing/type_name.hpp>

#include <cstddef>
#include <cstdint>
#include <exception>
#include <optional>
#include <random>
#include <sstream>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace streamclust::testing {

template <class L>
struct LinkageLawOptions {
  std::vector<typename L::Params> params;          ///< parameter sets to test; empty: the defaults
  std::vector<typename L::Params> invalid_params;  ///< each must throw std::invalid_argument
  std::vector<std::pair<Sample, Sample>> must_link;   ///< linked at the default parameters
  std::vector<std::pair<Sample, Sample>> must_split;  ///< not linked at the default parameters
  std::vector<std::pair<Sample, Sample>> pairs;       ///< more candidate pairs of your own
  std::size_t random_pairs = 20000;   ///< random_candidate_pairs(seed, n)
  std::size_t livox_pairs = 4000;     ///< livox_candidate_pairs(n, seed)
  std::size_t boundary_pairs = 2000;  ///< per parameter set, at most
  std::uint32_t seed = 2024;
};

namespace internal {

template <class L>
std::string linkage_context(std::size_t params_index) {
  return "linkage " + type_name<L>() + ", parameter set " + std::to_string(params_index);
}

inline std::string pair_text(const Sample& a, const Sample& b) {
  return "a = " + describe(a) + ", b = " + describe(b);
}

/// The laws on one parameter set; "" when they hold.
template <class L>
std::string linkage_laws_on(const L& link, const typename L::Params& params,
                            const std::vector<std::pair<Sample, Sample>>& pairs, std::size_t& linked,
                            std::mt19937& rng) {
  std::ostringstream os;
  std::vector<std::uint8_t> decision(pairs.size());
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    const auto& [a, b] = pairs[i];
    const bool ab = link(a, b);
    const bool ba = link(b, a);
    if (ab != ba) {
      os << "not symmetric: link(a, b) = " << ab << " but link(b, a) = " << ba << " for " << pair_text(a, b);
      return os.str();
    }
    decision[i] = ab ? 1 : 0;
    linked += ab ? 1u : 0u;
  }
  // stateless: again in reverse order, then from a fresh instance and a copy
  for (std::size_t i = pairs.size(); i-- > 0;) {
    if (link(pairs[i].first, pairs[i].second) != (decision[i] != 0)) {
      os << "not deterministic: link(a, b) changed from " << int{decision[i]}
         << " when asked again (the pairs in reverse order) for " << pair_text(pairs[i].first, pairs[i].second)
         << "; a linkage must be stateless";
      return os.str();
    }
  }
  const L fresh{params};
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    const bool f = fresh(pairs[i].first, pairs[i].second);
    bool c = f;
    if constexpr (std::is_copy_constructible_v<L>) {
      const L copy = link;
      c = copy(pairs[i].second, pairs[i].first);
    }
    if (f != (decision[i] != 0) || c != (decision[i] != 0)) {
      os << "not deterministic: a fresh instance decides " << f << " and a copy " << c << " where the first decided "
         << int{decision[i]} << " for " << pair_text(pairs[i].first, pairs[i].second);
      return os.str();
    }
  }
  if constexpr (has_linkage_payload_v<L>) {
    using Payload = linkage_payload_t<L>;
    std::vector<Payload> ring;
    ring.reserve(pairs.size());
    for (std::size_t i = 0; i < pairs.size(); ++i) {
      const auto& [a, b] = pairs[i];
      const Payload pa = link.make_payload(a);
      const Payload pb = link.make_payload(b);
      const bool ab = link(pa, pb);
      const bool ba = link(pb, pa);
      if (ab != (decision[i] != 0) || ba != (decision[i] != 0)) {
        os << "the payload operator decides link(pa, pb) = " << ab << ", link(pb, pa) = " << ba
           << " where the Sample operator decides " << int{decision[i]} << " for " << pair_text(a, b)
           << " (define the Sample operator as the payload operator on make_payload of both)";
        return os.str();
      }
      if constexpr (has_linkage_ray_payload_v<L>) {
        Sample restored;
        L::restore_ray(pa, restored);
        if (!(restored.direction.array() == a.direction.array()).all() || !(restored.range == a.range)) {
          os << "restore_ray does not give back the direction and range bit for bit for a = " << describe(a)
             << ": restored " << describe(restored);
          return os.str();
        }
      }
      ring.push_back(pb);
    }
    if constexpr (has_linkage_link_many_v<L>) {
      // each pair's first Sample against 1-40 candidates of the ring in random
      // slots (its own partner first); a guard byte after `count` stays
      std::vector<std::uint32_t> slots;
      std::vector<std::uint8_t> many;
      for (std::size_t i = 0; i < pairs.size() && !ring.empty(); i += 7) {
        const Payload a = link.make_payload(pairs[i].first);
        const std::size_t count = 1 + rng() % 40;
        slots.resize(count);
        for (auto& slot : slots) slot = static_cast<std::uint32_t>(rng() % ring.size());
        slots[0] = static_cast<std::uint32_t>(i);
        many.assign(count + 1, 7);
        link.link_many(a, ring.data(), slots.data(), count, many.data());
        for (std::size_t k = 0; k < count; ++k) {
          const std::uint8_t expected = link(a, ring[slots[k]]) ? 1 : 0;
          if (many[k] != expected) {
            os << "link_many wrote " << int{many[k]} << " for candidate " << k << " of " << count
               << " where the pairwise payload operator decides " << int{expected} << " for "
               << pair_text(pairs[i].first, pairs[slots[k]].second);
            return os.str();
          }
        }
        if (many[count] != 7) {
          os << "link_many wrote past `count` (" << count << " candidates)";
          return os.str();
        }
      }
    }
  }
  return {};
}

}  // namespace internal

/// Every law of a linkage (see the file comment); the first failure.
template <class L>
LawResult check_linkage(const LinkageLawOptions<L>& options = {}) {
  static_assert(is_linkage_policy_v<L>, "check_linkage: L does not model the linkage concept (concepts/linkage.hpp)");
  const std::string name = "linkage " + type_name<L>();
  // Params: the defaults construct, the invalid ones throw std::invalid_argument
  if (const std::string failure = internal::default_params_failure<L>(name); !failure.empty())
    return law_failed(failure);
  for (std::size_t k = 0; k < options.invalid_params.size(); ++k) {
    try {
      const L bad{options.invalid_params[k]};
      (void)bad;
      return law_failed(name + ": invalid_params[" + std::to_string(k) +
                        "] was accepted; the constructor must throw std::invalid_argument naming the parameter");
    } catch (const std::invalid_argument&) {
    } catch (const std::exception& e) {
      return law_failed(name + ": invalid_params[" + std::to_string(k) +
                        "] threw an exception other than std::invalid_argument: " + e.what());
    }
  }
  // known decisions at the defaults, both ways
  const L defaults{typename L::Params{}};
  for (const auto& [a, b] : options.must_link) {
    if (!defaults(a, b) || !defaults(b, a))
      return law_failed(name + ": a must_link pair is not linked at the default parameters: " +
                        internal::pair_text(a, b));
  }
  for (const auto& [a, b] : options.must_split) {
    if (defaults(a, b) || defaults(b, a))
      return law_failed(name + ": a must_split pair is linked at the default parameters: " + internal::pair_text(a, b));
  }
  std::vector<std::pair<Sample, Sample>> pairs = random_candidate_pairs(options.seed, options.random_pairs);
  if (options.livox_pairs > 0) {
    for (auto& p : livox_candidate_pairs(options.livox_pairs, options.seed)) pairs.push_back(p);
  }
  pairs.insert(pairs.end(), options.pairs.begin(), options.pairs.end());
  const std::vector<typename L::Params> sets = internal::parameter_sets(options.params);
  std::mt19937 rng(options.seed + 1);
  std::size_t linked = 0;
  std::size_t decided = 0;
  for (std::size_t k = 0; k < sets.size(); ++k) {
    std::optional<L> link;
    if (const std::string thrown = internal::construct_from(sets[k], link); !thrown.empty())
      return law_failed(internal::linkage_context<L>(k) + ": the parameters do not construct: " + thrown);
    std::vector<std::pair<Sample, Sample>> all = pairs;
    for (auto& p : boundary_pairs(*link, pairs, options.boundary_pairs)) all.push_back(p);
    const std::string failure = internal::linkage_laws_on(*link, sets[k], all, linked, rng);
    if (!failure.empty()) return law_failed(internal::linkage_context<L>(k) + ": " + failure);
    decided += all.size();
  }
  if (linked == 0 || linked == decided) {
    return law_failed(name + ": every one of the " + std::to_string(decided) + " candidate pairs was " +
                      (linked == 0 ? "split" : "linked") +
                      ", so the laws prove little: give parameter sets or pairs on both sides of the threshold");
  }
  return law_passed(name + ": " + std::to_string(sets.size()) + " parameter sets, " + std::to_string(decided) +
                    " pairs, " + std::to_string(linked) + " linked");
}

}  // namespace streamclust::testing
