#include "base/memory_room.h"

#include <cmath>
#include <cstdio>
#include <fstream>

#include <sys/resource.h>
#include <unistd.h>

namespace bounce {

memory_room available_memory() {
  memory_room room{INFINITY, "no limit"};
  const double page = double(::sysconf(_SC_PAGESIZE));
  const long pages = ::sysconf(_SC_PHYS_PAGES);
  if (pages > 0 && page > 0.0) room = {double(pages) * page, "this machine's memory"};
  rlimit limit{};
  if (::getrlimit(RLIMIT_AS, &limit) == 0 && limit.rlim_cur != RLIM_INFINITY) {
    // statm's first field: the pages the process has mapped now.
    double mapped_pages = 0.0;
    std::ifstream("/proc/self/statm") >> mapped_pages;
    const double left = std::max(0.0, double(limit.rlim_cur) - mapped_pages * page);
    if (left < room.bytes) room = {left, "the address-space limit (ulimit -v) less what is mapped"};
  }
  return room;
}

std::string format_bytes(double bytes) {
  if (!std::isfinite(bytes)) return "unlimited";
  const char* units[] = {"bytes", "kB", "MB", "GB", "TB", "PB"};
  int unit = 0;
  while (bytes >= 999.5 && unit < 5) {
    bytes /= 1000.0;
    ++unit;
  }
  char text[32];
  std::snprintf(text, sizeof text, unit == 0 || bytes >= 99.5 ? "%.0f %s" : "%.3g %s", bytes, units[unit]);
  return text;
}

}  // namespace bounce
