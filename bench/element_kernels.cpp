// Google Benchmark of the per-element kernel (force law, chord, J, K_G, tangent).
#include <benchmark/benchmark.h>

#include "tsmframe/element/beam_element.hpp"

static void BM_BeamResponse(benchmark::State& state) {
  using namespace tsm::element;
  const InitialChord chord = initial_chord({0.0, 0.0}, {0.5, 0.0});
  const Matrix3 s = basic_stiffness({.EA = 2e9, .EI = 1.7e6, .shear_flexibility = 2.6e-3}, chord.length);
  Vector6 d;
  d << 0.01, 0.02, 0.3, -0.02, 0.1, 0.5;
  const bool with_tangent = state.range(0) != 0;
  for (auto _ : state) {
    BeamResponse r = beam_response(chord, s, d, 0.1, with_tangent);
    benchmark::DoNotOptimize(r);
  }
}
BENCHMARK(BM_BeamResponse)->Arg(0)->Arg(1);

BENCHMARK_MAIN();
