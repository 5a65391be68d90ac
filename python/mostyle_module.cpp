// The Python module `mostyle`: read, blend, mix, transfer and info as mostyle-cli runs them
// (app/cli/synthesis_request.h: one code path for both), takes and results as numpy arrays.
// Every C++ exception becomes a Python one here, and the engine runs with the GIL released.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <new>
#include <string>
#include <vector>

#include "app/cli/cli_common.h"
#include "app/cli/cli_pipeline_common.h"
#include "app/cli/synthesis_request.h"
#include "app/cli/take_info.h"
#include "engine/base/error.h"
#include "engine/io/motion_file.h"
#include "engine/kinematics/kinematics.h"
#include "engine/kinematics/resample.h"
#include "python/take_arrays.h"

namespace py = pybind11;

namespace mostyle {
namespace {

using cli::BlendRequest;
using cli::MixRequest;
using cli::SynthesisOptions;
using cli::SynthesisResult;
using cli::TakeSource;
using cli::TransferRequest;

using RowMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

// A take or a result. Its clip is shared with the requests it is handed to, never copied.
struct Take {
  std::shared_ptr<const Clip> clip;
  std::string source;                   // the path it was read from; "" from arrays or a result
  RowMatrix positions;                  // F x 3P; empty until asked for (a take: FK of every joint)
  std::vector<std::string> position_joints;
  std::string report;                   // a result's report as JSON text; "" for a take
  std::vector<std::string> warnings;    // the reader's and the alignment's
  // The clip as arrays, made at the first property read: the clip never changes, and a caller
  // such as the Blender add-on reads several properties of one result in turn.
  std::shared_ptr<const TakeArrays> arrays_cache;

  const TakeArrays& arrays() {
    if (!arrays_cache) arrays_cache = std::make_shared<const TakeArrays>(arrays_from_clip(*clip));
    return *arrays_cache;
  }

