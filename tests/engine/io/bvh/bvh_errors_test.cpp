// Every way a BVH file can be refused: the message names the file and the line, says what was
// expected and what was found. Malformed variants of real files never crash, hang or allocate
// without bound: they load or throw InputError.
#include <catch2/catch.hpp>
#include <random>
#include <string>

#include "engine/base/atomic_file.h"
#include "engine/io/bvh/bvh_read.h"
#include "engine/io/bvh/bvh_write.h"
#include "engine/base/error.h"
#include "engine/kinematics/kinematics.h"
#include "tests/engine/small_bvh.h"
#include "tests/test_data.h"

using namespace mostyle;

namespace {

const std::string& kSmall = test::kSmallBvh;                                                     // 20

// kSmall with `from` (which must occur) replaced by `to`.
std::string with(const std::string& from, const std::string& to) {
  const size_t at = kSmall.find(from);
  REQUIRE(at != std::string::npos);
  return kSmall.substr(0, at) + to + kSmall.substr(at + from.size());
}

// The first `lines` lines of kSmall.
std::string first_lines(int lines) {
  size_t at = 0;
  for (int i = 0; i < lines; ++i) at = kSmall.find('\n', at) + 1;
  return kSmall.substr(0, at);
}

std::string error_of(const std::string& text) {
  try {
    parse_bvh(text, "bad.bvh");
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no error)";
}

// Loads or throws InputError; anything else (another exception, a crash under the sanitizers)
// fails the test.
void loads_or_refuses(const std::string& text, const std::string& what) {
  INFO(what);
  try {
    std::vector<std::string> warnings;
    const Clip clip = parse_bvh(text, "fuzz.bvh", &warnings);
    CHECK(clip.motion.cols() == clip.skeleton.channel_count);
    CHECK(clip.motion.allFinite());
    // What loads can be used: FK and writing work.
    if (clip.frames() > 0) CHECK(joint_positions(clip).allFinite());
    CHECK_NOTHROW(format_bvh(clip));
  } catch (const InputError& e) {
    const std::string message = e.what();
    CHECK(message.rfind("fuzz.bvh:", 0) == 0);
    CHECK(message.find('\n') == std::string::npos);
  }
}

}  // namespace

TEST_CASE("empty and non-BVH input", "[bvh]") {
  CHECK(error_of("") == "bad.bvh:1: expected HIERARCHY, found an empty file");
  CHECK(error_of(" \n\t\r\n\n") == "bad.bvh:1: expected HIERARCHY, found an empty file");
  CHECK(error_of("hello world\n") == "bad.bvh:1: expected HIERARCHY, found 'hello'");
  CHECK(error_of("\n\n{\"json\": 1}") == "bad.bvh:3: expected HIERARCHY, found '{\"json\":'");
  CHECK(error_of(std::string("\x7f" "ELF\x02\x01\x01\0\0\0", 10)) ==
        "bad.bvh:1: expected HIERARCHY, found '\\x7fELF\\x02\\x01\\x01\\x00\\x00\\x00'");
  CHECK(error_of("HIERARCHY junk\n") == "bad.bvh:1: expected end of line after HIERARCHY, found 'junk'");
  CHECK(error_of(std::string(1000, 'x')) ==
        "bad.bvh:1: expected HIERARCHY, found 'xxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxx...'");
}

