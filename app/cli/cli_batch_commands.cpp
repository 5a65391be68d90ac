#include "app/cli/cli_batch_commands.h"

#include <algorithm>
#include <charconv>
#include <chrono>
#include <cmath>
#include <cctype>
#include <filesystem>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <thread>

#include "app/batch/batch_summary.h"
#include "app/batch/job_line.h"
#include "app/batch/job_outputs.h"
#include "app/batch/job_runner.h"
#include "app/batch/stop_signal.h"
#include "app/cli/cli_common.h"
#include "engine/base/atomic_file.h"
#include "engine/base/error.h"

namespace mostyle::cli {
namespace {

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

// The jobs of one shard and how each went, in JOBS order.
struct ShardRun {
  std::vector<JobLine> jobs;
  std::vector<JobResult> results;  // results[k]: how jobs[k] went
  std::vector<JobStatus> status;   // status[k]: ok, failed or skipped
  std::vector<int> failed_lines;   // lines (from 1) of the failed jobs, in order
  size_t skipped = 0;
  double seconds = 0.0;            // wall time, reading JOBS included
};

struct BatchSettings {
  Shard shard;
  JobRunnerOptions runner;
  bool skip_existing = false;
  SummaryJournal* journal = nullptr;  // null without --summary
};

// A job whose output options all name files that exist; a job that names none is always run.
bool outputs_exist(const std::vector<std::string>& args) {
  const std::vector<std::string> outputs = job_outputs(args);
  std::error_code ec;
  return !outputs.empty() &&
         std::all_of(outputs.begin(), outputs.end(), [&](const std::string& f) { return fs::exists(f, ec); });
}

// Runs the shard's jobs of `all` (every line of JOBS); a line that is not a job is a failed job
// with its parse error. Each record goes to the journal as soon as it is known. t0: when batch
// began reading JOBS.
ShardRun run_shard(const std::vector<JobLine>& all, const BatchSettings& settings, Clock::time_point t0) {
  ShardRun r;
  const Shard& shard = settings.shard;
  for (size_t k = 0; k < all.size(); ++k)
    if (static_cast<int>(k % static_cast<size_t>(shard.count)) == shard.index) r.jobs.push_back(all[k]);
  std::vector<std::vector<std::string>> commands;
  std::vector<size_t> slot;  // slot[k]: the index in r.jobs of commands[k]
  r.results.resize(r.jobs.size());
  r.status.assign(r.jobs.size(), JobStatus::kFailed);
  auto record = [&](size_t k) {
    if (settings.journal) settings.journal->append(job_record(r.jobs[k].line, r.jobs[k].args, r.status[k], r.results[k]));
  };
  for (size_t k = 0; k < r.jobs.size(); ++k) {
    r.results[k].error = r.jobs[k].error;
    if (!r.jobs[k].error.empty()) {
      record(k);
    } else if (settings.skip_existing && outputs_exist(r.jobs[k].args)) {
      r.status[k] = JobStatus::kSkipped;
      r.results[k].ok = true;
      ++r.skipped;
      record(k);
    } else {
      commands.push_back(r.jobs[k].args);
      slot.push_back(k);
    }
  }
  JobRunnerOptions o = settings.runner;
  // Called one at a time (run_jobs serializes them); each writes only its own job's slot.
  o.on_finished = [&](size_t index, const JobResult& result) {
    const size_t k = slot[index];
    // A killed job (a crash, the timeout, a stop) may have been between writing an output's
    // temporary file and renaming it.
    if (result.exit_status == -1)
      for (int pid : result.pids) remove_leftovers(job_outputs(r.jobs[k].args), pid);
    r.results[k] = result;
    r.status[k] = result.ok ? JobStatus::kOk : JobStatus::kFailed;
    record(k);
  };
  // Jobs a stop request kept from starting have a result but no on_finished call.
  const std::vector<JobResult> ran = run_jobs(commands, o);
  for (size_t k = 0; k < ran.size(); ++k) r.results[slot[k]] = ran[k];
  for (size_t k = 0; k < r.jobs.size(); ++k)
    if (r.status[k] == JobStatus::kFailed) r.failed_lines.push_back(r.jobs[k].line);
  r.seconds = std::chrono::duration<double>(Clock::now() - t0).count();
  return r;
}

Json records_json(const ShardRun& r) {
  Json records = Json::array();
  for (size_t k = 0; k < r.jobs.size(); ++k)
    records.push_back(job_record(r.jobs[k].line, r.jobs[k].args, r.status[k], r.results[k]));
  return records;
}

size_t ok_count(const ShardRun& r) { return r.jobs.size() - r.failed_lines.size() - r.skipped; }

// The failures, one line each naming JOBS:LINE, then the totals.
// of_shard: "" or " of shard I/N".
void print_summary(const ShardRun& r, const std::string& jobs_file, const std::string& of_shard, int parallel) {
  for (size_t k = 0; k < r.jobs.size(); ++k) {
    if (r.status[k] != JobStatus::kFailed) continue;
    const JobLine& job = r.jobs[k];
    // A line that is not a job already has its error naming JOBS:LINE.
    if (!job.error.empty())
      std::cout << job.error << "\n";
    else
      std::cout << jobs_file << ":" << job.line << ": " << job.args[0] << " failed: " << r.results[k].error << "\n";
  }
  std::cout << jobs_file << of_shard << ": " << plural(r.jobs.size(), "job") << ", " << ok_count(r) << " ok, "
            << r.failed_lines.size() << " failed, " << r.skipped << " skipped, "
            << number(std::round(r.seconds * 100) / 100) << " s, " << parallel << " at a time\n";
}

// What `batch` is given.
struct BatchArgs {
  std::string jobs_file;
  std::string shard = "0/1";
  int parallel = 0;
  std::string summary;
  double timeout = 0.0;
  int retries = 0;
  bool skip_existing = false;
};

void add_batch_options(CLI::App* cmd, BatchArgs& args) {
  cmd->add_option("JOBS", args.jobs_file,
                  "JSON lines: each non-empty line is one command's arguments as an array of strings, e.g. "
                  "[\"blend\", \"a.bvh\", \"b.bvh\", \"--out\", \"ab.bvh\"] (paths relative to the working folder)")
      ->required();
  const CLI::Validator shard_format(
      [](std::string& text) {
        Shard s;
        return parse_shard(text, &s) ? std::string() : "expected I/N with 0 <= I < N, found " + text;
      },
      "I/N");
  cmd->add_option("--shard", args.shard,
                  "Run only the jobs (non-empty lines, counted from 0) whose index modulo N is I: N copies, "
                  "on N machines, share one JOBS file without talking to each other")
      ->check(shard_format)
      ->capture_default_str();
  cmd->add_option("--jobs,-j", args.parallel, "Jobs at once (default: the number of cores)")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--summary", args.summary,
                  "JSON file: totals, and per job its line, args, status (ok, failed or skipped), error, seconds, "
                  "attempts and peak memory (max_rss_mb); kept current while jobs run in SUMMARY.journal (one "
                  "record per finished job, JSON lines), removed once the summary is written. Without it a "
                  "short summary goes to stdout");
  const CLI::Validator finite_seconds(
      [](std::string& text) {
        double v = 0;
        const auto r = std::from_chars(text.data(), text.data() + text.size(), v);
        const bool good = r.ec == std::errc() && r.ptr == text.data() + text.size() && std::isfinite(v) && v > 0;
        return good ? std::string() : "expected a number of seconds above 0, found " + text;
      },
      "SECONDS");
  cmd->add_option("--timeout", args.timeout,
                  "Seconds a job may run: one still running then is stopped (SIGTERM to its process group, SIGKILL "
                  "5 s later) and recorded as failed, \"timed out after SECONDS s\"; the others go on")
      ->check(finite_seconds);
  cmd->add_option("--retries", args.retries,
                  "Run a job killed by a signal (a crash, an out-of-memory kill) again, up to this many times; a job "
                  "that fails on its input (exit status 1), its usage (2) or the timeout is not run again")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  cmd->add_flag("--skip-existing", args.skip_existing,
                "Do not run a job whose outputs (--out, --positions-out, --report, --jobs-out) all exist: it is "
                "recorded as skipped. A job that names no output so is always run");
  cmd->footer(
      "Each job runs as a child process of this program in a process group of its own (its stdout discarded, its "
      "error line kept), so a crash in one is that job's failure only. A failed job does not stop the others. "
      "SIGINT, SIGTERM or SIGHUP stops the running jobs with the same signal (a second one with SIGKILL) and starts "
      "no more; the summary is written, then batch ends by that signal. "
      "Exit status 1 when any job failed (one line on stderr naming the lines), 0 when all succeeded or were "
      "skipped.");
}

// The summary file: totals, and a record per job.
void write_summary_file(const BatchArgs& args, const ShardRun& r, int parallel) {
  Json s;
  s["jobs_file"] = args.jobs_file;
  s["shard"] = args.shard;
  s["parallel"] = parallel;
  s["totals"] = {{"jobs", r.jobs.size()}, {"ok", ok_count(r)}, {"failed", r.failed_lines.size()},
                 {"skipped", r.skipped}, {"seconds", r.seconds}};
  s["jobs"] = records_json(r);
  // Messages quote file contents (joint names): invalid UTF-8 is replaced, not thrown on.
  write_output(args.summary, s.dump(2, ' ', false, Json::error_handler_t::replace) + "\n");
}

// 0 when no job failed; else 1, after one line on stderr naming the failed lines (at most ten).
int report_failed_lines(const BatchArgs& args, const ShardRun& r, const std::string& of_shard) {
  if (r.failed_lines.empty()) return 0;
  std::string lines;
  for (size_t k = 0; k < r.failed_lines.size() && k < 10; ++k)
    lines += (k ? ", " : "") + std::to_string(r.failed_lines[k]);
  if (r.failed_lines.size() > 10) lines += ", ...";
  std::cerr << "mostyle: " << args.jobs_file << ": " << r.failed_lines.size() << " of "
            << plural(r.jobs.size(), "job") << of_shard
            << " failed (line" << (r.failed_lines.size() == 1 ? " " : "s ") << lines << ")\n";
  return 1;
}

int run_batch(const BatchArgs& args) {
  // First, so that it is the last to go: the summary is written before a stop signal ends
  // the process.
  StopSignal stop;
  const auto t0 = Clock::now();
  // Read first: a JOBS file that cannot be read leaves no journal behind.
  const std::vector<JobLine> all = parse_jobs(read_file(args.jobs_file), args.jobs_file);
  BatchSettings settings;
  parse_shard(args.shard, &settings.shard);
  JobRunnerOptions& o = settings.runner;
  o.parallel = args.parallel > 0 ? args.parallel : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  o.timeout_seconds = args.timeout;
  o.retries = args.retries;
  o.stop = &stop.requested();
  settings.skip_existing = args.skip_existing;
  std::unique_ptr<SummaryJournal> journal;
  if (!args.summary.empty()) {
    journal = std::make_unique<SummaryJournal>(journal_path(args.summary));
    settings.journal = journal.get();
  }
  const ShardRun r = run_shard(all, settings, t0);
  const std::string of_shard = settings.shard.count > 1 ? " of shard " + args.shard : "";
  if (journal) {
    if (!journal->error().empty()) std::cerr << "mostyle: warning: " << journal->error() << "\n";
    write_summary_file(args, r, o.parallel);
    journal->remove();
  } else {
    print_summary(r, args.jobs_file, of_shard, o.parallel);
  }
  return report_failed_lines(args, r, of_shard);
}

}  // namespace

void add_batch_command(CLI::App& app, std::function<int()>* run) {
  auto* cmd = app.add_subcommand("batch", "Run the mostyle-cli commands of a JOBS file, several at a time");
  auto args = std::make_shared<BatchArgs>();
  add_batch_options(cmd, *args);
  cmd->callback([=] { *run = [=] { return run_batch(*args); }; });
}

}  // namespace mostyle::cli
