// SPDX-License-Identifier: MIT
// Positive control of tests/cmake/compile_fail.cmake: the same script, include
// directories and engine instantiation as tests/compile_fail/*.cpp, with the
// preset unchanged, must compile. Kept outside tests/compile_fail/ on purpose.
#include <streamclust/presets.hpp>
#include <streamclust/stream_clusterer.hpp>

struct Cfg : streamclust::CArcConfig {};

void instantiate() {
  streamclust::StreamClusterer<streamclust::CArcConfig> a;
  streamclust::StreamClusterer<Cfg> b;
  (void)a;
  (void)b;
}

int main() { instantiate(); }