TEST_CASE("a cut header", "[bvh]") {
  CHECK(error_of(first_lines(1)) == "bad.bvh:1: expected ROOT, found end of file");
  CHECK(error_of(first_lines(2)) == "bad.bvh:2: expected '{', found end of file");
  CHECK(error_of(first_lines(3)) == "bad.bvh:3: expected OFFSET, found end of file");
  CHECK(error_of(first_lines(9)) == "bad.bvh:9: expected '}', found end of file");
  CHECK(error_of(first_lines(15)) == "bad.bvh:15: expected MOTION, found end of file");
  CHECK(error_of(first_lines(16)) == "bad.bvh:16: expected 'Frames: N', found end of file");
  CHECK(error_of(first_lines(17)) == "bad.bvh:17: expected 'Frame Time: seconds', found end of file");
  // Cut in the middle of a line.
  CHECK(error_of(kSmall.substr(0, kSmall.find("CHANNELS 3") + 10)) ==
        "bad.bvh:9: expected 3 channel names for joint 'Spine', found 0");
  CHECK(error_of(kSmall.substr(0, kSmall.find("OFFSET 0 10") + 9)) ==
        "bad.bvh:8: expected 3 numbers after OFFSET of joint 'Spine', found 1");
}

TEST_CASE("missing and extra braces", "[bvh]") {
  CHECK(error_of(with("  JOINT Spine\n  {\n", "  JOINT Spine\n")) ==
        "bad.bvh:7: expected '{', found 'OFFSET'");
  // Spine's '}' missing: MOTION comes while Hips is still open.
  CHECK(error_of(with("    }\n  }\n}\n", "    }\n}\n")) ==
        "bad.bvh:15: expected CHANNELS, JOINT, End Site or '}', found 'MOTION'");
  CHECK(error_of(with("}\nMOTION", "}\n}\nMOTION")) == "bad.bvh:16: expected ROOT or MOTION, found '}'");
  CHECK(error_of(with("ROOT Hips\n{", "ROOT Hips\n{ OFFSET")) ==
        "bad.bvh:3: expected end of line after '{', found 'OFFSET'");
  CHECK(error_of(with("  }\n}\n", "  } }\n}\n")) == "bad.bvh:14: expected end of line after '}', found '}'");
}

TEST_CASE("unknown and miscounted channels", "[bvh]") {
  CHECK(error_of(with("Xrotation Yrotation\n", "Xrotation Wrotation\n")) ==
        "bad.bvh:9: expected a channel name (Xposition .. Zrotation) for joint 'Spine', found 'Wrotation'");
  CHECK(error_of(with("CHANNELS 3", "CHANNELS 4")) ==
        "bad.bvh:9: expected 4 channel names for joint 'Spine', found 3");
  CHECK(error_of(with("CHANNELS 3", "CHANNELS 2")) ==
        "bad.bvh:9: expected 2 channel names for joint 'Spine', found 3");
  CHECK(error_of(with("CHANNELS 3", "CHANNELS 7")) ==
        "bad.bvh:9: expected a channel count from 0 to 6 after CHANNELS, found '7'");
  CHECK(error_of(with("CHANNELS 3", "CHANNELS -3")) ==
        "bad.bvh:9: expected a channel count from 0 to 6 after CHANNELS, found '-3'");
  CHECK(error_of(with("CHANNELS 3", "CHANNELS three")) ==
        "bad.bvh:9: expected a channel count from 0 to 6 after CHANNELS, found 'three'");
  CHECK(error_of(with("CHANNELS 3 Zrotation Xrotation Yrotation", "CHANNELS")) ==
        "bad.bvh:9: expected a channel count from 0 to 6 after CHANNELS, found end of line");
  CHECK(error_of(with("Zrotation Xrotation Yrotation", "Zrotation Xrotation Xrotation")) ==
        "bad.bvh:9: joint 'Spine' lists channel Xrotation twice");
  CHECK(error_of(with("CHANNELS 3 Zrotation Xrotation Yrotation\n",
                      "CHANNELS 3 Zrotation Xrotation Yrotation\n    CHANNELS 0\n")) ==
        "bad.bvh:10: joint 'Spine' has a second CHANNELS");
  CHECK(error_of(with("      OFFSET 0 5 0\n", "      OFFSET 0 5 0\n      CHANNELS 1 Xrotation\n")) ==
        "bad.bvh:13: expected OFFSET or '}' in an End Site, found 'CHANNELS'");
}

