#include "radiosity/hierarchical/link_refinement.h"

#include <algorithm>
#include <atomic>
#include <utility>

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include "base/parallel.h"
#include "radiosity/hierarchical/closed_scene.h"
#include "radiosity/hierarchical/element_refinement.h"
#include "radiosity/hierarchical/oracle.h"
#include "radiosity/hierarchical/transport.h"
#include "radiosity/hierarchical/view_importance.h"

namespace bounce {
namespace {

// One refinement's shared state: the oracle's inputs and what it makes,
// per thread.
struct refine_context {
  refine_context(const hierarchical_solver& s, const std::vector<rgb>& b, const std::vector<rgb>& e, double t)
      : solver(s), node_b(b), node_e(e), tolerance(t) {}

  const hierarchical_solver& solver;
  const std::vector<rgb>& node_b;
  const std::vector<rgb>& node_e;  // the emission pulled to every node
  double tolerance;                // absolute: power units
  tbb::enumerable_thread_specific<std::vector<hierarchy_link>> links;
  tbb::enumerable_thread_specific<std::vector<mirror_link>> mirror_links;
  tbb::enumerable_thread_specific<std::vector<std::pair<int, int>>> marks;  // (element, bisections)
  std::atomic<std::size_t> count{0};
  std::atomic<std::uint64_t> rays{0};
  std::atomic<bool> limit_hit{false};
  std::atomic<bool> out_of_time{false};
  const bool has_deadline = solver.deadline != std::chrono::steady_clock::time_point::max();

  bool leaves(int i, int j) const {
    return solver.hierarchy.tree.nodes[std::size_t(i)].leaf() && solver.hierarchy.tree.nodes[std::size_t(j)].leaf();
  }
  bool splittable(int i, int j) { return !leaves(i, j) && !limit_hit.load(std::memory_order_relaxed) && !time_is_up(); }
  bool time_is_up() {
    if (!has_deadline) return false;  // no clock read per pair when nothing limits the time
    if (out_of_time.load(std::memory_order_relaxed)) return true;
    if (std::chrono::steady_clock::now() < solver.deadline) return false;
    out_of_time.store(true, std::memory_order_relaxed);
    return true;
  }
  int rays_for(int i, int j) const {
    return leaves(i, j) ? solver.params.leaf_visibility_rays : solver.params.visibility_rays;
  }
  const mirror_chain* chain(int c) const { return c >= 0 ? &solver.hierarchy.chains[std::size_t(c)] : nullptr; }

