// The worker thread (engine/worker.h). Built as its own executable, mostyle_worker_tests, which
// CI also runs under ThreadSanitizer.
#include "engine/worker/worker.h"

#include <atomic>
#include <catch2/catch.hpp>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <thread>
#include <vector>

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

// What a caller makes of a snapshot: mix_palette on its own prepared and decomposed takes, with
// `weights` (equal ones when empty).
MixResult mix_of(const WorkerSnapshot& s, std::vector<double> weights = {}) {
  const int n = s.prepared->size();
  MixParams params;
  params.layers = take_layers(weights.empty() ? std::vector<double>(static_cast<size_t>(n), 1.0 / n) : weights);
  MixScratch scratch;
  MixResult out;
  mix_palette(*s.prepared, *s.decomposed, params, scratch, out);
  return out;
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

std::vector<std::string> assets(const std::vector<std::string>& names) {
  std::vector<std::string> paths;
  for (const std::string& n : names) paths.push_back(test::asset(n));
  return paths;
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
  CHECK(s->error.empty());
  CHECK(s->version == 0);
  // Parameters without takes wait for them; they are not an error.
  DecomposeParams d;
  d.components = 3;
  w.decompose(d);
  w.wait_idle();
  CHECK(w.snapshot()->error.empty());
  CHECK_FALSE(w.status().pending);
}

TEST_CASE("loads the bundled pair and decomposes it: all a blend needs", "[worker]") {
  Worker w;
  const std::string a = test::asset(kHappy), b = test::asset(kJoy);
  w.load({a, b});
  w.wait_idle();
  const auto s = w.snapshot();
  INFO(s->error);
  REQUIRE(s->error.empty());
  REQUIRE(s->prepared);
  REQUIRE(s->decomposed);
  CHECK(s->paths[0] == a);
  CHECK(s->paths[1] == b);
  CHECK(s->version >= 2);  // loaded, decomposed
  CHECK(s->decompose_params.components == DecomposeParams().components);
  CHECK(s->decompose_params.sparsity == DecomposeParams().sparsity);
  CHECK(s->decomposed->params.components == s->decompose_params.components);
  CHECK(s->times.load_ms > 0);  // beside the stage values
  CHECK(s->times.decompose_ms > 0);
  // A blend of the snapshot plays on its own timeline (timing blended), within A's frames.
  const MixResult blend = mix_of(*s, {0.5, 0.5});
  CHECK(blend.motion.world.rows() == blend.sources.col(0).size());
  CHECK(blend.sources.col(0).maxCoeff() <= s->prepared->takes[0].world.rows() - 1);
  CHECK(blend.motion.world.cols() == 3 * static_cast<Eigen::Index>(s->prepared->majors.size()));
  CHECK(max_bone_length_error(blend.motion.world, s->prepared->parents, s->prepared->lengths) < 1e-9);
  const WorkerStatus status = w.status();
  CHECK(status.stage == WorkerStage::kIdle);
  CHECK_FALSE(status.pending);
  CHECK(status.progress == 0.0f);
}

TEST_CASE("one file is loaded as the take with itself", "[worker]") {
  Worker w;
  const std::string a = test::asset(kClumsy);
  w.load({a});
  w.wait_idle();
  const auto s = w.snapshot();
  REQUIRE(s->decomposed);
  CHECK(s->paths[1] == a);
  CHECK(s->prepared->takes[0].clip == s->prepared->takes[1].clip);  // read once
}

TEST_CASE("new decomposition parameters decompose again, on the same takes", "[worker]") {
  Worker w;
  w.load({test::asset(kHappy), test::asset(kJoy)});
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
  CHECK(after->version == before->version + 1);
  // The old snapshot is untouched: results are immutable.
  CHECK(before->decomposed->components() == DecomposeParams().components);
}

TEST_CASE("errors become sentences in the snapshot and keep what was loaded", "[worker]") {
  Worker w;
  w.load({test::asset(kHappy), test::asset(kJoy)});
  w.wait_idle();
  const auto good = w.snapshot();
  REQUIRE(good->decomposed);

  SECTION("a malformed file") {
    const std::string bad = temporary_file("mostyle_worker_test_bad.bvh", "HIERARCHY\nROOT Hips\n{\n  OFFSET 0 0\n");
    w.load({bad, test::asset(kJoy)});
    w.wait_idle();
    const auto s = w.snapshot();
    INFO(s->error);
    CHECK(s->error.rfind(bad + ":", 0) == 0);  // "FILE:LINE: ..."
    CHECK(s->prepared == good->prepared);
    CHECK(s->decomposed == good->decomposed);
    CHECK(s->paths[0] == good->paths[0]);
    CHECK_FALSE(w.status().pending);
    std::filesystem::remove(bad);
  }
  SECTION("a missing file") {
    w.load({"/nonexistent/walk.bvh"});
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
  }
  // A later success clears the error.
  DecomposeParams d;
  d.components = 5;
  w.decompose(d);
  w.wait_idle();
  CHECK(w.snapshot()->error.empty());
  CHECK(w.snapshot()->decomposed->components() == 5);
}

TEST_CASE("loads are bounded by the memory limit the worker was given", "[worker]") {
  // 2000 frames x 6 channels x 8 bytes = 94 KB of frames; the file itself is 24 KB.
  std::string text = "HIERARCHY\nROOT Hips\n{\nOFFSET 0 0 0\nCHANNELS 6 Xposition Yposition Zposition "
                     "Zrotation Xrotation Yrotation\nEnd Site\n{\nOFFSET 0 1 0\n}\n}\nMOTION\nFrames: 2000\n"
                     "Frame Time: 0.01\n";
  for (int f = 0; f < 2000; ++f) text += "0 0 0 0 0 0\n";
  const std::string big = temporary_file("mostyle_worker_test_limit.bvh", text);
  BvhReadOptions read;
  read.max_bytes = 64 << 10;
  Worker w(read);
  SECTION("a pair") {
    w.load({big, test::asset(kJoy)});
    w.wait_idle();
    CHECK(w.snapshot()->error == big + ":12: expected frames within the memory limit of 64 KB, found Frames: 2000 "
                                       "of 6 values each (93.8 KB)");
    CHECK_FALSE(w.snapshot()->prepared);
  }
  SECTION("a palette") {
    // The big take first: the bundled ones are larger than 64 KB too.
    w.load({big, test::asset(kJoy), test::asset(kHappy)});
    w.wait_idle();
    INFO(w.snapshot()->error);
    CHECK(w.snapshot()->error.rfind(big + ":12: expected frames within the memory limit of 64 KB", 0) == 0);
    CHECK_FALSE(w.snapshot()->prepared);
  }
  SECTION("a file larger than the limit is not read") {
    Worker tiny(BvhReadOptions{16 << 10});
    tiny.load({big});
    tiny.wait_idle();
    CHECK(tiny.snapshot()->error == big + ": cannot read: its 23.7 KB exceed the memory limit of 16 KB");
  }
  std::filesystem::remove(big);
}

TEST_CASE("a new request cancels a long decomposition at its next iteration", "[worker]") {
  Worker w;
  w.load({test::asset(kHappy), test::asset(kJoy)});
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
    w.load({test::asset(kHappy), test::asset(kJoy)});
    DecomposeParams endless;
    endless.max_iterations = 100000000;
    endless.tolerance = 0;
    w.decompose(endless);
    REQUIRE(wait_for_stage(w, WorkerStage::kDecomposing));
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    DecomposeParams quick;
    quick.max_iterations = 3;
    w.load({test::asset(kClumsy), test::asset(kMarching)});
    w.decompose(quick);
    w.wait_idle();
    CHECK(w.snapshot()->paths[0] == test::asset(kClumsy));
    CHECK(w.snapshot()->decompose_params.max_iterations == 3);
    w.decompose(endless);
    REQUIRE(wait_for_stage(w, WorkerStage::kDecomposing));
  }  // destroyed while decomposing
  CHECK(seconds_since(t0) < 60.0);
}

