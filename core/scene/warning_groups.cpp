#include "scene/warning_groups.h"

#include <unordered_map>

namespace bounce {

std::vector<warning_group> group_warnings(const std::vector<std::string>& warnings) {
  std::vector<warning_group> groups;
  std::unordered_map<std::string, std::size_t> index;
  for (const std::string& w : warnings) {
    const std::size_t split = w.find(": ");
    const std::string where = split == std::string::npos ? std::string() : w.substr(0, split);
    const std::string text = split == std::string::npos ? w : w.substr(split + 2);
    const auto [it, added] = index.try_emplace(text, groups.size());
    if (added) groups.push_back({text, 0, where, where});
    warning_group& g = groups[it->second];
    ++g.count;
    g.last_at = where;
  }
  return groups;
}

std::string describe(const warning_group& group) {
  if (group.count == 1) return group.first_at.empty() ? group.text : group.first_at + ": " + group.text;
  std::string line = group.text + ": " + std::to_string(group.count) + " times";
  if (!group.first_at.empty()) line += " (first at " + group.first_at + ", last at " + group.last_at + ")";
  return line;
}

}  // namespace bounce
