// app/batch/job_outputs: which files a job writes, for batch --skip-existing.
#include "app/batch/job_outputs.h"

#include <unistd.h>

#include <algorithm>
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>

using mostyle::cli::job_outputs;
using Args = std::vector<std::string>;

TEST_CASE("job outputs: the values of the output options, both spellings", "[batch][cli]") {
  CHECK(job_outputs({"blend", "a.bvh", "b.bvh", "--alpha", "0.5", "--out", "ab.bvh", "--report", "ab.json"}) ==
        Args{"ab.bvh", "ab.json"});
  CHECK(job_outputs({"mix", "a.bvh", "b.bvh", "--positions-out=p.csv", "--out=m.bvh"}) == Args{"p.csv", "m.bvh"});
  CHECK(job_outputs({"fk", "a.bvh", "--out", "p.csv"}) == Args{"p.csv"});
  CHECK(job_outputs({"grid", "--takes", "a.bvh", "b.bvh", "--jobs-out", "j.jsonl", "--", "--report", "x"}) ==
        Args{"j.jsonl"});
}

TEST_CASE("job outputs: none for jobs that name no output by option", "[batch][cli]") {
  CHECK(job_outputs({"info", "a.bvh", "--json"}).empty());
  CHECK(job_outputs({"convert", "in.bvh", "out.bvh"}).empty());
  CHECK(job_outputs({"blend", "a.bvh", "b.bvh", "--out"}).empty());  // no value: blend's usage error
  CHECK(job_outputs({"blend", "--outline", "--out-dir", "x", "--reports=y"}).empty());
  CHECK(job_outputs({}).empty());
}

TEST_CASE("job outputs: remove_leftovers removes a killed process's temporary outputs only", "[batch][cli]") {
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / ("mostyle_job_outputs_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  const std::vector<std::string> names = {"ab.bvh", "ab.bvh.tmp123_0", "ab.bvh.tmp123_7", "ab.json.tmp123_1",
                                          "ab.bvh.tmp1234_0", "ab.bvh.tmp123_", "ab.bvh.tmp123_x", "cd.bvh.tmp123_0"};
  for (const std::string& n : names) std::ofstream(dir / n) << "x";
  const std::string out = (dir / "ab.bvh").string(), report = (dir / "ab.json").string();
  CHECK(mostyle::cli::remove_leftovers({out, report}, 123) == 3);
  std::vector<std::string> left;
  for (const auto& e : fs::directory_iterator(dir)) left.push_back(e.path().filename().string());
  std::sort(left.begin(), left.end());
  CHECK(left == Args{"ab.bvh", "ab.bvh.tmp1234_0", "ab.bvh.tmp123_", "ab.bvh.tmp123_x", "cd.bvh.tmp123_0"});
  CHECK(mostyle::cli::remove_leftovers({(dir / "none" / "x.bvh").string()}, 123) == 0);  // no such folder
  fs::remove_all(dir);
}
