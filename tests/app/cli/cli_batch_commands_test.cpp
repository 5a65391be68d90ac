// mostyle-cli batch | grid, run as a user runs them: shards that share one JOBS file run every
// job exactly once, a failed job is reported and never stops the others, exit 1 when one
// failed, 2 on bad usage.
#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <string>
#include <thread>

#include "engine/io/bvh/bvh_read.h"
#include "tests/app/cli/cli_sandbox.h"
#include "tests/test_data.h"

extern char** environ;

namespace fs = std::filesystem;
using Json = nlohmann::json;
using namespace mostyle;

namespace {

using Run = test::CliRun;
using test::slurp;

std::string quoted(const std::string& s) { return test::shell_quoted(s); }

// A scratch folder of this test file's own.
class Sandbox : public test::CliSandbox {
 public:
  Sandbox() : test::CliSandbox("mostyle_batch_test") {}
};

std::string job(const std::vector<std::string>& args) { return Json(args).dump() + "\n"; }

// Starts mostyle-cli with `args` as a child of this test, its output discarded; its process id.
pid_t start_cli(std::vector<std::string> args) {
  args.insert(args.begin(), MOSTYLE_CLI);
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 1, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_addopen(&actions, 2, "/dev/null", O_WRONLY, 0);
  pid_t pid = 0;
  const int error = ::posix_spawn(&pid, MOSTYLE_CLI, &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  return error == 0 ? pid : -1;
}

// Waits (60 s at most) until `file` holds `lines` lines.
void wait_for_lines(const std::string& file, long lines) {
  for (int i = 0; i < 6000; ++i) {
    const std::string text = slurp(file);
    if (std::count(text.begin(), text.end(), '\n') >= lines) return;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
}

// Whether `parent` has a child process (Linux: /proc/PID/stat's fourth field is the parent).
bool has_child(pid_t parent) {
  for (const auto& e : fs::directory_iterator("/proc")) {
    const std::string stat = slurp(e.path() / "stat");
    const size_t paren = stat.rfind(')');
    if (paren == std::string::npos) continue;
    std::istringstream fields(stat.substr(paren + 1));
    std::string state;
    long ppid = 0;
    if (fields >> state >> ppid && ppid == parent) return true;
  }
  return false;
}

// Whether a process has `fifo` open for reading (a writer can then open it without waiting).
bool fifo_has_reader(const std::string& fifo) {
  const int fd = ::open(fifo.c_str(), O_WRONLY | O_NONBLOCK);
  if (fd < 0) return false;
  ::close(fd);
  return true;
}

std::vector<std::string> files_in(const std::string& dir) {
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(dir)) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

const std::vector<std::string> kFast = {"--components", "4", "--iterations", "20"};

std::vector<std::string> blend(const std::string& a, const std::string& b, const std::string& alpha,
                               const std::string& out) {
  std::vector<std::string> args = {"blend", a, b, "--alpha", alpha, "--out", out};
  args.insert(args.end(), kFast.begin(), kFast.end());
  return args;
}

}  // namespace

TEST_CASE("cli batch: two shards run every job once, failures reported, the rest go on", "[batch][cli]") {
  Sandbox box;
  const std::vector<std::string> takes = test::asset_motions();
  REQUIRE(takes.size() == 4);
  fs::create_directory(box.path("out"));
  const std::string missing = box.path("missing.bvh");
  const std::string not_bvh = box.write("not_bvh.bvh", "hello\n");
  // Jobs 0..7 (shard 0 runs the even ones, shard 1 the odd ones); a blank line after job 0, so
  // job k >= 1 is on line k + 2. Both bad jobs fall in shard 1.
  const std::vector<std::vector<std::string>> jobs = {
      blend(takes[0], takes[1], "0.5", box.path("out/g0.bvh")),
      blend(takes[1], takes[2], "0.25", box.path("out/g1.bvh")),
      blend(takes[2], takes[3], "0.75", box.path("out/g2.bvh")),
      blend(missing, takes[0], "0.5", box.path("out/bad_missing.bvh")),
      blend(takes[3], takes[0], "1", box.path("out/g3.bvh")),
      blend(takes[1], not_bvh, "0.5", box.path("out/bad_not_bvh.bvh")),
      blend(takes[0], takes[2], "0", box.path("out/g4.bvh")),
      blend(takes[2], takes[1], "0.5", box.path("out/g5.bvh")),
  };
  std::string text;
  for (size_t k = 0; k < jobs.size(); ++k) text += job(jobs[k]) + (k == 0 ? "\n" : "");
  const std::string file = box.write("jobs.jsonl", text);

  const Run s0 = box.cli("batch " + quoted(file) + " --shard 0/2 --jobs 2 --summary " + quoted(box.path("s0.json")));
  CHECK(s0.status == 0);
  CHECK(s0.out.empty());
  CHECK(s0.err.empty());
  const Run s1 = box.cli("batch " + quoted(file) + " --shard 1/2 --jobs 2 --summary " + quoted(box.path("s1.json")));
  CHECK(s1.status == 1);
  CHECK(s1.err == "mostyle: " + file + ": 2 of 4 jobs of shard 1/2 failed (lines 5, 7)\n");

  std::map<int, Json> records;  // line -> record, over both shards
  for (const std::string& summary : {box.path("s0.json"), box.path("s1.json")}) {
    const Json s = Json::parse(slurp(summary));
    CHECK(s["totals"]["jobs"] == 4);
    CHECK(s["parallel"] == 2);
    for (const Json& r : s["jobs"]) CHECK(records.emplace(r["line"].get<int>(), r).second);  // once only
  }
  REQUIRE(records.size() == 8);
  CHECK(Json::parse(slurp(box.path("s0.json")))["totals"]["failed"] == 0);
  CHECK(Json::parse(slurp(box.path("s1.json")))["totals"]["failed"] == 2);
  for (size_t k = 0; k < jobs.size(); ++k) {
    const int line = k == 0 ? 1 : static_cast<int>(k) + 2;
    INFO("line " << line);
    const Json& r = records.at(line);
    CHECK(r["args"] == Json(jobs[k]));
    CHECK(r["seconds"].get<double>() > 0.0);
    if (k == 3 || k == 5) continue;
    CHECK(r["status"] == "ok");
    CHECK(r["error"] == "");
  }
  CHECK(records.at(5)["status"] == "failed");
  CHECK(records.at(5)["error"].get<std::string>().rfind(missing + ": cannot read: ", 0) == 0);
  CHECK(records.at(7)["status"] == "failed");
  CHECK(records.at(7)["error"] == not_bvh + ":1: expected HIERARCHY, found 'hello'");
  // Exactly the six good outputs, no temporary files left.
  CHECK(files_in(box.path("out")) ==
        std::vector<std::string>{"g0.bvh", "g1.bvh", "g2.bvh", "g3.bvh", "g4.bvh", "g5.bvh"});
  for (int g = 0; g < 6; ++g) CHECK(read_bvh_file(box.path("out/g" + std::to_string(g) + ".bvh")).frames() > 100);

  // Without --summary: the failures and a total on stdout.
  const Run human = box.cli("batch " + quoted(file) + " --shard 1/2 --jobs 2");
  CHECK(human.status == 1);
  std::istringstream lines(human.out);
  std::string line;
  std::getline(lines, line);
  CHECK(line.rfind(file + ":5: blend failed: " + missing + ": cannot read: ", 0) == 0);
  std::getline(lines, line);
  CHECK(line == file + ":7: blend failed: " + not_bvh + ":1: expected HIERARCHY, found 'hello'");
  std::getline(lines, line);
  CHECK(line.rfind(file + " of shard 1/2: 4 jobs, 2 ok, 2 failed, ", 0) == 0);
  CHECK(line.find(" s, 2 at a time") != std::string::npos);
  CHECK_FALSE(std::getline(lines, line));
}

TEST_CASE("cli batch: a line that is not a job is a failed job naming its line", "[batch][cli]") {
  Sandbox box;
  const std::string take = test::asset("motions/cmu142_walk_joy.bvh");
  const std::string file = box.write("jobs.jsonl", job({"info", take}) +
                                                       "{\"blend\": 1}\n"
                                                       "\n"
                                                       "[\"blend\", 3]\r\n"
                                                       "not json\n"
                                                       "[]\n"
                                                       "[\"batch\", \"other.jsonl\"]\n"
                                                       "[1e400, \"x\"]\n"
                                                       // No newline at the end of the file.
                                                       "[\"blend\", \"a.bvh\", \"b.bvh\", \"--bogus\"]");
  const Run r = box.cli("batch " + quoted(file) + " --summary " + quoted(box.path("s.json")));
  CHECK(r.status == 1);
  CHECK(r.err == "mostyle: " + file + ": 7 of 8 jobs failed (lines 2, 4, 5, 6, 7, 8, 9)\n");
  const Json s = Json::parse(slurp(box.path("s.json")));
  CHECK(s["shard"] == "0/1");
  CHECK(s["totals"]["jobs"] == 8);
  CHECK(s["totals"]["ok"] == 1);
  CHECK(s["totals"]["failed"] == 7);
  const Json& j = s["jobs"];
  REQUIRE(j.size() == 8);
  const std::string expected = "expected a JSON array of strings (the arguments of one mostyle-cli command), found ";
  CHECK(j[0]["line"] == 1);
  CHECK(j[0]["status"] == "ok");
  CHECK(j[1]["line"] == 2);
  CHECK(j[1]["status"] == "failed");
  CHECK(j[1]["args"] == Json::array());
  CHECK(j[1]["error"] == file + ":2: " + expected + "an object");
  CHECK(j[2]["line"] == 4);
  CHECK(j[2]["error"] == file + ":4: " + expected + "a number as item 2");
  CHECK(j[3]["line"] == 5);
  CHECK(j[3]["error"].get<std::string>().rfind(file + ":5: " + expected + "invalid JSON at column ", 0) == 0);
  CHECK(j[4]["error"] == file + ":6: expected a mostyle-cli command such as [\"blend\", ...], found an empty array");
  CHECK(j[5]["error"] == file + ":7: a job cannot be a batch itself");
  CHECK(j[6]["error"] == file + ":8: " + expected + "a number too large for JSON");
  CHECK(j[7]["line"] == 9);
  CHECK(j[7]["args"] == Json({"blend", "a.bvh", "b.bvh", "--bogus"}));
  CHECK(j[7]["error"] == "bad usage: The following argument was not expected: --bogus");
}

TEST_CASE("cli batch: bad usage exits 2, an unreadable JOBS file 1", "[batch][cli]") {
  Sandbox box;
  const std::string file = box.write("jobs.jsonl", "");
  for (const char* shard : {"2/2", "1/0", "-1/2", "1", "a/b", "0/2/3", "/2", "0/"}) {
    INFO(shard);
    const Run r = box.cli("batch " + quoted(file) + " --shard " + quoted(shard));
    CHECK(r.status == 2);
    CHECK(r.out.empty());
  }
  CHECK(box.cli("batch " + quoted(file) + " --jobs 0").status == 2);
  for (const char* bad : {"0", "-1", "nan", "inf", "soon", "1s"}) {
    INFO(bad);
    CHECK(box.cli("batch " + quoted(file) + " --timeout " + bad).status == 2);
  }
  for (const char* bad : {"-1", "1.5", "many"}) {
    INFO(bad);
    CHECK(box.cli("batch " + quoted(file) + " --retries " + bad).status == 2);
  }
  CHECK(box.cli("batch").status == 2);
  const Run missing = box.cli("batch " + quoted(box.path("none.jsonl")) + " --summary " + quoted(box.path("s.json")));
  CHECK(missing.status == 1);
  CHECK_FALSE(fs::exists(box.path("s.json")));
  CHECK_FALSE(fs::exists(box.path("s.json.journal")));
  CHECK(missing.err.rfind("mostyle: " + box.path("none.jsonl") + ": cannot read: ", 0) == 0);
  CHECK(std::count(missing.err.begin(), missing.err.end(), '\n') == 1);
  // No jobs (here: none in this shard) is success.
  const Run empty = box.cli("batch " + quoted(file) + " --shard 1/3");
  CHECK(empty.status == 0);
  CHECK(empty.out.rfind(file + " of shard 1/3: 0 jobs, 0 ok, 0 failed, ", 0) == 0);
}

TEST_CASE("cli batch: a job that hangs is stopped at the timeout, the others finish", "[batch][cli]") {
  Sandbox box;
  const std::vector<std::string> takes = test::asset_motions();
  // A FIFO that no one writes: reading it waits forever.
  const std::string fifo = box.path("hang.bvh");
  REQUIRE(::mkfifo(fifo.c_str(), 0600) == 0);
  const std::string file = box.write("jobs.jsonl", job({"info", takes[0]}) + job({"info", fifo}) +
                                                       job({"fk", takes[1], "--out", box.path("p.csv")}) +
                                                       job({"info", takes[2]}));
  // The timeout is long enough for the other jobs on a loaded machine under a sanitizer.
  const Run r = box.cli("batch " + quoted(file) + " --jobs 2 --timeout 10 --retries 2 --summary " +
                        quoted(box.path("s.json")));
  CHECK(r.status == 1);
  CHECK(r.err == "mostyle: " + file + ": 1 of 4 jobs failed (line 2)\n");
  const Json s = Json::parse(slurp(box.path("s.json")));
  CHECK(s["totals"]["ok"] == 3);
  CHECK(s["totals"]["failed"] == 1);
  CHECK(s["totals"]["skipped"] == 0);
  const Json& j = s["jobs"];
  REQUIRE(j.size() == 4);
  CHECK(j[1]["status"] == "failed");
  CHECK(j[1]["error"] == "timed out after 10 s");
  CHECK(j[1]["attempts"] == 1);  // a timeout is not retried
  for (int k : {0, 2, 3}) {
    INFO(k);
    CHECK(j[k]["status"] == "ok");
    CHECK(j[k]["attempts"] == 1);
    CHECK(j[k]["max_rss_mb"].get<double>() > 0.0);
  }
  CHECK(fs::exists(box.path("p.csv")));
  CHECK_FALSE(fs::exists(box.path("s.json.journal")));  // merged into the summary
}

TEST_CASE("cli batch: --skip-existing runs only the jobs whose outputs are not all there", "[batch][cli]") {
  Sandbox box;
  const std::vector<std::string> takes = test::asset_motions();
  const std::string old_csv = box.write("old.csv", "kept\n");
  std::vector<std::string> partial = blend(takes[0], takes[1], "0.5", box.path("ab.bvh"));
  partial.insert(partial.end(), {"--report", box.path("ab.json")});
  box.write("ab.bvh", "an older blend\n");  // its report is missing: the job runs again
  const std::string bad = box.path("missing.bvh");
  const std::string file = box.write("jobs.jsonl", job({"fk", takes[0], "--out", box.path("new.csv")}) +
                                                       job({"fk", takes[1], "--out=" + old_csv}) +
                                                       job({"info", takes[2]}) + job(partial) +
                                                       job({"fk", bad, "--out", box.path("bad.csv")}));
  const std::string summary = " --summary " + quoted(box.path("s.json"));
  Run r = box.cli("batch " + quoted(file) + " --skip-existing --jobs 2" + summary);
  CHECK(r.status == 1);
  Json s = Json::parse(slurp(box.path("s.json")));
  CHECK(s["totals"]["jobs"] == 5);
  CHECK(s["totals"]["ok"] == 3);
  CHECK(s["totals"]["failed"] == 1);
  CHECK(s["totals"]["skipped"] == 1);
  std::vector<std::string> status;
  for (const Json& record : s["jobs"]) status.push_back(record["status"]);
  CHECK(status == std::vector<std::string>{"ok", "skipped", "ok", "ok", "failed"});
  CHECK(s["jobs"][1]["attempts"] == 0);
  CHECK(s["jobs"][1]["error"] == "");
  CHECK(slurp(old_csv) == "kept\n");
  CHECK(read_bvh_file(box.path("ab.bvh")).frames() > 100);
  CHECK(fs::exists(box.path("ab.json")));

  // Again: every job with outputs is skipped (the failed one still has none, so it runs and
  // fails again); the job without output options runs.
  r = box.cli("batch " + quoted(file) + " --skip-existing --jobs 2" + summary);
  CHECK(r.status == 1);
  s = Json::parse(slurp(box.path("s.json")));
  status.clear();
  for (const Json& record : s["jobs"]) status.push_back(record["status"]);
  CHECK(status == std::vector<std::string>{"skipped", "skipped", "ok", "skipped", "failed"});
  // Without --summary: the skipped jobs counted on stdout.
  r = box.cli("batch " + quoted(file) + " --skip-existing");
  CHECK(r.out.find(": 5 jobs, 1 ok, 1 failed, 3 skipped, ") != std::string::npos);
}

TEST_CASE("cli batch: SIGTERM stops the running jobs, the summary is written, batch ends by it", "[batch][cli]") {
  Sandbox box;
  const std::vector<std::string> takes = test::asset_motions();
  const std::string fifo = box.path("hang.bvh");
  REQUIRE(::mkfifo(fifo.c_str(), 0600) == 0);
  const std::string file =
      box.write("jobs.jsonl", job({"info", takes[0]}) + job({"info", fifo}) + job({"info", takes[1]}));
  const std::string summary = box.path("s.json");
  const pid_t pid = start_cli({"batch", file, "--jobs", "1", "--summary", summary, "--retries", "2"});
  REQUIRE(pid > 0);
  wait_for_lines(summary + ".journal", 1);
  // The second job then starts and waits on the FIFO. (Opening the FIFO to look would end it.)
  for (int i = 0; i < 500 && !has_child(pid); ++i) std::this_thread::sleep_for(std::chrono::milliseconds(10));
  ::kill(pid, SIGTERM);
  int status = 0;
  ::waitpid(pid, &status, 0);
  CHECK(WIFSIGNALED(status));
  CHECK(WTERMSIG(status) == SIGTERM);
  CHECK_FALSE(fifo_has_reader(fifo));  // the job went with it
  const Json s = Json::parse(slurp(summary));
  CHECK(s["totals"]["ok"] == 1);
  CHECK(s["totals"]["failed"] == 2);
  const Json& j = s["jobs"];
  REQUIRE(j.size() == 3);
  CHECK(j[0]["status"] == "ok");
  CHECK(j[1]["error"] == "killed by signal 15 (Terminated)");
  CHECK(j[1]["attempts"] == 1);
  CHECK(j[2]["error"] == "not run: stopped by signal 15 (Terminated)");
  CHECK(j[2]["attempts"] == 0);
  CHECK_FALSE(fs::exists(summary + ".journal"));
}

TEST_CASE("cli batch: a shard killed with SIGKILL keeps the records of its finished jobs", "[batch][cli]") {
  Sandbox box;
  const std::vector<std::string> takes = test::asset_motions();
  const std::string fifo = box.path("hang.bvh");
  REQUIRE(::mkfifo(fifo.c_str(), 0600) == 0);
  // One at a time: three quick jobs, then one that waits on the FIFO until it is killed.
  const std::string file = box.write("jobs.jsonl", job({"info", takes[0]}) + job({"info", takes[1]}) +
                                                       job({"info", box.path("none.bvh")}) + job({"info", fifo}) +
                                                       job({"info", takes[2]}));
  const std::string summary = box.path("s.json");
  const pid_t pid = start_cli({"batch", file, "--jobs", "1", "--summary", summary});
  REQUIRE(pid > 0);
  const std::string journal = summary + ".journal";
  wait_for_lines(journal, 3);
  ::kill(pid, SIGKILL);
  int status = 0;
  ::waitpid(pid, &status, 0);
  CHECK(WIFSIGNALED(status));
  // The job still waiting on the FIFO outlived the batch: a writer that comes and goes ends it.
  for (int i = 0; i < 500 && !fifo_has_reader(fifo); ++i) std::this_thread::sleep_for(std::chrono::milliseconds(10));
  CHECK_FALSE(fs::exists(summary));
  std::vector<Json> records;
  std::istringstream in(slurp(journal));
  for (std::string line; std::getline(in, line);) records.push_back(Json::parse(line));
  REQUIRE(records.size() == 3);
  for (int k = 0; k < 3; ++k) {
    INFO(k);
    CHECK(records[k]["line"] == k + 1);
    CHECK(records[k]["status"] == (k == 2 ? "failed" : "ok"));
    CHECK(records[k]["args"][0] == "info");
  }
  CHECK(records[2]["error"].get<std::string>().rfind(box.path("none.bvh") + ": cannot read: ", 0) == 0);
}
