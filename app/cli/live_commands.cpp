#include "app/cli/live_commands.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "app/cli/cli_common.h"
#include "app/cli/cli_pipeline_common.h"
#include "app/live/live_run.h"
#include "engine/base/error.h"
#include "engine/base/numbers.h"
#include "engine/live/live_style.h"
#include "engine/synthesize/mix_palette.h"
#include "engine/align/prepare_takes.h"

namespace mostyle::cli {
namespace {

// The takes and strengths of `live`, as typed: --neutral/--style/--strength or --mix/--weights.
struct StyleFlags {
  std::string neutral;
  std::vector<std::string> styles, strengths;
  std::vector<std::string> mix;
  std::string weights;

  // The files in LiveStyleSpec's order and the strengths; checks the numbers before any file
  // is read. Throws InputError.
  std::vector<std::string> files(std::vector<double>* strengths_out) const {
    const bool transfer = !neutral.empty() || !styles.empty();
    if (transfer == !mix.empty())
      throw InputError("give --neutral with --style (the style to put on the stream), or --mix with --weights");
    if (transfer) return transfer_files(strengths_out);
    return mix_files(strengths_out);
  }

 private:
  std::vector<std::string> transfer_files(std::vector<double>* strengths_out) const {
    if (neutral.empty()) throw InputError("--style needs --neutral: the take of the action without the style");
    if (styles.empty()) throw InputError("--neutral needs at least one --style");
    if (styles.size() + 1 > static_cast<size_t>(kMaxPaletteTakes))
      throw InputError("live takes at most " + std::to_string(kMaxPaletteTakes - 1) + " styles, found " +
                       std::to_string(styles.size()));
    std::vector<double> s;
    for (const std::string& text : strengths)
      for (double v : parse_numbers(text, "--strength")) s.push_back(v);
    if (strengths.empty()) s.assign(styles.size(), 1.0);
    if (s.size() != styles.size())
      throw InputError("expected " + std::to_string(styles.size()) + " strengths, one per --style, found " +
                       std::to_string(s.size()));
    *strengths_out = s;
    std::vector<std::string> files{neutral};
    files.insert(files.end(), styles.begin(), styles.end());
    return files;
  }

