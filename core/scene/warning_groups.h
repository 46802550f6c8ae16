// A scene reader's warnings grouped by what they say: a model with 11,163
// degenerate faces gets one line with the count, not 11,163 lines. The
// terminal and the window's import report show the same groups.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace bounce {

struct warning_group {
  std::string text;  // what the warnings say, without where
  std::size_t count = 0;
  std::string first_at;  // where the first one was ("file:line", or "file" when it names no line)
  std::string last_at;
};

// Groups "where: text" warnings (as load_report holds them) by their text,
// in the order each text first appears. `where` is what comes before the
// first ": ", a file with its line if it has one.
std::vector<warning_group> group_warnings(const std::vector<std::string>& warnings);

// One line for a group: the warning itself when it is alone, else its text,
// its count and where the first and the last were.
std::string describe(const warning_group& group);

}  // namespace bounce
