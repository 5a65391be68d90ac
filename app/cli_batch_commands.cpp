#include "app/cli_batch_commands.h"

#include <algorithm>
#include <charconv>
#include <chrono>
#include <cmath>
#include <cctype>
#include <filesystem>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <set>
#include <thread>

#include "app/cli_common.h"
#include "app/cli_pipeline_commands.h"
#include "app/job_line.h"
#include "app/job_runner.h"
#include "engine/io/motion_file.h"
#include "engine/io/atomic_file.h"
#include "engine/io/error.h"

namespace mostyle::cli {
namespace {

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

namespace fs = std::filesystem;
using Json = nlohmann::ordered_json;
using Clock = std::chrono::steady_clock;

struct Shard {
  int index = 0;  // 0 <= index < count
  int count = 1;
};

bool parse_int(std::string_view text, int* v) {
  const auto r = std::from_chars(text.data(), text.data() + text.size(), *v);
  return r.ec == std::errc() && r.ptr == text.data() + text.size();
}

// "I/N" with 0 <= I < N; false on anything else.
bool parse_shard(const std::string& text, Shard* shard) {
  const size_t slash = text.find('/');
  if (slash == std::string::npos) return false;
  const std::string_view all = text;
  return parse_int(all.substr(0, slash), &shard->index) && parse_int(all.substr(slash + 1), &shard->count) &&
         shard->count >= 1 && shard->index >= 0 && shard->index < shard->count;
}

// One non-empty line of JOBS: the arguments of one mostyle-cli command, or why it is not one.
struct JobLine {
  int line = 0;                   // 1-based line number in JOBS
  std::vector<std::string> args;  // empty when error is set
  std::string error;              // "JOBS:LINE: what is wrong" when the line is not a job
};

std::vector<JobLine> parse_jobs(const std::string& text, const std::string& path) {
  std::vector<JobLine> jobs;
  int number = 0;
  for (size_t begin = 0; begin < text.size();) {
    const size_t end = std::min(text.find('\n', begin), text.size());
    const std::string line = text.substr(begin, end - begin);
    begin = end + 1;
    ++number;
    if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
    JobLine job;
    job.line = number;
    try {
      job.args = parse_job_line(line, path, number);
    } catch (const InputError& e) {
      job.error = e.what();  // a failed job of its own; the other lines still run
    }
    jobs.push_back(std::move(job));
  }
  return jobs;
}

std::string plural(size_t n, const std::string& word) {
  return std::to_string(n) + " " + word + (n == 1 ? "" : "s");
}

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

// The jobs of one shard and how each went, in JOBS order.
struct ShardRun {
  std::vector<JobLine> jobs;
  std::vector<JobResult> results;  // results[k]: how jobs[k] went
  std::vector<int> failed_lines;   // lines (from 1) of the failed jobs, in order
  double seconds = 0.0;            // wall time, reading JOBS included
};

// Reads JOBS (InputError when it cannot) and runs the shard's jobs; a line that is not a job is
// a failed job with its parse error.
ShardRun run_shard(const std::string& jobs_file, const Shard& shard, const JobRunnerOptions& o) {
  const auto t0 = Clock::now();
  ShardRun r;
  const std::vector<JobLine> all = parse_jobs(read_file(jobs_file), jobs_file);
  for (size_t k = 0; k < all.size(); ++k)
    if (static_cast<int>(k % static_cast<size_t>(shard.count)) == shard.index) r.jobs.push_back(all[k]);
  std::vector<std::vector<std::string>> commands;
  std::vector<size_t> slot;  // slot[k]: the index in r.jobs of commands[k]
  r.results.resize(r.jobs.size());
  for (size_t k = 0; k < r.jobs.size(); ++k) {
    r.results[k].error = r.jobs[k].error;
    if (!r.jobs[k].error.empty()) continue;
    commands.push_back(r.jobs[k].args);
    slot.push_back(k);
  }
  const std::vector<JobResult> ran = run_jobs(commands, o);
  for (size_t k = 0; k < ran.size(); ++k) r.results[slot[k]] = ran[k];
  for (size_t k = 0; k < r.jobs.size(); ++k)
    if (!r.results[k].ok) r.failed_lines.push_back(r.jobs[k].line);
  r.seconds = std::chrono::duration<double>(Clock::now() - t0).count();
  return r;
}

Json records_json(const ShardRun& r) {
  Json records = Json::array();
  for (size_t k = 0; k < r.jobs.size(); ++k) {
    Json record;
    record["line"] = r.jobs[k].line;
    record["args"] = r.jobs[k].args;
    record["status"] = r.results[k].ok ? "ok" : "failed";
    record["error"] = r.results[k].error;
    record["seconds"] = r.results[k].seconds;
    records.push_back(record);
  }
  return records;
}

// The failures, one line each naming JOBS:LINE, then the totals.
// of_shard: "" or " of shard I/N".
void print_summary(const ShardRun& r, const std::string& jobs_file, const std::string& of_shard, int parallel) {
  for (size_t k = 0; k < r.jobs.size(); ++k) {
    if (r.results[k].ok) continue;
    const JobLine& job = r.jobs[k];
    // A line that is not a job already has its error naming JOBS:LINE.
    if (!job.error.empty())
      std::cout << job.error << "\n";
    else
      std::cout << jobs_file << ":" << job.line << ": " << job.args[0] << " failed: " << r.results[k].error << "\n";
  }
  std::cout << jobs_file << of_shard << ": " << plural(r.jobs.size(), "job") << ", "
            << r.jobs.size() - r.failed_lines.size() << " ok, " << r.failed_lines.size() << " failed, "
            << number(std::round(r.seconds * 100) / 100) << " s, " << parallel << " at a time\n";
}

}  // namespace

void add_batch_command(CLI::App& app, std::function<int()>* run) {
  auto* cmd = app.add_subcommand("batch", "Run the mostyle-cli commands of a JOBS file, several at a time");
  struct Args {
    std::string jobs_file;
    std::string shard = "0/1";
    int parallel = 0;
    std::string summary;
  };
  auto args = std::make_shared<Args>();
  cmd->add_option("JOBS", args->jobs_file,
                  "JSON lines: each non-empty line is one command's arguments as an array of strings, e.g. "
                  "[\"blend\", \"a.bvh\", \"b.bvh\", \"--out\", \"ab.bvh\"] (paths relative to the working folder)")
      ->required();
  const CLI::Validator shard_format(
      [](std::string& text) {
        Shard s;
        return parse_shard(text, &s) ? std::string() : "expected I/N with 0 <= I < N, found " + text;
      },
      "I/N");
  cmd->add_option("--shard", args->shard,
                  "Run only the jobs (non-empty lines, counted from 0) whose index modulo N is I: N copies, "
                  "on N machines, share one JOBS file without talking to each other")
      ->check(shard_format)
      ->capture_default_str();
  cmd->add_option("--jobs,-j", args->parallel, "Jobs at once (default: the number of cores)")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--summary", args->summary,
                  "JSON file: totals, and per job its line, args, status (ok or failed), error and seconds; "
                  "without it a short summary goes to stdout");
  cmd->footer(
      "Each job runs as a child process of this program (its stdout discarded, its error line kept), so a crash "
      "in one is that job's failure only. A failed job does not stop the others. Exit status 1 when any job "
      "failed (one line on stderr naming the lines), 0 when all succeeded.");
  cmd->callback([=] {
    *run = [=] {
      Shard shard;
      parse_shard(args->shard, &shard);
      JobRunnerOptions o;
      o.parallel = args->parallel > 0 ? args->parallel
                                      : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
      const ShardRun r = run_shard(args->jobs_file, shard, o);
      const std::string of_shard = shard.count > 1 ? " of shard " + args->shard : "";
      if (!args->summary.empty()) {
        Json s;
        s["jobs_file"] = args->jobs_file;
        s["shard"] = args->shard;
        s["parallel"] = o.parallel;
        s["totals"] = {{"jobs", r.jobs.size()}, {"ok", r.jobs.size() - r.failed_lines.size()},
                       {"failed", r.failed_lines.size()}, {"seconds", r.seconds}};
        s["jobs"] = records_json(r);
        // Messages quote file contents (joint names): invalid UTF-8 is replaced, not thrown on.
        write_output(args->summary, s.dump(2, ' ', false, Json::error_handler_t::replace) + "\n");
      } else {
        print_summary(r, args->jobs_file, of_shard, o.parallel);
      }
      if (r.failed_lines.empty()) return 0;
      std::string lines;
      for (size_t k = 0; k < r.failed_lines.size() && k < 10; ++k)
        lines += (k ? ", " : "") + std::to_string(r.failed_lines[k]);
      if (r.failed_lines.size() > 10) lines += ", ...";
      std::cerr << "mostyle: " << args->jobs_file << ": " << r.failed_lines.size() << " of "
                << plural(r.jobs.size(), "job") << of_shard
                << " failed (line" << (r.failed_lines.size() == 1 ? " " : "s ") << lines << ")\n";
      return 1;
    };
  });
}

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
  cmd->add_option("--takes", args->takes, "Takes (BVH, FBX, glTF; FILE#ANIMATION for one animation), 2 or more; each is A with every other one as B")->required();
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
      if (!stems.insert(take_stem(t)).second)
        throw CLI::ValidationError("--takes", "two takes are named '" + take_stem(t) +
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
                take_stem(a) + "__" + take_stem(b) + "__a" + number(alpha);
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
