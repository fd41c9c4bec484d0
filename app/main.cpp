// The `tsmframe` command: a thin shell over the library (docs/format.md, "Command line").
// Exit status: 0 converged to the end; 1 ran but did not reach the end (results written: a step
// failed, or Ctrl-C / SIGTERM interrupted it); 2 bad input or usage; 3 the system failed us (a
// file that cannot be written, memory run out). The outputs appear whole or not at all
// (io/output_directory.hpp).

#include <omp.h>

#include <CLI/CLI.hpp>
#include <cstdio>
#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <optional>
#include <sstream>
#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>
#include <vector>

#include "tsmframe/io/input_error.hpp"
#include "tsmframe/io/system_error.hpp"
#include "tsmframe/io/json_writer.hpp"
#include "tsmframe/io/model_drawing.hpp"
#include "tsmframe/io/model_reader.hpp"
#include "tsmframe/io/output_directory.hpp"
#include "tsmframe/io/output_file.hpp"
#include "tsmframe/io/restart_reader.hpp"
#include "tsmframe/io/results_writer.hpp"
#include "tsmframe/io/vtk_writer.hpp"
#include "tsmframe/model/mechanism.hpp"
#include "tsmframe/solver/analysis.hpp"
#include "tsmframe/solver/unloaded_mechanism.hpp"
#include "tsmframe/version.hpp"
#include "exit_codes.hpp"
#include "progress.hpp"
#include "python_script.hpp"
#include "stop_signals.hpp"
#include "study_command.hpp"

