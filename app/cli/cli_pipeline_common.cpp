#include "app/cli/cli_pipeline_common.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <functional>

#include "app/cli/cli_common.h"
#include "engine/base/atomic_file.h"
#include "engine/base/error.h"
#include "engine/base/numbers.h"

namespace mostyle::cli {

void add_align_options(CLI::App* cmd, AlignOptions& align) {
  cmd->add_option("--fps", align.fps, "Working and output frame rate (0 keeps the reference's)")->capture_default_str();
  cmd->add_option("--time-base", align.time_base,
                  "cycles: each cycle of the reference matched with a cycle of each other take (a short take's "
                  "reused in order), so the whole reference is kept, the others' posture where it does not repeat; "
                  "whole: one open-ended alignment of the whole takes (what takes that do not repeat get)")
      ->check(CLI::IsMember({"cycles", "whole"}))
      ->capture_default_str();
  cmd->add_option("--dtw", align.dtw,
                  "slope: slope-limited, open-ended DTW with a smooth warp; paper: the paper's plain "
                  "end-to-end left-foot DTW")
      ->check(CLI::IsMember({"slope", "paper"}))
      ->capture_default_str();
  cmd->add_option("--align-on", align.align_on,
                  "What to align on: auto (left foot for locomotion, else the joints that move), left-foot, "
                  "feet, hands or body")
      ->check(CLI::IsMember({"auto", "left-foot", "feet", "hands", "body"}))
      ->capture_default_str();
  cmd->add_option("--max-slope", align.max_slope, "Neither take runs more than this many times faster than the other (2-4)")
      ->capture_default_str();
  cmd->add_flag("--closed-ends", align.closed_ends, "Align first frames to first and last to last (no open ends)");
  cmd->add_option("--band", align.band, "--dtw paper: Sakoe-Chiba band half-width in frames (-1: none)")
      ->capture_default_str();
}

void add_channels_option(CLI::App* cmd, std::string& channels) {
  cmd->add_option("--channels", channels,
                  "Channel layout of --out: rotations (rotations only below the root, constant translations in "
                  "OFFSET, so every BVH reader agrees) or as-source (the reference's own channels); default "
                  "rotations where the reference's position channels below the root keep one value")
      ->check(CLI::IsMember({"as-source", "rotations"}));
}

MappingOverrides load_mapping(const std::string& path) {
  if (path.empty()) return {};
  return parse_mapping_overrides(read_file(path), path);
}

std::vector<double> parse_numbers(const std::string& list, const std::string& flag) {
  std::vector<double> values;
  for (size_t begin = 0; begin <= list.size();) {
    const size_t comma = std::min(list.find(',', begin), list.size());
    const std::string text = list.substr(begin, comma - begin);
    begin = comma + 1;
    double v = 0.0;
    if (!parse_number(text, &v))
      throw InputError("expected a number or a fraction such as 1/3 in " + flag + ", found '" + text + "'");
    values.push_back(v);
  }
  return values;
}

std::vector<std::pair<double, std::vector<double>>> parse_keys(const std::string& text, const std::string& flag,
                                                               size_t count) {
  if (text.empty()) return {};
  // Split into keys: at ';', and with one number a key also at a ',' that a "T:" follows.
  std::vector<std::string> keys;
  std::string current;
  for (size_t i = 0; i <= text.size(); ++i) {
    const bool end = i == text.size() || text[i] == ';' ||
                     (count == 1 && text[i] == ',' && current.find(':') != std::string::npos);
    if (!end) {
      current += text[i];
      continue;
    }
    keys.push_back(current);
    current.clear();
  }
  std::vector<std::pair<double, std::vector<double>>> out;
  for (const std::string& key : keys) {
    const size_t colon = key.find(':');
    if (colon == std::string::npos)
      throw InputError("expected keys as SECONDS:" + std::string(count == 1 ? "value" : "v1,v2,...") + " in " + flag +
                       " (keys apart by ';'), found '" + key + "'");
    double seconds = 0.0;
    if (!parse_number(key.substr(0, colon), &seconds))
      throw InputError("expected a time in seconds before ':' in " + flag + ", found '" + key.substr(0, colon) + "'");
    std::vector<double> values = parse_numbers(key.substr(colon + 1), flag);
    if (values.size() != count)
      throw InputError("expected " + std::to_string(count) + (count == 1 ? " value" : " values") + " after " +
                       key.substr(0, colon) + ": in " + flag + ", found " + std::to_string(values.size()));
    out.emplace_back(seconds, std::move(values));
  }
  return out;
}

Json keys_json(const WeightKeys& keys) {
  Json out = Json::array();
  for (const WeightKey& k : keys) out.push_back({{"seconds", k.seconds}, {"weights", k.weights}});
  return out;
}

namespace {

std::string fixed(double v, int decimals) {
  char text[64];
  std::snprintf(text, sizeof text, "%.*f", decimals, v);
  return text;
}

// The keys in time of a report ("keys": seconds and one weight per take), each key's values
// taken from its weights by `values` (an alpha, the weights, a transfer's strengths):
// "0.00 at 0.00 s, 1.00 at 3.00 s".
std::string keys_in_words(const Json& keys, const std::function<std::string(const std::vector<double>&)>& values) {
  std::string text;
  for (const Json& k : keys) {
    if (!text.empty()) text += ", ";
    text += values(k["weights"].get<std::vector<double>>()) + " at " + duration_in_words(k["seconds"].get<double>());
  }
  return text;
}

std::string file_name(const std::string& path) { return std::filesystem::path(path).filename().string(); }

// v[from..] as text, `decimals` decimals each, space separated.
std::string joined(const std::vector<double>& v, size_t from, int decimals) {
  std::string out;
  for (size_t i = from; i < v.size(); ++i) out += (i > from ? " " : "") + fixed(v[i], decimals);
  return out;
}

// The summary's first line: what was made of which takes, with which weights. With keys in time
// the weights given as constants are not used: the keys are said instead.
std::string result_headline(const Json& r) {
  const std::string command = r.value("command", std::string("blend"));
  const bool keyed = r.contains("keys") && !r["keys"].empty();
  std::string text;
  if (command == "blend") {
    text = "blend of " + file_name(r["a"]) + " and " + file_name(r["b"]);
    if (keyed)
      text += ", alpha keyed " + keys_in_words(r["keys"], [&](const std::vector<double>& w) { return fixed(w[1], 2); });
    else
      text += " at alpha " + fixed(r["alpha"].get<double>(), 2);
  } else if (command == "mix") {
    text = "mix of " + std::to_string(r["takes"].size()) + " takes onto " + file_name(r["takes"][0]["file"]);
    if (keyed) {
      text += ", weights keyed " +
              keys_in_words(r["keys"], [&](const std::vector<double>& w) { return joined(w, 0, 3); });
    } else {
      text += ", weights";
      for (const Json& t : r["takes"]) text += " " + fixed(t["weight"].get<double>(), 3);
    }
  } else {
    // A transfer without a neutral take measures the change from the content itself.
    text = "transfer onto " + file_name(r["content"]) +
           (r.value("neutral", Json()).is_string() ? " from " + file_name(r["neutral"]) + " to"
                                                   : " (its own neutral) to");
    for (const Json& s : r["styles"]) text += " " + file_name(s);
    if (keyed) {
      // The styles' weights are the last of each key's: their strengths.
      const size_t styles = r["styles"].size();
      text += ", strength keyed " + keys_in_words(r["keys"], [&](const std::vector<double>& w) {
                return joined(w, w.size() - styles, 2);
              });
    } else {
      text += ", strength";
      for (const Json& s : r["strengths"]) text += " " + fixed(s.get<double>(), 2);
    }
  }
  return text;
}

// "\n  major joints of FILE: HOW" for each take whose major joints were not all found by their
// names (the report has every take's).
std::string major_joints_not_by_name(const Json& r) {
  std::string text;
  if (!r.contains("takes")) return text;
  for (const Json& t : r["takes"]) {
    if (!t.contains("major_joints") || !t.contains("file")) continue;
    const std::string how = t["major_joints"].value("how", std::string());
    bool by_names = how.find("structure:") == std::string::npos;
    for (const Json& j : t["major_joints"]["joints"]) {
      const std::string by = j.value("found_by", std::string());
      by_names = by_names && (by == "name" || by == "none");
    }
    if (!by_names) text += "\n  major joints of " + file_name(t["file"]) + ": " + how;
  }
  return text;
}

}  // namespace

std::string report_summary(const Json& r, const std::string& out, const std::string& positions_out) {
  const double height = r.value("skeleton_height", 0.0);
  auto of_height = [&](double v) { return height > 0 ? fixed(100.0 * v / height, 2) + "% of height" : fixed(v, 3); };
  std::string text = result_headline(r);
  text += "\n  " + std::to_string(r["frames"].get<long>()) + " frames at " + fixed(r["fps"].get<double>(), 0) +
          " fps (" + duration_in_words(r["duration_s"].get<double>()) + ")";
  if (r.contains("loop")) text += ", a loop of " + std::to_string(r["loop"].value("cycles", 0)) + " cycles";
  text += "\n  limb lengths within " + of_height(r["limb_length_max_error"].get<double>());
  // Planted feet in the measure's own body height (the same for the inputs and the output).
  const Json& sliding = r["foot_sliding"];
  const double body = sliding.value("body_height", height);
  auto of_body = [&](const char* key) {
    const double v = sliding[key].get<double>();
    return body > 0 ? fixed(100.0 * v / body, 2) + "% of height/s" : fixed(v, 3) + "/s";
  };
  text += "\n  planted feet move " + of_body("raw") + ", " +
          (r.value("foot_lock", false) ? "locked to " + of_body("cleaned") : std::string("not locked")) +
          "; the takes' own " + of_body("inputs");
  if (sliding.contains("ratio") && sliding["ratio"].is_number())
    text += " (" + fixed(sliding["ratio"].get<double>(), 2) + "x)";
  const Json& fastest = r["fastest_joint"];
  if (fastest["ratio"].is_number())
    text += "\n  fastest joint " + fixed(fastest["ratio"].get<double>(), 2) + "x the takes' fastest";
  if (!out.empty()) {
    text += "\n  wrote " + out;
    if (r.contains("export_fit"))
      text += " (follows the result within " + of_height(r["export_fit"]["mean"].get<double>()) + " mean, " +
              of_height(r["export_fit"]["max"].get<double>()) + " at worst)";
  }
  text += major_joints_not_by_name(r);
  if (!positions_out.empty()) text += "\n  wrote " + positions_out;
  if (out.empty() && positions_out.empty()) text += "\n  nothing written: give --out, --positions-out or --report";
  return text + "\n";
}

std::vector<std::pair<BodyPart, std::vector<double>>> parse_part_entries(const std::vector<std::string>& entries,
                                                                         const std::string& flag, size_t count) {
  std::vector<std::pair<BodyPart, std::vector<double>>> out;
  for (const std::string& e : entries) {
    const size_t colon = e.find(':');
    if (colon == std::string::npos) throw InputError("expected PART:value in " + flag + ", found '" + e + "'");
    std::vector<double> values = parse_numbers(e.substr(colon + 1), flag + " " + e.substr(0, colon));
    if (count > 0 && values.size() != count)
      throw InputError("expected " + std::to_string(count) + (count == 1 ? " number" : " numbers") + " after '" +
                       e.substr(0, colon + 1) + "' in " + flag + ", found " + std::to_string(values.size()));
    out.emplace_back(parse_body_part(e.substr(0, colon)), std::move(values));
  }
  return out;
}

Json range_json(int first, int last, double fps) {
  return {{"first", first}, {"last", last}, {"first_s", first / fps}, {"last_s", last / fps}};
}

// Take `take`'s alignment onto the reference: what it aligned on, the matched ranges, its quality.
Json cycles_json(const TakeCycles& cycles, double fps) {
  Json j;
  j["kind"] = cycle_kind_name(cycles.kind);
  if (cycles.kind == CycleKind::kGait) j["foot"] = cycles.foot == 0 ? "left" : "right";
  j["period_s"] = cycles.period / fps;
  if (cycles.kind == CycleKind::kGait) j["strike_phase"] = cycles.strike_phase;
  if (cycles.loops()) j["loop_frames"] = cycles.loop_frames;
  if (!cycles.reason.empty()) j["reason"] = cycles.reason;
  Json list = Json::array();
  for (const Cycle& c : cycles.cycles) list.push_back({{"start", c.begin}, {"end", c.end}, {"seconds", c.frames() / fps}});
  j["cycles"] = list;
  return j;
}

std::string cycles_summary(const TakeCycles& cycles, double fps, int frames) {
  const std::string loop =
      cycles.loops() ? ", a loop of " + std::to_string(cycles.loop_frames) + " frames" : std::string();
  if (cycles.kind == CycleKind::kNone)
    return "none (" + (cycles.reason.empty() ? std::string("the take does not repeat") : cycles.reason) + ")" + loop;
  std::string s = std::string(cycle_kind_name(cycles.kind)) + ", " + std::to_string(cycles.cycles.size()) +
                  (cycles.cycles.size() == 1 ? " cycle" : " cycles");
  if (cycles.kind == CycleKind::kGait) s += cycles.foot == 0 ? " (left foot)" : " (right foot)";
  char median[32];
  std::snprintf(median, sizeof median, "%.2f", cycles.period / fps);
  s += ", median " + std::string(median) + " s, " +
       std::to_string(static_cast<int>(std::lround(100.0 * cycles.frames_in_cycles() / std::max(frames, 1)))) +
       "% of the take" + loop;
  if (cycles.kind == CycleKind::kGait && cycles.loops() && cycles.strike_phase > 0.0) {
    char phase[48];
    std::snprintf(phase, sizeof phase, ", its strike at %.0f%% of the cycle", 100.0 * cycles.strike_phase);
    s += phase;
  }
  if (!cycles.reason.empty()) s += " (no gait: " + cycles.reason + ")";
  return s;
}

Json alignment_json(const PreparedTakes& p, int take) {
  const Alignment& al = p.takes[static_cast<size_t>(take)].alignment;
  Json j;
  j["method"] = dtw_method_name(al.options.method);
  // What it was aligned by (cycles fall back to structure or whole).
  j["time_base"] = al.by_cycles() ? "cycles" : al.by_structure ? "structure" : "whole";
  if (!al.notes.empty()) j["notes"] = al.notes;
  if (!al.whole_because.empty()) j["whole_because"] = al.whole_because;
  j["feature"] = align_on_name(al.feature.on);
  j["locomotion"] = al.feature.locomotion;
  Json joints = Json::array();
  for (int c : al.feature.columns) joints.push_back(p.reference().names[c]);
  j["joints"] = joints;
  j["weights"] = al.feature.weights;
  if (al.options.method == DtwMethod::kSlope) {
    j["max_slope"] = al.options.slope.max_slope;
    j["open_ends"] = al.options.slope.open_ends;
    j["end_penalty"] = al.end_penalty;
  }
  j["cost"] = al.cost;
  j["typical_cost"] = al.typical_cost;
  j["frames_a"] = al.frames_a;
  j["frames_b"] = al.frames_b;
  j["matched_a"] = range_json(al.a_first, al.a_last, p.fps);
  j["matched_b"] = range_json(al.b_first, al.b_last, p.fps);
  j["samples"] = al.warp.samples();
  j["max_cost_ratio"] = al.cost_ratio.size() ? al.cost_ratio.maxCoeff() : 0.0;
  j["slope_range"] = {al.slope.size() ? al.slope.minCoeff() : 0.0, al.slope.size() ? al.slope.maxCoeff() : 0.0};
  Json poor = Json::array();
  for (const auto& [first, last] : al.poor)
    poor.push_back({{"a", {al.warp.a[first], al.warp.a[last]}}, {"b", {al.warp.b[first], al.warp.b[last]}},
                    {"cost_ratio", al.cost_ratio.segment(first, last - first + 1).mean()}});
  j["poor_matches"] = poor;
  j["warnings"] = al.warnings;
  return j;
}

// One list of joint names per component (the report's `component_joints`).
Json component_joints_json(const std::vector<ComponentJoints>& parts, const std::vector<std::string>& names) {
  Json out = Json::array();
  for (const ComponentJoints& c : parts) {
    Json joints = Json::array();
    for (int column : c.columns) joints.push_back(names[static_cast<size_t>(column)]);
    out.push_back(joints);
  }
  return out;
}

// Per component: its plain name, body region and centre joint.
Json component_regions_json(const std::vector<ComponentJoints>& parts) {
  Json out = Json::array();
  for (const ComponentJoints& c : parts) out.push_back({{"name", c.name}, {"region", body_region_name(c.region)}});
  return out;
}

Json major_joints_json(const MajorMapping& mapping, const Skeleton& skeleton) {
  Json joints = Json::array();
  for (int i = 0; i < kMajorJointCount; ++i) {
    const int j = mapping.joint[static_cast<size_t>(i)];
    joints.push_back({{"role", major_joint_name(i)},
                      {"joint", j >= 0 ? Json(skeleton.joints[static_cast<size_t>(j)].name) : Json()},
                      {"found_by", major_source_name(mapping.source[static_cast<size_t>(i)])}});
  }
  return {{"how", mapping.how}, {"joints", joints}};
}

Json vector_json(const Eigen::VectorXd& v) { return std::vector<double>(v.data(), v.data() + v.size()); }

Json loop_json(const LoopCut& loop, double fps) {
  return {{"cycles", loop.cycles},
          {"frames", loop.frames()},
          {"seconds", loop.frames() / fps},
          {"cycle_seconds", loop.frames() / fps / std::max(1, loop.cycles)},
          {"begin", loop.begin},
          {"end", loop.end},
          {"travel", {loop.travel.x(), loop.travel.y()}},
          {"travel_distance", loop.travel.norm()},
          {"turn_removed_degrees", loop.turn_removed * 57.29577951308232}};
}

void add_result_measures(const MixMeasures& measures, Json& report) {
  const ResultMeasures& m = *measures.result;
  const double body_height = measures.body_height;
  auto of_height = [&](double v) { return body_height > 0.0 ? v / body_height : 0.0; };
  auto ratio = [](const std::optional<double>& r) { return r ? Json(*r) : Json(nullptr); };
  report["limb_length_max_error"] = m.limb_length_max_error;
  report["foot_sliding"] = {{"measure", "mean horizontal speed of ankles and toes within 3% of body height of their floor"},
                            {"body_height", body_height},
                            {"raw", m.planted_raw},
                            {"cleaned", m.planted_cleaned},
                            {"inputs", m.planted_inputs},
                            {"raw_of_height", of_height(m.planted_raw)},
                            {"cleaned_of_height", of_height(m.planted_cleaned)},
                            {"inputs_of_height", of_height(m.planted_inputs)},
                            {"ratio", ratio(m.planted_ratio())}};
  report["fastest_joint"] = {{"measure", "99.9th percentile over frame steps of the fastest joint's speed"},
                             {"result", m.fastest_joint},
                             {"inputs", m.fastest_inputs},
                             {"ratio", ratio(m.fastest_ratio())}};
}

}  // namespace mostyle::cli
