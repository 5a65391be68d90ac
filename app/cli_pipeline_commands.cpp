#include "app/cli_pipeline_commands.h"

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>

#include "app/cli_common.h"
#include "app/cli_pipeline_common.h"
#include "engine/io/atomic_file.h"
#include "engine/io/csv_io.h"
#include "engine/align/dtw.h"
#include "engine/align/time_warp.h"
#include "engine/io/error.h"
#include "engine/export/export_solve.h"
#include "engine/run/pipeline.h"
#include "engine/kinematics/units.h"

namespace mostyle::cli {
namespace {

using Clock = std::chrono::steady_clock;

double ms_since(Clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

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
  AlignFlags align;
  std::string mapping_a, mapping_b;

  void add_to(CLI::App* cmd) {
    cmd->add_option("A", a, "BVH take A (the reference: its skeleton, units and world frame)")->required();
    cmd->add_option("B", b, "BVH take B (retargeted onto A and aligned onto it in time)")->required();
    align.add_to(cmd);
    cmd->add_option("--mapping-a", mapping_a, "Major-joint mapping file for A (see assets/mappings)");
    cmd->add_option("--mapping-b", mapping_b, "Major-joint mapping file for B");
  }

  std::shared_ptr<const PreparedTakes> prepare(double* load_ms) const {
    PrepareOptions o = align.options();
    const auto t0 = Clock::now();
    auto clip_a = std::make_shared<const Clip>(load_clip(a));
    auto clip_b = std::make_shared<const Clip>(load_clip(b));
    *load_ms = ms_since(t0);
    o.mapping_a = load_mapping(mapping_a);
    o.mapping_b = load_mapping(mapping_b);
    auto p = prepare_takes({clip_a, clip_b}, o);
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
      double load_ms = 0;
      const auto p = pair->prepare(&load_ms);
      const Alignment& al = p->takes[1].alignment;
      if (*json) {
        Json j;
        j["a"] = pair->a;
        j["b"] = pair->b;
        j["fps"] = p->fps;
        j["alignment"] = alignment_json(*p, 1);
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
        j["timings_ms"] = {{"load", load_ms}, {"preprocess", p->times.preprocess_ms}, {"dtw", p->times.dtw_ms}};
        std::cout << j.dump() << "\n";
      } else {
        std::string joints;
        for (int c : al.feature.columns) joints += (joints.empty() ? "" : ", ") + p->reference().names[c];
        std::cout << "aligned on: " << align_on_name(al.feature.on) << " (" << joints << "), "
                  << dtw_method_name(al.options.method) << " DTW\n"
                  << "frames: " << al.frames_a << " / " << al.frames_b << " at "
                  << number(p->fps) << " fps\n"
                  << "matched: A " << al.a_first << "-" << al.a_last << ", B " << al.b_first << "-" << al.b_last
                  << "\n"
                  << "dtw cost: " << number(al.cost) << " (A's units), path of " << al.path.size() << " steps, "
                  << number(p->times.dtw_ms) << " ms\n";
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

void add_blend_command(CLI::App& app, std::function<int()>* run) {
  auto* cmd = app.add_subcommand("blend", "Blend the styles of two takes");
  struct Args {
    PairOptions pair;
    double alpha = 0.5;
    int components = 10;
    double sparsity = 0.1;
    int iterations = 100;
    std::string mode = "shared";
    int basic = 0;
    std::vector<double> basic_sparsities;
    int swap = 0;
    std::vector<double> component_alpha;
    std::vector<std::string> part_alpha;
    bool no_limb = false;
    bool no_foot_lock = false;
    std::string timing = "blend";
    bool loop = false;
    bool components_only = false;
    bool no_local = false;
    std::string out, positions_out, report;
    ChannelsFlag channels;
  };
  auto args = std::make_shared<Args>();
  args->pair.add_to(cmd);
  cmd->add_option("--alpha", args->alpha, "0 gives A, 1 gives B (shared mode)")->capture_default_str();
  cmd->add_option("--components,-k", args->components, "Number of components k")->capture_default_str();
  cmd->add_option("--sparsity,-f", args->sparsity, "Fraction of non-zeros kept in C, in (0, 1]")->capture_default_str();
  cmd->add_option("--iterations", args->iterations, "Decomposition iteration cap")->capture_default_str();
  cmd->add_option("--mode", args->mode, "shared (one component set, alpha 1 is B) or paper (core components)")
      ->check(CLI::IsMember({"shared", "paper"}))
      ->capture_default_str();
  cmd->add_option("--basic", args->basic, "Paper mode: decompose into M basic motions")->capture_default_str();
  cmd->add_option("--basic-sparsity", args->basic_sparsities, "Sparsity of each basic motion")->delimiter(',');
  cmd->add_option("--swap", args->swap, "Basic motion (0-based) whose core is taken from B")->capture_default_str();
  cmd->add_option("--part-alpha", args->part_alpha,
                  "Shared mode: PART:a, the alpha of one body part's components (legs, arms, spine, left-leg, "
                  "right-leg, left-arm, right-arm; repeat for several, a side wins over both sides); the rest "
                  "take --alpha");
  cmd->add_option("--component-alpha", args->component_alpha, "Shared mode: one alpha per component, comma separated")
      ->delimiter(',');
  cmd->add_flag("--no-limb-constraint", args->no_limb, "Skip the limb-length constraint (paper 3.7)");
  cmd->add_flag("--no-foot-lock", args->no_foot_lock, "Leave planted feet free (no foot-contact IK clean-up)");
  cmd->add_option("--timing", args->timing,
                  "blend: the output's timing moves from A's (alpha 0) to B's (alpha 1); a: keep A's timeline")
      ->check(CLI::IsMember({"blend", "a"}))
      ->capture_default_str();
  cmd->add_flag("--no-local", args->no_local,
                "Shared mode: components may take channels anywhere instead of one connected piece of the "
                "skeleton each");
  cmd->add_flag("--components-only", args->components_only,
                "Shared mode: blend only what the k components reconstruct (the paper's synthesis), "
                "leaving out each take's residual detail");
  cmd->add_flag("--loop", args->loop,
                "Cut a seamless loop of 1 to 4 whole gait cycles (root travel per cycle kept)");
  cmd->add_option("--out", args->out, "File of the blend on A's skeleton: BVH (A's rotation orders), or glTF 2.0 when it ends in .glb or .gltf");
  args->channels.add_to(cmd);
  cmd->add_option("--positions-out", args->positions_out,
                  "CSV frame,joint,x,y,z of the blend's final major-joint positions (after the foot lock)");
  cmd->add_option("--report", args->report, "JSON report");
  cmd->callback([=] {
    *run = [=] {
      StageTimes times;
      const auto p = args->pair.prepare(&times.load_ms);
      times.preprocess_ms = p->times.preprocess_ms;
      times.dtw_ms = p->times.dtw_ms;
      DecomposeParams dp;
      dp.mode = args->mode == "paper" ? BlendMode::kPaper : BlendMode::kShared;
      dp.components = args->components;
      dp.sparsity = args->sparsity;
      dp.max_iterations = args->iterations;
      dp.basic_motions = args->basic;
      dp.basic_sparsities = args->basic_sparsities;
      dp.local = !args->no_local;
      const auto d = decompose_takes(*p, dp);
      times.decompose_ms = d->elapsed_ms;
      BlendParams bp;
      bp.alpha = args->alpha;
      bp.component_alpha = args->component_alpha;
      if (!args->part_alpha.empty()) {
        if (!args->component_alpha.empty()) throw InputError("give --part-alpha or --component-alpha, not both");
        if (dp.mode != BlendMode::kShared) throw InputError("--part-alpha needs shared mode (--mode shared)");
        std::vector<std::pair<BodyPart, double>> given;
        std::vector<std::string> entries;  // "legs:0.2,arms:0.8" or repeated
        for (const std::string& e : args->part_alpha)
          for (size_t begin = 0; begin <= e.size();) {
            const size_t comma = std::min(e.find(',', begin), e.size());
            entries.push_back(e.substr(begin, comma - begin));
            begin = comma + 1;
          }
        for (const auto& [part, values] : parse_part_entries(entries, "--part-alpha", 1))
          given.emplace_back(part, values[0]);
        bp.component_alpha = weights_for_parts(given, d->component_joints, args->alpha);
      }
      bp.swap_level = args->swap;
      bp.limb_lengths = !args->no_limb;
      bp.foot_lock = !args->no_foot_lock;
      bp.timing_a = args->timing == "a";
      bp.loop = args->loop;
      bp.residual = !args->components_only;
      BlendScratch scratch;
      BlendResult result;
      blend_pair(*p, *d, bp, scratch, result);
      times.synthesize_ms = result.synthesize_ms;
      times.postprocess_ms = result.postprocess_ms;

      std::vector<int> columns(p->majors.size());
      for (size_t i = 0; i < columns.size(); ++i) columns[i] = static_cast<int>(i);
      ExportFit fit;
      const Clip& clip_a = *p->reference().clip;
      const std::vector<std::string>& names = p->reference().names;
      const Alignment& al = p->takes[1].alignment;
      const ChannelLayout layout = args->channels.layout(clip_a);
      if (!args->out.empty()) {
        const auto t_export = Clock::now();
        fit = export_blend_bvh(clip_a, export_joints(*p), result.world, source_frames_in_clip(*p, result),
                               p->fps, args->out, layout)
                  .fit;
        times.export_ms = ms_since(t_export);
      }
      if (!args->positions_out.empty())
        write_output(args->positions_out, positions_csv(result.world, columns, names));

      Json r;
      r["command"] = "blend";
      r["a"] = args->pair.a;
      r["b"] = args->pair.b;
      r["frames"] = result.world.rows();
      r["fps"] = p->fps;
      r["alpha"] = args->alpha;
      r["components"] = args->components;
      r["sparsity"] = args->sparsity;
      r["mode"] = args->mode;
      if (args->basic > 0) {
        r["basic_motions"] = args->basic;
        r["swap"] = args->swap;
      }
      r["joints"] = names;
      r["timing"] = args->timing;
      r["residual"] = bp.residual;
      r["dtw"] = {{"cost", al.cost}, {"path_length", al.path.size()}};
      Json alignment = alignment_json(*p, 1);
      // Per output frame: where in A and B it is, how well they match there, the warp's slope.
      Eigen::VectorXd ratio(result.sample.size()), slope(result.sample.size());
      for (Eigen::Index k = 0; k < result.sample.size(); ++k) {
        const Eigen::Index u = std::lround(result.sample[k]);
        ratio[k] = al.cost_ratio[u];
        slope[k] = al.slope[u];
      }
      alignment["per_frame"] = {{"source_a", vector_json(result.source_a)},
                                {"source_b", vector_json(result.source_b)},
                                {"cost_ratio", vector_json(ratio)},
                                {"slope", vector_json(slope)}};
      r["alignment"] = alignment;
      r["duration_s"] = result.world.rows() / p->fps;
      if (args->loop) r["loop"] = loop_json(result.loop, p->fps);
      r["reconstruction_rmse"] = {{"a", d->rmse[0]}, {"b", d->rmse[1]}};
      r["component_nonzero_fraction"] = {{"a", d->nonzero[0]}, {"b", d->nonzero[1]}};
      r["iterations"] = d->iterations;
      r["local"] = dp.local && dp.mode == BlendMode::kShared;
      r["component_joints"] = component_joints_json(d->component_joints, names);
      r["component_regions"] = component_regions_json(d->component_joints);
      r["limb_length_max_error"] = result.limb_length_max_error;
      if (!args->out.empty()) {
        r["export_fit"] = {{"max", fit.max}, {"mean", fit.mean}};
        r["channels"] = channel_layout_name(layout);
      }
      r["foot_lock"] = bp.foot_lock;
      r["foot_sliding"] = {{"a", p->takes[0].foot_sliding},
                           {"b", p->takes[1].foot_sliding},
                           {"raw_blend", result.foot_sliding_raw},
                           {"cleaned_blend", result.foot_sliding_cleaned}};
      r["skeleton_height"] = guess_units(clip_a).height;
      r["timings_ms"] = {{"load", times.load_ms},         {"preprocess", times.preprocess_ms},
                         {"dtw", times.dtw_ms},           {"decompose", times.decompose_ms},
                         {"synthesize", times.synthesize_ms}, {"postprocess", times.postprocess_ms},
                         {"export", times.export_ms}};
      if (!args->report.empty()) write_output(args->report, r.dump(2) + "\n");
      else std::cout << report_summary(r, args->out, args->positions_out);
      return 0;
    };
  });
}

}  // namespace mostyle::cli
