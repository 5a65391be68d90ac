// app/batch/job_runner: child processes a few at a time, results in job order, a failed, killed or
// missing program is that job's result. Jobs here are /bin/sh scripts; CI runs this under
// ThreadSanitizer (tests/run.sh --sanitize thread).
#include "app/batch/job_runner.h"

#include <unistd.h>

#include <signal.h>

#include <atomic>
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include "engine/base/error.h"

namespace fs = std::filesystem;
using namespace mostyle;
using namespace mostyle::cli;

namespace {

std::vector<std::string> sh(const std::string& script) { return {"-c", script}; }

JobRunnerOptions shell(int parallel) {
  JobRunnerOptions o;
  o.program = "/bin/sh";
  o.parallel = parallel;
  return o;
}

}  // namespace

TEST_CASE("job runner: results in job order, exit status and error line", "[batch][jobs]") {
  std::vector<std::vector<std::string>> jobs;
  for (int i = 0; i < 24; ++i)
    jobs.push_back(sh(i % 3 == 0 ? "exit 0" : "echo 'mostyle: job" + std::to_string(i) + ".bvh:1: bad' >&2; exit 1"));
  const std::vector<JobResult> r = run_jobs(jobs, shell(4));
  REQUIRE(r.size() == jobs.size());
  for (int i = 0; i < 24; ++i) {
    INFO(i);
    CHECK(r[i].ok == (i % 3 == 0));
    CHECK(r[i].exit_status == (i % 3 == 0 ? 0 : 1));
    CHECK(r[i].error == (i % 3 == 0 ? "" : "job" + std::to_string(i) + ".bvh:1: bad"));
    CHECK(r[i].seconds >= 0.0);
  }
  CHECK(run_jobs({}, shell(4)).empty());
}

TEST_CASE("job runner: warnings, usage errors, silent failures, stdout", "[batch][jobs]") {
  const std::vector<JobResult> r = run_jobs(
      {sh("echo 'mostyle: warning: w.bvh:8: short' >&2; exit 0"),
       sh("echo 'mostyle: warning: w.bvh:8: short' >&2; echo 'mostyle: a.bvh:2: wrong' >&2; exit 1"),
       sh("echo 'The following argument was not expected: --bogus' >&2; echo 'Run with --help' >&2; exit 2"),
       sh("exit 3"),
       // Lots of output on both streams: stdout goes nowhere, stderr keeps its end.
       sh("i=0; while [ $i -lt 3000 ]; do echo 'mostyle: warning: xxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxx'; "
          "echo 'mostyle: warning: yyyyyyyyyyyyyyyyyyyyyyyyyyyyyyyyyyyyyyyy' >&2; i=$((i+1)); done; "
          "echo 'mostyle: last.bvh:9: the end' >&2; exit 1")},
      shell(2));
  CHECK(r[0].ok);
  CHECK(r[0].error.empty());
  CHECK(r[1].error == "a.bvh:2: wrong");
  CHECK(r[2].error == "bad usage: The following argument was not expected: --bogus");
  CHECK(r[2].exit_status == 2);
  CHECK(r[3].error == "exit status 3 and no message");
  CHECK(r[4].error == "last.bvh:9: the end");
}

TEST_CASE("job runner: a killed job and a missing program are that job's failure", "[batch][jobs]") {
  std::vector<JobResult> r = run_jobs({sh("echo 'mostyle: x' >&2; kill -KILL $$"), sh("exit 0")}, shell(2));
  CHECK_FALSE(r[0].ok);
  CHECK(r[0].exit_status == -1);
  CHECK(r[0].error == "killed by signal 9 (Killed): x");
  CHECK(r[1].ok);
  JobRunnerOptions missing;
  missing.program = "/no/such/program";
  r = run_jobs({{}, {"a"}}, missing);
  for (const JobResult& m : r) {
    CHECK_FALSE(m.ok);
    CHECK(m.pids.empty());
    CHECK(m.error == "cannot start /no/such/program: No such file or directory");
  }
}

TEST_CASE("job runner: jobs run at the same time", "[batch][jobs]") {
  // The first job waits (5 s at most) for a file that only the second job creates: it succeeds
  // only when both run at once.
  const fs::path flag = fs::temp_directory_path() / ("mostyle_job_runner_" + std::to_string(::getpid()));
  fs::remove(flag);
  const std::string f = "'" + flag.string() + "'";
  const std::vector<JobResult> r = run_jobs(
      {sh("i=0; while [ ! -e " + f + " ]; do sleep 0.01; i=$((i+1)); [ $i -gt 500 ] && exit 1; done; exit 0"),
       sh("touch " + f)},
      shell(2));
  fs::remove(flag);
  CHECK(r[0].ok);
  CHECK(r[1].ok);
}

