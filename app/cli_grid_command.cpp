#include "app/cli_grid_command.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <set>

#include "app/cli_common.h"
#include "app/cli_pipeline_commands.h"
#include "engine/io/error.h"

namespace mostyle::cli {
namespace {

namespace fs = std::filesystem;
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

}  // namespace

void add_grid_command(CLI::App& app, std::function<int()>* run) {
  auto* cmd = app.add_subcommand(
      "grid", "Write a JOBS file for batch: one blend per ordered pair of different takes and alpha");
  struct Args {
    std::vector<std::string> takes;
    std::vector<double> alphas;
    std::string out_dir, jobs_out;
    std::vector<std::string> blend_options;
  };
  auto args = std::make_shared<Args>();
  cmd->add_option("--takes", args->takes, "BVH takes, 2 or more; each is A with every other one as B")->required();
  cmd->add_option("--alphas", args->alphas, "Alpha values, comma separated, e.g. 0,0.25,0.5")
      ->required()
      ->delimiter(',');
  cmd->add_option("--out-dir", args->out_dir,
                  "Folder of the outputs (created): OUT_DIR/<A>__<B>__a<alpha>.bvh and its report, .json")
      ->required();
  cmd->add_option("--jobs-out", args->jobs_out, "JOBS file to write (default: stdout)");
  cmd->add_option("BLEND_OPTIONS", args->blend_options,
                  "After --: blend options for every job, e.g. -- --components 4 --loop");
  cmd->footer("Each line is [\"blend\", A, B, \"--alpha\", a, \"--out\", ..., \"--report\", ..., BLEND_OPTIONS]. "
              "A grid of style transfers will come with the transfer subcommand.");
  cmd->callback([=] {
    // Bad values are usage errors (exit 2), found before any file is written.
    if (args->takes.size() < 2)
      throw CLI::ValidationError("--takes", "expected 2 or more takes, found " + std::to_string(args->takes.size()));
    std::set<std::string> stems, alphas;
    for (const std::string& t : args->takes)
      if (!stems.insert(fs::path(t).stem().string()).second)
        throw CLI::ValidationError("--takes", "two takes are named '" + fs::path(t).stem().string() +
                                                  "', so their outputs would have the same names");
    for (double a : args->alphas) {
      if (!std::isfinite(a)) throw CLI::ValidationError("--alphas", "expected finite numbers, found " + number(a));
      if (!alphas.insert(number(a)).second) throw CLI::ValidationError("--alphas", number(a) + " is given twice");
    }
    for (const std::string& option : args->blend_options)
      for (const char* own : {"--alpha", "--out", "--report", "--positions-out"})
        if (option == own || option.rfind(std::string(own) + "=", 0) == 0)
          throw CLI::ValidationError("BLEND_OPTIONS", std::string(own) +
                                                          " cannot be given: grid sets --alpha, --out and --report "
                                                          "per job, and one --positions-out would be shared by all");
    // The options must parse as blend's, or every job would fail the same way.
    CLI::App probe;
    std::function<int()> unused;
    add_blend_command(probe, &unused);
    std::vector<std::string> argv = {"blend", args->takes[0], args->takes[1]};
    argv.insert(argv.end(), args->blend_options.begin(), args->blend_options.end());
    std::reverse(argv.begin(), argv.end());  // CLI11 takes them last first
    try {
      probe.parse(argv);
    } catch (const CLI::ParseError& e) {
      throw CLI::ValidationError("BLEND_OPTIONS", e.what());
    }
    *run = [=] {
      std::error_code ec;
      fs::create_directories(args->out_dir, ec);
      if (ec) throw InputError(args->out_dir + ": cannot create: " + ec.message());
      std::string text;
      for (size_t i = 0; i < args->takes.size(); ++i)
        for (size_t j = 0; j < args->takes.size(); ++j) {
          if (i == j) continue;
          const std::string& a = args->takes[i];
          const std::string& b = args->takes[j];
          for (double alpha : args->alphas) {
            const std::string name =
                fs::path(a).stem().string() + "__" + fs::path(b).stem().string() + "__a" + number(alpha);
            const std::string base = (fs::path(args->out_dir) / name).string();
            std::vector<std::string> job = {"blend", a, b, "--alpha", number(alpha), "--out", base + ".bvh",
                                            "--report", base + ".json"};
            job.insert(job.end(), args->blend_options.begin(), args->blend_options.end());
            text += json_line(job);
          }
        }
      if (args->jobs_out.empty())
        std::cout << text;
      else
        write_output(args->jobs_out, text);
      return 0;
    };
  });
}

}  // namespace mostyle::cli