  void count_link() {
    if (count.fetch_add(1, std::memory_order_relaxed) + 1 >= solver.params.max_links)
      limit_hit.store(true, std::memory_order_relaxed);
  }
  void mark(int i, int j, double factor, float visibility, int c) {
    const int bisections = bisections_needed(solver, node_b, tolerance, i, j, factor, visibility, chain(c));
    if (bisections > 0) marks.local().emplace_back(solver.hierarchy.tree.nodes[std::size_t(i)].element, bisections);
  }
};

void refine_pair(refine_context& ctx, int i, int j, int c);

// Splits the pair's larger side and refines the pairs with its children
// (through the same chain `c`, when >= 0).
void split_pair(refine_context& ctx, int i, int j, int c) {
  const cluster_node& r = ctx.solver.hierarchy.tree.nodes[std::size_t(i)];
  const cluster_node& s = ctx.solver.hierarchy.tree.nodes[std::size_t(j)];
  const bool split_receiver = !r.leaf() && (s.leaf() || r.area >= s.area);
  const cluster_node& split = split_receiver ? r : s;
  auto body = [&](int k) { split_receiver ? refine_pair(ctx, k, j, c) : refine_pair(ctx, i, k, c); };
  // Large pairs fan out over the threads; small ones stay on this one.
  if (ctx.solver.params.parallel && r.elements + s.elements > 4096) {
    tbb::parallel_for(split.first_child, split.first_child + split.child_count, body);
  } else {
    for (int k = split.first_child; k < split.first_child + split.child_count; ++k) body(k);
  }
}

// A new pair (plain when c < 0, else through chain c): split, keep as a
// link, or drop.
void refine_pair(refine_context& ctx, int i, int j, int c) {
  const hierarchical_solver& solver = ctx.solver;
  const link_estimate e = c < 0 ? estimate(solver, i, j) : estimate_through(solver, i, j, *ctx.chain(c));
  if (e.none) return;
  const pair_charge charged =
      c < 0 ? charge(solver, ctx.node_b, i, j, e) : charge_through(solver, ctx.node_b, i, j, c, e);
  const pair_decision d =
      decide(charged, ctx.splittable(i, j), ctx.tolerance, solver.params.partial_factor, /*dark_is_partial=*/c >= 0,
             [&] { return pair_visibility(solver, i, j, ctx.rays_for(i, j), c, ctx.rays); });
  if (d.verdict == pair_verdict::split) return split_pair(ctx, i, j, c);
  const bool leaves = ctx.leaves(i, j);
  if (c < 0) {
    // A pair whose estimate is 0 but that is not culled is kept: parts of
    // it may face each other, and a later refinement (with more light)
    // splits it. Between leaves there is nothing left to split.
    if (!(e.factor > 0.0) && leaves) return;
    if (leaves) ctx.mark(i, j, e.factor, d.visibility, c);
    ctx.links.local().push_back({i, j, float(kept_factor(solver, i, j, e, node_emits(ctx.node_e, j))), d.visibility});
  } else {
    // Through mirrors most pairs see the chain partly or not at all:
    // keeping those that see nothing would cost memory for nothing.
    if (d.visibility == 0.0f || !(e.factor > 0.0)) return;
    if (leaves) ctx.mark(i, j, e.factor, d.visibility, c);
    ctx.mirror_links.local().push_back({{i, j, float(e.factor), d.visibility}, c});
  }
  ctx.count_link();
}

// An existing plain link at a new tolerance (or on a refined tree): split
// by the same rule, with the visibility it already has; else kept as it is.
void reexamine(refine_context& ctx, const hierarchy_link& link) {
  if (ctx.time_is_up()) {  // kept as it is, without the oracle's look
    ctx.links.local().push_back(link);
    ctx.count_link();
    return;
  }
  const hierarchical_solver& solver = ctx.solver;
  const int i = link.receiver, j = link.source;
  const link_estimate e = estimate(solver, i, j);
  const pair_decision d =
      decide(charge(solver, ctx.node_b, i, j, e), ctx.splittable(i, j), ctx.tolerance, solver.params.partial_factor,
             /*dark_is_partial=*/false, [&] { return link.visibility; });
  if (d.verdict == pair_verdict::split) return split_pair(ctx, i, j, -1);
  if (ctx.leaves(i, j)) ctx.mark(i, j, e.factor, link.visibility, -1);
  ctx.links.local().push_back(link);
  ctx.count_link();
}

// A node with itself: its children with each other, and each with itself.
// Oriented nodes do not see themselves.
void refine_self(refine_context& ctx, int i) {
  const cluster_node& node = ctx.solver.hierarchy.tree.nodes[std::size_t(i)];
  if (node.oriented || node.leaf()) return;
  auto body = [&](int a) {
    refine_self(ctx, a);
    for (int b = node.first_child; b < node.first_child + node.child_count; ++b)
      if (b != a) refine_pair(ctx, a, b, -1);
  };
  if (ctx.solver.params.parallel && node.elements > 4096)
    tbb::parallel_for(node.first_child, node.first_child + node.child_count, body);
  else
    for (int a = node.first_child; a < node.first_child + node.child_count; ++a) body(a);
}

// Per element the most bisections any pair or the lamps asked for; the marks are
// dropped when too few elements ask (params.min_marked_fraction).
void collect_marks(hierarchical_solver& solver, refine_context& ctx, const std::vector<std::pair<int, int>>& lamp) {
  solver.split_marks.clear();
  std::size_t marked = 0;
  auto mark = [&](int element, int bisections) {
    if (solver.split_marks.empty()) solver.split_marks.assign(solver.mesh().element_count(), 0);
    std::uint8_t& m = solver.split_marks[std::size_t(element)];
    marked += m == 0 ? 1 : 0;
    m = std::max(m, std::uint8_t(bisections));
  };
  for (const auto& part : ctx.marks)
    for (const auto& [element, bisections] : part) mark(element, bisections);
  for (const auto& [element, bisections] : lamp) mark(element, bisections);
  solver.progress.split_marks += marked;
  // With a view, of the elements it sees: the rest of a large scene may
  // need nothing, and the view's few hundred are what the picture shows.
  std::size_t counted = solver.mesh().element_count();
  if (!solver.view.seen.empty()) {
    counted = 0;
    for (std::size_t e = 0; e < solver.mesh().element_count(); ++e)
      counted += solver.view.seen[std::size_t(solver.meshes.input_element[e])] > 0.0 ? 1 : 0;
  }
  if (double(marked) < solver.params.min_marked_fraction * double(counted)) solver.split_marks.clear();
}

}  // namespace

void refine_links(hierarchical_solver& solver, double tolerance) {
  link_hierarchy& h = solver.hierarchy;
  if (h.tree.nodes.empty()) return;
  update_view_weights(solver);  // the receivers' weights, on the tree and links as they stand
  solver.view.retarget = false;
  std::vector<rgb> node_b(h.tree.nodes.size());
  pull(solver, solver.light.total, node_b, nullptr);  // the oracle charges the mean
  // The tolerance is relative to the power leaving all surfaces now (at
  // least the emitted power): at high reflectance far more power circulates
  // than is emitted, and each link's share of it is what matters.
  double leaving = 0.0;
  for (std::size_t e = 0; e < solver.light.total.size(); ++e)
    leaving += std::max(0.0, channel_sum(solver.light.total[e])) * solver.mesh().element_areas[e];
  const double power = std::max(leaving, solver.sources.emitted_power) / 3.0;
  std::vector<rgb> node_e(h.tree.nodes.size());
  pull(solver, solver.sources.emission, node_e, nullptr);
  refine_context ctx(solver, node_b, node_e, tolerance * power);
  if (h.links.empty()) {
    refine_self(ctx, 0);
  } else {
    const std::vector<hierarchy_link>& old = h.links.links;
    for_each_block(solver.params.parallel, old.size(), 256, [&](std::size_t b, std::size_t e) {
      for (std::size_t l = b; l < e; ++l) reexamine(ctx, old[l]);
    });
  }
  for_each_block(solver.params.parallel, h.chains.size(), 1, [&](std::size_t b, std::size_t e) {
    for (std::size_t c = b; c < e; ++c) refine_pair(ctx, 0, 0, int(c));
  });
  std::vector<hierarchy_link> links;
  links.reserve(ctx.count.load());
  for (auto& part : ctx.links) links.insert(links.end(), part.begin(), part.end());
  h.links.links = std::move(links);
  h.mirror_links.links.clear();
  for (auto& part : ctx.mirror_links) h.mirror_links.links.insert(h.mirror_links.links.end(), part.begin(), part.end());
  index_links(h.links, h.tree.nodes.size());
  index_links(h.mirror_links, h.tree.nodes.size());
  std::uint64_t lamp_rays = 0;
  collect_marks(solver, ctx, lamp_marks(solver, tolerance * power, lamp_rays));
  solver.progress.rays += ctx.rays.load() + lamp_rays;
  ++solver.progress.refinements;
  if (ctx.limit_hit)
    solver.progress.warning = "link limit reached (" + std::to_string(h.links.size()) + " links, " +
                              std::to_string(h.links.size() * sizeof(hierarchy_link) >> 20) +
                              " MiB): the solution keeps coarser links there";
  // Cut short by the time limit: the links are not yet those of the
  // tolerance, and a run that goes on refines them again.
  solver.progress.links_cut_short = ctx.out_of_time.load();
  if (ctx.out_of_time) solver.progress.links_final = false;
  update_normalizer(solver, node_e);
}

}  // namespace bounce
