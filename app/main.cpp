// towsim: the command-line front end (docs/contract.md §U2). Argument parsing only;
// each subcommand is registered by its own add_*_command function and runs a
// function of app/commands.hpp. Exit statuses: see ExitStatus.
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <csignal>
#include <iostream>
#include <memory>
#include <type_traits>

#include "commands.hpp"
#include "plot.hpp"
#include "report.hpp"
#include "sweep.hpp"
#include "towsim/version.hpp"

namespace {

using namespace towsim::cli;

static_assert(std::is_same_v<std::sig_atomic_t, int>, "stop flag is passed to simulate() as volatile int");

/// Set by SIGINT/SIGTERM; simulate() polls it and stops cleanly.
volatile std::sig_atomic_t g_stop = 0;

extern "C" void on_stop_signal(int sig) {
  g_stop = 1;
  std::signal(sig, SIG_DFL);  // a second signal ends the program at once
}

/// Add the scenario inputs shared by run and check: SCENARIO, --example, --set.
void add_input_options(CLI::App* cmd, InputOptions& in) {
  cmd->add_option("scenario", in.scenario, "Scenario file (YAML)");
  cmd->add_option("--example", in.example, "Use a built-in example instead (see `towsim examples`)");
  cmd->add_option("--set", in.sets, "Override a scenario value: KEY=VALUE, KEY a dotted path (repeatable)")
      ->allow_extra_args(false)
      ->type_name("KEY=VALUE");
}

/// Require exactly one of SCENARIO and --example.
void require_one_input(const InputOptions& in) {
  if (in.scenario.empty() == in.example.empty())
    throw CLI::ValidationError("give exactly one of SCENARIO or --example NAME");
}

/// `towsim run SCENARIO.yaml --out DIR [--set K=V]... [--quiet]`.
void add_run_command(CLI::App& app, int& status) {
  auto opts = std::make_shared<RunOptions>();
  CLI::App* cmd = app.add_subcommand("run", "Simulate a scenario and write the output files into DIR");
  add_input_options(cmd, opts->input);
  cmd->add_option("--out,-o", opts->out_dir, "Output directory (created if missing)")->required();
  cmd->add_flag("--quiet,-q", opts->quiet, "Print nothing but errors");
  cmd->callback([opts, &status] {
    require_one_input(opts->input);
    opts->progress = !opts->quiet && ::isatty(STDERR_FILENO) == 1;
    std::signal(SIGINT, on_stop_signal);
    std::signal(SIGTERM, on_stop_signal);
    status = run_command(*opts, std::cout, std::cerr, &g_stop);
  });
}

/// `towsim check SCENARIO.yaml [--set K=V]...`.
void add_check_command(CLI::App& app, int& status) {
  auto in = std::make_shared<InputOptions>();
  CLI::App* cmd = app.add_subcommand("check", "Validate a scenario and print derived quantities (no simulation)");
  add_input_options(cmd, *in);
  cmd->callback([in, &status] {
    require_one_input(*in);
    status = check_command(*in, std::cout, std::cerr);
  });
}

/// `towsim examples [NAME]`.
void add_examples_command(CLI::App& app, int& status) {
  auto name = std::make_shared<std::string>();
  CLI::App* cmd = app.add_subcommand("examples", "List the built-in examples, or print one as YAML");
  cmd->add_option("name", *name, "Example to print");
  cmd->callback([name, &status] { status = examples_command(*name, std::cout, std::cerr); });
}

/// `towsim plot DIR`: figures of a run's outputs (app/plot.cpp).
void add_plot_command(CLI::App& app, int& status) {
  auto dir = std::make_shared<std::string>();
  auto opts = std::make_shared<PlotOptions>();
  CLI::App* cmd = app.add_subcommand("plot", "Render figures of a run's outputs into DIR/plots (gnuplot)");
  cmd->add_option("dir", *dir, "Output directory of `towsim run`")->required();
  cmd->add_option("--width", opts->width, "Figure width [pixels]")->check(CLI::Range(200, 8000));
  cmd->add_option("--height", opts->height, "Figure height [pixels]")->check(CLI::Range(150, 8000));
  cmd->add_option("--snapshots", opts->snapshots, "Cable shapes drawn in cable_shapes_*")->check(CLI::Range(1, 100));
  cmd->callback([dir, opts, &status] { status = plot_run(*dir, std::cerr, *opts); });
}

/// `towsim report DIR`: DIR/report.html (src/io/report.cpp).
void add_report_command(CLI::App& app, int& status) {
  auto dir = std::make_shared<std::string>();
  auto opts = std::make_shared<ReportOptions>(default_report_options());
  auto no_plots = std::make_shared<bool>(false);
  CLI::App* cmd = app.add_subcommand(
      "report", "Write DIR/report.html: a self-contained page with a 3-D view, the figures and the summary");
  cmd->add_option("dir", *dir, "Output directory of `towsim run` or `towsim statics --out`")->required();
  cmd->add_option("--frames", opts->max_frames, "Animation frames (spread over the output times)")
      ->check(CLI::Range(1, 5000));
  cmd->add_flag("--no-plots", *no_plots, "Use DIR/plots as it is instead of rendering the figures first");
  cmd->callback([dir, opts, no_plots, &status] {
    opts->plots = !*no_plots;
    status = report_run(*dir, std::cerr, *opts);
  });
}

/// `towsim statics SCENARIO.yaml [--set K=V]... [--out DIR]`.
void add_statics_command(CLI::App& app, int& status) {
  auto opts = std::make_shared<StaticsOptions>();
  CLI::App* cmd = app.add_subcommand("statics", "Steady-tow equilibrium at the tow law's final speed");
  add_input_options(cmd, opts->input);
  cmd->add_option("--out,-o", opts->out_dir, "Write the configuration (timeseries.csv, nodes.csv) here");
  cmd->add_option("--target-depth", opts->target_depth,
                  "Find the deployed cable length that puts the body (or the cable end) at this depth [m]");
  cmd->add_option("--trim", opts->trim_body,
                  "Find the link point (link_point x) that gives this body (an in-line body's name, or 'body') "
                  "the pitch of --trim-pitch");
  cmd->add_option("--trim-pitch", opts->trim_pitch, "The pitch --trim looks for [deg] (default 0: level)");
  cmd->add_option("--line", opts->line,
                  "A network's line from the vessel whose length --target-depth varies (for the deepest body below "
                  "it); needed when several lines hang from the vessel");
  cmd->callback([opts, &status] {
    require_one_input(opts->input);
    std::signal(SIGINT, on_stop_signal);
    std::signal(SIGTERM, on_stop_signal);
    status = statics_command(*opts, std::cout, std::cerr, &g_stop);
  });
}

/// `towsim sweep SWEEP.yaml --out DIR [--jobs N] [--quiet]`.
void add_sweep_command(CLI::App& app, int& status) {
  auto opts = std::make_shared<SweepOptions>();
  CLI::App* cmd = app.add_subcommand("sweep", "Run a base scenario over a grid or list of overrides; DIR/sweep.csv");
  cmd->add_option("sweep", opts->file, "Sweep file (YAML; docs/scenario.md \"Sweeps\")")->required();
  cmd->add_option("--out,-o", opts->out_dir, "Output directory (created if missing)")->required();
  cmd->add_option("--jobs,-j", opts->jobs, "Cases run at once (default: every core)")->check(CLI::Range(1, 4096));
  cmd->add_flag("--quiet,-q", opts->quiet, "Print nothing but errors");
  cmd->callback([opts, &status] {
    std::signal(SIGINT, on_stop_signal);
    std::signal(SIGTERM, on_stop_signal);
    status = sweep_command(*opts, std::cout, std::cerr, &g_stop);
  });
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"towsim: simulator of underwater towed cables and towed bodies"};
  app.require_subcommand(1);
  app.set_version_flag("--version", std::string("towsim ") + towsim::kVersion, "Print the version and exit");
  int status = kExitOk;
  add_run_command(app, status);
  add_check_command(app, status);
  add_examples_command(app, status);
  add_plot_command(app, status);
  add_statics_command(app, status);
  add_report_command(app, status);
  add_sweep_command(app, status);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int rc = app.exit(e);
    return rc == 0 ? kExitOk : kExitInvalid;
  }
  return status;
}