// A scratch folder of this test's own, removed at the end.
struct Scratch {
  fs::path dir = fs::temp_directory_path() / ("mostyle_job_runner_dir_" + std::to_string(::getpid()));
  Scratch() {
    fs::remove_all(dir);
    fs::create_directories(dir);
  }
  ~Scratch() { fs::remove_all(dir); }
  std::string path(const std::string& name) const { return "'" + (dir / name).string() + "'"; }
};

TEST_CASE("job runner: a job still running at the timeout is stopped with its process group", "[batch][jobs]") {
  Scratch scratch;
  JobRunnerOptions o = shell(3);
  o.timeout_seconds = 0.8;
  o.grace_seconds = 0.2;
  // A job that starts a grandchild holding stderr open: the group is stopped, not just the job.
  // One that ignores SIGTERM: SIGKILL after the grace. The grandchild would create a file if it
  // lived on.
  const std::string late = scratch.path("late");
  const std::vector<JobResult> r =
      run_jobs({sh("(sleep 1; touch " + late + ") & sleep 30"), sh("trap '' TERM; sleep 30; exit 0"),
                sh("echo 'mostyle: quick.bvh:1: bad' >&2; exit 1"), sh("exit 0")},
               o);
  for (int i : {0, 1}) {
    INFO(i);
    CHECK_FALSE(r[i].ok);
    CHECK(r[i].timed_out);
    CHECK(r[i].exit_status == -1);
    CHECK(r[i].error == "timed out after 0.8 s");
    CHECK(r[i].attempts == 1);
  }
  CHECK(r[2].error == "quick.bvh:1: bad");
  CHECK_FALSE(r[2].timed_out);
  CHECK(r[3].ok);
  CHECK_FALSE(r[3].timed_out);
  // A timeout too long for the clock is no limit, not an overflow.
  o.timeout_seconds = 1e300;
  CHECK(run_jobs({sh("exit 0")}, o)[0].ok);
  std::this_thread::sleep_for(std::chrono::milliseconds(1500));
  CHECK_FALSE(fs::exists(scratch.dir / "late"));
}

TEST_CASE("job runner: a job killed by a signal is run again, a failed one never", "[batch][jobs]") {
  Scratch scratch;
  // Each run appends a line to its counter file; the job kills itself on its first two runs.
  auto flaky = [&](const std::string& counter) {
    const std::string f = scratch.path(counter);
    return sh("echo x >> " + f + "; [ $(wc -l < " + f + ") -ge 3 ] && exit 0; kill -KILL $$");
  };
  auto lines = [&](const std::string& counter) {
    std::ifstream in(scratch.dir / counter);
    int n = 0;
    for (std::string line; std::getline(in, line);) ++n;
    return n;
  };
  JobRunnerOptions o = shell(2);
  o.retries = 2;
  const std::string bad = scratch.path("bad");
  std::vector<JobResult> r = run_jobs(
      {flaky("a"), sh("echo x >> " + bad + "; echo 'mostyle: in.bvh:3: wrong' >&2; exit 1"),
       sh("echo x >> " + scratch.path("usage") + "; exit 2")},
      o);
  CHECK(r[0].ok);
  CHECK(r[0].attempts == 3);
  CHECK(r[0].pids.size() == 3);
  CHECK(lines("a") == 3);
  CHECK(r[1].error == "in.bvh:3: wrong");
  CHECK(r[1].attempts == 1);
  CHECK(lines("bad") == 1);
  CHECK(r[2].attempts == 1);
  CHECK(lines("usage") == 1);
  o.retries = 1;
  r = run_jobs({flaky("b")}, o);
  CHECK_FALSE(r[0].ok);
  CHECK(r[0].attempts == 2);
  CHECK(r[0].error == "killed by signal 9 (Killed)");
  CHECK(lines("b") == 2);
  // A timed-out job is not run again: it would most likely hang again.
  o.timeout_seconds = 0.2;
  o.grace_seconds = 0.1;
  r = run_jobs({sh("echo x >> " + scratch.path("slow") + "; sleep 30")}, o);
  CHECK(r[0].timed_out);
  CHECK(r[0].attempts == 1);
  CHECK(lines("slow") == 1);
}