  // The stream stands in for the first take: the others' weights are the strengths.
  std::vector<std::string> mix_files(std::vector<double>* strengths_out) const {
    const size_t n = mix.size();
    if (n < 2 || n > static_cast<size_t>(kMaxPaletteTakes))
      throw InputError("--mix takes from 2 to " + std::to_string(kMaxPaletteTakes) + " takes, found " +
                       std::to_string(n));
    const std::vector<double> w = normalized_weights(weights.empty() ? std::vector<double>(n, 1.0 / double(n))
                                                                     : parse_numbers(weights, "--weights"));
    if (w.size() != n)
      throw InputError("expected " + std::to_string(n) + " weights, one per --mix take, found " +
                       std::to_string(w.size()));
    MixParams mp;
    mp.layers = take_layers(w);
    mp.Validate(static_cast<int>(n), 0);
    strengths_out->assign(w.begin() + 1, w.end());
    return mix;
  }
};

bool ends_in_bvh(std::string path) {
  std::transform(path.begin(), path.end(), path.begin(), [](unsigned char c) { return std::tolower(c); });
  return path.size() > 4 && path.compare(path.size() - 4, 4, ".bvh") == 0;
}

// The stream's skeleton and rate: a BVH whose frames are ignored.
Clip load_skeleton(const std::string& path) {
  std::vector<std::string> warnings;
  Clip clip = read_bvh_file(path, &warnings, bvh_read_options_from_environment());
  if (clip.skeleton.channel_count == 0) throw InputError(path + ": the skeleton has no channels to stream");
  return clip;
}

std::unique_ptr<BvhRecorder> recorder(const std::string& path, const std::string& flag, const Clip& skeleton) {
  if (path.empty()) return nullptr;
  if (!ends_in_bvh(path)) throw InputError(path + ": " + flag + " writes BVH: give a name ending in .bvh");
  return std::make_unique<BvhRecorder>(path, skeleton.skeleton, skeleton.frame_time);
}

// --connect-timeout as typed: seconds from 0 up; none: for ever (-1).
double parse_connect_timeout(const std::string& text) {
  if (text.empty()) return -1.0;
  double seconds = 0.0;
  if (!parse_number(text, &seconds) || seconds < 0.0)
    throw InputError("--connect-timeout: expected seconds from 0 (one try, and the end when the source closes) up, "
                     "found '" + text + "'");
  return seconds;
}

// --max-clients as typed: enough for any studio, few enough that descriptors never run out.
int checked_max_clients(int n) {
  constexpr int kMostClients = 1024;
  if (n < 1 || n > kMostClients)
    throw InputError("--max-clients: expected from 1 to " + std::to_string(kMostClients) + " clients, found " +
                     std::to_string(n));
  return n;
}

constexpr const char* kServeHelp =
    "PORT: this machine only (127.0.0.1); ADDRESS:PORT opens it to a network on purpose: 0.0.0.0:PORT every IPv4 "
    "interface, an interface's own address, [::]:PORT every interface; port 0 picks a free one. Where it listens is "
    "printed";

}  // namespace

void add_live_command(CLI::App& app, std::function<int()>* run) {
  auto* cmd = app.add_subcommand(
      "live",
      "Put a style on a live motion-capture stream in Axis Neuron's BVH broadcasting format (string, TCP) and "
      "serve it on in the same format, each frame as it comes");
  struct Args {
    std::string connect, skeleton, serve, record, record_input, connect_timeout;
    bool reconnect = false;
    int max_clients = live::kDefaultMaxClients;
    StyleFlags style;
  };
  auto args = std::make_shared<Args>();
  cmd->add_option("--connect", args->connect,
                  "HOST:PORT of the source (Axis Neuron or Axis Studio with BVH broadcasting on, string format; or "
                  "mostyle-cli live-send)")
      ->required();
  cmd->add_option("--skeleton", args->skeleton,
                  "BVH file whose hierarchy and channels match the stream (its frames are ignored; its Frame Time "
                  "gives the stream's rate), e.g. one exported from Axis with the same output settings")
      ->required();
  cmd->add_option("--neutral", args->style.neutral, "Take of the action without the style");
  cmd->add_option("--style", args->style.styles, "Take of the action in the style (repeat for several styles)");
  cmd->add_option("--strength", args->style.strengths,
                  "How much of each style, one per --style, comma separated (default 1 each)");
  cmd->add_option("--mix", args->style.mix,
                  "Takes T1 T2 ... to mix; the stream stands in for T1 (instead of --neutral/--style)")
      ->expected(2, kMaxPaletteTakes);
  cmd->add_option("--weights", args->style.weights,
                  "With --mix: one weight per take, comma separated, summing to 1 (default: equal)");
  cmd->add_option("--serve", args->serve,
                  std::string("Where to serve the styled stream (the Unity or Unreal Axis plugin set to this machine "
                              "and port). ") + kServeHelp);
  cmd->add_option("--max-clients", args->max_clients,
                  "The most clients served at once (default 16); one more is refused, with a warning on stderr");
  cmd->add_option("--record", args->record,
                  "BVH file of the styled stream, written frame by frame (a valid BVH file at every moment)");
  cmd->add_option("--record-input", args->record_input, "BVH file of the stream as it came, written the same way");
  cmd->add_option("--connect-timeout", args->connect_timeout,
                  "Seconds to wait for the source, at the start and after it closes, trying again every 0.25 s to "
                  "2 s (default: for ever, as the Axis plugins do, so a restart of the mocap software is "
                  "survived); 0: one try, and the end when the source closes");
  cmd->add_flag("--reconnect", args->reconnect,
                "Kept for older command lines: waiting for the source and reconnecting is the default now "
                "(--connect-timeout)");
  cmd->callback([=] {
    *run = [=] {
      live::LiveConfig config;
      config.source = live::parse_host_port(args->connect, "--connect");
      config.connect_timeout_s = parse_connect_timeout(args->connect_timeout);
      if (!args->serve.empty()) config.serve = live::parse_serve_address(args->serve, "--serve");
      config.max_clients = checked_max_clients(args->max_clients);
      if (!args->record.empty() && args->record == args->record_input)
        throw InputError(args->record + ": --record and --record-input name the same file");
      LiveStyleSpec spec;
      const std::vector<std::string> files = args->style.files(&spec.strengths);
      const Clip skeleton = load_skeleton(args->skeleton);
      for (const std::string& f : files) spec.takes.push_back(std::make_shared<const Clip>(load_clip(f)));
      config.skeleton = skeleton.skeleton;
      config.record = recorder(args->record, "--record", skeleton);
      config.record_input = recorder(args->record_input, "--record-input", skeleton);
      LiveStyle style(skeleton.skeleton, skeleton.fps(), spec);
      return live::run_live(config, style);
    };
  });
}

void add_live_send_command(CLI::App& app, std::function<int()>* run) {
  auto* cmd = app.add_subcommand(
      "live-send",
      "Serve a take as Axis Neuron serves a live stream (BVH broadcasting, string format, TCP): waits for the first "
      "client, then sends each frame at the take's rate to every client");
  struct Args {
    std::string file, serve;
    double rate = 0.0;
    bool loop = false;
    int clients = 1;
    int max_clients = live::kDefaultMaxClients;
  };
  auto args = std::make_shared<Args>();
  cmd->add_option("FILE", args->file, "The take (BVH; FBX or glTF are sampled at their own rate)")->required();
  cmd->add_option("--serve", args->serve,
                  std::string("Where to serve; sending starts when the first client connects, so a test or a plugin "
                              "started later misses nothing. ") + kServeHelp)
      ->required();
  cmd->add_option("--max-clients", args->max_clients,
                  "The most clients served at once (default 16); one more is refused, with a warning on stderr");
  cmd->add_option("--rate", args->rate, "Frames per second (default: the take's own)");
  cmd->add_flag("--loop", args->loop, "Start over after the last frame, until stopped (Ctrl-C)");
  cmd->add_option("--clients", args->clients,
                  "Start sending once this many clients have connected (default 1), so that a measuring client and "
                  "mostyle-cli live both get every frame");
  cmd->callback([=] {
    *run = [=] {
      live::LiveSendConfig config;
      if (args->clients < 1 || args->clients > 64) throw InputError("--clients: expected from 1 to 64 clients, found " + std::to_string(args->clients));
      config.clients = args->clients;
      config.max_clients = checked_max_clients(args->max_clients);
      if (config.clients > config.max_clients)
        throw InputError("--clients: " + std::to_string(config.clients) + " clients cannot connect with --max-clients " +
                         std::to_string(config.max_clients));
      config.serve = live::parse_serve_address(args->serve, "--serve");
      if (!(std::isfinite(args->rate) && args->rate >= 0.0))
        throw InputError("--rate: expected frames per second above 0");
      config.rate = args->rate;
      config.loop = args->loop;
      const Clip clip = load_clip(args->file);
      if (clip.frames() == 0) throw InputError(args->file + ": the take has no frames to send");
      return live::run_live_send(clip, args->file, config);
    };
  });
}

}  // namespace mostyle::cli