TEST_CASE("a thousand parameter changes while another thread reads results", "[worker]") {
  Worker w;
  w.load({test::asset(kHappy), test::asset(kJoy)});

  std::atomic<bool> stop{false};
  std::atomic<long> reads{0}, bad_reads{0};
  std::thread reader([&] {
    std::uint64_t last_version = 0;
    while (!stop.load()) {
      const auto s = w.snapshot();
      const WorkerStatus status = w.status();
      bool ok = s && s->version >= last_version && status.progress >= 0.0f && status.progress <= 1.0f;
      if (ok) last_version = s->version;
      if (ok && s->decomposed) {
        // A published decomposition comes with the takes it was made from; read all of it.
        const Decomposed& d = *s->decomposed;
        ok = s->prepared && d.support.rows() == d.components() && d.components() == s->decompose_params.components;
        double sum = 0;
        for (Eigen::Index i = 0; i < d.support.size(); ++i) sum += d.support.data()[i];
        ok = ok && std::isfinite(sum);
      }
      bad_reads += ok ? 0 : 1;
      ++reads;
    }
  });

  std::mt19937 random(42);
  DecomposeParams last_decompose;
  std::string last_a = test::asset(kHappy), last_b = test::asset(kJoy);
  for (int i = 0; i < 1000; ++i) {
    if (i % 250 == 125) {
      const bool first = (i / 250) % 2 == 0;
      last_a = test::asset(first ? kClumsy : kHappy);
      last_b = test::asset(first ? kMarching : kJoy);
      w.load({last_a, last_b});
    } else {
      last_decompose.components = 2 + static_cast<int>(random() % 11);
      last_decompose.sparsity = 0.2 + 0.1 * static_cast<double>(random() % 9);
      last_decompose.max_iterations = 20;
      w.decompose(last_decompose);
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
  REQUIRE(s->decomposed);
  CHECK(s->paths[0] == last_a);
  CHECK(s->paths[1] == last_b);
  CHECK(s->decompose_params.components == last_decompose.components);
  CHECK(s->decompose_params.sparsity == last_decompose.sparsity);
  CHECK(s->decompose_params.max_iterations == last_decompose.max_iterations);
  CHECK(s->decomposed->components() == last_decompose.components);
  CHECK_FALSE(w.status().pending);
}

// The style palette: the same worker, with prepare_palette, decompose_palette and mix_palette.

TEST_CASE("loads a palette of three bundled takes and decomposes it", "[worker][palette]") {
  Worker w;
  const std::vector<std::string> paths = assets({kHappy, kMarching, kJoy});
  w.load(paths);
  w.wait_idle();
  const auto s = w.snapshot();
  INFO(s->error);
  REQUIRE(s->error.empty());
  REQUIRE(s->prepared);
  REQUIRE(s->decomposed);
  CHECK(s->prepared->size() == 3);
  CHECK(s->paths == paths);
  CHECK(s->prepared->takes.front().clip->source == paths.front());
  CHECK(s->version >= 2);  // loaded, decomposed
  // The current parameters: the default decomposition.
  CHECK(s->decomposed->components() == DecomposeParams().components);
  CHECK(s->decomposed->params.mode == DecompositionMode::kShared);
  // A mix of the snapshot has frames, one pose column per shared joint, a source per take.
  const MixResult mix = mix_of(*s);
  CHECK(mix.motion.world.rows() > 0);
  CHECK(mix.motion.world.cols() == 3 * static_cast<Eigen::Index>(s->prepared->majors.size()));
  CHECK(mix.sources.cols() == 3);
  const WorkerStatus status = w.status();
  CHECK(status.stage == WorkerStage::kIdle);
  CHECK_FALSE(status.pending);
}

TEST_CASE("new decomposition parameters decompose the palette again, in shared mode", "[worker][palette]") {
  Worker w;
  w.load(assets({kHappy, kMarching, kJoy}));
  w.wait_idle();
  const auto before = w.snapshot();
  REQUIRE(before->decomposed);
  DecomposeParams d;
  d.components = 4;
  d.sparsity = 0.3;
  SECTION("shared mode") {}
  SECTION("paper mode with basic motions, which are the pair's, decomposes shared components") {
    d.mode = DecompositionMode::kPaper;
    d.basic_motions = 2;
  }
  w.decompose(d);
  w.wait_idle();
  const auto after = w.snapshot();
  INFO(after->error);
  CHECK(after->error.empty());
  CHECK(after->prepared == before->prepared);
  REQUIRE(after->decomposed);
  CHECK(after->decomposed != before->decomposed);
  CHECK(after->decomposed->components() == 4);
  CHECK(after->decomposed->params.sparsity == 0.3);
  CHECK(after->decomposed->params.mode == DecompositionMode::kShared);
  CHECK(after->decomposed->params.basic_motions == 0);
  CHECK(after->decompose_params.mode == d.mode);  // the request, as made

  // Parameters decompose_palette refuses keep the decomposition.
  DecomposeParams bad;
  bad.components = 1000;
  w.decompose(bad);
  w.wait_idle();
  const auto s = w.snapshot();
  CHECK(s->error.rfind("expected from 1 to", 0) == 0);
  CHECK(s->decomposed == after->decomposed);
}

TEST_CASE("one chain for any number of takes: two, three, two again", "[worker][palette]") {
  Worker w;
  w.load({test::asset(kHappy), test::asset(kJoy)});
  w.wait_idle();
  REQUIRE(w.snapshot()->decomposed);

  const std::vector<std::string> paths = assets({kClumsy, kMarching, kJoy});
  w.load(paths);
  w.wait_idle();
  const auto palette = w.snapshot();
  INFO(palette->error);
  REQUIRE(palette->decomposed);
  CHECK(palette->paths == paths);
  CHECK(palette->prepared->size() == 3);
  CHECK(mix_of(*palette).sources.cols() == 3);

  // Two takes again: decomposed with the parameters asked for, basic motions and all.
  DecomposeParams d;
  d.mode = DecompositionMode::kPaper;
  d.basic_motions = 1;
  d.components = 4;
  w.decompose(d);
  w.load({test::asset(kHappy), test::asset(kJoy)});
  w.wait_idle();
  const auto pair = w.snapshot();
  INFO(pair->error);
  REQUIRE(pair->decomposed);
  CHECK(pair->prepared->size() == 2);
  CHECK(pair->decomposed->params.mode == DecompositionMode::kPaper);
  CHECK(pair->decomposed->params.basic_motions == 1);
  CHECK(mix_of(*pair, {0.25, 0.75}).sources.cols() == 2);
}

TEST_CASE("a failing palette load keeps what was loaded and names the file", "[worker][palette]") {
  Worker w;
  const std::string missing = "/nonexistent/walk.bvh";
  SECTION("after a palette") {
    w.load(assets({kHappy, kMarching, kJoy}));
    w.wait_idle();
    const auto good = w.snapshot();
    REQUIRE(good->decomposed);
    w.load({test::asset(kHappy), missing, test::asset(kJoy)});
    w.wait_idle();
    const auto s = w.snapshot();
    INFO(s->error);
    CHECK(s->error.find(missing) != std::string::npos);
    CHECK(s->prepared == good->prepared);
    CHECK(s->decomposed == good->decomposed);
    CHECK(s->paths == good->paths);
    CHECK_FALSE(w.status().pending);
    // Seventeen takes are too many.
    w.load(std::vector<std::string>(17, test::asset(kHappy)));
    w.wait_idle();
    CHECK_FALSE(w.snapshot()->error.empty());
    CHECK(w.snapshot()->prepared == good->prepared);
  }
  SECTION("after a pair") {
    w.load({test::asset(kHappy), test::asset(kJoy)});
    w.wait_idle();
    const auto good = w.snapshot();
    REQUIRE(good->decomposed);
    w.load({test::asset(kHappy), test::asset(kJoy), missing});
    w.wait_idle();
    const auto s = w.snapshot();
    INFO(s->error);
    CHECK(s->error.find(missing) != std::string::npos);
    CHECK(s->prepared == good->prepared);
    CHECK(s->decomposed == good->decomposed);
    CHECK(s->paths == good->paths);
    // The pair still takes parameters (nothing of the failed palette waits to run).
    DecomposeParams d;
    d.components = 5;
    w.decompose(d);
    w.wait_idle();
    CHECK(w.snapshot()->error.empty());
    CHECK(w.snapshot()->decomposed->components() == 5);
  }
}

TEST_CASE("a new palette load replaces a running one and ends with the latest", "[worker][palette]") {
  Worker w;
  const std::vector<std::string> first = assets({kHappy, kMarching, kJoy});
  const std::vector<std::string> latest = assets({kClumsy, kJoy});
  w.load(first);
  // The first load is usually seen running; when it is not, the second one replaced it pending.
  const bool seen = wait_for_stage(w, WorkerStage::kLoading, 5.0);
  INFO("first load seen running: " << seen);
  w.load(latest);
  w.wait_idle();
  const auto s = w.snapshot();
  INFO(s->error);
  CHECK(s->error.empty());
  CHECK(s->paths == latest);
  REQUIRE(s->prepared);
  CHECK(s->prepared->size() == 2);
  CHECK(s->prepared->takes.front().clip->source == latest.front());
  REQUIRE(s->decomposed);
  CHECK_FALSE(w.status().pending);
}

TEST_CASE("a palette load cancels a long decomposition, and so does a new decomposition", "[worker][palette]") {
  Worker w;
  w.load(assets({kHappy, kMarching, kJoy}));
  w.wait_idle();
  DecomposeParams endless;
  endless.components = 20;
  endless.max_iterations = 100000000;
  endless.tolerance = 0;  // never converges: hours of work
  w.decompose(endless);
  REQUIRE(wait_for_stage(w, WorkerStage::kDecomposing));
  std::this_thread::sleep_for(std::chrono::milliseconds(50));
  const WorkerStatus running = w.status();
  CHECK(running.progress >= 0.0f);
  CHECK(running.progress <= 1.0f);

  DecomposeParams quick;
  quick.components = 3;
  quick.max_iterations = 5;
  SECTION("a palette load") {
    const std::vector<std::string> paths = assets({kClumsy, kHappy});
    w.load(paths);
    w.decompose(quick);
    w.wait_idle();
    CHECK(w.snapshot()->paths == paths);
  }
  SECTION("a new decomposition") {
    const auto t0 = Clock::now();
    w.decompose(quick);
    w.wait_idle();
    INFO("cancelled and redone in " << seconds_since(t0) << " s");
    CHECK(seconds_since(t0) < 5.0);  // an iteration is milliseconds (more under sanitizers)
  }
  const auto s = w.snapshot();
  INFO(s->error);
  CHECK(s->error.empty());
  REQUIRE(s->decomposed);
  CHECK(s->decomposed->components() == 3);
  CHECK(s->decompose_params.max_iterations == 5);
}

TEST_CASE("decomposition and load requests on a palette while another thread reads results",
          "[worker][palette]") {
  Worker w;
  const std::vector<std::string> palette_a = assets({kHappy, kMarching, kJoy});
  const std::vector<std::string> palette_b = assets({kClumsy, kJoy, kHappy});
  w.load(palette_a);

  std::atomic<bool> stop{false};
  std::atomic<long> reads{0}, bad_reads{0};
  std::thread reader([&] {
    std::uint64_t last_version = 0;
    while (!stop.load()) {
      const auto s = w.snapshot();
      const WorkerStatus status = w.status();
      bool ok = s && s->version >= last_version && status.progress >= 0.0f && status.progress <= 1.0f;
      if (ok) last_version = s->version;
      if (ok && s->decomposed) {
        // A published decomposition comes with the takes it was made from (three, or a pair in
        // between).
        ok = s->prepared && s->paths.size() == static_cast<size_t>(s->prepared->size()) &&
             s->decomposed->rmse.size() == static_cast<size_t>(s->prepared->size());
        double sum = 0;
        for (Eigen::Index i = 0; i < s->decomposed->support.size(); ++i) sum += s->decomposed->support.data()[i];
        ok = ok && std::isfinite(sum);
      }
      bad_reads += ok ? 0 : 1;
      ++reads;
    }
  });

  std::mt19937 random(7);
  DecomposeParams last_decompose;
  std::vector<std::string> last_paths = palette_a;
  for (int i = 0; i < 200; ++i) {
    if (i == 60) {
      w.load({test::asset(kHappy), test::asset(kJoy)});  // a pair in between
    } else if (i == 100) {
      last_paths = palette_b;
      w.load(last_paths);
    } else {
      last_decompose.components = 2 + static_cast<int>(random() % 9);
      last_decompose.max_iterations = 20;
      w.decompose(last_decompose);
    }
    if (i % 10 == 0) std::this_thread::sleep_for(std::chrono::milliseconds(2));
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
  REQUIRE(s->decomposed);
  CHECK(s->paths == last_paths);
  CHECK(s->decomposed->components() == last_decompose.components);
  CHECK_FALSE(w.status().pending);
}

TEST_CASE("the worker calls its change callback after each job, with the result published", "[worker]") {
  Worker w;
  std::atomic<int> calls{0};
  std::atomic<std::uint64_t> seen_version{0};
  std::atomic<bool> idle_when_called{true};
  w.set_on_change([&] {
    // What an event loop woken by it reads: the job's snapshot is there already.
    seen_version = w.snapshot()->version;
    idle_when_called = idle_when_called && w.status().stage == WorkerStage::kIdle;
    ++calls;
  });
  w.load({test::asset(kHappy), test::asset(kJoy)});
  w.wait_idle();
  // Each call happens after the job's end; wait_idle may return just before the last call.
  const auto t0 = Clock::now();
  while (calls < 2 && seconds_since(t0) < 30.0) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  CHECK(calls >= 2);  // load, decomposition
  const auto t1 = Clock::now();
  while (seen_version != w.snapshot()->version && seconds_since(t1) < 30.0)
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  CHECK(seen_version == w.snapshot()->version);
  CHECK(idle_when_called);
  // A failed request calls it too (the error is news as well).
  const int before = calls;
  w.load({test::asset("motions/no_such_take.bvh")});
  w.wait_idle();
  const auto t2 = Clock::now();
  while (calls == before && seconds_since(t2) < 30.0) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  CHECK(calls > before);
  CHECK_FALSE(w.snapshot()->error.empty());
  w.set_on_change(nullptr);
}
