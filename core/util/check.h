// Invariant checks inside core/ (pbrt's CHECK_EQ): print both values and where, then abort.
// Compiled in for tests and non-Release builds (KDSWAP_CHECKS); user errors use kdswap::Error.
#pragma once

#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <string>

namespace kdswap::detail {

[[noreturn]] inline void checkFailed(const char* file, int line, const std::string& what) {
  std::fprintf(stderr, "kdswap: internal check failed at %s:%d: %s\n", file, line, what.c_str());
  std::abort();
}

template <typename A, typename B>
std::string describePair(const char* ea, const char* op, const char* eb, const A& a, const B& b) {
  std::ostringstream s;
  s << ea << " " << op << " " << eb << " (" << a << " vs " << b << ")";
  return s.str();
}

}  // namespace kdswap::detail

#if defined(KDSWAP_CHECKS) && KDSWAP_CHECKS
#define KDSWAP_CHECK(cond) \
  do { if (!(cond)) ::kdswap::detail::checkFailed(__FILE__, __LINE__, #cond); } while (0)
#define KDSWAP_CHECK_OP(a, op, b)                                                             \
  do {                                                                                        \
    const auto& kdswapA_ = (a);                                                               \
    const auto& kdswapB_ = (b);                                                               \
    if (!(kdswapA_ op kdswapB_))                                                              \
      ::kdswap::detail::checkFailed(__FILE__, __LINE__,                                       \
          ::kdswap::detail::describePair(#a, #op, #b, kdswapA_, kdswapB_));                   \
  } while (0)
#else
#define KDSWAP_CHECK(cond) do { (void)sizeof(cond); } while (0)
#define KDSWAP_CHECK_OP(a, op, b) do { (void)sizeof(a); (void)sizeof(b); } while (0)
#endif

#define KDSWAP_CHECK_EQ(a, b) KDSWAP_CHECK_OP(a, ==, b)
#define KDSWAP_CHECK_LE(a, b) KDSWAP_CHECK_OP(a, <=, b)
#define KDSWAP_CHECK_LT(a, b) KDSWAP_CHECK_OP(a, <, b)
#define KDSWAP_CHECK_GE(a, b) KDSWAP_CHECK_OP(a, >=, b)
