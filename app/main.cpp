// The `tsmframe` command: a thin shell over the library (FORMAT.md, "Command line").
// Exit status: 0 converged to the end; 1 ran but did not reach the end (results written); 2 bad
// input or usage; 3 the system failed us (a file that cannot be written, memory run out).

#include <omp.h>

#include <CLI/CLI.hpp>
#include <cstdio>
#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <sstream>

#include "tsmframe/io/input_error.hpp"
#include "tsmframe/io/system_error.hpp"
#include "tsmframe/io/json_writer.hpp"
#include "tsmframe/io/model_reader.hpp"
#include "tsmframe/io/results_writer.hpp"
#include "tsmframe/io/vtk_writer.hpp"
#include "tsmframe/solver/analysis.hpp"
#include "tsmframe/study/study_runner.hpp"
#include "tsmframe/study/study_writer.hpp"
#include "tsmframe/version.hpp"

namespace {

constexpr int exit_converged = 0;
constexpr int exit_not_converged = 1;
constexpr int exit_bad_input = 2;
constexpr int exit_system = 3;

struct RunOptions {
  std::string model;
  std::string out = "out";
  bool quiet = false;
  bool log_iterations = false;
  bool vtk = false;
  bool plot = false;
  bool curves = false;  // results.json's "curves" (on with --plot, whose drawings read them)
  int threads = 0;  // 0: all cores
};

std::string progress_line(const tsm::Model& model, const tsm::solver::StepRecord& step, bool log_iterations) {
  std::ostringstream os;
  os << "step " << step.step << "  load factor " << tsm::io::format_number(step.load_factor) << "  iterations "
     << step.iterations << "  residual "
     << (step.residual_norms.empty() ? std::string("-") : tsm::io::format_number(step.residual_norms.back()));
  if (step.arc_length > 0.0) os << "  arc length " << tsm::io::format_number(step.arc_length);
  if (step.converged) os << " (" << tsm::solver::criterion_name(step.criterion) << ")";
  else os << "  FAILED: " << step.message;
  if (step.cutbacks > 0) os << "  after " << step.cutbacks << " cutbacks";
  if (log_iterations) {
    os << "\n  residual per iterate:";
    for (double r : step.residual_norms) os << ' ' << tsm::io::format_number(r);
    // How many contacts touch at each iterate, then α of each contact that touched at some
    // iterate: element:α (element:α+other at a vertex), or "-" when the node is not in contact.
    const auto& iterates = step.contact_iterates;
    if (!iterates.empty() && !iterates.front().empty()) {
      os << "\n  contacts in touch per iterate:";
      for (const auto& iterate : iterates)
        os << ' ' << std::count_if(iterate.begin(), iterate.end(), [](const tsm::solver::ContactPoint& p) { return p.element >= 0; });
    }
    for (size_t c = 0; !iterates.empty() && c < iterates.front().size(); ++c) {
      if (std::none_of(iterates.begin(), iterates.end(), [&](const auto& iterate) { return iterate[c].element >= 0; }))
        continue;
      os << "\n  contact at node " << model.nodes[model.contacts[c].node].id << " element:alpha per iterate:";
      for (const auto& iterate : iterates) {
        const tsm::solver::ContactPoint& p = iterate[c];
        if (p.element < 0) os << " -";
        else os << ' ' << p.element + 1 << ':' << tsm::io::format_number(p.alpha);
        if (p.partner >= 0) os << '+' << p.partner + 1;
      }
    }
  }
  return os.str();
}

int run(const RunOptions& options) {
  if (options.threads > 0) omp_set_num_threads(options.threads);
  tsm::Model model;
  try {
    model = tsm::io::read_model_file(options.model);
  } catch (const tsm::io::InputError& e) {
    std::cerr << options.model << ": " << e.what() << '\n';
    return exit_bad_input;
  }
  // ParaView files are written as the steps converge (each step's full state exists only then).
  const std::filesystem::path vtk_dir = std::filesystem::path(options.out) / "vtk";
  std::vector<std::pair<double, std::string>> vtk_steps;
  std::string vtk_error;
  if (options.vtk) {
    std::error_code error;
    std::filesystem::create_directories(vtk_dir, error);
    if (error) vtk_error = vtk_dir.string() + ": " + error.message();
  }
  const auto observer = [&](const tsm::solver::StepRecord& step) {
    if (!options.quiet) std::cerr << progress_line(model, step, options.log_iterations) << std::endl;
    if (!options.vtk || !vtk_error.empty() || !step.converged || !step.has_state) return;
    char name[32];
    std::snprintf(name, sizeof name, "step-%05d.vtu", step.step);
    try {
      tsm::io::write_vtu((vtk_dir / name).string(), model, step);
      vtk_steps.emplace_back(step.load_factor, name);
    } catch (const std::exception& e) {
      vtk_error = e.what();
    }
  };
  const tsm::solver::RunResult result = tsm::solver::run_analysis(model, observer);
  try {
    tsm::io::write_results(options.out, model, result, {.curves = options.curves || options.plot});
    if (options.vtk && vtk_error.empty()) tsm::io::write_pvd((vtk_dir / "results.pvd").string(), vtk_steps);
  } catch (const std::exception& e) {
    std::cerr << "tsmframe: " << e.what() << '\n';
    return exit_bad_input;
  }
  if (!vtk_error.empty()) {
    std::cerr << "tsmframe: ParaView files not written: " << vtk_error << '\n';
    return exit_not_converged;
  }
  if (options.plot) {
    const std::string command = std::string("/usr/bin/python3 \"") + TSMFRAME_SCRIPTS_DIR + "/plot_run.py\" \"" +
                                options.out + "\"" + (options.quiet ? " >/dev/null" : "");
    if (std::system(command.c_str()) != 0) {
      std::cerr << "tsmframe: --plot failed (it needs Debian's python3-matplotlib: bash scripts/setup.sh)\n";
      return exit_not_converged;
    }
  }
  int converged_steps = 0, iterations = 0;
  for (const auto& step : result.steps) {
    converged_steps += step.converged ? 1 : 0;
    iterations += step.iterations;
  }
  for (const std::string& note : result.notes) std::cerr << options.model << ": note: " << note << '\n';
  if (result.status != tsm::solver::Status::converged) {
    std::cerr << options.model << ": did not converge (" << tsm::solver::status_name(result.status)
              << "): " << result.message << "; " << converged_steps << " converged steps written to "
              << options.out << "/results.json\n";
    return exit_not_converged;
  }
  if (!options.quiet)
    std::cerr << "converged: " << converged_steps << " steps, " << iterations << " iterations; results in "
              << options.out << "/\n";
  return exit_converged;
}

struct StudyOptions {
  std::string study;
  std::string out = "out/study";
  bool quiet = false;
  int jobs = 0;  // 0: all cores
};

int study(const StudyOptions& options) {
  omp_set_num_threads(1);  // the cases run in parallel; each one on one thread
  tsm::study::Study definition;
  try {
    definition = tsm::study::read_study_file(options.study);
  } catch (const tsm::io::InputError& e) {
    std::cerr << options.study << ": " << e.what() << '\n';
    return exit_bad_input;
  }
  const size_t total = definition.case_count();
  size_t done = 0;
  const auto progress = [&](const tsm::study::CaseResult& row) {
    ++done;
    if (options.quiet) return;
    std::cerr << "case " << row.index + 1 << '/' << total;
    for (size_t p = 0; p < definition.parameters.size(); ++p)
      std::cerr << "  " << definition.parameters[p].name << ' ' << definition.parameters[p].labels[row.choice[p]];
    std::cerr << "  " << row.status << "  " << row.steps << " steps, " << row.iterations << " iterations  [" << done
              << " done]\n";
  };
  const std::vector<tsm::study::CaseResult> rows = tsm::study::run_study(definition, options.jobs, options.out, progress);
  try {
    tsm::study::write_study(options.out, definition, rows);
  } catch (const std::exception& e) {
    std::cerr << "tsmframe: " << e.what() << '\n';
    return exit_bad_input;
  }
  const auto bad = [](const tsm::study::CaseResult& r) { return r.status == "bad-input"; };
  const size_t failed = std::count_if(rows.begin(), rows.end(), [](const auto& r) { return !r.converged; });
  const size_t invalid = std::count_if(rows.begin(), rows.end(), bad);
  std::cerr << options.study << ": " << rows.size() << " cases, " << failed - invalid << " did not converge";
  // A model the sweep made invalid is most often a typo in the study (a path to a key the model
  // does not have): the first such case's reason, on the terminal, not only in the rows.
  if (invalid > 0) {
    const auto first = std::find_if(rows.begin(), rows.end(), bad);
    std::cerr << ", " << invalid << " had a model the sweep made invalid (bad-input; case " << first->index + 1 << ": "
              << first->message << ")";
  }
  std::cerr << "; rows in " << options.out << "/study.csv and study.json\n";
  return failed == 0 ? exit_converged : exit_not_converged;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"tsmframe: geometrically nonlinear plane frames by the Tangent Stiffness Method"};
  app.set_version_flag("--version", std::string("tsmframe ") + tsm::version);
  app.require_subcommand(1);

