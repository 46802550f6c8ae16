// Programmer errors: invariants that no input, however bad, can break. Bad
// input gets an error message with its file and line (scene/reader_support.h);
// a failed check is a bug in Bounce, and stops the program with the
// condition, the file and the line.
//
// BOUNCE_CHECK is on in every build: for cheap checks (O(1) per call, or
// small next to the work around them). BOUNCE_DCHECK is on where
// assertions are (builds without NDEBUG: the sanitizer preset that CI
// runs): for checks that cost time. The comparing forms (BOUNCE_CHECK_LT(a,
// b), ..._LE, _EQ, _NE, _GE, _GT, and their DCHECK twins) evaluate each side
// once and print both values when they fail.
#pragma once

#include <cstdint>
#include <string>
#include <type_traits>

namespace bounce {

[[noreturn]] void check_failed(const char* condition, const char* file, int line);
[[noreturn]] void check_failed(const char* condition, const std::string& left, const std::string& right,
                               const char* file, int line);

namespace check_detail {

std::string show(double value);
std::string show(long long value);
std::string show(unsigned long long value);

// A value as the failure message prints it: numbers, enums and pointers
// (their address); other types as "?".
template <typename T>
std::string show_value(const T& value) {
  if constexpr (std::is_floating_point_v<T>) {
    return show(static_cast<double>(value));
  } else if constexpr (std::is_enum_v<T>) {
    return show_value(static_cast<std::underlying_type_t<T>>(value));
  } else if constexpr (std::is_same_v<T, bool>) {
    return value ? "true" : "false";
  } else if constexpr (std::is_integral_v<T> && std::is_signed_v<T>) {
    return show(static_cast<long long>(value));
  } else if constexpr (std::is_integral_v<T>) {
    return show(static_cast<unsigned long long>(value));
  } else if constexpr (std::is_pointer_v<T>) {
    return show(static_cast<unsigned long long>(reinterpret_cast<std::uintptr_t>(value)));
  } else {
    return "?";
  }
}

}  // namespace check_detail
}  // namespace bounce

#define BOUNCE_CHECK(condition) \
  ((condition) ? static_cast<void>(0) : ::bounce::check_failed(#condition, __FILE__, __LINE__))

#define BOUNCE_CHECK_OP(a, op, b)                                                                            \
  do {                                                                                                       \
    const auto& bounce_check_a = (a);                                                                        \
    const auto& bounce_check_b = (b);                                                                        \
    if (!(bounce_check_a op bounce_check_b))                                                                 \
      ::bounce::check_failed(#a " " #op " " #b, ::bounce::check_detail::show_value(bounce_check_a),         \
                             ::bounce::check_detail::show_value(bounce_check_b), __FILE__, __LINE__);        \
  } while (false)

#define BOUNCE_CHECK_EQ(a, b) BOUNCE_CHECK_OP(a, ==, b)
#define BOUNCE_CHECK_NE(a, b) BOUNCE_CHECK_OP(a, !=, b)
#define BOUNCE_CHECK_LT(a, b) BOUNCE_CHECK_OP(a, <, b)
#define BOUNCE_CHECK_LE(a, b) BOUNCE_CHECK_OP(a, <=, b)
#define BOUNCE_CHECK_GT(a, b) BOUNCE_CHECK_OP(a, >, b)
#define BOUNCE_CHECK_GE(a, b) BOUNCE_CHECK_OP(a, >=, b)

#ifdef NDEBUG
#define BOUNCE_DCHECK(condition) static_cast<void>(sizeof(static_cast<bool>(condition)))
#define BOUNCE_DCHECK_OP(a, op, b) static_cast<void>(sizeof(static_cast<bool>((a)op(b))))
#else
#define BOUNCE_DCHECK(condition) BOUNCE_CHECK(condition)
#define BOUNCE_DCHECK_OP(a, op, b) BOUNCE_CHECK_OP(a, op, b)
#endif

#define BOUNCE_DCHECK_EQ(a, b) BOUNCE_DCHECK_OP(a, ==, b)
#define BOUNCE_DCHECK_NE(a, b) BOUNCE_DCHECK_OP(a, !=, b)
#define BOUNCE_DCHECK_LT(a, b) BOUNCE_DCHECK_OP(a, <, b)
#define BOUNCE_DCHECK_LE(a, b) BOUNCE_DCHECK_OP(a, <=, b)
#define BOUNCE_DCHECK_GT(a, b) BOUNCE_DCHECK_OP(a, >, b)
#define BOUNCE_DCHECK_GE(a, b) BOUNCE_DCHECK_OP(a, >=, b)
