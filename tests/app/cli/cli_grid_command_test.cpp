// mostyle-cli grid, run as a user runs it: one blend per ordered pair of takes and alpha, or one
// transfer per content, style and strength; bad usage exits 2 and writes nothing.
#include <algorithm>
#include <catch2/catch.hpp>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <string>

#include "tests/app/cli/cli_sandbox.h"
#include "tests/test_data.h"

namespace fs = std::filesystem;
using Json = nlohmann::json;
using namespace mostyle;

namespace {

using Run = test::CliRun;
using test::slurp;

std::string quoted(const std::string& s) { return test::shell_quoted(s); }

class Sandbox : public test::CliSandbox {
 public:
  Sandbox() : test::CliSandbox("mostyle_grid_test") {}
};

std::vector<std::string> files_in(const std::string& dir) {
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(dir)) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

std::vector<Json> json_lines(const std::string& text) {
  std::vector<Json> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(Json::parse(line));
  return lines;
}

}  // namespace

TEST_CASE("cli grid: one blend per ordered pair and alpha, run by batch", "[batch][cli]") {
  Sandbox box;
  const std::vector<std::string> takes = test::asset_motions();
  const std::string a = takes[0], b = takes[1], c = takes[2];
  const std::string out = box.path("grid");
  const Run r = box.cli("grid --takes " + quoted(a) + " " + quoted(b) + " " + quoted(c) + " --alphas 0,0.5 --out-dir " +
                        quoted(out) + " --jobs-out " + quoted(box.path("grid.jsonl")) +
                        " -- --components 4 --iterations 20");
  CHECK(r.status == 0);
  CHECK(r.out.empty());
  CHECK(fs::is_directory(out));
  std::vector<Json> lines;
  std::istringstream in(slurp(box.path("grid.jsonl")));
  for (std::string line; std::getline(in, line);) lines.push_back(Json::parse(line));
  REQUIRE(lines.size() == 3 * 2 * 2);
  const std::string base = out + "/cmu142_walk_clumsy__cmu142_walk_happy__a";
  CHECK(lines[0] == Json({"blend", a, b, "--alpha", "0", "--out", base + "0.bvh", "--report", base + "0.json",
                          "--components", "4", "--iterations", "20"}));
  CHECK(lines[1][4] == "0.5");
  CHECK(lines[1][6] == base + "0.5.bvh");
  std::set<std::string> outputs;
  for (const Json& l : lines) {
    CHECK(l[1] != l[2]);
    outputs.insert(l[6].get<std::string>());
  }
  CHECK(outputs.size() == lines.size());
  CHECK(outputs.count(out + "/cmu142_walk_joy__cmu142_walk_clumsy__a0.5.bvh") == 1);

  // To stdout without --jobs-out; two takes and two alphas, then run.
  const Run small = box.cli("grid --takes " + quoted(a) + " " + quoted(b) + " --alphas 0.25,1 --out-dir " +
                            quoted(out) + " -- --components 4 --iterations 20");
  CHECK(small.status == 0);
  CHECK(std::count(small.out.begin(), small.out.end(), '\n') == 4);
  const std::string jobs = box.write("small.jsonl", small.out);
  const Run ran = box.cli("batch " + quoted(jobs) + " --jobs 2");
  CHECK(ran.status == 0);
  CHECK(ran.out.rfind(jobs + ": 4 jobs, 4 ok, 0 failed, ", 0) == 0);
  CHECK(files_in(out) == std::vector<std::string>{
                             "cmu142_walk_clumsy__cmu142_walk_happy__a0.25.bvh",
                             "cmu142_walk_clumsy__cmu142_walk_happy__a0.25.json",
                             "cmu142_walk_clumsy__cmu142_walk_happy__a1.bvh",
                             "cmu142_walk_clumsy__cmu142_walk_happy__a1.json",
                             "cmu142_walk_happy__cmu142_walk_clumsy__a0.25.bvh",
                             "cmu142_walk_happy__cmu142_walk_clumsy__a0.25.json",
                             "cmu142_walk_happy__cmu142_walk_clumsy__a1.bvh",
                             "cmu142_walk_happy__cmu142_walk_clumsy__a1.json",
                         });
}

TEST_CASE("cli grid: bad usage exits 2 and writes nothing", "[batch][cli]") {
  Sandbox box;
  const std::vector<std::string> takes = test::asset_motions();
  const std::string two = " --takes " + quoted(takes[0]) + " " + quoted(takes[1]);
  const std::string rest = " --out-dir " + quoted(box.path("out")) + " --jobs-out " + quoted(box.path("g.jsonl"));
  for (const std::string& args : {
           "grid --takes " + quoted(takes[0]) + " --alphas 0.5" + rest,        // one take
           "grid" + two + " --takes " + quoted(box.path("x/" + fs::path(takes[0]).filename().string())) +
               " --alphas 0.5" + rest,                                          // same name twice
           "grid" + two + " --alphas 0,nan" + rest,                             // not finite
           "grid" + two + " --alphas 0.5,0.50" + rest,                          // same alpha twice
           "grid" + two + " --alphas 0,5" + rest,                               // beyond blend's -0.5 to 1.5
           "grid" + two + " --alphas 0.5" + rest + " -- --out x.bvh",           // set by grid
           "grid" + two + " --alphas 0.5" + rest + " -- --report=x.json",       // set by grid
           "grid" + two + " --alphas 0.5" + rest + " -- --bogus",               // not a blend option
           "grid" + two + " --alphas 0.5" + rest + " -- --mode fancy",          // not a blend value
           "grid" + two + rest,                                                 // no --alphas
       }) {
    INFO(args);
    const Run r = box.cli(args);
    CHECK(r.status == 2);
    CHECK_FALSE(fs::exists(box.path("g.jsonl")));
    CHECK_FALSE(fs::exists(box.path("out")));
  }
}

