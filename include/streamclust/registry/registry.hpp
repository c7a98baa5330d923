// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// PolicyRegistry<Policies...>: the policies a tool offers, each registered
/// by its PolicyDescriptor (registry/descriptor.hpp). From this one list
/// come the command-line choices (--linkage angular|euclidean|...), the
/// parsing of every policy option into its policy's Params, the help text,
/// the options' names for JSON and Python, and the run-time dispatch from a
/// chosen name to the compiled policy type (with_policy). Stateless: every
/// member is static; Values holds the parsed parameters.
///
///     using Tools = registry::PolicyRegistry<AngularLinkage, EuclideanLinkage, my::GatedLinkage>;
///     Tools::Values values;                                  // every Params at its default
///     Tools::parse_option("--theta", [] { return std::string("30"); }, values);
///     Tools::with_policy<registry::Slot::linkage>("angular", [&](auto tag) {
///       using Linkage = typename decltype(tag)::type;        // AngularLinkage
///       return run<Linkage>(values.get<Linkage>());
///     });

#include <streamclust/registry/descriptor.hpp>
#include <streamclust/registry/option.hpp>
#include <streamclust/registry/values.hpp>

#include <cstddef>
#include <string>
#include <tuple>
#include <type_traits>
#include <vector>

namespace streamclust::registry {

/// A policy type as a value, for generic lambdas.
template <class T>
struct TypeTag {
  using type = T;
};

/// One registered option, for listings (help, Python keywords, tests).
struct OptionInfo {
  Slot slot;
  std::string policy;   ///< the policy's name ("angular")
  std::string name;     ///< "--theta"
  std::string metavar;  ///< "DEG"
  std::string key;      ///< "theta_deg"
  std::string keyword;  ///< "theta"
  std::string help;
  std::string default_text;  ///< "10"
  bool integral = false;     ///< a whole number
};

/// One registered option's value in a Values (reports).
struct OptionValue {
  std::string key;  ///< "theta_deg"
  double value = 0.0;
  bool integral = false;
};

template <class... Policies>
class PolicyRegistry {
  static_assert(sizeof...(Policies) > 0, "STREAMCLUST_REGISTRY_EMPTY: register at least one policy");
  static_assert((is_registered<Policies>::value && ...),
                "STREAMCLUST_POLICY_NOT_REGISTERED: specialise registry::PolicyDescriptor<Policy> "
                "(slot, name, summary, options()) for every policy of the registry");

  template <class P, class First, class... Rest>
  static constexpr std::size_t index_of() {
    if constexpr (std::is_same_v<P, First>) {
      return 0;
    } else {
      static_assert(sizeof...(Rest) > 0, "STREAMCLUST_POLICY_NOT_IN_REGISTRY: the policy is not in this registry");
      return 1 + index_of<P, Rest...>();
    }
  }

 public:
  /// The parameters of every registered policy (one Params each, at their
  /// defaults until options or presets set them). Copyable.
  class Values {
   public:
    template <class P>
    typename P::Params& get() {
      return std::get<index_of<P, Policies...>()>(params_);
    }
    template <class P>
    const typename P::Params& get() const {
      return std::get<index_of<P, Policies...>()>(params_);
    }

   private:
    std::tuple<typename Policies::Params...> params_;
  };

  /// Calls `f(TypeTag<P>{})` for every registered policy, in order.
  template <class F>
  static void for_each(F&& f) {
    (f(TypeTag<Policies>{}), ...);
  }

  /// The names of the policies of `slot`, in registration order.
  static std::vector<std::string> names(Slot slot) {
    std::vector<std::string> out;
    for_each([&](auto tag) {
      using D = PolicyDescriptor<typename decltype(tag)::type>;
      if (D::slot == slot) out.emplace_back(D::name);
    });
    return out;
  }

  /// The first registered policy of `slot`: the default choice.
  static std::string default_name(Slot slot) {
    const auto all = names(slot);
    return all.empty() ? std::string() : all.front();
  }

  /// `value` when it names a policy of `slot`; otherwise a UsageError
  /// "--linkage: expected angular|euclidean|range-adaptive, got 'x'".
  static std::string choose(Slot slot, const std::string& value) {
    std::string list;
    for (const std::string& n : names(slot)) {
      if (n == value) return value;
      if (!list.empty()) list += '|';
      list += n;
    }
    throw UsageError(std::string(slot_option(slot)) + ": expected " + list + ", got '" + value + "'");
  }

  /// Every option of every policy, in registration order (an option two
  /// policies share is listed once per policy).
  static std::vector<OptionInfo> options() {
    std::vector<OptionInfo> out;
    for_each([&](auto tag) {
      using D = PolicyDescriptor<typename decltype(tag)::type>;
      for (const auto& o : D::options()) {
        out.push_back({D::slot, D::name, o.name, o.metavar, o.key, o.keyword(), o.help, o.default_text(), o.integral});
      }
    });
    return out;
  }

