// cutaway/scene/benchmark_city.hpp — a generated city at the size of Konev18's Table 1
// (1190 pipes of 4.6 nodes on average, 1156 shafts, a 2.9M-triangle terrain), or `scale`
// times that, for `cutaway bench --city`: streets on a jittered grid, each pipe a walk of 2–6
// segments under them at 2–4 m, cut open over its middle, shafts at the pipes' starts, the
// terrain a noise-displaced grid opened above the network (§4), a soil quad below it.
//
//   cutaway::Scene city = cutaway::benchmarkCity({.scale = 10});
#pragma once

#include <cstdint>

#include "cutaway/scene/scene.hpp"

namespace cutaway {

struct BenchmarkCityOptions {
  int scale = 1;  // multiplies pipes, shafts, terrain triangles and area
  std::uint32_t seed = 1;
};

Scene benchmarkCity(const BenchmarkCityOptions& options);

}  // namespace cutaway