TEST_CASE("cli grid --transfer: one transfer per content, style and strength, run by batch", "[batch][cli]") {
  Sandbox box;
  const std::vector<std::string> takes = test::asset_motions();
  // clumsy and happy as contents, joy the neutral, marching and happy as styles.
  const std::string out = box.path("tr");
  const Run r = box.cli("grid --transfer --contents " + quoted(takes[0]) + " " + quoted(takes[1]) + " --neutral " +
                        quoted(takes[2]) + " --styles " + quoted(takes[3]) + "," + quoted(takes[1]) +
                        " --strengths 0.5,1 --out-dir " + quoted(out) + " --jobs-out " +
                        quoted(box.path("t.jsonl")) + " -- --components 4 --iterations 20");
  CHECK(r.status == 0);
  CHECK(r.out.empty());
  const std::vector<Json> lines = json_lines(slurp(box.path("t.jsonl")));
  REQUIRE(lines.size() == 2 * 2 * 2);
  const std::string base = out + "/cmu142_walk_clumsy__cmu142_walk_marching__s";
  CHECK(lines[0] == Json({"transfer", takes[0], "--neutral", takes[2], "--style", takes[3], "--strength", "0.5",
                          "--out", base + "0.5.bvh", "--report", base + "0.5.json", "--components", "4",
                          "--iterations", "20"}));
  CHECK(lines[1][7] == "1");
  CHECK(lines[2][5] == takes[1]);
  std::set<std::string> outputs;
  for (const Json& l : lines) outputs.insert(l[9].get<std::string>());
  CHECK(outputs.size() == lines.size());
  CHECK(outputs.count(out + "/cmu142_walk_happy__cmu142_walk_happy__s1.bvh") == 1);

  // One content, one style, one strength, to stdout, then run.
  const Run one = box.cli("grid --transfer --contents " + quoted(takes[0]) + " --neutral " + quoted(takes[2]) +
                          " --styles " + quoted(takes[3]) + " --strengths 1 --out-dir " + quoted(out) +
                          " -- --components 4 --iterations 20");
  CHECK(one.status == 0);
  const std::string jobs = box.write("one.jsonl", one.out);
  const Run ran = box.cli("batch " + quoted(jobs));
  CHECK(ran.status == 0);
  CHECK(files_in(out) == std::vector<std::string>{"cmu142_walk_clumsy__cmu142_walk_marching__s1.bvh",
                                                  "cmu142_walk_clumsy__cmu142_walk_marching__s1.json"});
  CHECK(Json::parse(slurp(out + "/cmu142_walk_clumsy__cmu142_walk_marching__s1.json"))["command"] == "transfer");

  // No neutral: each content is its own; the lines have no --neutral and the outputs the same names.
  const Run own = box.cli("grid --transfer --contents " + quoted(takes[0]) + " --styles " + quoted(takes[3]) +
                          " --strengths 1 --out-dir " + quoted(out) + " -- --components 4 --iterations 20");
  CHECK(own.status == 0);
  const std::vector<Json> own_lines = json_lines(own.out);
  REQUIRE(own_lines.size() == 1);
  const std::string named = out + "/cmu142_walk_clumsy__cmu142_walk_marching__s1";
  CHECK(own_lines[0] == Json({"transfer", takes[0], "--style", takes[3], "--strength", "1", "--out", named + ".bvh",
                              "--report", named + ".json", "--components", "4", "--iterations", "20"}));
}

TEST_CASE("cli grid --transfer: bad usage exits 2 and writes nothing", "[batch][cli]") {
  Sandbox box;
  const std::vector<std::string> takes = test::asset_motions();
  const std::string c = " --contents " + quoted(takes[0]);
  const std::string n = " --neutral " + quoted(takes[1]);
  const std::string st = " --styles " + quoted(takes[2]);
  const std::string rest = " --out-dir " + quoted(box.path("out")) + " --jobs-out " + quoted(box.path("g.jsonl"));
  for (const std::string& args : {
           "grid" + c + n + st + " --strengths 1" + rest,                            // no --transfer
           "grid --transfer" + n + st + " --strengths 1" + rest,                     // no content
           "grid --transfer" + c + n + " --strengths 1" + rest,                      // no style
           "grid --transfer" + c + n + st + rest,                                    // no strength
           "grid --transfer" + c + n + st + " --strengths 2.5" + rest,               // out of range
           "grid --transfer" + c + n + st + " --strengths 1,nan" + rest,             // not finite
           "grid --transfer" + c + n + st + " --strengths 1,1.0" + rest,             // twice
           "grid --transfer" + c + n + st + "," + quoted(box.path("x/" + fs::path(takes[2]).filename().string())) +
               " --strengths 1" + rest,                                              // same name twice
           "grid --transfer" + c + n + st + " --strengths 1 --alphas 0.5" + rest,    // a blend grid's
           "grid --transfer" + c + n + st + " --strengths 1" + rest + " -- --strength 2",   // set by grid
           "grid --transfer" + c + n + st + " --strengths 1" + rest + " -- --style x.bvh",  // set by grid
           "grid --transfer" + c + n + st + " --strengths 1" + rest + " -- --alpha 0.5",    // not transfer's
           "grid --transfer" + c + n + st + " --strengths 1" + rest + " -- --timing a",     // not transfer's
       }) {
    INFO(args);
    const Run r = box.cli(args);
    CHECK(r.status == 2);
    CHECK_FALSE(fs::exists(box.path("g.jsonl")));
    CHECK_FALSE(fs::exists(box.path("out")));
  }
}