  RunOptions options;
  CLI::App* run_command = app.add_subcommand("run", "Analyse MODEL.json; write results.json and steps.csv");
  run_command->add_option("model", options.model, "model file (FORMAT.md, tsmframe-model/1)")->required();
  run_command->add_option("-o,--out", options.out, "output directory (default: out)");
  run_command->add_flag("-q,--quiet", options.quiet, "no progress lines");
  run_command->add_flag("--log-iterations", options.log_iterations, "print the residual of every iterate");
  run_command->add_flag("--vtk", options.vtk, "ParaView files: DIR/vtk/results.pvd and one .vtu per converged step");
  run_command->add_flag("--plot", options.plot, "plots: deformed shapes and load-displacement curves in DIR/plots/ (implies --curves)");
  run_command->add_flag("--curves", options.curves,
                        "results.json: each element's deflected curve at every step with state (\"curves\")");
  run_command->add_option("-j,--threads", options.threads, "threads for the element loop and the factorisation (default: all cores; results are identical; models under 1,000 elements use one)")
      ->check(CLI::Range(1, 1024));

  StudyOptions study_options;
  CLI::App* study_command = app.add_subcommand("study", "Run a parameter study: one row per case in study.csv and study.json");
  study_command->add_option("study", study_options.study, "study file (tsmframe-study/1, see README)")->required();
  study_command->add_option("-o,--out", study_options.out, "output directory (default: out/study)");
  study_command->add_flag("-q,--quiet", study_options.quiet, "no progress lines");
  study_command->add_option("-j,--jobs", study_options.jobs, "cases run at once (default: all cores)")->check(CLI::Range(1, 1024));

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == static_cast<int>(CLI::ExitCodes::Success)) return app.exit(e);
    std::cerr << "tsmframe: " << e.what() << " (see tsmframe --help)\n";
    return exit_bad_input;
  }
  try {
    if (run_command->parsed()) return run(options);
    if (study_command->parsed()) return study(study_options);
  } catch (const tsm::io::SystemError& e) {
    std::cerr << "tsmframe: " << e.what() << '\n';
    return exit_system;
  } catch (const std::bad_alloc&) {
    std::cerr << "tsmframe: out of memory (the machine has less than this run needs)\n";
    return exit_system;
  } catch (const std::exception& e) {
    std::cerr << "tsmframe: internal error: " << e.what() << '\n';
    return exit_not_converged;
  }
  return exit_bad_input;
}
