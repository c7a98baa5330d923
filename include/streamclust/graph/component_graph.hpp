// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// Boost.Graph adaptor of an engine's component graph: local clusters are
/// the vertices (numbered by cluster slot; recycled slots are isolated
/// vertices, test `engine.cluster_alive(v)`), bridges are the undirected
/// edges. Models VertexListGraph and IncidenceGraph with an identity
/// vertex_index map. Meaningful after `retrieve()` (pending clusters are
/// validated there). A view: valid until the engine is next modified.
///
/// \code
/// auto g = streamclust::component_graph(engine);
/// std::vector<int> component(boost::num_vertices(g));
/// boost::connected_components(g, component.data());
/// \endcode

#include <streamclust/graph/point_graph.hpp>

namespace streamclust {

template <class Engine>
class ComponentGraph {
 public:
  explicit ComponentGraph(const Engine& engine) : engine_(&engine) {}
  const Engine& engine() const { return *engine_; }

  /// Out-edges of one cluster: one per bridge.
  class OutEdgeIterator
      : public boost::iterator_facade<OutEdgeIterator, GraphEdge, boost::random_access_traversal_tag, GraphEdge> {
   public:
    OutEdgeIterator() = default;
    OutEdgeIterator(const Engine* e, std::size_t v, std::size_t i) : engine_(e), vertex_(v), i_(i) {}

   private:
    friend class boost::iterator_core_access;
    GraphEdge dereference() const {
      return GraphEdge{vertex_, engine_->bridges(static_cast<ClusterId>(vertex_))[i_].other};
    }
    void increment() { ++i_; }
    void decrement() { --i_; }
    void advance(std::ptrdiff_t n) { i_ = static_cast<std::size_t>(static_cast<std::ptrdiff_t>(i_) + n); }
    std::ptrdiff_t distance_to(const OutEdgeIterator& o) const {
      return static_cast<std::ptrdiff_t>(o.i_) - static_cast<std::ptrdiff_t>(i_);
    }
    bool equal(const OutEdgeIterator& o) const { return i_ == o.i_; }

    const Engine* engine_ = nullptr;
    std::size_t vertex_ = 0;
    std::size_t i_ = 0;
  };

 private:
  const Engine* engine_;
};

/// The component graph of `engine` as a Boost.Graph.
template <class Engine>
ComponentGraph<Engine> component_graph(const Engine& engine) {
  return ComponentGraph<Engine>(engine);
}

template <class Engine>
std::pair<boost::counting_iterator<std::size_t>, boost::counting_iterator<std::size_t>> vertices(
    const ComponentGraph<Engine>& g) {
  return {boost::counting_iterator<std::size_t>(0), boost::counting_iterator<std::size_t>(g.engine().cluster_slots())};
}
template <class Engine>
std::size_t num_vertices(const ComponentGraph<Engine>& g) {
  return g.engine().cluster_slots();
}
template <class Engine>
std::pair<typename ComponentGraph<Engine>::OutEdgeIterator, typename ComponentGraph<Engine>::OutEdgeIterator>
out_edges(std::size_t v, const ComponentGraph<Engine>& g) {
  using It = typename ComponentGraph<Engine>::OutEdgeIterator;
  return {It(&g.engine(), v, 0), It(&g.engine(), v, out_degree(v, g))};
}
template <class Engine>
std::size_t out_degree(std::size_t v, const ComponentGraph<Engine>& g) {
  return g.engine().cluster_alive(static_cast<ClusterId>(v)) ? g.engine().bridges(static_cast<ClusterId>(v)).size() : 0;
}
namespace detail {
template <class Engine>
struct is_graph_view<ComponentGraph<Engine>> : std::true_type {};
}  // namespace detail

}  // namespace streamclust

namespace boost {

template <class Engine>
struct graph_traits<streamclust::ComponentGraph<Engine>>
    : streamclust::detail::view_graph_traits<streamclust::ComponentGraph<Engine>> {};

template <class Engine>
struct property_map<streamclust::ComponentGraph<Engine>, vertex_index_t> {
  using type = typed_identity_property_map<std::size_t>;
  using const_type = type;
};

}  // namespace boost
