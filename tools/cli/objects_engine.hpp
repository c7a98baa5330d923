// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// The objects method of `streamclust evaluate --objects` with any
/// registered linkage: a StreamClusterer of the objects preset
/// (ObjectsConfig) whose linkage slot is the chosen policy, every other slot
/// and parameter the preset's (rebind_params), behind one virtual interface
/// (a call per stretch of records or per retrieval, never per point).
/// make_objects_engine picks the linkage by its registered name
/// (cli::ToolRegistry); the engine of each linkage is defined in
/// objects_engine_impl.hpp and instantiated in the tool's generated
/// translation unit of the spherical projection and that linkage
/// (STREAMCLUST_INSTANTIATE_OBJECTS_ENGINE), so a researcher's linkage added
/// with streamclust_add_tool gets one too.

#include "cli/options.hpp"

#include <streamclust/clustering.hpp>
#include <streamclust/io/record.hpp>
#include <streamclust/objects_presets.hpp>
#include <streamclust/tracking/object_boxes.hpp>

#include <cstddef>
#include <memory>
#include <string>
#include <type_traits>
#include <vector>

namespace streamclust::cli {

/// The objects engine of one evaluation (and, with verification, the batch
/// clusterer of the same configuration). Not thread-safe.
class ObjectsEngine {
 public:
  virtual ~ObjectsEngine() = default;
  /// Inserts records [first, last) in order, timed. O(last - first) engine work.
  virtual void feed(const std::vector<io::Record>& records, std::size_t first, std::size_t last) = 0;
  /// Advances to stream time `time` [s] and retrieves, timed; the reference
  /// stays valid until the next call.
  virtual const Clustering& retrieve(double time) = 0;
  /// The work since the previous call [ms].
  virtual double take_cost() = 0;
  virtual bool calibrating() const = 0;
  /// The objects of the last retrieval with an oriented box and an
  /// in-window velocity (tracking::ObjectBoxes, the engine's world frame);
  /// none while calibrating. The reference stays valid until the next call.
  /// O(window points).
  virtual const std::vector<tracking::ObjectObservation>& boxes() = 0;
  /// The last retrieval against the batch clusterer on its object points
  /// (records: the stream the engine was fed; `outside`: labelled points
  /// outside the scored window): "" when equal, else what differs. Only for
  /// an engine made with `verify`. O(window) batch work.
  virtual std::string verify(const std::vector<io::Record>& records, std::size_t outside) = 0;
};

/// The objects preset with `Linkage` in its linkage slot: ObjectsConfig
/// itself for the preset's own linkage (the same compiled engine as the
/// library's preset).
template <class Linkage>
struct ObjectsConfigWith : ObjectsConfig {
  using linkage = Linkage;
};
template <class Linkage>
using ObjectsEngineConfig =
    std::conditional_t<std::is_same_v<Linkage, ObjectsConfig::linkage>, ObjectsConfig, ObjectsConfigWith<Linkage>>;

/// The registered name of the objects preset's linkage ("range-adaptive").
inline const char* objects_preset_linkage() { return registry::PolicyDescriptor<ObjectsConfig::linkage>::name; }

/// Every registered policy's Params at its default, the objects preset's
/// linkage at the preset's values: the start of `evaluate --objects`'s
/// linkage options.
inline ToolRegistry::Values objects_linkage_values() {
  ToolRegistry::Values values;
  values.get<ObjectsConfig::linkage>() = objects_params(SphericalProjection::Params{}).linkage;
  return values;
}

/// The engine of `Linkage` with `preset`'s other slots and parameters
/// (objects_engine_impl.hpp). Throws UsageError for parameters the linkage
/// rejects.
template <class Linkage>
std::unique_ptr<ObjectsEngine> make_objects_engine_for(const ClustererParams<ObjectsConfig>& preset,
                                                       const typename Linkage::Params& linkage, bool verify);

/// The engine of the registered linkage `linkage` with its Params in
/// `values`, every other slot and parameter `preset`'s; with `verify`, a
/// batch clusterer too. Throws UsageError for an unknown name or rejected
/// parameters.
inline std::unique_ptr<ObjectsEngine> make_objects_engine(const std::string& linkage,
                                                          const ToolRegistry::Values& values,
                                                          const ClustererParams<ObjectsConfig>& preset, bool verify) {
  return ToolRegistry::with_policy<Slot::linkage>(linkage, [&](auto tag) {
    using Linkage = typename decltype(tag)::type;
    return make_objects_engine_for<Linkage>(preset, values.template get<Linkage>(), verify);
  });
}

}  // namespace streamclust::cli
