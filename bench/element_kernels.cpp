// Google Benchmark of the per-element kernel (force law, chord, J, K_G, tangent).
#include <benchmark/benchmark.h>

#include "tsmframe/contact/contact_response.hpp"
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

// One contact point on an element (the press's: a 3-cm element of a stiff beam, the point near
// its middle), along the chord's normal (0) or the bent beam's (1), with the tangent.
static void BM_ContactResponse(benchmark::State& state) {
  using namespace tsm;
  contact::ContactElementData data;
  data.initial = element::initial_chord({0.0, 0.0}, {1.0 / 30.0, 0.0});
  data.section = {.EA = 2e9, .EI = 4e6, .shear_flexibility = 2.6e-5};
  data.k0 = element::basic_stiffness(data.section, data.initial.length);
  data.contact_start = {0.013, 0.01};
  data.offset = 0.01;
  data.min_compliance = 4e-13;
  data.normal = state.range(0) != 0 ? ContactNormal::deflected : ContactNormal::chord;
  contact::Vector9 d;
  d << 1e-4, -2e-3, 1e-3, 2e-4, -2.1e-3, 2e-3, 1e-4, -1.2e-2, 0.0;
  for (auto _ : state) {
    contact::ContactResponse r = contact::contact_response(data, d, 0.0, true);
    benchmark::DoNotOptimize(r);
  }
}
BENCHMARK(BM_ContactResponse)->Arg(0)->Arg(1);

BENCHMARK_MAIN();
