// SPDX-License-Identifier: MIT
// doctest main of streamclust_fma_tests: the linkage tests built with FMA
// instructions and -ffp-contract=fast (tests/CMakeLists.txt). On a CPU
// without FMA the binary cannot run them: it exits 77, which CTest reports
// as skipped.
#define DOCTEST_CONFIG_IMPLEMENT
#include <doctest/doctest.h>

#include <cstdio>

int main(int argc, char** argv) {
#if defined(__GNUC__) && (defined(__x86_64__) || defined(__i386__))
  if (!__builtin_cpu_supports("fma")) {
    std::puts("streamclust_fma_tests: this CPU has no FMA instructions; skipped");
    return 77;
  }
#endif
  return doctest::Context(argc, argv).run();
}