  void compute_positions() {
    if (positions.size() > 0 || clip->frames() == 0) return;
    positions = joint_positions(*clip);
    for (const Joint& j : clip->skeleton.joints) position_joints.push_back(j.name);
  }
};

// Runs f, turning what the C++ side throws into mostyle.Error (an InputError, as the CLI says it)
// so that nothing reaches the interpreter as an abort; Python's own errors pass as they are.
template <class F>
auto guarded(F&& f) -> decltype(f()) {
  try {
    return f();
  } catch (const py::error_already_set&) {
    throw;
  } catch (const py::cast_error& e) {
    // A value of the wrong type where a number, text or list was expected.
    throw InputError(std::string("wrong type of value: ") + e.what());
  } catch (const py::builtin_exception&) {
    throw;
  } catch (const InputError&) {
    throw;
  } catch (const std::bad_alloc&) {
    throw InputError("out of memory");
  } catch (const std::exception& e) {
    // Our own bug, not the input's: still an error, never a crash.
    throw InputError(std::string("internal error: ") + e.what());
  }
}

std::string type_name(py::handle value) { return py::str(py::type::of(value).attr("__name__")); }

std::string path_text(py::handle value, const std::string& what) {
  py::object os = py::module_::import("os");
  if (py::isinstance<py::str>(value) || py::hasattr(value, "__fspath__"))
    return py::str(os.attr("fspath")(value));
  throw InputError("expected " + what + " as a path, found " + type_name(value));
}

TakeSource take_source(py::handle value, const std::string& what) {
  if (py::isinstance<Take>(value)) {
    const Take& t = value.cast<const Take&>();
    return {t.source, t.clip};
  }
  if (value.is_none()) throw InputError("expected " + what + " (a path or a mostyle.Take), found None");
  if (!py::isinstance<py::str>(value) && !py::hasattr(value, "__fspath__"))
    throw InputError("expected " + what + " as a path or a mostyle.Take, found " + type_name(value));
  return {path_text(value, what), nullptr};
}

std::vector<TakeSource> take_sources(py::handle value, const std::string& what) {
  std::vector<TakeSource> takes;
  if (py::isinstance<py::list>(value) || py::isinstance<py::tuple>(value)) {
    for (py::handle item : value) takes.push_back(take_source(item, what));
  } else {
    takes.push_back(take_source(value, what));
  }
  return takes;
}

// Numbers as the CLI's text takes them ("0.2,0.8"): each written so it reads back exactly.
std::string numbers_text(py::handle value) {
  if (py::isinstance<py::str>(value)) return value.cast<std::string>();
  std::string text;
  if (py::isinstance<py::list>(value) || py::isinstance<py::tuple>(value) || py::hasattr(value, "__array__")) {
    for (py::handle item : py::iter(value)) text += (text.empty() ? "" : ",") + cli::number(item.cast<double>());
    return text;
  }
  return cli::number(value.cast<double>());
}

// Per-part values as the CLI's entries ("legs:0.2,0.8"): a dict {part: values} or the entries.
std::vector<std::string> part_entries(py::handle value) {
  std::vector<std::string> entries;
  if (py::isinstance<py::dict>(value)) {
    for (auto [part, values] : value.cast<py::dict>())
      entries.push_back(part.cast<std::string>() + ":" + numbers_text(values));
  } else if (py::isinstance<py::str>(value)) {
    entries.push_back(value.cast<std::string>());
  } else {
    for (py::handle item : value) entries.push_back(item.cast<std::string>());
  }
  return entries;
}

// Keys in time as the CLI's text ("T:v1,v2;T:..."): a dict {seconds: values}, (seconds, values)
// pairs, or the text.
std::string keys_text(py::handle value) {
  if (py::isinstance<py::str>(value)) return value.cast<std::string>();
  std::string text;
  auto add = [&](py::handle seconds, py::handle values) {
    text += (text.empty() ? "" : ";") + cli::number(seconds.cast<double>()) + ":" + numbers_text(values);
  };
  if (py::isinstance<py::dict>(value)) {
    for (auto [seconds, values] : value.cast<py::dict>()) add(seconds, values);
  } else {
    for (py::handle pair : value) {
      py::sequence p = pair.cast<py::sequence>();
      if (p.size() != 2) throw InputError("expected keys as (seconds, values) pairs");
      add(p[0], p[1]);
    }
  }
  return text;
}

// The request an option sets: the shared options, and the command's own request.
struct Request {
  SynthesisOptions* options = nullptr;
  BlendRequest* blend = nullptr;
  MixRequest* mix = nullptr;
  TransferRequest* transfer = nullptr;
};

enum Commands : unsigned { kBlend = 1, kMix = 2, kTransfer = 4, kAll = 7 };

struct Option {
  const char* name;  // the CLI's long flag with '-' as '_' (or its short name, or a flag's positive form)
  unsigned commands;
  std::function<void(Request&, py::handle)> set;
};

// Every keyword argument blend, mix and transfer take, once. Defaults are the requests' own.
const std::vector<Option>& option_table() {
  static const std::vector<Option> table = {
      {"fps", kAll, [](Request& r, py::handle v) { r.options->align.fps = v.cast<double>(); }},
      {"time_base", kAll, [](Request& r, py::handle v) { r.options->align.time_base = v.cast<std::string>(); }},
      {"dtw", kAll, [](Request& r, py::handle v) { r.options->align.dtw = v.cast<std::string>(); }},
      {"align_on", kAll, [](Request& r, py::handle v) { r.options->align.align_on = v.cast<std::string>(); }},
      {"max_slope", kAll, [](Request& r, py::handle v) { r.options->align.max_slope = v.cast<int>(); }},
      {"closed_ends", kAll, [](Request& r, py::handle v) { r.options->align.closed_ends = v.cast<bool>(); }},
      {"band", kAll, [](Request& r, py::handle v) { r.options->align.band = v.cast<int>(); }},
      {"components", kAll, [](Request& r, py::handle v) { r.options->components = v.cast<int>(); }},
      {"k", kAll, [](Request& r, py::handle v) { r.options->components = v.cast<int>(); }},
      {"sparsity", kAll, [](Request& r, py::handle v) { r.options->sparsity = v.cast<double>(); }},
      {"f", kAll, [](Request& r, py::handle v) { r.options->sparsity = v.cast<double>(); }},
      {"iterations", kAll, [](Request& r, py::handle v) { r.options->iterations = v.cast<int>(); }},
      {"no_limb_constraint", kAll, [](Request& r, py::handle v) { r.options->no_limb_constraint = v.cast<bool>(); }},
      {"limb_constraint", kAll, [](Request& r, py::handle v) { r.options->no_limb_constraint = !v.cast<bool>(); }},
      {"no_foot_lock", kAll, [](Request& r, py::handle v) { r.options->no_foot_lock = v.cast<bool>(); }},
      {"foot_lock", kAll, [](Request& r, py::handle v) { r.options->no_foot_lock = !v.cast<bool>(); }},
      {"timing", kAll, [](Request& r, py::handle v) { r.options->timing = v.cast<std::string>(); }},
      {"no_local", kAll, [](Request& r, py::handle v) { r.options->no_local = v.cast<bool>(); }},
      {"local", kAll, [](Request& r, py::handle v) { r.options->no_local = !v.cast<bool>(); }},
      {"components_only", kAll, [](Request& r, py::handle v) { r.options->components_only = v.cast<bool>(); }},
      {"loop", kAll, [](Request& r, py::handle v) { r.options->loop = v.cast<bool>(); }},
      {"out", kAll, [](Request& r, py::handle v) { r.options->out = path_text(v, "out"); }},
      {"channels", kAll, [](Request& r, py::handle v) { r.options->channels = v.cast<std::string>(); }},
      {"positions_out", kAll, [](Request& r, py::handle v) { r.options->positions_out = path_text(v, "positions_out"); }},
      {"report", kAll, [](Request& r, py::handle v) { r.options->report = path_text(v, "report"); }},
      {"mapping_a", kBlend, [](Request& r, py::handle v) { r.blend->mapping_a = path_text(v, "mapping_a"); }},
      {"mapping_b", kBlend, [](Request& r, py::handle v) { r.blend->mapping_b = path_text(v, "mapping_b"); }},
      {"mode", kBlend, [](Request& r, py::handle v) { r.blend->mode = v.cast<std::string>(); }},
      {"basic", kBlend, [](Request& r, py::handle v) { r.blend->basic = v.cast<int>(); }},
      {"basic_sparsity", kBlend,
       [](Request& r, py::handle v) {
         r.blend->basic_sparsities = cli::parse_numbers(numbers_text(v), "--basic-sparsity");
       }},
      {"swap", kBlend, [](Request& r, py::handle v) { r.blend->swap = v.cast<int>(); }},
      {"part_alpha", kBlend, [](Request& r, py::handle v) { r.blend->part_alpha = part_entries(v); }},
      {"component_alpha", kBlend,
       [](Request& r, py::handle v) {
         r.blend->component_alpha = cli::parse_numbers(numbers_text(v), "--component-alpha");
       }},
      {"alpha_at", kBlend, [](Request& r, py::handle v) { r.blend->alpha_at = keys_text(v); }},
      {"weights_at", kMix, [](Request& r, py::handle v) { r.mix->weights_at = keys_text(v); }},
      {"part_strength", kTransfer, [](Request& r, py::handle v) { r.transfer->part_strengths = part_entries(v); }},
      {"strength_at", kTransfer, [](Request& r, py::handle v) { r.transfer->strength_at = keys_text(v); }},
  };
  return table;
}

// Sets each keyword argument through the table; one it does not list for `command` is refused,
// naming the ones it does.
void set_options(Request& request, unsigned command, const char* command_name, const py::kwargs& kwargs) {
  for (auto [key, value] : kwargs) {
    const std::string name = key.cast<std::string>();
    const Option* found = nullptr;
    for (const Option& o : option_table())
      if ((o.commands & command) && name == o.name) found = &o;
    if (found == nullptr) {
      std::string valid;
      for (const Option& o : option_table())
        if (o.commands & command) valid += (valid.empty() ? "" : ", ") + std::string(o.name);
      throw InputError("unknown option '" + name + "' for " + command_name + "; the options are " + valid);
    }
    if (value.is_none()) continue;  // None: the default
    try {
      found->set(request, value);
    } catch (const py::cast_error&) {
      throw InputError("option " + name + ": cannot use a " + type_name(value) + " here");
    }
  }
}

py::object json_to_python(const std::string& text) {
  return py::module_::import("json").attr("loads")(text);
}

// Rows `at` (clip frames, rounded to the nearest, clamped) of a matrix with a row per frame,
// column by column as Eigen stores them.
template <class M>
M nearest_rows(const M& m, const Eigen::VectorXd& at) {
  std::vector<Eigen::Index> rows(static_cast<size_t>(at.size()));
  for (Eigen::Index f = 0; f < at.size(); ++f)
    rows[static_cast<size_t>(f)] =
        std::clamp<Eigen::Index>(static_cast<Eigen::Index>(std::lround(at[f])), 0, m.rows() - 1);
  M out(at.size(), m.cols());
  for (Eigen::Index c = 0; c < m.cols(); ++c)
    for (Eigen::Index f = 0; f < at.size(); ++f) out(f, c) = m(rows[static_cast<size_t>(f)], c);
  return out;
}

// The reference at the frames a result shows, its nearest own frame each (no interpolation:
// Euler angles and quaternions are interpolated with trigonometry, which costs what the mix
// costs), at the result's rate; its arrays picked from `reference_arrays` alike, their signs made
// continuous again as arrays_from_clip makes them.
Take reference_at(const Clip& reference, const TakeArrays& reference_arrays, const Eigen::VectorXd& at, double fps) {
  Clip clip;
  clip.source = reference.source;
  clip.skeleton = reference.skeleton;
  clip.motion = nearest_rows(reference.motion, at);
  clip.frame_time = 1.0 / fps;
  // Only the skeleton's arrays are copied whole: the per-frame ones are the reference's length,
  // several times the frames shown when it was read at a higher rate.
  TakeArrays a;
  a.joint_names = reference_arrays.joint_names;
  a.parents = reference_arrays.parents;
  a.offsets = reference_arrays.offsets;
  a.fps = clip.fps();
  a.rotations = nearest_rows(reference_arrays.rotations, at);
  a.translations = nearest_rows(reference_arrays.translations, at);
  a.root_positions = nearest_rows(reference_arrays.root_positions, at);
  Eigen::MatrixXd& q = a.rotations;
  for (Eigen::Index j = 0; j < q.cols(); j += 4)
    for (Eigen::Index f = 1; f < q.rows(); ++f) {
      const double dot = q(f, j) * q(f - 1, j) + q(f, j + 1) * q(f - 1, j + 1) + q(f, j + 2) * q(f - 1, j + 2) +
                         q(f, j + 3) * q(f - 1, j + 3);
      if (dot < 0.0)
        for (int k = 0; k < 4; ++k) q(f, j + k) = -q(f, j + k);
    }
  Take take;
  take.clip = std::make_shared<const Clip>(std::move(clip));
  take.arrays_cache = std::make_shared<const TakeArrays>(std::move(a));
  return take;
}

// A result as a Take, its outputs written. Called with the GIL released. A result whose clip
// was not solved carries the reference's own frames it shows (reference_at; `reference_arrays`
// the reference's arrays): its rotations are the reference's, its positions the result's.
Take result_take(SynthesisResult& result, const SynthesisOptions& options,
                 const TakeArrays* reference_arrays = nullptr) {
  cli::write_synthesis_outputs(result, options);
  Take take;
  if (result.solved) {
    take.clip = std::make_shared<const Clip>(std::move(result.clip.clip));
  } else {
    const PreparedTakes& palette = *result.prepared;
    take = reference_at(*palette.takes.front().clip, *reference_arrays, source_frames_in_clip(palette, result.mix),
                        palette.fps);
  }
  take.positions = result.mix.motion.world;
  take.position_joints = result.joints;
  take.report = result.report.dump(-1, ' ', false, cli::Json::error_handler_t::replace);
  return take;
}

// Runs a request with the GIL released and makes its result a Take.
template <class R>
Take run_request(R& request, SynthesisResult (*run)(const R&)) {
  std::vector<std::string> messages;
  request.options.solve_clip = true;
  request.options.message = [&messages](const std::string& line) { messages.push_back(line); };
  Take take;
  {
    py::gil_scoped_release release;
    SynthesisResult result = run(request);
    take = result_take(result, request.options);
  }
  take.warnings = std::move(messages);
  return take;
}

Take read_take(py::handle path, py::handle take_name) {
  return guarded([&] {
    const std::string text = path_text(path, "the take");
    MotionReadOptions options = cli::motion_read_options_from_environment();
    if (!take_name.is_none()) options.take = take_name.cast<std::string>();
    Take t;
    // The report names it as the CLI would have been given it: FILE#ANIMATION.
    t.source = options.take.empty() ? text : join_take_path(split_take_path(text).path, options.take);
    std::vector<std::string> warnings, notes;
    {
      py::gil_scoped_release release;
      t.clip = std::make_shared<const Clip>(read_motion_file(text, &warnings, options, &notes));
    }
    for (const std::string& w : warnings) t.warnings.push_back("warning: " + w);
    for (const std::string& n : notes) t.warnings.push_back("note: " + n);
    return t;
  });
}

Take blend(py::handle a, py::handle b, double alpha, const py::kwargs& kwargs) {
  return guarded([&] {
    BlendRequest request;
    request.a = take_source(a, "take A");
    request.b = take_source(b, "take B");
    request.alpha = alpha;
    Request r{&request.options, &request, nullptr, nullptr};
    set_options(r, kBlend, "blend", kwargs);
    return run_request(request, &cli::blend_takes);
  });
}

Take mix(py::handle takes, py::handle weights, py::handle part_weights, const py::kwargs& kwargs) {
  return guarded([&] {
    MixRequest request;
    if (!py::isinstance<py::list>(takes) && !py::isinstance<py::tuple>(takes))
      throw InputError("expected the takes as a list, found " + type_name(takes));
    request.takes = take_sources(takes, "a take");
    if (!weights.is_none()) request.weights = numbers_text(weights);
    if (!part_weights.is_none()) request.part_weights = part_entries(part_weights);
    Request r{&request.options, nullptr, &request, nullptr};
    set_options(r, kMix, "mix", kwargs);
    return run_request(request, &cli::mix_takes);
  });
}

Take transfer(py::handle content, py::handle style, py::handle neutral, py::handle strength,
              const py::kwargs& kwargs) {
  return guarded([&] {
    TransferRequest request;
    request.content = take_source(content, "the content");
    request.styles = take_sources(style, "a style");
    if (!neutral.is_none()) request.neutral = take_source(neutral, "the neutral");
    if (!strength.is_none()) request.strengths = {numbers_text(strength)};
    Request r{&request.options, nullptr, nullptr, &request};
    set_options(r, kTransfer, "transfer", kwargs);
    return run_request(request, &cli::transfer_style);
  });
}

// A set of takes prepared once (read, aligned, decomposed) and mixed again with other weights:
// what a slider that moves asks for. One mix at a time per handle (its scratch is shared);
// several handles mix at once.
struct Prepared {
  std::shared_ptr<const cli::PreparedSynthesis> synthesis;
  py::dict options;          // prepare's keyword arguments, set on every request made from it
  bool has_neutral = false;  // takes are content, neutral, styles: only transfer
  std::vector<std::string> warnings;
  std::unique_ptr<std::mutex> busy = std::make_unique<std::mutex>();
  std::shared_ptr<MixScratch> scratch = std::make_shared<MixScratch>();
  std::shared_ptr<const TakeArrays> reference;  // the reference's arrays, made at the first mix without a solve
};

MixRequest prepared_mix_request(const Prepared& p, py::handle weights, py::handle part_weights) {
  if (p.has_neutral) throw InputError("takes prepared with a neutral transfer a style: call transfer(), or prepare them without it to mix");
  MixRequest request;
  request.takes = p.synthesis->takes;
  Request r{&request.options, nullptr, &request, nullptr};
  set_options(r, kMix, "mix", py::kwargs(p.options));
  if (!weights.is_none()) request.weights = numbers_text(weights);
  if (!part_weights.is_none()) request.part_weights = part_entries(part_weights);
  return request;
}

TransferRequest prepared_transfer_request(const Prepared& p, py::handle strength, py::handle part_strength) {
  const std::vector<TakeSource>& takes = p.synthesis->takes;
  TransferRequest request;
  Request r{&request.options, nullptr, nullptr, &request};
  set_options(r, kTransfer, "transfer", py::kwargs(p.options));
  // Takes prepared to be mixed keep the alignment they were prepared with (the mix's default
  // rate, unless fps was given): a transfer of them is not aligned again.
  if (!p.has_neutral) request.options.align = p.synthesis->align;
  request.content = takes.front();
  size_t first_style = 1;
  if (p.has_neutral) request.neutral = takes[first_style++];
  if (takes.size() <= first_style) throw InputError("a transfer needs the content and at least one style take");
  request.styles.assign(takes.begin() + static_cast<std::ptrdiff_t>(first_style), takes.end());
  if (!strength.is_none()) request.strengths = {numbers_text(strength)};
  if (!part_strength.is_none()) request.part_strengths = part_entries(part_strength);
  return request;
}

// Mixes a request made from a handle with the GIL released. solve: the result's clip solved on
// the reference's skeleton, as mix and transfer give it; else its positions only, beside the
// reference's own rotations (see result_take).
template <class R>
Take run_prepared(Prepared& p, R& request, bool solve,
                  SynthesisResult (*run)(const cli::PreparedSynthesis&, const R&, MixScratch&)) {
  request.options.solve_clip = solve;
  Take take;
  {
    py::gil_scoped_release release;
    std::lock_guard<std::mutex> lock(*p.busy);
    SynthesisResult result = run(*p.synthesis, request, *p.scratch);
    if (!result.solved && !p.reference)
      p.reference = std::make_shared<const TakeArrays>(arrays_from_clip(*p.synthesis->prepared->takes.front().clip));
    take = result_take(result, request.options, p.reference.get());
  }
  take.warnings = p.warnings;
  return take;
}

Prepared prepare(py::handle takes, py::handle neutral, const py::kwargs& kwargs) {
  return guarded([&] {
    if (!py::isinstance<py::list>(takes) && !py::isinstance<py::tuple>(takes))
      throw InputError("expected the takes as a list, found " + type_name(takes));
    Prepared p;
    p.options = py::dict(kwargs);
    p.has_neutral = !neutral.is_none();
    std::vector<std::string> messages;
    const cli::MessageSink sink = [&messages](const std::string& line) { messages.push_back(line); };
    const std::vector<TakeSource> sources = take_sources(takes, "a take");
    if (p.has_neutral) {
      if (sources.size() < 2) throw InputError("a transfer needs the content and at least one style take");
      TransferRequest request;
      request.content = sources.front();
      request.neutral = take_source(neutral, "the neutral");
      request.styles.assign(sources.begin() + 1, sources.end());
      Request r{&request.options, nullptr, nullptr, &request};
      set_options(r, kTransfer, "prepare with a neutral (transfer)", kwargs);
      request.options.message = sink;
      py::gil_scoped_release release;
      p.synthesis = std::make_shared<const cli::PreparedSynthesis>(cli::prepare_transfer(request));
    } else {
      MixRequest request;
      request.takes = sources;
      Request r{&request.options, nullptr, &request, nullptr};
      set_options(r, kMix, "prepare", kwargs);
      request.options.message = sink;
      py::gil_scoped_release release;
      p.synthesis = std::make_shared<const cli::PreparedSynthesis>(cli::prepare_mix(request));
    }
    p.warnings = std::move(messages);
    return p;
  });
}

py::object info(py::handle path, py::handle take, double fps, py::handle mapping) {
  return guarded([&] {
    const std::string text = path_text(path, "the file");
    const std::string take_name = take.is_none() ? "" : take.cast<std::string>();
    const std::string mapping_file = mapping.is_none() ? "" : path_text(mapping, "mapping");
    std::string json;
    {
      py::gil_scoped_release release;
      const cli::FileInfo file = cli::read_file_info(text, take_name, fps, mapping_file);
      json = cli::info_json(text, file).dump(-1, ' ', false, cli::Json::error_handler_t::replace);
    }
    return json_to_python(json);
  });
}

// A C-ordered float64 array of the given shape (-1: any size); `name` says which in errors.
py::array_t<double> array_of_shape(py::handle value, const std::string& name, std::vector<py::ssize_t> shape,
                                   const std::string& shape_words) {
  auto a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(value);
  if (!a) throw InputError("expected " + name + " as a numeric array of " + shape_words + ", found " + type_name(value));
  bool ok = a.ndim() == static_cast<py::ssize_t>(shape.size());
  for (size_t d = 0; ok && d < shape.size(); ++d) ok = shape[d] < 0 || a.shape(d) == shape[d];
  if (!ok) {
    std::string found;
    for (py::ssize_t d = 0; d < a.ndim(); ++d) found += (d ? " x " : "") + std::to_string(a.shape(d));
    throw InputError("expected " + name + " of " + shape_words + ", found " + (found.empty() ? "a scalar" : found));
  }
  return a;
}

Eigen::MatrixXd to_matrix(const py::array_t<double>& a, Eigen::Index rows, Eigen::Index cols) {
  return Eigen::Map<const RowMatrix>(a.data(), rows, cols);
}

Take take_from_arrays(py::handle joint_names, py::handle parents, py::handle offsets, py::handle rotations,
                      py::handle root_positions, double fps, py::handle translations) {
  return guarded([&] {
    TakeArrays arrays;
    try {
      arrays.joint_names = joint_names.cast<std::vector<std::string>>();
    } catch (const py::cast_error&) {
      throw InputError("expected joint_names as a list of strings, found " + type_name(joint_names));
    }
    const py::ssize_t joints = static_cast<py::ssize_t>(arrays.joint_names.size());
    const std::string j = std::to_string(joints);
    auto p = py::array_t<long long, py::array::c_style | py::array::forcecast>::ensure(parents);
    if (!p || p.ndim() != 1 || p.shape(0) != joints)
      throw InputError("expected parents as " + j + " joint indices (-1 for the root), one per joint name");
    arrays.parents.assign(p.data(), p.data() + joints);
    const auto o = array_of_shape(offsets, "offsets", {joints, 3}, j + " x 3 (joints x 3)");
    const auto r = array_of_shape(rotations, "rotations", {-1, joints, 4}, "frames x " + j + " x 4 (w, x, y, z)");
    const py::ssize_t frames = r.shape(0);
    const auto t = array_of_shape(root_positions, "root_positions", {frames, 3},
                                  std::to_string(frames) + " x 3 (a row per frame of rotations)");
    arrays.offsets = to_matrix(o, joints, 3);
    arrays.rotations = to_matrix(r, frames, 4 * joints);
    arrays.root_positions = to_matrix(t, frames, 3);
    if (!translations.is_none()) {
      const auto l = array_of_shape(translations, "translations", {frames, joints, 3},
                                    std::to_string(frames) + " x " + j + " x 3 (frames x joints x 3)");
      arrays.translations = to_matrix(l, frames, 3 * joints);
    }
    arrays.fps = fps;
    Take take;
    take.clip = std::make_shared<const Clip>(clip_from_arrays(arrays, "take from arrays"));
    return take;
  });
}

py::array_t<double> numpy_copy(const RowMatrix& m, std::vector<py::ssize_t> shape) {
  py::array_t<double> out(shape);
  std::copy(m.data(), m.data() + m.size(), out.mutable_data());
  return out;
}

void write_take(const Take& take, py::handle path) {
  guarded([&] {
    const std::string text = path_text(path, "the file to write");
    if (!is_written_motion_path(text))
      throw InputError("cannot write '" + text + "': the formats written are " + kWrittenMotionFormats);
    py::gil_scoped_release release;
    write_motion_file(*take.clip, text);
  });
}

}  // namespace
}  // namespace mostyle

