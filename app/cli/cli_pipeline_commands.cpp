#include "app/cli/cli_pipeline_commands.h"

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>

#include "app/cli/cli_common.h"
#include "app/cli/cli_pipeline_common.h"
#include "engine/base/atomic_file.h"
#include "engine/base/clock.h"
#include "engine/io/csv/csv_read.h"
#include "engine/align/dtw.h"
#include "engine/align/time_warp.h"
#include "engine/base/error.h"
#include "engine/export/export_solve.h"
#include "engine/kinematics/units.h"

namespace mostyle::cli {
namespace {

using Clock = std::chrono::steady_clock;

Json path_json(const DtwPath& path) {
  Json steps = Json::array();
  for (const auto& [i, j] : path.steps) steps.push_back({i, j});
  return steps;
}

Json rows_json(const Eigen::MatrixXd& m) {
  Json rows = Json::array();
  for (Eigen::Index r = 0; r < m.rows(); ++r) {
    Json row = Json::array();
    for (Eigen::Index c = 0; c < m.cols(); ++c) row.push_back(m(r, c));
    rows.push_back(row);
  }
  return rows;
}


// Options shared by align and blend: the pair's files and how it is prepared and aligned.
struct PairOptions {
  std::string a, b;
  AlignOptions align;
  std::string mapping_a, mapping_b;

  void add_to(CLI::App* cmd) {
    cmd->add_option("A", a, "BVH take A (the reference: its skeleton, units and world frame)")->required();
    cmd->add_option("B", b, "BVH take B (retargeted onto A and aligned onto it in time)")->required();
    add_align_options(cmd, align);
    cmd->add_option("--mapping-a", mapping_a, "Major-joint mapping file for A (see assets/mappings)");
    cmd->add_option("--mapping-b", mapping_b, "Major-joint mapping file for B");
  }