TEST_CASE("short, long and non-numeric OFFSETs, structure out of place", "[bvh]") {
  CHECK(error_of(with("OFFSET 0 10 0", "OFFSET 0 10")) ==
        "bad.bvh:8: expected 3 numbers after OFFSET of joint 'Spine', found 2");
  CHECK(error_of(with("OFFSET 0 10 0", "OFFSET 0 10 0 0")) ==
        "bad.bvh:8: expected 3 numbers after OFFSET of joint 'Spine', found 4");
  CHECK(error_of(with("OFFSET 0 10 0", "OFFSET 0 ten 0")) ==
        "bad.bvh:8: expected a finite number in OFFSET of joint 'Spine', found 'ten'");
  CHECK(error_of(with("OFFSET 0 10 0", "OFFSET 0 nan 0")) ==
        "bad.bvh:8: expected a finite number in OFFSET of joint 'Spine', found 'nan'");
  CHECK(error_of(with("OFFSET 0 10 0", "OFFSET 0 1e999 0")) ==
        "bad.bvh:8: expected a finite number in OFFSET of joint 'Spine', found '1e999'");
  CHECK(error_of(with("OFFSET 0 10 0", "OFFSET 0 1,5 0")) ==
        "bad.bvh:8: expected a finite number in OFFSET of joint 'Spine', found '1,5'");
  CHECK(error_of(with("      OFFSET 0 5 0\n", "")) ==
        "bad.bvh:12: expected OFFSET in the End Site of 'Spine', found '}'");
  // CHANNELS before OFFSET is fine; a child before any OFFSET is not.
  CHECK(error_of(with("    OFFSET 0 10 0\n", "")) == "bad.bvh:9: expected OFFSET in joint 'Spine', found 'End'");
  CHECK(error_of(with("    OFFSET 0 10 0\n", "    Offside\n")) == "bad.bvh:8: expected OFFSET, found 'Offside'");
  CHECK(error_of(with("    OFFSET 0 10 0\n", "    OFFSET 0 10 0\n    OFFSET 0 10 0\n")) ==
        "bad.bvh:9: joint 'Spine' has a second OFFSET");
  CHECK(error_of(with("      OFFSET 0 5 0\n", "      OFFSET 0 5 0\n      JOINT x\n")) ==
        "bad.bvh:13: expected '}' closing the End Site, found 'JOINT'");
  CHECK(error_of(with("    End Site\n", "    End Zone\n")) == "bad.bvh:10: expected 'Site' after End, found 'Zone'");
  CHECK(error_of(with("    End Site\n", "    Bone x\n")) ==
        "bad.bvh:10: expected CHANNELS, JOINT, End Site or '}', found 'Bone'");
  CHECK(error_of(with("MOTION", "MOTION now")) == "bad.bvh:16: expected end of line after MOTION, found 'now'");
  CHECK(error_of("HIERARCHY\nMOTION\n") == "bad.bvh:2: expected ROOT, found 'MOTION'");
}

TEST_CASE("nameless joints", "[bvh]") {
  CHECK(error_of(with("ROOT Hips", "ROOT")) == "bad.bvh:2: expected a joint name, found end of line");
  CHECK(error_of(with("JOINT Spine", "JOINT")) == "bad.bvh:6: expected a joint name, found end of line");
  CHECK(error_of(with("JOINT Spine\n  {", "JOINT {")) == "bad.bvh:6: expected a joint name, found end of line");
}

TEST_CASE("a joint name ending in '{', which no BVH text can hold", "[bvh]") {
  // Found by tests/fuzz (regressions/bvh/): the writer could not write it back.
  CHECK(error_of(with("ROOT Hips\n{", "ROOT Hips {{")) == "bad.bvh:2: expected a joint name not ending in '{', found 'Hips {'");
  CHECK(error_of(with("JOINT Spine\n  {", "JOINT Spine{ {")) ==
        "bad.bvh:6: expected a joint name not ending in '{', found 'Spine{'");
  CHECK(error_of(with("JOINT Spine\n  {", "JOINT { {")) == "bad.bvh:6: expected a joint name not ending in '{', found '{'");
}

