#include "app/cli/cli_grid_command.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <set>

#include "app/cli/cli_common.h"
#include "app/cli/cli_synthesis_commands.h"
#include "app/cli/cli_pipeline_commands.h"
#include "engine/base/error.h"
#include "engine/io/motion_file.h"
#include "engine/synthesize/mix_palette.h"

namespace mostyle::cli {
namespace {

namespace fs = std::filesystem;

// A take's name in the grid's output names: the file's stem, and for FILE#ANIMATION "_" and the
// animation's name with characters a file name should not hold replaced ("walks_run").
std::string take_stem(const std::string& take) {
  const TakePath tp = split_take_path(take);
  std::string stem = std::filesystem::path(tp.path).stem().string();
  if (!tp.take.empty()) {
    stem += '_';
    for (char c : tp.take)
      stem += std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_' || c == '.' ? c : '_';
  }
  return stem;
}
using Json = nlohmann::ordered_json;

// Checks one JSON string per argument so that an invalid one is named, not just refused.
std::string json_line(const std::vector<std::string>& args) {
  for (const std::string& a : args) {
    try {
      (void)Json(a).dump();
    } catch (const Json::type_error&) {
      throw InputError(a + ": the name is not valid UTF-8, which a JOBS file (JSON) cannot hold");
    }
  }
  return Json(args).dump() + "\n";
}

// Stems of the files, checked to differ: the outputs are named after them.
void check_stems(const std::vector<std::string>& files, const std::string& option) {
  std::set<std::string> stems;
  for (const std::string& f : files)
    if (!stems.insert(take_stem(f)).second)
      throw CLI::ValidationError(option, "two files are named '" + take_stem(f) +
                                             "', so their outputs would have the same names");
}

// Finite, each once, within [low, high].
void check_values(const std::vector<double>& values, const std::string& option, double low, double high) {
  std::set<std::string> seen;
  for (double v : values) {
    if (!std::isfinite(v)) throw CLI::ValidationError(option, "expected finite numbers, found " + number(v));
    if (v < low || v > high)
      throw CLI::ValidationError(option, "expected numbers from " + number(low) + " to " + number(high) +
                                             ", found " + number(v));
    if (!seen.insert(number(v)).second) throw CLI::ValidationError(option, number(v) + " is given twice");
  }
}

// The options after "--" must parse as the command's own (blend or transfer), or every job would
// fail the same way; options grid sets per job cannot be among them.
void check_job_options(const std::vector<std::string>& options, std::vector<std::string> argv,
                       const std::vector<std::string>& set_by_grid,
                       void (*add_command)(CLI::App&, std::function<int()>*)) {
  std::string names;
  for (const std::string& own : set_by_grid) names += (names.empty() ? "" : ", ") + own;
  for (const std::string& option : options)
    for (const std::string& own : set_by_grid)
      if (option == own || option.rfind(own + "=", 0) == 0)
        throw CLI::ValidationError("JOB_OPTIONS", own + " cannot be given: grid sets " + names +
                                                  " per job (one --positions-out would be shared by all)");
  CLI::App probe;
  std::function<int()> unused;
  add_command(probe, &unused);
  argv.insert(argv.end(), options.begin(), options.end());
  std::reverse(argv.begin(), argv.end());  // CLI11 takes them last first
  try {
    probe.parse(argv);
  } catch (const CLI::ParseError& e) {
    throw CLI::ValidationError("JOB_OPTIONS", e.what());
  }
}

// A job's two outputs, OUT_DIR/NAME.bvh and its report OUT_DIR/NAME.json, then the options.
std::string job_line(std::vector<std::string> job, const std::string& out_dir, const std::string& name,
                     const std::vector<std::string>& options) {
  const std::string base = (fs::path(out_dir) / name).string();
  job.insert(job.end(), {"--out", base + ".bvh", "--report", base + ".json"});
  job.insert(job.end(), options.begin(), options.end());
  return json_line(job);
}

// A transfer job's command: CONTENT [--neutral N] --style S [--strength s]; no neutral: the
// content is its own.
std::vector<std::string> transfer_job(const std::string& content, const std::string& neutral, const std::string& style,
                                      const std::string& strength = "") {
  std::vector<std::string> job{"transfer", content};
  if (!neutral.empty()) job.insert(job.end(), {"--neutral", neutral});
  job.insert(job.end(), {"--style", style});
  if (!strength.empty()) job.insert(job.end(), {"--strength", strength});
  return job;
}

// What `grid` is given.
struct GridArgs {
  std::vector<std::string> takes;
  std::vector<double> alphas;
  bool transfer = false;
  std::vector<std::string> contents, styles;
  std::string neutral;
  std::vector<double> strengths;
  std::string out_dir, jobs_out;
  std::vector<std::string> options;
};

void add_grid_options(CLI::App* cmd, GridArgs& args) {
  cmd->add_option("--takes", args.takes, "Blends: takes (BVH, FBX, glTF; FILE#ANIMATION for one animation), 2 or more; each is A with every other one as B");
  cmd->add_option("--alphas", args.alphas, "Blends: alpha values, comma separated, e.g. 0,0.25,0.5")->delimiter(',');
  cmd->add_flag("--transfer", args.transfer, "Style transfers instead of blends (--contents, --neutral, --styles, "
                                             "--strengths)");
  cmd->add_option("--contents", args.contents, "Transfers: takes (BVH, FBX, glTF, FILE#ANIMATION) that take on the styles, 1 or more");
  cmd->add_option("--neutral", args.neutral,
                  "Transfers: take of the action without the styles; without it each content is its own neutral");
  cmd->add_option("--styles", args.styles, "Transfers: takes of the action in each style, comma separated")
      ->delimiter(',');
  cmd->add_option("--strengths", args.strengths, "Transfers: strengths, comma separated, each from -1 to 2")
      ->delimiter(',');
  cmd->add_option("--out-dir", args.out_dir,
                  "Folder of the outputs (created): OUT_DIR/<A>__<B>__a<alpha>.bvh, or with --transfer "
                  "OUT_DIR/<CONTENT>__<STYLE>__s<strength>.bvh, and its report, .json")
      ->required();
  cmd->add_option("--jobs-out", args.jobs_out, "JOBS file to write (default: stdout)");
  cmd->add_option("JOB_OPTIONS", args.options,
                  "After --: blend (or with --transfer, transfer) options for every job, e.g. -- --components 4 --loop");
  cmd->footer("Each line is [\"blend\", A, B, \"--alpha\", a, \"--out\", ..., \"--report\", ..., JOB_OPTIONS], or "
              "[\"transfer\", CONTENT, \"--neutral\", N, \"--style\", S, \"--strength\", s, \"--out\", ..., "
              "\"--report\", ..., JOB_OPTIONS] (without --neutral, no \"--neutral\", N).");
}

// Bad values are usage errors (exit 2), found before any file is written.
void check_grid_args(const GridArgs& args) {
  const bool blend_given = !args.takes.empty() || !args.alphas.empty();
  const bool transfer_given =
      !args.contents.empty() || !args.neutral.empty() || !args.styles.empty() || !args.strengths.empty();
  if (!args.transfer) {
    if (transfer_given)
      throw CLI::ValidationError("--transfer", "--contents, --neutral, --styles and --strengths need --transfer");
    if (args.takes.size() < 2)
      throw CLI::ValidationError("--takes", "expected 2 or more takes, found " + std::to_string(args.takes.size()));
    if (args.alphas.empty()) throw CLI::ValidationError("--alphas", "expected alpha values, found none");
    check_stems(args.takes, "--takes");
    check_values(args.alphas, "--alphas", kMinMixWeight, kMaxMixWeight);  // as blend checks --alpha
    check_job_options(args.options, {"blend", args.takes[0], args.takes[1]},
                      {"--alpha", "--out", "--report", "--positions-out"}, &add_blend_command);
  } else {
    if (blend_given) throw CLI::ValidationError("--transfer", "--takes and --alphas are a blend grid's");
    if (args.contents.empty()) throw CLI::ValidationError("--contents", "expected 1 or more takes, found none");
    if (args.styles.empty()) throw CLI::ValidationError("--styles", "expected 1 or more takes, found none");
    if (args.strengths.empty()) throw CLI::ValidationError("--strengths", "expected strengths, found none");
    check_stems(args.contents, "--contents");
    check_stems(args.styles, "--styles");
    check_values(args.strengths, "--strengths", kMinStrength, kMaxStrength);
    check_job_options(args.options, transfer_job(args.contents[0], args.neutral, args.styles[0]),
                      {"--neutral", "--style", "--strength", "--out", "--report", "--positions-out"},
                      &add_transfer_command);
  }
}

int run_grid(const GridArgs& args) {
  std::error_code ec;
  fs::create_directories(args.out_dir, ec);
  if (ec) throw InputError(args.out_dir + ": cannot create: " + ec.message());
  std::string text;
  if (!args.transfer) {
    for (const std::string& a : args.takes)
      for (const std::string& b : args.takes) {
        if (&a == &b) continue;
        for (double alpha : args.alphas)
          text += job_line({"blend", a, b, "--alpha", number(alpha)}, args.out_dir,
                           take_stem(a) + "__" + take_stem(b) + "__a" + number(alpha), args.options);
      }
  } else {
    for (const std::string& content : args.contents)
      for (const std::string& style : args.styles)
        for (double s : args.strengths)
          text += job_line(transfer_job(content, args.neutral, style, number(s)), args.out_dir,
                           take_stem(content) + "__" + take_stem(style) + "__s" + number(s), args.options);
  }
  if (args.jobs_out.empty())
    std::cout << text;
  else
    write_output(args.jobs_out, text);
  return 0;
}

}  // namespace

void add_grid_command(CLI::App& app, std::function<int()>* run) {
  auto* cmd = app.add_subcommand(
      "grid",
      "Write a JOBS file for batch: one blend per ordered pair of different takes and alpha, or with --transfer "
      "one transfer per content, style and strength");
  auto args = std::make_shared<GridArgs>();
  add_grid_options(cmd, *args);
  cmd->callback([=] {
    check_grid_args(*args);
    *run = [=] { return run_grid(*args); };
  });
}

}  // namespace mostyle::cli
