// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// StableIdVotes: which of the previous retrieval's component ids each new
/// component keeps.

#include <streamclust/detail/growth.hpp>
#include <streamclust/detail/hints.hpp>

#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

namespace streamclust {

/// The stable-id rule. The previous result's components are the old GROUPS
/// (each carries one id, at its place in that result, which is sorted by
/// id). Votes (old group, new component, weight) say how much of an old
/// group went where. Then: each old id goes to the component with the
/// heaviest vote for it (ties: the lower component number), and each
/// component keeps the heaviest id it won (ties: the older id, that is the
/// lower place); components left without one get fresh ids (ComponentResult).
///
/// Weights: the paper's strategy votes once per local cluster with its
/// current size; the rebuilding strategies once per point present at the
/// previous retrieval (weight 1). Either way a vote adds to the (group,
/// component) pair's total.
///
/// Cost: a vote walks its group's list of components, kept most recent
/// first (in practice O(1): consecutive points of a group vote alike);
/// `resolve` is O(groups + votes). A group with exactly one point left
/// keeps no list (`begin`'s `sole`), which matters on fragmented windows
/// where most groups are single points. Allocates only when a vote count or
/// a group count exceeds its previous peak.
/// Thread safety: none.
class StableIdVotes {
 public:
  /// No place / no vote.
  static constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();

  /// Starts a round over `groups` old groups; `sole(g)` is true for a group
  /// with one point left, which may then vote once with weight 1 (`vote_one`)
  /// and never through `vote`. O(groups).
  template <class Sole>
  void begin(std::uint32_t groups, Sole&& sole) {
    detail::reserve_geometric(head_, groups);
    head_.resize(groups);
    for (std::uint32_t g = 0; g < groups; ++g) head_[g] = sole(g) ? kSoleMark : kNone;
    votes_.clear();
  }

  /// Reserves room for `count` votes before the first round (later rounds
  /// grow only past their peak). O(1) amortised.
  void reserve(std::size_t count) {
    if (votes_.capacity() == 0) votes_.reserve(count);
  }
  bool reserved() const { return votes_.capacity() != 0; }

  /// One point of group `g` votes for component `k` with weight 1 (a sole
  /// point or one of many). O(votes of g), in practice O(1).
  STREAMCLUST_ALWAYS_INLINE void vote_one(std::uint32_t g, std::uint32_t k) {
    std::uint32_t& head = head_[g];
    if (head == kSoleMark) {
      head = kSoleVote + k;
    } else {
      vote(g, k, 1);
    }
  }

  /// Group `g` (not a sole one) votes for component `k` with `weight`.
  /// O(votes of g), in practice O(1): the list is kept most recent first.
  STREAMCLUST_ALWAYS_INLINE void vote(std::uint32_t g, std::uint32_t k, std::uint32_t weight) {
    std::uint32_t before = kNone;
    std::uint32_t v = head_[g];
    while (v != kNone && votes_[v].component != k) {
      before = v;
      v = votes_[v].next;
    }
    if (v == kNone) {
      votes_.push_back(Vote{k, weight, head_[g]});
      head_[g] = static_cast<std::uint32_t>(votes_.size() - 1);
      return;
    }
    votes_[v].weight += weight;
    if (before != kNone) {
      // Move to front: the next points of `g` most likely vote the same way
      // (without it a group that shed many pieces walks all of them per point).
      votes_[before].next = votes_[v].next;
      votes_[v].next = head_[g];
      head_[g] = v;
    }
  }

  /// Prefetches group `g`'s list head (a pass whose groups are scattered).
  void prefetch(std::uint32_t g) const { detail::prefetch(&head_[g]); }

  /// Resolves the round for `components` new components. `place(g)` is group
  /// g's place in the previous result. Returns, per component, the place of
  /// the id it keeps, or kNone (a fresh id). O(groups + votes + components).
  template <class Place>
  const std::vector<std::uint32_t>& resolve(std::uint32_t components, Place&& place) {
    detail::reserve_geometric(won_weight_, components);
    won_weight_.resize(components);  // read only where an id was won
    detail::reserve_geometric(won_place_, components);
    won_place_.assign(components, kNone);
    const auto groups = static_cast<std::uint32_t>(head_.size());
    for (std::uint32_t g = 0; g < groups; ++g) {
      std::uint32_t best = head_[g];
      if (best >= kSoleMark) continue;  // no point left to vote (a sole mark cannot remain: its point voted)
      std::uint32_t k = 0;
      std::uint32_t w = 1;
      if (best >= kSoleVote) {
        k = best - kSoleVote;
      } else {
        for (std::uint32_t v = votes_[best].next; v != kNone; v = votes_[v].next) {
          if (votes_[v].weight > votes_[best].weight ||
              (votes_[v].weight == votes_[best].weight && votes_[v].component < votes_[best].component)) {
            best = v;
          }
        }
        k = votes_[best].component;
        w = votes_[best].weight;
      }
      const std::uint32_t at = place(g);
      if (won_place_[k] == kNone || w > won_weight_[k] || (w == won_weight_[k] && at < won_place_[k])) {
        won_weight_[k] = w;
        won_place_[k] = at;
      }
    }
    return won_place_;
  }

  std::size_t heap_bytes() const {
    return (head_.capacity() + won_weight_.capacity() + won_place_.capacity()) * sizeof(std::uint32_t) +
           votes_.capacity() * sizeof(Vote);
  }

 private:
  /// One (group, component) pair; chained per group.
  struct Vote {
    std::uint32_t component;
    std::uint32_t weight;
    std::uint32_t next;  ///< next vote of the same group
  };
  /// head_ of a group with one point left, before it voted.
  static constexpr std::uint32_t kSoleMark = kNone - 1;
  /// head_ = kSoleVote + k: that one point voted for component k
  /// (components stay below 2^31: fewer than 2^31 window points).
  static constexpr std::uint32_t kSoleVote = std::uint32_t{1} << 31;


  std::vector<std::uint32_t> head_;  ///< per group: its most recent vote, kNone, or a sole mark/vote
  std::vector<Vote> votes_;
  std::vector<std::uint32_t> won_weight_;
  std::vector<std::uint32_t> won_place_;
};

}  // namespace streamclust
