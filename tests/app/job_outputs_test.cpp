// app/job_outputs: which files a job writes, for batch --skip-existing.
#include "app/job_outputs.h"

#include <catch2/catch.hpp>

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
