// The memory estimate against the peak it estimates (README, "Memory"): reads a model file as
// `tsmframe run` does, but within no budget, prints the estimate and its parts, then (unless
// --estimate-only) runs the analysis and prints the peak resident memory and estimate / peak.
// Usage: tsmframe_memory MODEL.json [--estimate-only]
#include <sys/resource.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <exception>
#include <nlohmann/json.hpp>

#include "tsmframe/io/input_file.hpp"
#include "tsmframe/io/json_input.hpp"
#include "tsmframe/io/memory_budget.hpp"
#include "tsmframe/io/model_reader.hpp"
#include "tsmframe/solver/analysis.hpp"

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: tsmframe_memory MODEL.json [--estimate-only]\n");
    return 2;
  }
  try {
    tsm::Model model;
    double bytes = 0.0;
    {
      nlohmann::json document;
      {
        const std::string text = tsm::io::read_input_file(argv[1]);
        bytes = static_cast<double>(text.size());
        document = tsm::io::parse_json(text);
      }
      model = tsm::io::read_model(document, {INFINITY, "no limit"}, bytes);
    }
    const tsm::MemoryEstimate estimate = tsm::estimate_memory(tsm::model_counts(model, bytes));
    std::printf("estimate %s:", tsm::io::bytes_text(estimate.total()).c_str());
    for (const tsm::MemoryPart& p : estimate.parts()) std::printf(" %s %s;", p.name.c_str(), tsm::io::bytes_text(p.bytes).c_str());
    std::printf("\n");
    if (argc > 2 && std::strcmp(argv[2], "--estimate-only") == 0) return 0;
    const tsm::solver::RunResult result = tsm::solver::run_analysis(model);
    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    const double peak = 1024.0 * static_cast<double>(usage.ru_maxrss);
    std::printf("peak %s (%s, %zu steps): estimate / peak %.2f\n", tsm::io::bytes_text(peak).c_str(),
                tsm::solver::status_name(result.status), result.steps.size(), estimate.total() / peak);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: %s\n", argv[1], e.what());
    return 2;
  }
  return 0;
}
