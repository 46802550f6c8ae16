#include "radiosity/hierarchical/link_table.h"

#include <tbb/parallel_sort.h>

#include "base/check.h"

namespace bounce {
namespace {

template <typename link_type>
void make_offsets(link_table<link_type>& table, std::size_t nodes) {
  table.offsets.assign(nodes + 1, 0);
  for (const link_type& l : table.links) {
    const hierarchy_link& link = link_of(l);
    BOUNCE_DCHECK(link.receiver >= 0 && std::size_t(link.receiver) < nodes);
    BOUNCE_DCHECK(link.source >= 0 && std::size_t(link.source) < nodes);
    ++table.offsets[std::size_t(link.receiver) + 1];
  }
  for (std::size_t i = 0; i < nodes; ++i) table.offsets[i + 1] += table.offsets[i];
  BOUNCE_CHECK_EQ(table.offsets.back(), table.links.size());
}

}  // namespace

void index_links(link_table<hierarchy_link>& table, std::size_t nodes) {
  tbb::parallel_sort(table.links.begin(), table.links.end(), [](const hierarchy_link& a, const hierarchy_link& b) {
    return a.receiver != b.receiver ? a.receiver < b.receiver : a.source < b.source;
  });
  make_offsets(table, nodes);
}

void index_links(link_table<mirror_link>& table, std::size_t nodes) {
  tbb::parallel_sort(table.links.begin(), table.links.end(), [](const mirror_link& a, const mirror_link& b) {
    if (a.link.receiver != b.link.receiver) return a.link.receiver < b.link.receiver;
    return a.chain != b.chain ? a.chain < b.chain : a.link.source < b.link.source;
  });
  make_offsets(table, nodes);
}

}  // namespace bounce