  std::shared_ptr<const PreparedTakes> prepare(StageTimes* times) const {
    PrepareOptions o = align.options();
    const auto t0 = Clock::now();
    auto clip_a = std::make_shared<const Clip>(load_clip(a));
    auto clip_b = std::make_shared<const Clip>(load_clip(b));
    times->load_ms = ms_since(t0);
    o.mapping_a = load_mapping(mapping_a);
    o.mapping_b = load_mapping(mapping_b);
    auto p = prepare_takes({clip_a, clip_b}, o, nullptr, times);
    for (const std::string& w : p->takes[1].alignment.warnings) std::cerr << "mostyle: warning: " << w << "\n";
    return p;
  }
};

}  // namespace

void add_dtw_command(CLI::App& app, std::function<int()>* run) {
  auto* cmd = app.add_subcommand("dtw", "Dynamic time warping of two CSV series (rows = time steps)");
  struct Args {
    std::string a, b;
    int band = -1;
    bool json = false;
  };
  auto args = std::make_shared<Args>();
  cmd->add_option("A", args->a, "CSV series A")->required();
  cmd->add_option("B", args->b, "CSV series B (same number of columns)")->required();
  cmd->add_option("--band", args->band, "Sakoe-Chiba band half-width in rows (-1: none)")->capture_default_str();
  cmd->add_flag("--json", args->json, "Print {\"cost\": c, \"path\": [[i, j], ...]}");
  cmd->callback([=] {
    *run = [=] {
      const size_t limit = memory_limit_from_environment();
      const Eigen::MatrixXd a = read_csv_matrix(args->a, limit);
      const Eigen::MatrixXd b = read_csv_matrix(args->b, limit);
      if (a.cols() != b.cols())
        throw InputError(args->b + ": expected " + std::to_string(a.cols()) + " columns like " + args->a +
                         ", found " + std::to_string(b.cols()));
      if (args->band < -1) throw InputError("expected a band of 0 or more rows, found " + std::to_string(args->band));
      DtwOptions o;
      o.band = args->band;
      const DtwPath path = align_dtw(a, b, o);
      if (args->json) {
        Json j;
        j["cost"] = path.cost;
        j["path"] = path_json(path);
        std::cout << j.dump() << "\n";
      } else {
        std::cout << "cost " << number(path.cost) << ", path of " << path.steps.size() << " steps\n";
      }
      return 0;
    };
  });
}

void add_align_command(CLI::App& app, std::function<int()>* run) {
  auto* cmd = app.add_subcommand("align", "Align two BVH takes in time (left foot for walks, moving joints otherwise)");
  auto pair = std::make_shared<PairOptions>();
  auto json = std::make_shared<bool>(false);
  pair->add_to(cmd);
  cmd->add_flag("--json", *json,
                "Print the alignment: feature, matched ranges, path, warp, per-sample quality and the feature "
                "signals before and after warping");
  cmd->callback([=] {
    *run = [=] {
      StageTimes times;
      const auto p = pair->prepare(&times);
      const Alignment& al = p->takes[1].alignment;
      if (*json) {
        Json j;
        j["a"] = pair->a;
        j["b"] = pair->b;
        j["fps"] = p->fps;
        j["alignment"] = alignment_json(*p, 1);
        j["cycles"] = {{"a", cycles_json(p->takes[0].cycles, p->fps)}, {"b", cycles_json(p->takes[1].cycles, p->fps)}};
        Json path = Json::array();
        for (const auto& [i, k] : al.path) path.push_back({i, k});
        j["path"] = path;
        Json warp = Json::array();
        for (int u = 0; u < al.warp.samples(); ++u) warp.push_back({al.warp.a[u], al.warp.b[u]});
        j["warp"] = warp;
        j["cost_ratio"] = vector_json(al.cost_ratio);
        j["slope"] = vector_json(al.slope);
        j["signal_a"] = rows_json(al.feature.a);
        j["signal_b"] = rows_json(al.feature.b);
        j["signal_a_warped"] = rows_json(sample_rows(al.feature.a, al.warp.a));
        j["signal_b_warped"] = rows_json(sample_rows(al.feature.b, al.warp.b));
        j["timings_ms"] = {{"load", times.load_ms}, {"preprocess", times.preprocess_ms}, {"dtw", times.dtw_ms}};
        std::cout << j.dump() << "\n";
      } else {
        std::string joints;
        for (int c : al.feature.columns) joints += (joints.empty() ? "" : ", ") + p->reference().names[c];
        // A's frames as its file counts them: its own timeline plays its last cycles again where
        // B has more cycles (cycle_slots.h), which the alignment's frames count.
        const Eigen::VectorXd a_own =
            frames_in_take(p->reference(), Eigen::Vector3d(al.a_first, al.a_last, al.frames_a - 1));
        const int frames_a = static_cast<int>(std::lround(a_own[2])) + 1;
        const int replayed = static_cast<int>(p->reference().timeline_cycles().cycles.size() - p->reference().cycles.cycles.size());
        std::cout << "aligned on: " << align_on_name(al.feature.on) << " (" << joints << "), "
                  << dtw_method_name(al.options.method) << " DTW\n"
                  << "frames: " << frames_a << " / " << al.frames_b << " at "
                  << number(p->fps) << " fps\n"
                  << "matched: A " << std::lround(a_own[0]) << "-" << std::lround(a_own[1]) << ", B " << al.b_first << "-"
                  << al.b_last << "\n"
                  << (replayed > 0 ? "A's last cycles played again for B's " + std::to_string(replayed) +
                                         " more (a blend plays them as B's weight calls for them)\n"
                                   : std::string())
                  << "dtw cost: " << number(al.cost) << " (A's units), path of " << al.path.size() << " steps, "
                  << number(times.dtw_ms) << " ms\n"
                  << "cycles: A " << cycles_summary(p->takes[0].cycles, p->fps, frames_a) << "\n"
                  << "        B " << cycles_summary(p->takes[1].cycles, p->fps, al.frames_b) << "\n";
      }
      return 0;
    };
  });
}

void add_decompose_command(CLI::App& app, std::function<int()>* run) {
  auto* cmd = app.add_subcommand("decompose", "Sparse-coding decomposition X = W C of one take");
  struct Args {
    std::string file;
    int components = 10;
    double sparsity = 0.1;
    int iterations = 100;
    double fps = 30;
    std::string mapping;
    bool json = false;
    bool no_local = false;
  };
  auto args = std::make_shared<Args>();
  cmd->add_option("FILE", args->file, "BVH take")->required();
  cmd->add_flag("--no-local", args->no_local,
                "Components may take channels anywhere (the paper's plain sparsity) instead of one connected piece "
                "of the skeleton each");
  cmd->add_option("--components,-k", args->components, "Number of components k")->capture_default_str();
  cmd->add_option("--sparsity,-f", args->sparsity, "Fraction of non-zeros kept in C, in (0, 1]")->capture_default_str();
  cmd->add_option("--iterations", args->iterations, "Iteration cap")->capture_default_str();
  cmd->add_option("--fps", args->fps, "Working frame rate (0 keeps the file's)")->capture_default_str();
  cmd->add_option("--mapping", args->mapping, "Major-joint mapping file");
  cmd->add_flag("--json", args->json, "Print JSON");
  cmd->callback([=] {
    *run = [=] {
      auto clip = std::make_shared<const Clip>(load_clip(args->file));
      PrepareOptions o;
      o.fps = args->fps;
      o.mapping_a = o.mapping_b = load_mapping(args->mapping);
      // A take paired with itself: the same preprocessing as a blend, normalized on its own.
      const auto p = prepare_takes({clip, clip}, o);
      const PreparedTake& take = p->reference();
      DecompositionOptions d;
      d.components = args->components;
      d.sparsity = args->sparsity;
      d.max_iterations = args->iterations;
      if (!args->no_local) d.locality_parents = p->parents;
      const Decomposition r = decompose(take.x, d);
      const std::vector<ComponentJoints> parts = describe_components(r.components, p->majors);
      const double rmse = r.rmse * p->scale;
      if (args->json) {
        Json j;
        j["file"] = args->file;
        j["frames"] = take.x.rows();
        j["fps"] = p->fps;
        j["joints"] = take.names;
        j["components"] = args->components;
        j["sparsity"] = args->sparsity;
        j["reconstruction_rmse"] = rmse;
        j["reconstruction_rmse_normalized"] = r.rmse;
        j["nonzero_fraction"] = r.nonzero_fraction;
        j["iterations"] = r.iterations;
        j["converged"] = r.converged;
        j["time_ms"] = r.elapsed_ms;
        j["local"] = !args->no_local;
        j["component_joints"] = component_joints_json(parts, take.names);
        j["component_regions"] = component_regions_json(parts);
        std::cout << j.dump(2) << "\n";
      } else {
        std::cout << args->file << ": " << take.x.rows() << " frames x " << take.names.size()
                  << " joints at " << number(p->fps) << " fps\n"
                  << "reconstruction RMSE " << number(rmse) << " (file units), non-zero fraction "
                  << number(r.nonzero_fraction) << ", " << r.iterations << " iterations"
                  << (r.converged ? " (converged)" : "") << ", " << number(r.elapsed_ms) << " ms\n";
      }
      return 0;
    };
  });
}

}  // namespace mostyle::cli
