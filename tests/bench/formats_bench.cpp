// Reading FBX and glTF beside BVH, on the same motion: a CMU take (cmu142_walk_joy
// from ../shared/motions, else the trimmed one in assets/) repeated into one long take and
// written by the benchmark as a 20 MB GLB (our writer), a 20 MB ASCII FBX (the tests' writer,
// tests/engine/io/fbx/fbx_ascii.h: mostyle writes no binary FBX) and the BVH of the same frames.
// Each reads from memory to a sampled Clip at the file's rate (parse + sample), so the numbers
// compare the whole read. MB/s via SetBytesProcessed; frames per file in the counters.
#include <benchmark/benchmark.h>

#include <filesystem>
#include <string>

#include "engine/base/atomic_file.h"
#include "engine/io/bvh/bvh_read.h"
#include "engine/io/bvh/bvh_write.h"
#include "engine/io/fbx/fbx_read.h"
#include "engine/io/gltf/gltf_read.h"
#include "engine/io/gltf/gltf_write.h"
#include "engine/io/scene_animation.h"
#include "tests/engine/io/fbx/fbx_ascii.h"

namespace {

namespace fs = std::filesystem;
using mostyle::Clip;

constexpr size_t kTargetBytes = 20u << 20;

const Clip& source_take() {
  static const Clip clip = [] {
    const fs::path shared = fs::path(MOSTYLE_SHARED_MOTIONS) / "cmu142_walk_joy.bvh";
    std::error_code ec;
    return mostyle::read_bvh_file(fs::exists(shared, ec) ? shared.string()
                                                         : std::string(MOSTYLE_ASSETS_DIR) + "/motions/cmu142_walk_joy.bvh");
  }();
  return clip;
}

Clip repeated(int frames) {
  const Clip& s = source_take();
  Clip big = s;
  big.motion.resize(frames, s.motion.cols());
  for (int f = 0; f < frames; ++f) big.motion.row(f) = s.motion.row(f % s.frames());
  return big;
}

// The frame count whose file `format` writes is about kTargetBytes: measured on 1000 frames.
template <typename Format>
int frames_for_target(Format format) {
  const size_t per_1000 = format(repeated(1000)).size();
  return static_cast<int>(1000.0 * kTargetBytes / per_1000);
}

struct Files {
  int frames = 0;
  std::string file;  // the FBX or GLB
  std::string bvh;   // the same frames as BVH
};

const Files& glb_files() {
  static const Files f = [] {
    const auto format = [](const Clip& c) { return mostyle::format_glb(c, "walk"); };
    Files out;
    out.frames = frames_for_target(format);
    const Clip c = repeated(out.frames);
    out.file = format(c);
    out.bvh = mostyle::format_bvh(c);
    return out;
  }();
  return f;
}

const Files& fbx_files() {
  static const Files f = [] {
    const auto format = [](const Clip& c) { return mostyle::test::format_fbx_ascii(c, "walk"); };
    Files out;
    out.frames = frames_for_target(format);
    const Clip c = repeated(out.frames);
    out.file = format(c);
    out.bvh = mostyle::format_bvh(c);
    return out;
  }();
  return f;
}

void report(benchmark::State& state, const std::string& bytes, int frames) {
  state.SetBytesProcessed(static_cast<int64_t>(state.iterations()) * static_cast<int64_t>(bytes.size()));
  state.counters["MB"] = bytes.size() / 1048576.0;
  state.counters["frames"] = frames;
}

void BM_ReadGlb20MB(benchmark::State& state) {
  const Files& f = glb_files();
  for (auto _ : state) {
    const mostyle::AnimatedScene scene = mostyle::parse_gltf(f.file, "walk.glb");
    benchmark::DoNotOptimize(mostyle::scene_take_to_clip(scene, 0));
  }
  report(state, f.file, f.frames);
}
BENCHMARK(BM_ReadGlb20MB)->Unit(benchmark::kMillisecond);

void BM_ReadBvhSameAsGlb(benchmark::State& state) {
  const Files& f = glb_files();
  for (auto _ : state) benchmark::DoNotOptimize(mostyle::parse_bvh(f.bvh, "walk.bvh"));
  report(state, f.bvh, f.frames);
}
BENCHMARK(BM_ReadBvhSameAsGlb)->Unit(benchmark::kMillisecond);

void BM_ReadFbxAscii20MB(benchmark::State& state) {
  const Files& f = fbx_files();
  for (auto _ : state) {
    const mostyle::AnimatedScene scene = mostyle::parse_fbx(f.file, "walk.fbx");
    benchmark::DoNotOptimize(mostyle::scene_take_to_clip(scene, 0));
  }
  report(state, f.file, f.frames);
}
BENCHMARK(BM_ReadFbxAscii20MB)->Unit(benchmark::kMillisecond);

void BM_ReadBvhSameAsFbx(benchmark::State& state) {
  const Files& f = fbx_files();
  for (auto _ : state) benchmark::DoNotOptimize(mostyle::parse_bvh(f.bvh, "walk.bvh"));
  report(state, f.bvh, f.frames);
}
BENCHMARK(BM_ReadBvhSameAsFbx)->Unit(benchmark::kMillisecond);

// The real files (Blender's), when ../shared/motions is there.
void BM_ReadSharedFormats(benchmark::State& state) {
  const char* const names[] = {"formats/cmu142_walk_joy.fbx", "formats/cmu142_walks_30fps.glb"};
  const fs::path path = fs::path(MOSTYLE_SHARED_MOTIONS) / names[state.range(0)];
  std::error_code ec;
  if (!fs::exists(path, ec)) {
    state.SkipWithError("../shared/motions is absent");
    return;
  }
  const std::string bytes = mostyle::read_file(path.string());
  for (auto _ : state) {
    const mostyle::AnimatedScene scene = state.range(0) == 0 ? mostyle::parse_fbx(bytes, path.string())
                                                             : mostyle::parse_gltf(bytes, path.string());
    benchmark::DoNotOptimize(mostyle::scene_take_to_clip(scene, 0));
  }
  state.SetLabel(path.filename().string());
  state.SetBytesProcessed(static_cast<int64_t>(state.iterations()) * static_cast<int64_t>(bytes.size()));
}
BENCHMARK(BM_ReadSharedFormats)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

}  // namespace
