// The link oracle: for a pair of tree nodes (receiver i <- source j,
// plain or through a chain of planar mirrors) it estimates the form
// factor, charges the pair with the error it would leave unrefined, casts
// shadow rays for the visible fraction, and decides whether the pair is
// split (on its larger side) or kept as one link.
//
// The charge is BF refinement's F x B x A (the power the link would
// carry, with F the estimate's bound), except where the side a split would
// divide is a piece of an element split while solving: pieces exist for
// how light varies over them, so a piece receiver is charged the
// variation of the form factor over its sample points times B x A, and a
// piece source is not divided for the light it carries. Through a mirror
// chain, the charge is F x kr x B x A, or from an inner node what the
// kernel's spread over the node's sample elements could carry, when that
// is more.
//
// The rule (decide): split while the charge exceeds the tolerance; a
// partly visible pair must carry partial_factor times less (shadows need
// pieces). Through mirrors, a pair that no ray passes counts as partly
// visible: it is split while it could matter, and dropped after.
#pragma once

#include <atomic>
#include <cstdint>
#include <vector>

#include "radiosity/hierarchical/state.h"

namespace bounce {

struct link_estimate {
  double factor = 0.0;  // what the link would carry per unit source radiosity
  double bound = 0.0;   // the form factor the oracle charges it with
  bool none = false;    // the two cannot exchange light (they face away, or no path through the chain)
};

// The estimate for receiver i <- source j: Lambert's exact
// point-to-polygon term from the receiver's centroid between leaves, the
// disc estimate otherwise. Overlapping bounds are charged the largest
// factor. Through `chain` (not null), the same to the source's image,
// culled where the chain's first mirror cannot be crossed.
link_estimate estimate(const hierarchical_solver& solver, int i, int j);
link_estimate estimate_through(const hierarchical_solver& solver, int i, int j, const mirror_chain& chain);

// What a pair is charged: `bf` decides whether a partly visible pair is
// split, `split` whether any pair is.
struct pair_charge {
  double bf = 0.0;
  double split = 0.0;
};

// node_b: the radiosity pulled to every node (the oracle's B).
pair_charge charge(const hierarchical_solver& solver, const std::vector<rgb>& node_b, int i, int j,
                   const link_estimate& e);
pair_charge charge_through(const hierarchical_solver& solver, const std::vector<rgb>& node_b, int i, int j, int chain,
                           const link_estimate& e);

// The visible fraction of a pair from `count` shadow rays between sample
// points of both (through chain `chain` when >= 0: to the source's image,
// the rays then having to pass the chain's mirrors), each ray weighted by
// the cosines at its ends. Seeded by the pair (and chain): the same rays
// whatever the thread. Adds the rays cast to `rays`.
float pair_visibility(const hierarchical_solver& solver, int i, int j, int count, int chain,
                      std::atomic<std::uint64_t>& rays);

// The visible fraction of source node j seen from point p (normal n), from
// `count` shadow rays to sample points of j, each weighted by the cosines
// at its ends over the squared distance. Seeded by the point: the same
// rays whatever the thread. Adds the rays cast to `rays`.
float point_visibility(const hierarchical_solver& solver, const vec3& p, const vec3& n, int j, int count,
                       std::uint64_t& rays);

// What a kept link from i <- j carries: the strata estimate from an inner
// node to an oriented receiver (except in a closed scene from a source
// that does not emit: the normaliser takes out the disc estimate's
// shortfall there; an emitter's links are taken as they are), else the
// estimate's factor.
double kept_factor(const hierarchical_solver& solver, int i, int j, const link_estimate& e, bool source_emits);

enum class pair_verdict { split, keep };

struct pair_decision {
  pair_verdict verdict = pair_verdict::keep;
  float visibility = 1.0f;  // when kept (or split on it)
};

// The split-or-keep rule, the one place it is written: plain pairs,
// re-examined links and pairs through mirrors all come here. `splittable`
// is false between two leaves and past the link limit. `visible()` gives
// the pair's visible fraction, asked for only when the charge alone does
// not split it. `dark_is_partial`: a pair that no ray passes counts as
// partly visible (pairs through mirrors).
template <typename visibility_source>
pair_decision decide(const pair_charge& charge, bool splittable, double tolerance, double partial_factor,
                     bool dark_is_partial, visibility_source&& visible) {
  if (splittable && charge.split > tolerance) return {pair_verdict::split, 1.0f};
  const float v = visible();
  const bool partial = v < 1.0f && (dark_is_partial || v > 0.0f);
  if (splittable && partial && partial_factor * charge.bf > tolerance) return {pair_verdict::split, v};
  return {pair_verdict::keep, v};
}

}  // namespace bounce
