#pragma once
// The loops of `mostyle-cli live` (a styled stream: read, style, serve, record, frame by frame)
// and `mostyle-cli live-send` (a take served as a stream, the stand-in for Axis Neuron).
#include <memory>
#include <string>

#include "app/live/tcp.h"
#include "engine/io/bvh_recorder.h"
#include "engine/base/clip.h"
#include "engine/live/live_style.h"

namespace mostyle::live {

struct LiveConfig {
  HostPort source;                 // --connect
  bool reconnect = false;          // --reconnect: wait for the source again when it closes
  int serve_port = -1;             // --serve; -1: no server
  Skeleton skeleton;               // the stream's: --skeleton's hierarchy and channels
  std::unique_ptr<BvhRecorder> record, record_input;  // --record (styled), --record-input; may be null
};

// Serves (when asked), connects to the source, then styles each frame line as it arrives and
// sends it on before reading the next; records both streams. Ends when the source closes
// (unless config.reconnect) or at SIGINT/SIGTERM, with the recordings complete and a one-line
// summary on stdout; returns 0. Bad lines are skipped, counted and warned about on stderr at
// most once a second. Throws InputError when the source cannot be found, or refuses the first
// connection without --reconnect. Memory: the styler's, one line per connection, each client's
// bounded queue.
int run_live(LiveConfig& config, LiveStyle& style);

struct LiveSendConfig {
  int port = 0;                            // --serve (0: any free port, printed)
  double rate = 0.0;                       // frames per second; 0: the take's own
  bool loop = false;                       // start over after the last frame, until stopped
  int clients = 1;                         // sending starts once this many clients have connected
  std::string avatar_name = "Avatar00";    // Axis's name of its first avatar
};

// Serves `clip`'s frames as Axis Neuron does: waits for the first client (config.clients), then sends frame k at
// t0 + k / rate (absolute deadlines on the steady clock: no drift) to every client. Without
// loop, drains the clients' queues (up to 5 s), closes the connections after the last frame
// and returns 0; SIGINT/SIGTERM end it the same way. Prints the port, then a one-line summary.
int run_live_send(const Clip& clip, const std::string& source, const LiveSendConfig& config);

}  // namespace mostyle::live
