#pragma once
// The editor's session file (.mostyle): the takes, every parameter (a Document,
// ui/model/document.h), the camera and the playback, as JSON, so that a day's work opens again as it
// was left. Version 3 reads:
//   {
//     "version": 3,
//     "takes": ["walks/happy.bvh", "walks/marching.bvh"],      (relative to the session's folder)
//     "layers": [{"weight": 0.7}, {"weight": 0.3, "component_weights": [0.3, null, ...]}],
//                                                               (one per take; a pair's: 1 - alpha, alpha)
//     "parameters": {"components": 10, "sparsity": 0.1},
//     "controls": {"mode": "shared", "per_part": false, "component_regions": ["left leg", ...], ...,
//                  "transfer": false, "neutral": 1, "content_neutral": false, "ghosts": true,
//                  "keys": [{"seconds": 0, "weights": [1, 0]}, {"seconds": 10, "weights": [0, 1]}],
//                  "align": {"method": "slope", "on": "auto", ...}},
//     "view": {"overlay": false},
//     "camera": {"target": [0, 9, 0], "yaw": 0.65, "pitch": 0.22, "distance": 80, "fov_y": 0.61},
//     "playback": {"time_s": 1.5, "playing": false, "speed": 1, "loop": true}
//   }
// Only "version" is required; a key left out keeps its default, an unknown key is refused (a
// typo is never silently ignored), and so is a value out of its range. The document's keys, the
// ranges they are read with (those the editor's controls allow) and the keys known are those of
// the one list of its fields (ui/model/document_fields.h). Versions 1 and 2 read too: version 2
// kept the weights beside their takes ("weights", a pair's "controls.component_alpha", a
// palette's "controls.palette" with its strengths and part weights), read into the layers;
// version 1 also kept a pair's weights as "parameters": {"alpha": a} and a palette's as
// "controls": {"palette": {"weights": [...]}}.
#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "ui/model/document.h"
#include "ui/model/editor_state.h"

namespace mostyle::ui {

constexpr int kSessionVersion = 3;  // the version written; 1 to 3 are read
constexpr const char* kSessionExtension = ".mostyle";
constexpr std::size_t kMaxSessionBytes = std::size_t{16} << 20;  // a larger file is refused unread

// render::OrbitCamera's pose as plain numbers (app/ converts: ui's files do not need render/).
struct SessionCamera {
  std::array<float, 3> target{0.0f, 0.0f, 0.0f};  // world units
  float yaw = 0.0f, pitch = 0.0f;                   // radians
  float distance = 10.0f;                           // world units, > 0
  float fov_y = 0.61f;                              // radians, in (0, 3.1]
};
bool operator==(const SessionCamera& x, const SessionCamera& y);
inline bool operator!=(const SessionCamera& x, const SessionCamera& y) { return !(x == y); }

struct SessionFile {
  Document document;                    // its files as the editor loads them (see parse_session)
  std::optional<SessionCamera> camera;  // none: the editor frames the takes as usual
  Playback playback;                    // position (time_s), playing, speed, loop
};

// The session as JSON text (two-space indents, keys in the order above, a final newline). Each
// take is written relative to the folder of `session_path` when it can be (so that a folder of
// takes and sessions can move as a whole), else as it is: give absolute paths, or paths relative
// to the same folder as `session_path`. Pure. O(size of the session).
std::string format_session(const SessionFile& session, const std::string& session_path);

// Reads session text. Takes given relative are resolved against the folder of `session_path`
// (lexically: "a/../b.bvh" becomes "b.bvh"); no file is opened, so a missing take is not an error
// here (missing_takes()). Throws InputError with one line "SESSION_PATH:LINE: ..." naming the
// line of the offending value: text that is not JSON (the parser's own reason), not an object, no
// or another version, an unknown key, a value of the wrong type or out of its range. Pure.
// O(size of the text).
SessionFile parse_session(std::string_view text, const std::string& session_path);

// parse_session of the file's bytes. Throws InputError: "PATH: cannot read: ..." or as above.
SessionFile read_session_file(const std::string& path);
// format_session into the file, written atomically (engine/base/atomic_file.h): a failed write
// leaves the previous file as it was. Throws InputError "PATH: cannot write: ...".
void write_session_file(const std::string& path, const SessionFile& session);

// The takes of `document` that are not there (no such file), each once, in order. Touches the
// file system (stat only).
std::vector<std::string> missing_takes(const Document& document);
// One sentence for the animator: "SESSION: cannot find the take PATH; ..." (several: "the takes
// A and B"), saying whether the other takes are open (others_open) or those loaded before stay,
// that the session file is left as it is, and how to keep a session without them. Empty when
// `missing` is.
std::string missing_takes_message(const std::string& session_path, const std::vector<std::string>& missing,
                                  bool others_open);

// Whether `path` names a session file: it ends in .mostyle (any case).
bool is_session_path(const std::string& path);

}  // namespace mostyle::ui