TEST_CASE("negative, absurd and malformed frame counts and frame times", "[bvh]") {
  CHECK(error_of(with("Frames: 2", "Frames: -1")) == "bad.bvh:17: expected a frame count of 0 or more, found '-1'");
  CHECK(error_of(with("Frames: 2", "Frames: 1000000000")) ==
        "bad.bvh:17: expected a frame count of at most 100000000, found '1000000000'");
  CHECK(error_of(with("Frames: 2", "Frames: 99999999999999999999999")) ==
        "bad.bvh:17: expected a frame count of at most 100000000, found '99999999999999999999999'");
  CHECK(error_of(with("Frames: 2", "Frames: -99999999999999999999999")) ==
        "bad.bvh:17: expected a frame count of 0 or more, found '-99999999999999999999999'");
  CHECK(error_of(with("Frames: 2", "Frames: 2.5")) == "bad.bvh:17: expected a whole frame count after Frames:, found '2.5'");
  CHECK(error_of(with("Frames: 2", "Frames: many")) == "bad.bvh:17: expected a whole frame count after Frames:, found 'many'");
  CHECK(error_of(with("Frames: 2", "Frames:")) == "bad.bvh:17: expected a frame count after Frames:, found end of line");
  CHECK(error_of(with("Frames: 2\n", "")) == "bad.bvh:17: expected 'Frames: N', found 'Frame'");
  CHECK(error_of(with("Frames: 2", "Framesx: 2")) == "bad.bvh:17: expected 'Frames: N', found 'Framesx:'");
  CHECK(error_of(with("Frame Time: 0.0333333", "Frame Time: 0")) ==
        "bad.bvh:18: expected a positive frame time in seconds, found '0'");
  CHECK(error_of(with("Frame Time: 0.0333333", "Frame Time: -0.1")) ==
        "bad.bvh:18: expected a positive frame time in seconds, found '-0.1'");
  CHECK(error_of(with("Frame Time: 0.0333333", "Frame Time: nan")) ==
        "bad.bvh:18: expected a positive frame time in seconds, found 'nan'");
  CHECK(error_of(with("Frame Time: 0.0333333", "Frame Time: 1/30")) ==
        "bad.bvh:18: expected a positive frame time in seconds, found '1/30'");
  CHECK(error_of(with("Frame Time: 0.0333333\n", "")) ==
        "bad.bvh:18: expected 'Frame Time: seconds', found '1'");
}

TEST_CASE("bad frame values name the frame and the channel", "[bvh]") {
  CHECK(error_of(with("4 5 6 90 0 0", "4 5 6 90 x 0")) ==
        "bad.bvh:20: expected a finite number for frame 2 channel 5 (Hips Yrotation), found 'x'");
  CHECK(error_of(with("4 5 6 90 0 0 0 0 0", "4 5 6 90 0 0 0 0 nan")) ==
        "bad.bvh:20: expected a finite number for frame 2 channel 9 (Spine Yrotation), found 'nan'");
  CHECK(error_of(with("1 2 3", "1 inf 3")) ==
        "bad.bvh:19: expected a finite number for frame 1 channel 2 (Hips Yposition), found 'inf'");
  CHECK(error_of(with("1 2 3", "1 -1e999 3")) ==
        "bad.bvh:19: expected a finite number for frame 1 channel 2 (Hips Yposition), found '-1e999'");
  CHECK(error_of(with("1 2 3", "1 2,5 3")) ==
        "bad.bvh:19: expected a finite number for frame 1 channel 2 (Hips Yposition), found '2,5'");
  CHECK(error_of(with("1 2 3", "1 +-2 3")) ==
        "bad.bvh:19: expected a finite number for frame 1 channel 2 (Hips Yposition), found '+-2'");
  CHECK(error_of(with("1 2 3", "1 0x10 3")) ==
        "bad.bvh:19: expected a finite number for frame 1 channel 2 (Hips Yposition), found '0x10'");
  CHECK(error_of(with("1 2 3", std::string("1 2\0 3", 6))) ==
        "bad.bvh:19: expected a finite number for frame 1 channel 2 (Hips Yposition), found '2\\x00'");
}

