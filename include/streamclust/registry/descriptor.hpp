// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// How a policy is registered: a specialisation of PolicyDescriptor beside
/// the policy (or in the user's tool header: the policy itself is not
/// edited). It names the policy's slot, its name on the command line, a
/// one-line summary and its options (registry/option.hpp):
///
///     template <>
///     struct streamclust::registry::PolicyDescriptor<my::IntensityGatedLinkage> {
///       static constexpr Slot slot = Slot::linkage;
///       static constexpr const char* name = "intensity-gated";
///       static constexpr const char* summary = "Euclidean within --distance and --intensity-gap";
///       static std::vector<Option<my::IntensityGatedLinkage::Params>> options() {
///         using P = my::IntensityGatedLinkage::Params;
///         return {option("--intensity-gap", &P::max_gap, "I", ValueKind::positive,
///                        "largest intensity difference of a link", "intensity_gap")};
///       }
///     };
///
/// Optional: `static std::string describe(const Params&)`, the policy and its
/// values in one phrase for the tool's summaries (default: the name and each
/// option's value).

#include <streamclust/registry/option.hpp>

#include <string>
#include <type_traits>
#include <vector>

namespace streamclust::registry {

/// The configuration slots a registered policy can fill.
enum class Slot { projection, spatial_index, linkage, window, connectivity };

/// The option that chooses a policy of `slot` ("--linkage"); empty for the
/// window, which the tool chooses by the option given (--window-time or
/// --window-count).
inline const char* slot_option(Slot slot) {
  switch (slot) {
    case Slot::projection: return "--projection";
    case Slot::spatial_index: return "--index";
    case Slot::linkage: return "--linkage";
    case Slot::connectivity: return "--connectivity";
    case Slot::window: break;
  }
  return "";
}

/// The registration of `Policy`: specialise it (see the file comment). Not
/// defined for an unregistered policy.
template <class Policy>
struct PolicyDescriptor;

/// True when PolicyDescriptor<Policy> is specialised.
template <class Policy, class = void>
struct is_registered : std::false_type {};
template <class Policy>
struct is_registered<Policy, std::void_t<decltype(PolicyDescriptor<Policy>::name)>> : std::true_type {};

/// True when the descriptor of `Policy` has its own describe().
template <class Policy, class = void>
struct has_describe : std::false_type {};
template <class Policy>
struct has_describe<Policy, std::void_t<decltype(PolicyDescriptor<Policy>::describe(
                                std::declval<const typename Policy::Params&>()))>> : std::true_type {};

/// The policy and its values in one phrase: the descriptor's describe(), or
/// "NAME KEY VALUE ..." from its options.
template <class Policy>
std::string describe(const typename Policy::Params& params) {
  using D = PolicyDescriptor<Policy>;
  if constexpr (has_describe<Policy>::value) {
    return D::describe(params);
  } else {
    std::string text = D::name;
    for (const auto& o : D::options()) text += " " + o.key + " " + o.format_number(o.value(params));
    return text;
  }
}

}  // namespace streamclust::registry
