// The worker thread (engine/worker.h). Built as its own executable, mostyle_worker_tests, which
// CI also runs under ThreadSanitizer.
#include "engine/run/worker.h"

#include <atomic>
#include <catch2/catch.hpp>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <thread>

#include "engine/kinematics/limb_length.h"
#include "tests/test_data.h"

using namespace mostyle;
using Clock = std::chrono::steady_clock;

namespace {

const std::string kHappy = "motions/cmu142_walk_happy.bvh";
const std::string kJoy = "motions/cmu142_walk_joy.bvh";
const std::string kClumsy = "motions/cmu142_walk_clumsy.bvh";
const std::string kMarching = "motions/cmu142_walk_marching.bvh";

double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

// The blend a snapshot should hold: blend_pair on its own prepared and decomposed pair.
Eigen::MatrixXd direct_blend(const WorkerSnapshot& s) {
  BlendScratch scratch;
  BlendResult out;
  blend_pair(*s.prepared, *s.decomposed, s.blend_params, scratch, out);
  return out.world;
}

// Waits (polling, as the UI does) until the worker runs `stage`; false after `timeout` seconds.
bool wait_for_stage(const Worker& w, WorkerStage stage, double timeout = 30.0) {
  const auto t0 = Clock::now();
  while (w.status().stage != stage) {
    if (seconds_since(t0) > timeout) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  return true;
}

std::string temporary_file(const std::string& name, const std::string& content) {
  const std::filesystem::path path = std::filesystem::temp_directory_path() / name;
  std::ofstream(path, std::ios::binary) << content;
  return path.string();
}

}  // namespace

TEST_CASE("stage names", "[worker]") {
  CHECK(std::string(worker_stage_name(WorkerStage::kIdle)) == "idle");
  CHECK(std::string(worker_stage_name(WorkerStage::kLoading)) == "loading");
  CHECK(std::string(worker_stage_name(WorkerStage::kDecomposing)) == "decomposing");
  CHECK(std::string(worker_stage_name(WorkerStage::kBlending)) == "blending");
}

TEST_CASE("a new worker is idle with an empty snapshot", "[worker]") {
  Worker w;
  w.wait_idle();  // returns at once
  const WorkerStatus status = w.status();
  CHECK(status.stage == WorkerStage::kIdle);
  CHECK_FALSE(status.pending);
  const auto s = w.snapshot();
  REQUIRE(s);
  CHECK_FALSE(s->prepared);
  CHECK_FALSE(s->decomposed);
  CHECK_FALSE(s->blend);
  CHECK(s->error.empty());
  CHECK(s->version == 0);
  // Parameters without a pair wait for one; they are not an error.
  w.blend(BlendParams());
  DecomposeParams d;
  d.components = 3;
  w.decompose(d);
  w.wait_idle();
  CHECK(w.snapshot()->error.empty());
  CHECK_FALSE(w.status().pending);
}

TEST_CASE("loads the bundled pair, decomposes and blends it", "[worker]") {
  Worker w;
  const std::string a = test::asset(kHappy), b = test::asset(kJoy);
  w.load(a, b);
  w.wait_idle();
  const auto s = w.snapshot();
  INFO(s->error);
  REQUIRE(s->error.empty());
  REQUIRE(s->prepared);
  REQUIRE(s->decomposed);
  REQUIRE(s->blend);
  CHECK(s->path_a == a);
  CHECK(s->path_b == b);
  CHECK(s->version >= 3);  // loaded, decomposed, blended
  CHECK(s->decompose_params.components == DecomposeParams().components);
  CHECK(s->decompose_params.sparsity == DecomposeParams().sparsity);
  CHECK(s->blend_params.alpha == BlendParams().alpha);
  CHECK(s->decomposed->params.components == s->decompose_params.components);
  CHECK(s->prepared->times.load_ms > 0);
  // The blend plays on its own timeline (timing blended with alpha), within A's frames.
  CHECK(s->blend->world.rows() == s->blend->source_a.size());
  CHECK(s->blend->source_a.maxCoeff() <= s->prepared->world_a.rows() - 1);
  CHECK(s->blend->world.cols() == 3 * static_cast<Eigen::Index>(s->prepared->majors.size()));
  CHECK(s->blend->world == direct_blend(*s));
  CHECK(max_bone_length_error(s->blend->world, s->prepared->parents, s->prepared->lengths_a) < 1e-9);
  const WorkerStatus status = w.status();
  CHECK(status.stage == WorkerStage::kIdle);
  CHECK_FALSE(status.pending);
  CHECK(status.progress == 0.0f);
}

TEST_CASE("one file is blended with itself", "[worker]") {
  Worker w;
  const std::string a = test::asset(kClumsy);
  w.load(a, "");
  w.wait_idle();
  const auto s = w.snapshot();
  REQUIRE(s->blend);
  CHECK(s->path_b == a);
  CHECK(s->prepared->clip_a == s->prepared->clip_b);  // read once
}

TEST_CASE("an alpha change re-runs only synthesis and post-processing", "[worker]") {
  Worker w;
  w.load(test::asset(kHappy), test::asset(kJoy));
  w.wait_idle();
  const auto before = w.snapshot();
  REQUIRE(before->blend);
  BlendParams params;
  params.alpha = 0.9;
  w.blend(params);
  w.wait_idle();
  const auto after = w.snapshot();
  CHECK(after->prepared == before->prepared);
  CHECK(after->decomposed == before->decomposed);  // the same decomposition, not a new one
  CHECK(after->blend != before->blend);
  CHECK(after->blend_params.alpha == 0.9);
  CHECK(after->version == before->version + 1);
  CHECK(after->blend->world == direct_blend(*after));
  // The old snapshot is untouched: results are immutable.
  CHECK(before->blend_params.alpha == BlendParams().alpha);
  CHECK(before->blend->world == direct_blend(*before));
}

TEST_CASE("new decomposition parameters re-decompose and re-blend", "[worker]") {
  Worker w;
  w.load(test::asset(kHappy), test::asset(kJoy));
  w.wait_idle();
  const auto before = w.snapshot();
  DecomposeParams d;
  d.components = 4;
  d.sparsity = 0.3;
  w.decompose(d);
  w.wait_idle();
  const auto after = w.snapshot();
  CHECK(after->prepared == before->prepared);
  CHECK(after->decomposed != before->decomposed);
  CHECK(after->decomposed->components() == 4);
  CHECK(after->decompose_params.sparsity == 0.3);
  REQUIRE(after->blend);
  CHECK(after->blend->world == direct_blend(*after));
}

TEST_CASE("errors become sentences in the snapshot and keep what was loaded", "[worker]") {
  Worker w;
  w.load(test::asset(kHappy), test::asset(kJoy));
  w.wait_idle();
  const auto good = w.snapshot();
  REQUIRE(good->blend);

  SECTION("a malformed file") {
    const std::string bad = temporary_file("mostyle_worker_test_bad.bvh", "HIERARCHY\nROOT Hips\n{\n  OFFSET 0 0\n");
    w.load(bad, test::asset(kJoy));
    w.wait_idle();
    const auto s = w.snapshot();
    INFO(s->error);
    CHECK(s->error.rfind(bad + ":", 0) == 0);  // "FILE:LINE: ..."
    CHECK(s->prepared == good->prepared);
    CHECK(s->decomposed == good->decomposed);
    CHECK(s->blend == good->blend);
    CHECK(s->path_a == good->path_a);
    CHECK_FALSE(w.status().pending);
    std::filesystem::remove(bad);
  }
  SECTION("a missing file") {
    w.load("/nonexistent/walk.bvh", "");
    w.wait_idle();
    const auto s = w.snapshot();
    CHECK(s->error.find("/nonexistent/walk.bvh") != std::string::npos);
    CHECK(s->prepared == good->prepared);
  }
  SECTION("bad decomposition parameters") {
    DecomposeParams d;
    d.components = 1000;
    w.decompose(d);
    w.wait_idle();
    const auto s = w.snapshot();
    INFO(s->error);
    CHECK(s->error.rfind("expected from 1 to", 0) == 0);
    CHECK(s->decomposed == good->decomposed);
    CHECK(s->blend == good->blend);
  }
  SECTION("a bad alpha") {
    BlendParams b;
    b.alpha = std::nan("");
    w.blend(b);
    w.wait_idle();
    const auto s = w.snapshot();
    CHECK(s->error == "expected a finite alpha");
    CHECK(s->blend == good->blend);
  }
  // A later success clears the error.
  BlendParams b;
  b.alpha = 0.25;
  w.blend(b);
  w.wait_idle();
  CHECK(w.snapshot()->error.empty());
  CHECK(w.snapshot()->blend_params.alpha == 0.25);
}

TEST_CASE("a new request cancels a long decomposition at its next iteration", "[worker]") {
  Worker w;
  w.load(test::asset(kHappy), test::asset(kJoy));
  w.wait_idle();
  DecomposeParams endless;
  endless.components = 20;
  endless.max_iterations = 100000000;
  endless.tolerance = 0;  // never converges: hours of work
  w.decompose(endless);
  REQUIRE(wait_for_stage(w, WorkerStage::kDecomposing));
  std::this_thread::sleep_for(std::chrono::milliseconds(100));
  const WorkerStatus running = w.status();
  CHECK(running.stage == WorkerStage::kDecomposing);
  CHECK(running.progress >= 0.0f);
  CHECK(running.progress <= 1.0f);
  DecomposeParams quick;
  quick.components = 3;
  quick.max_iterations = 5;
  const auto t0 = Clock::now();
  w.decompose(quick);
  w.wait_idle();
  const double elapsed = seconds_since(t0);
  INFO("cancelled and redone in " << elapsed << " s");
  CHECK(elapsed < 5.0);  // an iteration is milliseconds (more under sanitizers)
  const auto s = w.snapshot();
  CHECK(s->error.empty());
  CHECK(s->decompose_params.max_iterations == 5);
  CHECK(s->decomposed->components() == 3);
}

TEST_CASE("a load cancels a long decomposition, and so does the destructor", "[worker]") {
  const auto t0 = Clock::now();
  {
    Worker w;
    w.load(test::asset(kHappy), test::asset(kJoy));
    DecomposeParams endless;
    endless.max_iterations = 100000000;
    endless.tolerance = 0;
    w.decompose(endless);
    REQUIRE(wait_for_stage(w, WorkerStage::kDecomposing));
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    DecomposeParams quick;
    quick.max_iterations = 3;
    w.load(test::asset(kClumsy), test::asset(kMarching));
    w.decompose(quick);
    w.wait_idle();
    CHECK(w.snapshot()->path_a == test::asset(kClumsy));
    CHECK(w.snapshot()->decompose_params.max_iterations == 3);
    w.decompose(endless);
    REQUIRE(wait_for_stage(w, WorkerStage::kDecomposing));
  }  // destroyed while decomposing
  CHECK(seconds_since(t0) < 60.0);
}

TEST_CASE("a thousand parameter changes while another thread reads results", "[worker]") {
  Worker w;
  w.load(test::asset(kHappy), test::asset(kJoy));

  std::atomic<bool> stop{false};
  std::atomic<long> reads{0}, bad_reads{0};
  std::thread reader([&] {
    std::uint64_t last_version = 0;
    while (!stop.load()) {
      const auto s = w.snapshot();
      const WorkerStatus status = w.status();
      bool ok = s && s->version >= last_version && status.progress >= 0.0f && status.progress <= 1.0f;
      if (ok) last_version = s->version;
      if (ok && s->blend) {
        // A published blend comes with the pair and decomposition it was made from; read all of it.
        ok = s->prepared && s->decomposed && s->blend->world.rows() == s->blend->source_a.size() &&
             s->blend->source_a.maxCoeff() <= s->prepared->world_a.rows() - 1 &&
             s->blend_params.alpha >= 0.0 && s->blend_params.alpha <= 1.0;
        double sum = 0;
        for (Eigen::Index i = 0; i < s->blend->world.size(); ++i) sum += s->blend->world.data()[i];
        ok = ok && std::isfinite(sum) && s->decomposed->shared_synthesis.components.rows() == s->decomposed->components();
      }
      bad_reads += ok ? 0 : 1;
      ++reads;
    }
  });

  std::mt19937 random(42);
  DecomposeParams last_decompose;
  BlendParams last_blend;
  std::string last_a = test::asset(kHappy), last_b = test::asset(kJoy);
  for (int i = 0; i < 1000; ++i) {
    if (i % 250 == 125) {
      const bool first = (i / 250) % 2 == 0;
      last_a = test::asset(first ? kClumsy : kHappy);
      last_b = test::asset(first ? kMarching : kJoy);
      w.load(last_a, last_b);
    } else if (i % 10 == 3) {
      last_decompose.components = 2 + static_cast<int>(random() % 11);
      last_decompose.sparsity = 0.2 + 0.1 * static_cast<double>(random() % 9);
      last_decompose.max_iterations = 20;
      w.decompose(last_decompose);
    } else {
      last_blend.alpha = static_cast<double>(random() % 1001) / 1000.0;
      w.blend(last_blend);
    }
    if (i % 20 == 0) std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  w.wait_idle();
  stop = true;
  reader.join();

  INFO(reads.load() << " reads");
  CHECK(reads.load() > 0);
  CHECK(bad_reads.load() == 0);
  const auto s = w.snapshot();
  INFO(s->error);
  CHECK(s->error.empty());
  REQUIRE(s->blend);
  CHECK(s->path_a == last_a);
  CHECK(s->path_b == last_b);
  CHECK(s->decompose_params.components == last_decompose.components);
  CHECK(s->decompose_params.sparsity == last_decompose.sparsity);
  CHECK(s->decompose_params.max_iterations == last_decompose.max_iterations);
  CHECK(s->decomposed->components() == last_decompose.components);
  CHECK(s->blend_params.alpha == last_blend.alpha);
  CHECK(s->blend->world == direct_blend(*s));
  CHECK_FALSE(w.status().pending);
}