TEST_CASE("frame lines with extra values, or short ones that are not the last", "[bvh]") {
  CHECK(error_of(with("1 2 3 0 0 0 0 0 0\n", "1 2 3 0 0 0 0 0 0 7\n")) ==
        "bad.bvh:19: expected 9 values in frame 1, found 10");
  CHECK(error_of(with("4 5 6 90 0 0 0 0 0\n", "4 5 6 90 0 0 0 0 0 x y z\n")) ==
        "bad.bvh:20: expected 9 values in frame 2, found 12");
  // A short line followed by a full one: not a cut last line.
  CHECK(error_of(with("1 2 3 0 0 0 0 0 0\n", "1 2 3 0 0 0 0 0\n")) ==
        "bad.bvh:19: expected 9 values in frame 1, found 8");
  // Two short lines: the first one is named.
  CHECK(error_of(with("1 2 3 0 0 0 0 0 0\n4 5 6 90 0 0 0 0 0\n", "1 2 3\n4 5\n")) ==
        "bad.bvh:19: expected 9 values in frame 1, found 3");
  // A frame split over two lines.
  CHECK(error_of(with("4 5 6 90 0 0 0 0 0\n", "4 5 6 90\n0 0 0 0 0\n")) ==
        "bad.bvh:20: expected 9 values in frame 2, found 4");
}

TEST_CASE("a 20000-deep hierarchy that is cut or unbalanced fails cleanly", "[bvh]") {
  constexpr int kDepth = 20000;
  std::string text = "HIERARCHY\n";
  for (int i = 0; i < kDepth; ++i)
    text += (i ? "JOINT j" : "ROOT j") + std::to_string(i) + "\n{\nOFFSET 0 1 0\nCHANNELS 1 Xrotation\n";
  // Line count so far: 1 + 4 * kDepth. No closing braces at all.
  CHECK(error_of(text) == "bad.bvh:" + std::to_string(1 + 4 * kDepth) + ": expected '}', found end of file");
  std::string closed = text + "End Site\n{\nOFFSET 0 1 0\n}\n";
  for (int i = 0; i < kDepth - 1; ++i) closed += "}\n";
  closed += "MOTION\nFrames: 0\nFrame Time: 1\n";  // one '}' short
  CHECK(error_of(closed) == "bad.bvh:" + std::to_string(1 + 4 * kDepth + 4 + kDepth - 1 + 1) +
                                ": expected CHANNELS, JOINT, End Site or '}', found 'MOTION'");
}

TEST_CASE("malformed variants of a real file load or fail cleanly", "[bvh]") {
  // The CMU asset's header and its first 30 frames (CRLF, tabs), cut and garbled.
  const std::string full = read_file(test::asset("motions/cmu142_walk_happy.bvh"));
  size_t end = full.find("MOTION");
  for (int lines = 0; lines < 33; ++lines) end = full.find('\n', end) + 1;
  const std::string base = full.substr(0, end);
  loads_or_refuses(base, "the base text");

  // Every cut point in the header, and every 7th byte in the frames.
  const size_t header_end = base.find("MOTION") + 40;
  for (size_t cut = 0; cut < base.size(); cut += cut < header_end ? 1 : 7)
    loads_or_refuses(base.substr(0, cut), "cut at byte " + std::to_string(cut));

  std::mt19937 rng(2024);
  std::uniform_int_distribution<size_t> position(0, base.size() - 1);
  std::uniform_int_distribution<int> byte(0, 255);
  const char interesting[] = {'{', '}', '\n', '\r', ' ', '\t', '-', '.', 'e', '0', '\0', 'N', ':'};
  for (int trial = 0; trial < 3000; ++trial) {
    std::string text = base;
    const int edits = 1 + trial % 4;
    for (int e = 0; e < edits; ++e) {
      const size_t at = position(rng) % text.size();
      switch (trial % 3) {
        case 0: text[at] = static_cast<char>(byte(rng)); break;                        // flip
        case 1: text[at] = interesting[byte(rng) % sizeof interesting]; break;         // structural
        default: text.erase(at, std::min<size_t>(text.size() - at, 1 + byte(rng) % 40));  // delete
      }
      if (text.empty()) break;
    }
    loads_or_refuses(text, "trial " + std::to_string(trial));
  }
}

