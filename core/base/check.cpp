#include "base/check.h"

#include <cstdio>
#include <cstdlib>

namespace bounce {

void check_failed(const char* condition, const char* file, int line) {
  std::fprintf(stderr, "%s:%d: internal error: check failed: %s\n", file, line, condition);
  std::fflush(stderr);
  std::abort();
}

void check_failed(const char* condition, const std::string& left, const std::string& right, const char* file,
                  int line) {
  std::fprintf(stderr, "%s:%d: internal error: check failed: %s (%s vs %s)\n", file, line, condition, left.c_str(),
               right.c_str());
  std::fflush(stderr);
  std::abort();
}

namespace check_detail {

std::string show(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.17g", value);
  return text;
}

std::string show(long long value) {
  return std::to_string(value);
}

std::string show(unsigned long long value) {
  return std::to_string(value);
}

}  // namespace check_detail
}  // namespace bounce