namespace {

using tsm::app::exit_bad_input;
using tsm::app::exit_converged;
using tsm::app::exit_not_converged;
using tsm::app::exit_system;

struct RunOptions {
  std::string model;
  std::string out = "out";
  bool quiet = false;
  bool log_iterations = false;
  bool vtk = false;
  bool plot = false;
  bool curves = false;  // results.json's "curves" (on with --plot, whose drawings read them)
  bool report = false;  // DIR/report.html (scripts/report_run.py, through the built Python package)
  int threads = 0;  // 0: all cores
  std::string from;  // a restart: DIR/results.json[#STEP] (empty: none)
};

std::string progress_line(const tsm::Model& model, const tsm::solver::StepRecord& step, bool log_iterations) {
  std::ostringstream os;
  os << "step " << step.step;
  if (!model.stages.empty()) os << " (stage " << step.stage + 1 << ")";
  os << (step.cut_back ? "  from load factor " : "  load factor ") << tsm::io::format_number(step.load_factor);
  os << "  iterations "
     << step.iterations << "  residual "
     << (step.residual_norms.empty() ? std::string("-") : tsm::io::format_number(step.residual_norms.back()));
  if (step.arc_length > 0.0) os << "  arc length " << tsm::io::format_number(step.arc_length);
  if (step.converged) os << " (" << tsm::solver::criterion_name(step.criterion) << ")";
  else if (step.cut_back) os << "  cut back: " << step.message;
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


/// --plot: the drawings into `directory`/plots (named as the user named the directory); false,
/// said on stderr, where they fail (then no plots/: none half drawn).
bool draw_plots(const std::filesystem::path& directory, const RunOptions& options) {
  if (tsm::app::run_script("plot_run.py", {directory.string(), options.out}, options.quiet) == 0) return true;
  std::error_code ignored;
  std::filesystem::remove_all(directory / "plots", ignored);
  std::cerr << "tsmframe: --plot failed (it needs Debian's python3-matplotlib: bash scripts/setup.sh)\n";
  return false;
}

/// --report: `directory`/report.html; false, said on stderr, where it fails (then no report.html).
bool write_report(const std::filesystem::path& directory, const RunOptions& options) {
  if (tsm::app::run_script("report_run.py", {TSMFRAME_PYTHON_DIR, directory.string(), options.model, options.out}, options.quiet) == 0)
    return true;
  std::error_code ignored;
  std::filesystem::remove(directory / "report.html", ignored);
  std::cerr << "tsmframe: --report failed (it needs the Python module and Debian's python3-matplotlib: bash scripts/setup.sh)\n";
  return false;
}

/// The run's closing lines on stderr (its notes, how it ended); returns the exit code.
int report_run(const RunOptions& options, const tsm::solver::RunResult& result) {
  int converged_steps = 0, iterations = 0;
  for (const auto& step : result.steps) {
    converged_steps += step.converged ? 1 : 0;
    iterations += step.iterations;
  }
  for (const std::string& note : result.notes) std::cerr << options.model << ": note: " << note << '\n';
  if (!options.quiet && !result.buckling.modes.empty()) {  // analysis.buckling
    std::cerr << "buckling: critical load factors";
    for (const auto& mode : result.buckling.modes) std::cerr << ' ' << mode.load_factor;
    if (result.buckling.step == 0) std::cerr << " (linearised, at the unloaded state)\n";
    else std::cerr << " (linearised, at step " << result.buckling.step << ", load factor " << result.buckling.base_load_factor << ")\n";
  }
  const std::string written = "; " + std::to_string(converged_steps) + " converged steps written to " + options.out + "/results.json";
  if (result.status == tsm::solver::Status::interrupted) {
    const char* signal = tsm::app::stop_signal_name();
    std::cerr << options.model << ": " << (signal ? signal : "stop request") << ": " << result.message << written
              << (options.plot ? " (no plots drawn)" : "") << '\n';
    return exit_not_converged;
  }
  if (result.status != tsm::solver::Status::converged) {
    std::cerr << options.model << ": did not converge (" << tsm::solver::status_name(result.status)
              << "): " << result.message << written << '\n';
    return exit_not_converged;
  }
  if (!options.quiet)
    std::cerr << "converged: " << converged_steps << " steps, " << iterations << " iterations; results in "
              << options.out << "/\n";
  return exit_converged;
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
  std::optional<tsm::solver::RestartPoint> from;
  if (!options.from.empty()) {
    try {
      from = tsm::io::read_restart_file(options.from, model);
    } catch (const tsm::io::InputError& e) {
      std::cerr << options.from << ": " << e.what() << '\n';
      return exit_bad_input;
    } catch (const tsm::io::SystemError& e) {
      std::cerr << options.from << ": " << e.what() << '\n';
      return exit_system;
    }
  }
  const tsm::solver::StopRequest& stop = tsm::app::install_stop_signals();
  // Every output goes into the temporary directory, made (and so checked) before the analysis;
  // the commit puts it in place of --out in one step.
  tsm::io::OutputDirectory output(options.out, {"results.json", "steps.csv", "vtk", "plots", "report.html"});
  // ParaView files are written as the steps converge (each step's full state exists only then).
  const std::filesystem::path vtk_dir = output.path() / "vtk";
  if (options.vtk) tsm::io::make_directories(vtk_dir.string());
  std::vector<std::pair<double, std::string>> vtk_steps;
  // On a terminal a converged step's line gives way to the next; failed attempts and the
  // iterates' log stay.
  tsm::app::LiveLine live(std::cerr, tsm::app::stderr_is_terminal() && !options.log_iterations);
  const auto observer = [&](const tsm::solver::StepRecord& step) {
    if (!options.quiet) {
      const std::string line = progress_line(model, step, options.log_iterations);
      if (step.converged) live.passing(line);
      else live.lasting(line);
    }
    if (!options.vtk || !step.converged || !step.has_state) return;
    char name[32];
    std::snprintf(name, sizeof name, "step-%05d.vtu", step.step);
    tsm::io::write_vtu((vtk_dir / name).string(), model, step);
    vtk_steps.emplace_back(step.load_factor, name);
  };
  const tsm::solver::RunResult result = tsm::solver::run_analysis(model, observer, &stop, from ? &*from : nullptr);
  live.finish();
  tsm::io::write_results(output.path().string(), model, result, {.curves = options.curves || options.plot});
  if (options.vtk) {
    tsm::io::write_pvd((vtk_dir / "results.pvd").string(), vtk_steps);
    tsm::io::write_buckling_vtu(vtk_dir.string(), model, result.buckling);
  }
  // An interrupted run is asked to end: no plots.
  const bool interrupted = result.status == tsm::solver::Status::interrupted;
  const bool plotted = !options.plot || interrupted || draw_plots(output.path(), options);
  const bool reported = !options.report || interrupted || write_report(output.path(), options);
  output.commit();
  return plotted && reported ? report_run(options, result) : exit_not_converged;
}

struct PlotOptions {
  std::string model;
  std::string out;  // empty: the model's name with .png, in the current directory
};

/// `tsmframe plot`: the model drawn before solving (python/tsmframe/model_plot.py through
/// scripts/plot_model.py). A model that is a mechanism is drawn too, and then refused as a run
/// would refuse it (exit 2): the picture is where a missing support shows.
int plot(const PlotOptions& options) {
  std::filesystem::path out = options.out.empty() ? std::filesystem::path(options.model).stem().string() + ".png" : options.out;
  const std::string extension = out.extension().string();
  if (extension != ".png" && extension != ".svg" && extension != ".pdf") {
    std::cerr << "tsmframe: --out " << out.string() << ": the picture's format is unknown (expected .png, .svg or .pdf)\n";
    return exit_bad_input;
  }
  tsm::Model model;
  try {
    model = tsm::io::read_model_file(options.model, tsm::io::Mechanisms::allow);
  } catch (const tsm::io::InputError& e) {
    std::cerr << options.model << ": " << e.what() << '\n';
    return exit_bad_input;
  }
  const std::optional<tsm::solver::Mechanism> mechanism = tsm::solver::drawn_mechanism(model);
  const std::filesystem::path drawing =
      std::filesystem::temp_directory_path() / ("tsmframe-drawing-" + std::to_string(::getpid()) + ".json");
  const std::optional<std::string> named = mechanism ? std::optional<std::string>(mechanism->text) : std::nullopt;
  tsm::io::write_output_file(drawing.string(), [&](std::ostream& os) { tsm::io::write_model_drawing(os, model, named); });
  const int drawn = tsm::app::run_script("plot_model.py", {drawing.string(), out.string()});
  std::error_code ignored;
  std::filesystem::remove(drawing, ignored);
  if (drawn == exit_system) return exit_system;  // the picture could not be written: the script said why
  if (drawn != 0) {
    std::cerr << "tsmframe: plot failed (it needs Debian's python3-matplotlib: bash scripts/setup.sh)\n";
    return exit_system;
  }
  if (mechanism) {
    std::cerr << options.model << ": " << (mechanism->at_supports ? "supports: " : "") << mechanism->text << " (drawn in "
              << out.string() << ")\n";
    return exit_bad_input;
  }
  std::cerr << "drawn: " << out.string() << '\n';
  return exit_converged;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"tsmframe: geometrically nonlinear plane frames by the Tangent Stiffness Method"};
  app.set_version_flag("--version", std::string("tsmframe ") + tsm::version);
  app.require_subcommand(1);

  RunOptions options;
  CLI::App* run_command = app.add_subcommand("run", "Analyse MODEL.json; write results.json and steps.csv");
  run_command->add_option("model", options.model, "model file (docs/format.md, tsmframe-model/1)")->required();
  run_command->add_option("-o,--out", options.out, "output directory (default: out)");
  run_command->add_flag("-q,--quiet", options.quiet, "no progress lines");
  run_command->add_option("--from", options.from,
                          "go on from a kept step of an earlier run of this model: DIR/results.json (its newest step with "
                          "state) or DIR/results.json#STEP; steps are numbered on from it");
  run_command->add_flag("--log-iterations", options.log_iterations, "print the residual of every iterate");
  run_command->add_flag("--vtk", options.vtk, "ParaView files: DIR/vtk/results.pvd and one .vtu per converged step");
  run_command->add_flag("--plot", options.plot, "plots: deformed shapes and load-displacement curves in DIR/plots/ (implies --curves)");
  run_command->add_flag("--report", options.report,
                        "DIR/report.html: the model drawn, how the run ended, shapes, load-displacement, N/V/M, buckling modes");
  run_command->add_flag("--curves", options.curves,
                        "results.json: each element's deflected curve at every step with state (\"curves\")");
  run_command->add_option("-j,--threads", options.threads, "threads for the element loop and the factorisation (default: all cores; results are identical; models under 1,000 elements use one)")
      ->check(CLI::Range(1, 1024));

  PlotOptions plot_options;
  CLI::App* plot_command = app.add_subcommand("plot", "Draw MODEL.json before solving: members, supports, hinges, springs, loads, contacts");
  plot_command->add_option("model", plot_options.model, "model file (docs/format.md, tsmframe-model/1)")->required();
  plot_command->add_option("-o,--out", plot_options.out, "the picture: .png, .svg or .pdf (default: the model's name with .png, here)");

  tsm::app::StudyOptions study_options;
  CLI::App* study_command = app.add_subcommand("study", "Run a parameter study: one row per case in study.csv and study.json");
  study_command->add_option("study", study_options.study, "study file (tsmframe-study/1, see README)")->required();
  study_command->add_option("-o,--out", study_options.out, "output directory (default: out-study)");
  study_command->add_flag("-q,--quiet", study_options.quiet, "no progress lines");
  study_command->add_option("-j,--jobs", study_options.jobs, "cases run at once (default: all cores)")->check(CLI::Range(1, 1024));
  study_command->add_flag("--resume", study_options.resume,
                          "go on from the rows of an earlier run of the same study into the same --out (stopped or killed): "
                          "only the other cases run");
  study_command->add_option("--shard", study_options.shard,
                            "run this share of the cases only, I of N (a job array's task; case k where (k - 1) mod N = I - 1); "
                            "tsmframe study-merge joins the shards");
  study_command->add_option("--scheduler", study_options.scheduler,
                            "run the cases on a Dask cluster: its scheduler's address, tcp://HOST:8786 (python3-distributed; "
                            "tsmframe importable on the workers)");

  tsm::app::MergeOptions merge_options;
  CLI::App* merge_command = app.add_subcommand("study-merge", "Join the output directories of a study's shards into the whole study's");
  merge_command->add_option("study", merge_options.study, "the study file the shards ran")->required();
  merge_command->add_option("shards", merge_options.shards, "the shards' output directories (tsmframe study --shard I/N --out DIR)")
      ->required();
  merge_command->add_option("-o,--out", merge_options.out, "output directory (default: out-study)");

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == static_cast<int>(CLI::ExitCodes::Success)) return app.exit(e);
    std::cerr << "tsmframe: " << e.what() << " (see tsmframe --help)\n";
    return exit_bad_input;
  }
  try {
    if (run_command->parsed()) return run(options);
    if (study_command->parsed()) return tsm::app::study(study_options);
    if (merge_command->parsed()) return tsm::app::study_merge(merge_options);
    if (plot_command->parsed()) return plot(plot_options);
  } catch (const tsm::io::SystemError& e) {
    std::cerr << "tsmframe: " << e.what() << '\n';
    return exit_system;
  } catch (const tsm::io::InputError& e) {  // an --out that may not be replaced (the inputs' own: above)
    std::cerr << "tsmframe: " << e.what() << '\n';
    return exit_bad_input;
  } catch (const std::bad_alloc&) {
    std::cerr << "tsmframe: out of memory (the machine has less than this run needs)\n";
    return exit_system;
  } catch (const std::exception& e) {
    std::cerr << "tsmframe: internal error: " << e.what() << '\n';
    return exit_not_converged;
  }
  return exit_bad_input;
}