TEST_CASE("malformed variants of a Bandai file load or fail cleanly", "[bvh]") {
  MOSTYLE_REQUIRE_SHARED_MOTIONS();
  const std::string full = read_file(test::shared_motion("bandai_walk_angry.bvh"));
  const std::string base = full.substr(0, full.find('\n', full.find("MOTION") + 2000) + 1);
  std::mt19937 rng(7);
  std::uniform_int_distribution<size_t> position(0, base.size() - 1);
  std::uniform_int_distribution<int> byte(0, 255);
  for (int trial = 0; trial < 1000; ++trial) {
    std::string text = base;
    text[position(rng)] = static_cast<char>(byte(rng));
    if (trial % 2) text = text.substr(0, position(rng));
    loads_or_refuses(text, "trial " + std::to_string(trial));
  }
}

TEST_CASE("frames over the memory limit are refused at the Frames: line, before allocation", "[bvh]") {
  // kSmall's frames: 2 x 9 values x 8 bytes = 144 bytes.
  BvhReadOptions o;
  o.max_bytes = 143;
  CHECK_THROWS_WITH(parse_bvh(kSmall, "bad.bvh", nullptr, o),
                    "bad.bvh:17: expected frames within the memory limit of 143 bytes, found Frames: 2 "
                    "of 9 values each (144 bytes)");
  o.max_bytes = 144;
  CHECK(parse_bvh(kSmall, "bad.bvh", nullptr, o).frames() == 2);
  // A declared count the text cannot hold is judged by what the text can hold (37 bytes of frame
  // lines: at most 3 frames of 9 values), never by the count.
  o.max_bytes = 100;
  CHECK_THROWS_WITH(parse_bvh(with("Frames: 2", "Frames: 99999999"), "bad.bvh", nullptr, o),
                    "bad.bvh:17: expected frames within the memory limit of 100 bytes, found Frames: "
                    "99999999 of 9 values each (216 bytes for the frames this file can hold)");
  // More frames than declared: refused at the first frame past the limit.
  CHECK_THROWS_WITH(parse_bvh(with("Frames: 2", "Frames: 1"), "bad.bvh", nullptr, o),
                    "bad.bvh:20: expected frames within the memory limit of 100 bytes, found frame 2 "
                    "of 9 values (144 bytes)");
  // A real take: 1080 frames of 96 values need 810 KB.
  const std::string file = test::asset("motions/cmu142_walk_clumsy.bvh");
  o.max_bytes = 512 << 10;
  CHECK_THROWS_WITH(parse_bvh(read_file(file), file, nullptr, o),
                    file + ":186: expected frames within the memory limit of 512 KB, found Frames: 1080 "
                           "of 96 values each (810 KB)");
  // read_bvh_file refuses a file larger than the limit before reading it.
  CHECK_THROWS_WITH(read_bvh_file(file, nullptr, o),
                    file + ": cannot read: its 1004 KB exceed the memory limit of 512 KB");
  o.max_bytes = 1 << 20;
  CHECK(read_bvh_file(file, nullptr, o).frames() == 1080);
}
