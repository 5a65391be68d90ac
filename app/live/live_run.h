#pragma once
// The loops of `mostyle-cli live` (a styled stream: read, style, serve, record, frame by frame)
// and `mostyle-cli live-send` (a take served as a stream, the stand-in for Axis Neuron).
#include <memory>
#include <optional>
#include <string>

#include "app/live/frame_server.h"
#include "app/live/tcp.h"
#include "engine/live/bvh_recorder.h"
#include "engine/base/clip.h"
#include "engine/live/live_style.h"

namespace mostyle::live {

struct LiveConfig {
  HostPort source;                 // --connect
  // --connect-timeout: how long to wait for the source, at the start and after it closes, before
  // giving up; negative: for ever; 0: one try, and the end when it closes.
  double connect_timeout_s = -1.0;
  std::optional<HostPort> serve;   // --serve (a numeric address); none: no server
  int max_clients = kDefaultMaxClients;  // --max-clients
  Skeleton skeleton;               // the stream's: --skeleton's hierarchy and channels
  std::unique_ptr<BvhRecorder> record, record_input;  // --record (styled), --record-input; may be null
};

// Serves (when asked), connects to the source, then styles each frame line as it arrives and
// sends it on before reading the next; records both streams. A source not there yet, or gone,
// is tried again (after 0.25 s, doubling to 2 s between tries) and said so once on stderr, the
// clients served meanwhile staying connected; each new connection is styled as a new stream
// (style.restart()). Ends at SIGINT/SIGTERM, or when the source has not come back within
// config.connect_timeout_s after closing, with the recordings complete and a one-line summary on
// stdout; returns 0. Bad lines are skipped, counted and warned about on stderr at most once a
// second, and so are clients refused past config.max_clients. Throws InputError when the server
// cannot listen, the source cannot be found, or it is not there within connect_timeout_s of the
// start. Memory: the styler's, one line per connection, each client's bounded queue.
int run_live(LiveConfig& config, LiveStyle& style);

struct LiveSendConfig {
  HostPort serve{kDefaultServeHost, 0};    // --serve (a numeric address; port 0: any free one, printed)
  int max_clients = kDefaultMaxClients;    // --max-clients
  double rate = 0.0;                       // frames per second; 0: the take's own
  bool loop = false;                       // start over after the last frame, until stopped
  int clients = 1;                         // sending starts once this many clients have connected
  std::string avatar_name = "Avatar00";    // Axis's name of its first avatar
};

// Serves `clip`'s frames as Axis Neuron does: waits for the first client (config.clients), then sends frame k at
// t0 + k / rate (absolute deadlines on the steady clock: no drift) to every client. Without
// loop, drains the clients' queues (up to 5 s), closes the connections after the last frame
// and returns 0; SIGINT/SIGTERM end it the same way. Prints where it listens, then a one-line
// summary; clients past config.max_clients are refused and warned about on stderr at most once a
// second. Throws InputError when it cannot listen.
int run_live_send(const Clip& clip, const std::string& source, const LiveSendConfig& config);

}  // namespace mostyle::live