  /// The value of every registered option in `values`, in registration order
  /// (an option two policies share: the first policy's).
  static std::vector<OptionValue> values_of(const Values& values) {
    std::vector<OptionValue> out;
    for_each([&](auto tag) {
      using P = typename decltype(tag)::type;
      for (const auto& o : PolicyDescriptor<P>::options()) {
        bool seen = false;
        for (const OptionValue& v : out) seen = seen || v.key == o.key;
        if (!seen) out.push_back({o.key, o.value(values.template get<P>()), o.integral});
      }
    });
    return out;
  }

  /// True when `option` is a registered policy option.
  static bool has_option(const std::string& option) {
    bool found = false;
    for_each([&](auto tag) {
      for (const auto& o : PolicyDescriptor<typename decltype(tag)::type>::options()) found = found || o.name == option;
    });
    return found;
  }

  /// When `option` is a registered option, reads its value (`value()`, called
  /// once: it may move an argument cursor) into the Params of every policy
  /// that declares it and returns true; otherwise returns false and calls
  /// nothing. Throws UsageError for a bad value.
  template <class ValueFn>
  static bool parse_option(const std::string& option, ValueFn&& value, Values& values) {
    if (!has_option(option)) return false;
    const std::string text = value();
    for_each([&](auto tag) {
      using P = typename decltype(tag)::type;
      for (const auto& o : PolicyDescriptor<P>::options()) {
        if (o.name == option) o.read(values.template get<P>(), text);
      }
    });
    return true;
  }

  /// Calls `f(TypeTag<P>{})` with the policy of slot `S` named `name` and
  /// returns its result (the same type for every policy of the slot). Only
  /// the policies of slot `S` are instantiated. Throws UsageError for a name
  /// no policy of the slot has.
  template <Slot S, class F>
  static decltype(auto) with_policy(const std::string& name, F&& f) {
    return dispatch<S, F, Policies...>(name, f);
  }

  /// The policy of `slot` named `name` described with its values in `values`
  /// (registry/descriptor.hpp: describe).
  static std::string describe(Slot slot, const std::string& name, const Values& values) {
    std::string text;
    for_each([&](auto tag) {
      using P = typename decltype(tag)::type;
      using D = PolicyDescriptor<P>;
      if (D::slot == slot && name == D::name) text = registry::describe<P>(values.template get<P>());
    });
    return text;
  }

  /// The help of `slot`: its choice with each policy's summary, then every
  /// option of its policies with its default, e.g.
  ///
  ///       --linkage angular|euclidean|range-adaptive   (default angular)
  ///             angular         link when the angle between the rays exceeds --theta
  ///       --theta DEG (default 10)          angular: threshold on the angle [deg]
  ///
  /// `default_choice`: the tool's default (empty: the first registered);
  /// `column`: where the option help starts (the tool's help uses 36).
  static std::string help(Slot slot, const std::string& default_choice = {}, std::size_t column = 36) {
    return help(slot, default_choice, Values{}, column);
  }
  /// As above, each option's default read from `defaults` (a tool whose
  /// defaults are a preset's).
  static std::string help(Slot slot, const std::string& default_choice, const Values& defaults,
                          std::size_t column = 36) {
    std::string text;
    const auto all = names(slot);
    if (all.empty()) return text;
    std::size_t width = 0;
    for (const std::string& n : all) width = n.size() > width ? n.size() : width;
    if (*slot_option(slot) != '\0') {
      std::string list;
      for (const std::string& n : all) list += (list.empty() ? "" : "|") + n;
      text += "  " + std::string(slot_option(slot)) + " " + list + "   (default " +
              (default_choice.empty() ? all.front() : default_choice) + ")\n";
    }
    for_each([&](auto tag) {
      using D = PolicyDescriptor<typename decltype(tag)::type>;
      if (D::slot != slot) return;
      const std::string n = D::name;
      text += "        " + n + std::string(width + 2 - n.size(), ' ') + D::summary + "\n";
    });
    for_each([&](auto tag) {
      using P = typename decltype(tag)::type;
      using D = PolicyDescriptor<P>;
      if (D::slot != slot) return;
      for (const auto& o : D::options()) {
        std::string left =
            "  " + o.name + " " + o.metavar + " (default " + o.format_number(o.value(defaults.template get<P>())) + ")";
        left += left.size() + 1 < column ? std::string(column - left.size(), ' ') : "\n" + std::string(column, ' ');
        text += left + D::name + ": " + o.help + "\n";
      }
    });
    return text;
  }

 private:
  template <Slot S, class F, class P, class... Rest>
  static decltype(auto) dispatch(const std::string& name, F& f) {
    constexpr bool more_of_slot = ((PolicyDescriptor<Rest>::slot == S) || ... || false);
    if constexpr (PolicyDescriptor<P>::slot == S) {
      if constexpr (more_of_slot) {
        if (name != PolicyDescriptor<P>::name) return dispatch<S, F, Rest...>(name, f);
      } else {
        if (name != PolicyDescriptor<P>::name) choose(S, name);  // throws: no such policy
      }
      return f(TypeTag<P>{});
    } else {
      static_assert(more_of_slot, "STREAMCLUST_REGISTRY_SLOT_EMPTY: no policy of this slot is registered");
      return dispatch<S, F, Rest...>(name, f);
    }
  }
};

}  // namespace streamclust::registry