TEST_CASE("job runner: on_finished sees every job once, and its peak memory", "[batch][jobs]") {
  std::vector<std::vector<std::string>> jobs;
  for (int i = 0; i < 12; ++i) jobs.push_back(sh(i % 2 ? "exit 1" : "exit 0"));
  JobRunnerOptions o = shell(3);
  std::multiset<size_t> seen;  // guarded by run_jobs: one call at a time
  int ok = 0;
  o.on_finished = [&](size_t index, const JobResult& result) {
    seen.insert(index);
    ok += result.ok;
  };
  const std::vector<JobResult> r = run_jobs(jobs, o);
  CHECK(seen.size() == jobs.size());
  for (size_t i = 0; i < jobs.size(); ++i) CHECK(seen.count(i) == 1);
  CHECK(ok == 6);
  for (const JobResult& j : r) {
    CHECK(j.attempts == 1);
    CHECK(j.max_rss_mb > 0.0);  // a shell takes at least some pages
  }
}

TEST_CASE("job runner: a stop request signals the running jobs and starts no more", "[batch][jobs]") {
  std::atomic<int> stop{0};
  JobRunnerOptions o = shell(2);
  o.stop = &stop;
  o.retries = 3;  // a stopped job is not run again
  int finished = 0;
  o.on_finished = [&](size_t, const JobResult&) { ++finished; };
  // Each job says it started (a line on stdout would be lost: stderr goes to the runner) by
  // creating a file; the stop comes once both running jobs have.
  Scratch scratch;
  std::thread stopper([&] {
    for (int i = 0; i < 3000; ++i) {
      if (fs::exists(scratch.dir / "0") && fs::exists(scratch.dir / "1")) break;
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    stop.store(SIGTERM);
  });
  const std::vector<JobResult> r =
      run_jobs({sh("touch " + scratch.path("0") + "; sleep 30"), sh("touch " + scratch.path("1") + "; sleep 30"),
                sh("touch " + scratch.path("2") + "; exit 0")},
               o);
  stopper.join();
  for (int i : {0, 1}) {
    INFO(i);
    CHECK(r[i].error == "killed by signal 15 (Terminated)");
    CHECK(r[i].attempts == 1);
  }
  CHECK_FALSE(r[2].ok);
  CHECK(r[2].attempts == 0);
  CHECK(r[2].error == "not run: stopped by signal 15 (Terminated)");
  CHECK_FALSE(fs::exists(scratch.dir / "2"));
  CHECK(finished == 2);
}

TEST_CASE("job runner: a stop request that changes is passed on again (SIGTERM, then SIGKILL)", "[batch][jobs]") {
  Scratch scratch;
  std::atomic<int> stop{0};
  JobRunnerOptions o = shell(1);
  o.stop = &stop;
  std::thread stopper([&] {
    for (int i = 0; i < 3000 && !fs::exists(scratch.dir / "started"); ++i)
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    stop.store(SIGTERM);  // ignored by the job
    std::this_thread::sleep_for(std::chrono::milliseconds(300));
    stop.store(SIGKILL);
  });
  const std::vector<JobResult> r =
      run_jobs({sh("trap '' TERM; touch " + scratch.path("started") + "; sleep 30; exit 0")}, o);
  stopper.join();
  CHECK(r[0].error == "killed by signal 9 (Killed)");
}

TEST_CASE("job runner: error_line and options", "[batch][jobs]") {
  CHECK(error_line("") == "");
  CHECK(error_line("mostyle: warning: a\n") == "");
  CHECK(error_line("mostyle: warning: a\r\nmostyle: b.bvh:1: c\r\n") == "b.bvh:1: c");
  CHECK(error_line("first\nsecond\n") == "first");
  CHECK(error_line("terminate called\nmostyle: internal error: x") == "internal error: x");
  JobRunnerOptions o;
  CHECK_NOTHROW(o.Validate());
  o.parallel = 0;
  CHECK_THROWS_AS(o.Validate(), InputError);
  CHECK_THROWS_AS(run_jobs({{"x"}}, o), InputError);
  o.parallel = 1;
  o.program.clear();
  CHECK_THROWS_AS(o.Validate(), InputError);
  o.program = "/bin/sh";
  for (double t : {-1.0, std::nan(""), HUGE_VAL}) {
    o.timeout_seconds = t;
    CHECK_THROWS_AS(o.Validate(), InputError);
  }
  o.timeout_seconds = 0;
  for (double g : {0.0, -1.0, std::nan("")}) {
    o.grace_seconds = g;
    CHECK_THROWS_AS(o.Validate(), InputError);
  }
  o.grace_seconds = 1;
  o.retries = -1;
  CHECK_THROWS_AS(o.Validate(), InputError);
  o.retries = 0;
  CHECK_NOTHROW(o.Validate());
}
