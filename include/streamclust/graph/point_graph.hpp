// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// Boost.Graph adaptor of an engine's point graph: the points of the window
/// are the vertices (numbered by window position, 0 = oldest) and the live
/// point-level links are the undirected edges. Models VertexListGraph and
/// IncidenceGraph, with an identity vertex_index map, so BGL algorithms such
/// as `boost::connected_components` run on it directly, without a copy.
///
/// \code
/// auto g = streamclust::point_graph(engine);
/// std::vector<int> component(boost::num_vertices(g));
/// int n = boost::connected_components(g, component.data());
/// \endcode
///
/// A view: valid until the engine is next modified. O(1) to create.

#include <streamclust/stream_clusterer.hpp>

#include <boost/graph/graph_traits.hpp>
#include <boost/graph/properties.hpp>
#include <boost/iterator/counting_iterator.hpp>
#include <boost/iterator/iterator_facade.hpp>
#include <boost/property_map/property_map.hpp>

#include <cstddef>
#include <type_traits>
#include <utility>

namespace streamclust {

/// An edge of a graph view: (source, target) vertex numbers.
struct GraphEdge {
  std::size_t source = 0;
  std::size_t target = 0;
  friend bool operator==(const GraphEdge& a, const GraphEdge& b) {
    return a.source == b.source && a.target == b.target;
  }
  friend bool operator!=(const GraphEdge& a, const GraphEdge& b) { return !(a == b); }
};

template <class Engine>
class PointGraph {
 public:
  explicit PointGraph(const Engine& engine) : engine_(&engine) {}
  const Engine& engine() const { return *engine_; }

  /// Out-edges of one vertex: its live back edges, then its forward edges.
  class OutEdgeIterator
      : public boost::iterator_facade<OutEdgeIterator, GraphEdge, boost::forward_traversal_tag, GraphEdge> {
   public:
    OutEdgeIterator() = default;
    OutEdgeIterator(const Engine* e, std::size_t v, bool at_end)
        : engine_(e), vertex_(v), handle_(e->handle_at(v)), count_(e->back_edges_count(handle_)) {
      if (at_end) {
        back_ = count_;
        forward_ = kNoEdge;
      } else {
        forward_ = e->forward_edges_head(handle_);
        skip_dead();
      }
    }

   private:
    friend class boost::iterator_core_access;
    PointHandle neighbour() const {
      if (back_ < count_) return engine_->edge_older(engine_->back_edges_begin(handle_) + back_);
      return engine_->edge_newer(forward_);
    }
    GraphEdge dereference() const { return GraphEdge{vertex_, engine_->position_of(neighbour())}; }
    void increment() {
      if (back_ < count_) {
        ++back_;
        skip_dead();
      } else {
        forward_ = engine_->edge_next_forward(forward_);
      }
    }
    void skip_dead() {
      while (back_ < count_ && !engine_->is_live(engine_->edge_older(engine_->back_edges_begin(handle_) + back_))) {
        ++back_;
      }
    }
    bool equal(const OutEdgeIterator& o) const { return back_ == o.back_ && forward_ == o.forward_; }

    const Engine* engine_ = nullptr;
    std::size_t vertex_ = 0;
    PointHandle handle_ = 0;
    std::uint32_t count_ = 0;
    std::uint32_t back_ = 0;
    EdgeHandle forward_ = kNoEdge;
  };

 private:
  const Engine* engine_;
};

/// The point graph of `engine` as a Boost.Graph.
template <class Engine>
PointGraph<Engine> point_graph(const Engine& engine) {
  return PointGraph<Engine>(engine);
}

template <class Engine>
std::pair<boost::counting_iterator<std::size_t>, boost::counting_iterator<std::size_t>> vertices(
    const PointGraph<Engine>& g) {
  return {boost::counting_iterator<std::size_t>(0), boost::counting_iterator<std::size_t>(g.engine().size())};
}
template <class Engine>
std::size_t num_vertices(const PointGraph<Engine>& g) {
  return g.engine().size();
}
template <class Engine>
std::pair<typename PointGraph<Engine>::OutEdgeIterator, typename PointGraph<Engine>::OutEdgeIterator> out_edges(
    std::size_t v, const PointGraph<Engine>& g) {
  using It = typename PointGraph<Engine>::OutEdgeIterator;
  return {It(&g.engine(), v, false), It(&g.engine(), v, true)};
}
template <class Engine>
std::size_t out_degree(std::size_t v, const PointGraph<Engine>& g) {
  std::size_t n = 0;
  g.engine().for_each_neighbor(g.engine().handle_at(v), [&](PointHandle) { ++n; });
  return n;
}
namespace detail {
/// Graph views sharing the edge type and the identity vertex index.
template <class G>
struct is_graph_view : std::false_type {};
template <class Engine>
struct is_graph_view<PointGraph<Engine>> : std::true_type {};

/// The graph_traits of every graph view: undirected, incidence + vertex list.
template <class G>
struct view_graph_traits {
  struct traversal_category : boost::incidence_graph_tag, boost::vertex_list_graph_tag {};
  using vertex_descriptor = std::size_t;
  using edge_descriptor = GraphEdge;
  using directed_category = boost::undirected_tag;
  using edge_parallel_category = boost::disallow_parallel_edge_tag;
  using out_edge_iterator = typename G::OutEdgeIterator;
  using vertex_iterator = boost::counting_iterator<std::size_t>;
  using degree_size_type = std::size_t;
  using vertices_size_type = std::size_t;
  using edges_size_type = std::size_t;
  using in_edge_iterator = void;
  using edge_iterator = void;
  using adjacency_iterator = void;
  static vertex_descriptor null_vertex() { return static_cast<std::size_t>(-1); }
};
}  // namespace detail

template <class G, std::enable_if_t<detail::is_graph_view<G>::value, int> = 0>
std::size_t source(const GraphEdge& e, const G&) {
  return e.source;
}
template <class G, std::enable_if_t<detail::is_graph_view<G>::value, int> = 0>
std::size_t target(const GraphEdge& e, const G&) {
  return e.target;
}
template <class G, std::enable_if_t<detail::is_graph_view<G>::value, int> = 0>
boost::typed_identity_property_map<std::size_t> get(boost::vertex_index_t, const G&) {
  return {};
}

}  // namespace streamclust

namespace boost {

template <class Engine>
struct graph_traits<streamclust::PointGraph<Engine>>
    : streamclust::detail::view_graph_traits<streamclust::PointGraph<Engine>> {};

template <class Engine>
struct property_map<streamclust::PointGraph<Engine>, vertex_index_t> {
  using type = typed_identity_property_map<std::size_t>;
  using const_type = type;
};

}  // namespace boost