PYBIND11_MODULE(mostyle, m) {
  using namespace mostyle;
  m.doc() = "Blend, mix and transfer the styles of motion-capture takes, as mostyle-cli does.";
  py::register_exception<InputError>(m, "Error", PyExc_ValueError);

  py::class_<Take>(m, "Take",
                   "A take read from a file, built from arrays, or a result. Arrays are copies: "
                   "rotations F x J x 4 (local, w x y z), root_positions F x 3, offsets J x 3, file units; "
                   "translations F x J x 3 (optional) for joints below the root that move.")
      .def(py::init(&take_from_arrays), py::arg("joint_names"), py::arg("parents"), py::arg("offsets"),
           py::arg("rotations"), py::arg("root_positions"), py::arg("fps") = 30.0,
           py::arg("translations") = py::none())
      .def_property_readonly("joint_names", [](Take& t) { return t.arrays().joint_names; })
      .def_property_readonly("parents", [](Take& t) {
        const std::vector<int> p = t.arrays().parents;
        return py::array_t<long long>(static_cast<py::ssize_t>(p.size()), std::vector<long long>(p.begin(), p.end()).data());
      })
      .def_property_readonly("offsets", [](Take& t) {
        const TakeArrays& a = t.arrays();
        return numpy_copy(a.offsets, {a.offsets.rows(), 3});
      })
      .def_property_readonly("rotations", [](Take& t) {
        const TakeArrays& a = t.arrays();
        return numpy_copy(a.rotations, {a.rotations.rows(), a.rotations.cols() / 4, 4});
      })
      .def_property_readonly("root_positions", [](Take& t) {
        const TakeArrays& a = t.arrays();
        return numpy_copy(a.root_positions, {a.root_positions.rows(), 3});
      })
      .def_property_readonly("translations", [](Take& t) {
        const TakeArrays& a = t.arrays();
        return numpy_copy(a.translations, {a.translations.rows(), a.translations.cols() / 3, 3});
      }, "F x J x 3 local translations (a joint's offset, or its position channels where it has them)")
      .def_property_readonly("positions", [](Take& t) {
        t.compute_positions();
        return numpy_copy(t.positions, {t.positions.rows(), t.positions.cols() / 3, 3});
      }, "F x P x 3 joint positions (a result: its major joints, as --positions-out; a take: every joint)")
      .def_property_readonly("position_joints", [](Take& t) {
        t.compute_positions();
        return t.position_joints;
      }, "the names of positions' joints")
      .def_property_readonly("fps", [](const Take& t) { return t.clip->fps(); })
      .def_property_readonly("frames", [](const Take& t) { return t.clip->frames(); })
      .def_property_readonly("source", [](const Take& t) { return t.source; })
      .def_property_readonly("report", [](const Take& t) -> py::object {
        return t.report.empty() ? py::none() : json_to_python(t.report);
      }, "a result's report (the dict --report writes); None for a take")
      .def_property_readonly("warnings", [](const Take& t) { return t.warnings; })
      .def("write", &write_take, py::arg("path"),
           "Writes the take as the extension says (.bvh, .fbx, .glb, .gltf), as mostyle-cli's --out.")
      .def("__repr__", [](const Take& t) {
        return "<mostyle.Take " + (t.source.empty() ? std::string() : "'" + t.source + "' ") +
               std::to_string(t.clip->frames()) + " frames at " + cli::number(t.clip->fps()) + " fps, " +
               std::to_string(t.clip->skeleton.joint_count_without_end_sites()) + " joints>";
      });

  py::class_<Prepared>(m, "Prepared",
                       "Takes read, aligned and decomposed once, by mostyle.prepare: each mix() or transfer() "
                       "runs only the mix (and the result's solve), with the options prepare was given.")
      .def("mix", [](Prepared& p, py::handle weights, py::handle part_weights, bool solve) {
             return guarded([&] {
               MixRequest request = prepared_mix_request(p, weights, part_weights);
               return run_prepared(p, request, solve, &cli::mix_prepared);
             });
           }, py::arg("weights") = py::none(), py::arg("part_weights") = py::none(), py::arg("solve") = true,
           "What mostyle.mix gives for these takes and options with these weights. solve=False: the "
           "result's positions only, beside the reference's own rotations at the nearest of its frames "
           "to each frame shown, without solving them onto the reference's skeleton (the slow part "
           "of a mix once prepared).")
      .def("transfer", [](Prepared& p, py::handle strength, py::handle part_strength, bool solve) {
             return guarded([&] {
               TransferRequest request = prepared_transfer_request(p, strength, part_strength);
               return run_prepared(p, request, solve, &cli::transfer_prepared);
             });
           }, py::arg("strength") = py::none(), py::arg("part_strength") = py::none(), py::arg("solve") = true,
           "What mostyle.transfer gives with the first take as the content, the neutral prepare was "
           "given (none: the content is its own) and the other takes as the styles; strength one per "
           "style (default 1 each). solve as mix().")
      .def_property_readonly("takes", [](const Prepared& p) { return p.synthesis->takes.size(); },
                             "how many takes were prepared (a transfer's content, neutral and styles)")
      .def_property_readonly("warnings", [](const Prepared& p) { return p.warnings; })
      .def("__repr__", [](const Prepared& p) {
        return "<mostyle.Prepared " + std::to_string(p.synthesis->takes.size()) + " takes, " +
               std::to_string(p.synthesis->prepared->samples()) + " samples at " +
               cli::number(p.synthesis->prepared->fps) + " fps" + (p.has_neutral ? ", with a neutral>" : ">");
      });

  m.def("read", &read_take, py::arg("path"), py::arg("take") = py::none(),
        "Reads a take: BVH, FBX, glTF, or FILE#ANIMATION; take names the animation of an FBX or glTF file.");
  m.def("blend", &blend, py::arg("a"), py::arg("b"), py::arg("alpha") = cli::BlendRequest().alpha,
        "Blends two takes as mostyle-cli blend does; options as its flags ('-' as '_').");
  m.def("mix", &mix, py::arg("takes"), py::arg("weights") = py::none(), py::arg("part_weights") = py::none(),
        "Mixes 2 to 16 takes as mostyle-cli mix does; weights default to equal.");
  m.def("transfer", &transfer, py::arg("content"), py::arg("style"), py::arg("neutral") = py::none(),
        py::arg("strength") = py::none(),
        "Puts a style onto content as mostyle-cli transfer does; style is one take or a list, strength "
        "one per style (default 1 each).");
  m.def("prepare", &prepare, py::arg("takes"), py::arg("neutral") = py::none(),
        "Reads, aligns and decomposes takes once, for many mixes: options as mix's (transfer's with a "
        "neutral). Returns a Prepared whose mix() and transfer() give what mostyle.mix and "
        "mostyle.transfer give.");
  m.def("info", &info, py::arg("path"), py::arg("take") = py::none(), py::arg("fps") = 0.0,
        py::arg("mapping") = py::none(), "What mostyle-cli info --json prints, as a dict.");
}
