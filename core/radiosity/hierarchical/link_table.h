// Links and their table. A link (receiver <- source) joins two nodes of
// the cluster tree: the receiver gathers the source's radiosity times the
// link's form-factor estimate and visible fraction. A link through a chain
// of planar mirrors joins the receiver to the source's image in the chain
// (mirror_chains.h).
//
// Invariants of a link_table once indexed: the links are sorted by
// receiver (then by chain and source), offsets has one entry per tree node
// plus one, and the links of node i are [offsets[i], offsets[i + 1]).
#pragma once

#include <cstddef>
#include <span>
#include <vector>

namespace bounce {

// 16 bytes: what one link costs (plus the receiver index lists).
struct hierarchy_link {
  int receiver = -1;
  int source = -1;
  float factor = 0.0f;      // form factor (clusters: per unit area facing the source)
  float visibility = 1.0f;  // fraction of the shadow rays that pass
};

// A link through a chain of planar mirrors: the receiver sees the
// source's image (solver's chains[chain]); factor is the form factor to
// the image, visibility the share of rays that pass the chain.
struct mirror_link {
  hierarchy_link link;
  int chain = -1;
};

inline const hierarchy_link& link_of(const hierarchy_link& l) {
  return l;
}
inline const hierarchy_link& link_of(const mirror_link& m) {
  return m.link;
}
inline hierarchy_link& link_of(hierarchy_link& l) {
  return l;
}
inline hierarchy_link& link_of(mirror_link& m) {
  return m.link;
}

template <typename link_type>
struct link_table {
  std::vector<link_type> links;
  std::vector<std::size_t> offsets;  // per receiver node, plus one

  std::size_t size() const { return links.size(); }
  bool empty() const { return links.empty(); }
  std::span<const link_type> of(std::size_t receiver) const {
    return {links.data() + offsets[receiver], offsets[receiver + 1] - offsets[receiver]};
  }
  std::size_t count_of(std::size_t receiver) const { return offsets[receiver + 1] - offsets[receiver]; }
};

// Drops every link; offsets for `nodes` nodes, all empty.
template <typename link_type>
void clear_links(link_table<link_type>& table, std::size_t nodes) {
  table.links.clear();
  table.offsets.assign(nodes + 1, 0);
}

// Sorts the links (by receiver, then chain, then source) and indexes them
// for a tree of `nodes` nodes. Every endpoint must name a node.
void index_links(link_table<hierarchy_link>& table, std::size_t nodes);
void index_links(link_table<mirror_link>& table, std::size_t nodes);

// Renumbers every endpoint: node i becomes node_of_old[i].
template <typename link_type>
void renumber_links(link_table<link_type>& table, std::span<const int> node_of_old) {
  for (link_type& l : table.links) {
    hierarchy_link& link = link_of(l);
    link.receiver = node_of_old[std::size_t(link.receiver)];
    link.source = node_of_old[std::size_t(link.source)];
  }
}

}  // namespace bounce
