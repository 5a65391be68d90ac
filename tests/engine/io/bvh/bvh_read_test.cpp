#include "engine/io/bvh/bvh_read.h"
#include "engine/io/bvh/bvh_write.h"

#include <catch2/catch.hpp>
#include <charconv>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include "engine/base/atomic_file.h"
#include "engine/base/error.h"
#include "engine/kinematics/kinematics.h"
#include "tests/engine/io/bvh/bvh_checks.h"
#include "tests/engine/small_bvh.h"
#include "tests/test_data.h"

using namespace mostyle;

namespace {

using test::check_same_clip;
using test::replace_all;
const std::string& kSmall = test::kSmallBvh;                                                     // 20

}  // namespace

TEST_CASE("parses a small file: joints, channels, offsets, frames", "[bvh]") {
  std::vector<std::string> warnings;
  const Clip clip = parse_bvh(kSmall, "small.bvh", &warnings);
  CHECK(warnings.empty());
  CHECK(clip.source == "small.bvh");
  const Skeleton& s = clip.skeleton;
  REQUIRE(s.joints.size() == 3);
  CHECK(s.joints[0].name == "Hips");
  CHECK(s.joints[0].parent == -1);
  CHECK(s.joints[0].line == 2);
  CHECK(s.joints[0].channels.size() == 6);
  CHECK(s.joints[0].first_channel == 0);
  CHECK(s.joints[1].name == "Spine");
  CHECK(s.joints[1].parent == 0);
  CHECK(s.joints[1].offset == Eigen::Vector3d(0, 10, 0));
  CHECK(s.joints[1].first_channel == 6);
  CHECK(s.joints[1].channels ==
        std::vector<Channel>{Channel::kZrotation, Channel::kXrotation, Channel::kYrotation});
  CHECK(s.joints[2].end_site);
  CHECK(s.joints[2].name == "Spine End Site");
  CHECK(s.joints[2].parent == 1);
  CHECK(s.joints[2].line == 10);
  CHECK(s.channel_count == 9);
  CHECK(clip.frame_time == 0.0333333);
  CHECK(clip.fps() == 30.0);
  REQUIRE(clip.frames() == 2);
  CHECK(clip.motion(1, 0) == 4);
  CHECK(clip.motion(1, 3) == 90);
}

TEST_CASE("every file in ../shared/motions loads as its README says", "[bvh]") {
  MOSTYLE_REQUIRE_SHARED_MOTIONS();
  const std::vector<std::string> files = test::shared_motions();
  CHECK(files.size() == 11);
  for (const std::string& path : files) {
    INFO(path);
    std::vector<std::string> warnings;
    const Clip clip = read_bvh_file(path, &warnings);
    CHECK(warnings.empty());
    CHECK(clip.motion.allFinite());
    const bool bandai = path.find("bandai_") != std::string::npos;
    CHECK(clip.skeleton.joint_count_without_end_sites() == (bandai ? 22 : 31));
    CHECK(clip.skeleton.joints.size() == (bandai ? 27u : 38u));
    CHECK(clip.skeleton.channel_count == (bandai ? 132 : 96));
    CHECK(clip.fps() == (bandai ? 30.0 : 120.0));
    CHECK(clip.skeleton.find(bandai ? "Foot_L" : "LeftFoot") > 0);
  }
  // Frame counts from the README table.
  CHECK(read_bvh_file(test::shared_motion("bandai_walk_angry.bvh")).frames() == 143);
  CHECK(read_bvh_file(test::shared_motion("bandai_walk_sad.bvh")).frames() == 347);
  CHECK(read_bvh_file(test::shared_motion("cmu142_walk_happy.bvh")).frames() == 3033);
  CHECK(read_bvh_file(test::shared_motion("cmu142_walk_marching.bvh")).frames() == 3277);
}

TEST_CASE("every file in assets/motions loads", "[bvh]") {
  const std::vector<std::string> files = test::asset_motions();
  REQUIRE(!files.empty());
  for (const std::string& path : files) {
    INFO(path);
    std::vector<std::string> warnings;
    const Clip clip = read_bvh_file(path, &warnings);
    CHECK(warnings.empty());
    CHECK(clip.frames() > 100);
    CHECK(clip.skeleton.channel_count == 96);
    CHECK(clip.fps() == 120.0);
    // CMU root: "Xposition Yposition Zposition Zrotation Yrotation Xrotation".
    CHECK(clip.skeleton.joints[0].channels ==
          std::vector<Channel>{Channel::kXposition, Channel::kYposition, Channel::kZposition,
                               Channel::kZrotation, Channel::kYrotation, Channel::kXrotation});
  }
}

TEST_CASE("line endings: LF, CRLF, CR and mixed read the same", "[bvh]") {
  const Clip lf = parse_bvh(kSmall, "x.bvh");
  check_same_clip(parse_bvh(replace_all(kSmall, "\n", "\r\n"), "x.bvh"), lf);
  check_same_clip(parse_bvh(replace_all(kSmall, "\n", "\r"), "x.bvh"), lf);
  // Mixed: every third line CRLF, every other CR.
  std::string mixed;
  int line = 0;
  for (char c : kSmall) {
    if (c != '\n') {
      mixed += c;
      continue;
    }
    ++line;
    mixed += line % 3 == 0 ? "\r\n" : (line % 2 ? "\r" : "\n");
  }
  check_same_clip(parse_bvh(mixed, "x.bvh"), lf);
  // Line numbers still count CRLF once: an error on line 9.
  const std::string bad = replace_all(replace_all(kSmall, "Xrotation Yrotation\n", "Xrotation Wrotation\n"),
                                      "\n", "\r\n");
  CHECK_THROWS_WITH(parse_bvh(bad, "x.bvh"), Catch::StartsWith("x.bvh:9: "));
  const std::string bad_cr = replace_all(replace_all(kSmall, "Xrotation Yrotation\n", "Xrotation Wrotation\n"),
                                         "\n", "\r");
  CHECK_THROWS_WITH(parse_bvh(bad_cr, "x.bvh"), Catch::StartsWith("x.bvh:9: "));
}

TEST_CASE("layout oddities: tabs, blank lines, trailing spaces, no indent, braces on the line",
          "[bvh]") {
  const Clip reference = parse_bvh(kSmall, "x.bvh");
  // Tabs instead of spaces, and tabs between words.
  check_same_clip(parse_bvh(replace_all(kSmall, " ", "\t"), "x.bvh"), reference);
  // Blank lines and whitespace-only lines everywhere, trailing spaces on every line.
  check_same_clip(parse_bvh(replace_all(kSmall, "\n", " \t\n \n\n"), "x.bvh"), reference);
  // No indentation at all.
  std::string flat;
  for (size_t at = 0; at < kSmall.size();) {
    size_t end = kSmall.find('\n', at);
    std::string l = kSmall.substr(at, end - at);
    flat += l.substr(l.find_first_not_of(' ') == std::string::npos ? 0 : l.find_first_not_of(' ')) + "\n";
    at = end + 1;
  }
  check_same_clip(parse_bvh(flat, "x.bvh"), reference);
  // '{' on the ROOT/JOINT/End Site line.
  std::string braces = replace_all(kSmall, "Hips\n{", "Hips {");
  braces = replace_all(braces, "Spine\n  {", "Spine {");
  braces = replace_all(braces, "End Site\n    {", "End Site {");
  check_same_clip(parse_bvh(braces, "x.bvh"), reference);
  // A UTF-8 byte order mark, and keywords in other cases.
  check_same_clip(parse_bvh("\xEF\xBB\xBF" + kSmall, "x.bvh"), reference);
  std::string cases = replace_all(kSmall, "JOINT", "joint");
  cases = replace_all(cases, "OFFSET", "Offset");
  cases = replace_all(cases, "CHANNELS 3 Zrotation", "channels 3 ZROTATION");
  cases = replace_all(cases, "End Site", "END SITE");
  check_same_clip(parse_bvh(cases, "x.bvh"), reference);
  // A named End Site (some exporters do it; Blender ignores the name).
  check_same_clip(parse_bvh(replace_all(kSmall, "End Site\n", "End Site Spine_end\n"), "x.bvh"), reference);
}

TEST_CASE("Frames: and Frame Time: in any case and spacing, Frames: 0", "[bvh]") {
  for (const char* frames : {"Frames: 2", "FRAMES:\t2", "frames:2", "Frames :  2", "Frames 2"}) {
    for (const char* time : {"Frame Time: 0.0333333", "FRAME TIME:\t0.0333333", "frame  time:.0333333",
                             "Frame\tTime :\t\t3.33333e-2"}) {
      INFO(frames << " / " << time);
      std::string text = replace_all(kSmall, "Frames: 2", frames);
      text = replace_all(text, "Frame Time: 0.0333333", time);
      const Clip clip = parse_bvh(text, "x.bvh");
      CHECK(clip.frames() == 2);
      CHECK(clip.frame_time == Approx(0.0333333).epsilon(1e-15));
    }
  }
  std::vector<std::string> warnings;
  const std::string zero = kSmall.substr(0, kSmall.find("Frames: 2")) + "Frames: 0\nFrame Time: .0083333\n";
  const Clip clip = parse_bvh(zero, "x.bvh", &warnings);
  CHECK(warnings.empty());
  CHECK(clip.frames() == 0);
  CHECK(clip.motion.cols() == 9);
  CHECK(clip.frame_time == 0.0083333);
  CHECK(clip.fps() == 120.0);
}

TEST_CASE("numbers: scientific notation, -0, no leading zero, '+', tiny and huge", "[bvh]") {
  const std::string text = replace_all(
      kSmall, "4 5 6 90 0 0 0 0 0", "1.87007e-05 -0 .5 -.25 +3 1E+2 5. 1e-400 -4.9e-324");
  const Clip clip = parse_bvh(text, "x.bvh");
  CHECK(clip.motion(1, 0) == 1.87007e-05);
  CHECK(clip.motion(1, 1) == 0.0);
  CHECK(std::signbit(clip.motion(1, 1)));
  CHECK(clip.motion(1, 2) == 0.5);
  CHECK(clip.motion(1, 3) == -0.25);
  CHECK(clip.motion(1, 4) == 3);
  CHECK(clip.motion(1, 5) == 100);
  CHECK(clip.motion(1, 6) == 5);
  CHECK(clip.motion(1, 7) == 0.0);  // underflows to zero, as strtod does
  CHECK(clip.motion(1, 8) == -4.9e-324);
  // OFFSET in scientific notation, as Bandai writes it.
  const Clip offsets = parse_bvh(replace_all(kSmall, "OFFSET 0 10 0", "OFFSET 1e1 -0 8.98455e-01"), "x.bvh");
  CHECK(offsets.skeleton.joints[1].offset == Eigen::Vector3d(10, 0, 0.898455));
}

TEST_CASE("numbers: every value reads as std::from_chars reads it, bit for bit", "[bvh]") {
  // The reader's fast path for plain decimals against std::from_chars on random tokens
  // (fixed seed) and on the edges of the fast path: 19 and 20 digits, 2^53 and 2^53 + 1,
  // 22 and 23 decimals, signed zeros, no integer or no fraction digits, exponents.
  std::vector<std::string> tokens = {
      "9007199254740992", "9007199254740993", "-9007199254740993", "900719925474099.3",
      "1234567890123456789", "12345678901234567890", "0.1234567890123456789", "0.0000000000000000000001",
      "0.000000000000000000001", "1.0000000000000000000000001", "-0", "-0.0", "0.", "-.5", ".5", "5.",
      "00000000000000000000000001", "0.30000000000000004", "2.2250738585072014e-308", "1e22", "1e23",
      "179769313486231570000000000000000000000000000000000000000000000000000000000000000000000",
      "-23.251000", "0.008333", "93.9241"};
  std::mt19937 rng(11);
  std::uniform_int_distribution<int> digit(0, 9), count(0, 24), coin(0, 3), exponent(-30, 30);
  while (tokens.size() % 6 != 0 || tokens.size() < 60000) {
    std::string t = coin(rng) == 0 ? "-" : "";
    const int integer = count(rng), fraction = coin(rng) == 0 ? -1 : count(rng);
    for (int i = 0; i < integer; ++i) t += static_cast<char>('0' + digit(rng));
    if (fraction >= 0) t += '.';
    for (int i = 0; i < fraction; ++i) t += static_cast<char>('0' + digit(rng));
    if (integer == 0 && fraction <= 0) t += '7';
    if (coin(rng) == 0) t += (coin(rng) < 2 ? "e" : "E") + std::to_string(exponent(rng));
    tokens.push_back(t);
  }
  std::string text =
      "HIERARCHY\nROOT Hips\n{\nOFFSET 0 0 0\nCHANNELS 6 Xposition Yposition Zposition Zrotation "
      "Yrotation Xrotation\n}\nMOTION\nFrames: " + std::to_string(tokens.size() / 6) + "\nFrame Time: 0.01\n";
  for (size_t i = 0; i < tokens.size(); ++i) text += tokens[i] + (i % 6 == 5 ? "\n" : " ");
  std::vector<std::string> warnings;
  const Clip clip = parse_bvh(text, "n.bvh", &warnings);
  CHECK(warnings.empty());
  REQUIRE(clip.motion.size() == static_cast<Eigen::Index>(tokens.size()));
  int mismatches = 0;
  for (size_t i = 0; i < tokens.size(); ++i) {
    double expected = 0;
    const auto r = std::from_chars(tokens[i].data(), tokens[i].data() + tokens[i].size(), expected);
    REQUIRE(r.ptr == tokens[i].data() + tokens[i].size());
    const double got = clip.motion.data()[i];
    if (std::memcmp(&got, &expected, sizeof got) != 0) {
      UNSCOPED_INFO(tokens[i]);
      ++mismatches;
    }
  }
  CHECK(mismatches == 0);
}

TEST_CASE("names with spaces and colons, 0 to 6 channels in any order, each joint its order",
          "[bvh]") {
  const std::string text =
      "HIERARCHY\nROOT mixamorig:Hips\n{\n\tOFFSET 1 2 3\n\tCHANNELS 0\n"
      "\tJOINT Left Up Leg\n\t{\n\t\tOFFSET 1 0 0\n\t\tCHANNELS 1 Yrotation\n"
      "\t\tJOINT a\n\t\t{\n\t\t\tOFFSET 0 1 0\n\t\t\tCHANNELS 2 Zposition Xrotation\n"
      "\t\t\tJOINT b\n\t\t\t{\n\t\t\t\tOFFSET 0 1 0\n"
      "\t\t\t\tCHANNELS 6 Yrotation Xposition Zrotation Zposition Xrotation Yposition\n"
      "\t\t\t\tEnd Site\n\t\t\t\t{\n\t\t\t\t\tOFFSET 0 0 0\n\t\t\t\t}\n\t\t\t}\n\t\t}\n"
      "\t\tJOINT c\n\t\t{\n\t\t\tOFFSET 0 1 0\n\t\t\tCHANNELS 5 Xrotation Yposition Zrotation Yrotation Xposition\n"
      "\t\t\tEnd Site\n\t\t\t{\n\t\t\t\tOFFSET 0 0 0\n\t\t\t}\n\t\t}\n"
      "\t}\n\tJOINT no channels line\n\t{\n\t\tOFFSET 0 0 1\n\t}\n}\n"
      "MOTION\nFrames: 1\nFrame Time: 0.04\n"
      "1  2 3  4 5 6 7 8 9  10 11 12 13 14\n";
  const Clip clip = parse_bvh(text, "names.bvh");
  const Skeleton& s = clip.skeleton;
  CHECK(s.find("mixamorig:Hips") == 0);
  CHECK(s.find("Left Up Leg") == 1);
  CHECK(s.find("no channels line") == 7);
  CHECK(s.joints[7].channels.empty());
  CHECK(s.channel_count == 14);
  CHECK(s.joints[1].first_channel == 0);
  CHECK(s.joints[2].first_channel == 1);
  CHECK(s.joints[3].first_channel == 3);
  CHECK(s.joints[5].first_channel == 9);
  CHECK(s.joints[5].channels[4] == Channel::kXposition);
  CHECK(clip.motion(0, 13) == 14);
}

TEST_CASE("a 20000-deep hierarchy loads, formats and reads back", "[bvh]") {
  constexpr int kDepth = 20000;
  std::string text = "HIERARCHY\n";
  for (int i = 0; i < kDepth; ++i)
    text += (i ? "JOINT j" : "ROOT j") + std::to_string(i) + "\n{\nOFFSET 0 1 0\nCHANNELS 1 Xrotation\n";
  text += "End Site\n{\nOFFSET 0 1 0\n}\n";
  for (int i = 0; i < kDepth; ++i) text += "}\n";
  text += "MOTION\nFrames: 2\nFrame Time: 1\n";
  for (int f = 0; f < 2; ++f) {
    for (int i = 0; i < kDepth; ++i) text += i ? " 0.5" : "0.5";
    text += "\n";
  }
  const Clip clip = parse_bvh(text, "deep.bvh");
  CHECK(clip.skeleton.joints.size() == kDepth + 1);
  CHECK(clip.skeleton.joints.back().parent == kDepth - 1);
  CHECK(clip.frames() == 2);
  // The writer indents at most 32 tabs, so its text stays linear in the depth (not 20000 tabs
  // on the deepest lines, 2e8 in all): 5 lines of at most 33 tabs and 40 characters a joint.
  const std::string written = format_bvh(clip);
  CHECK(written.size() < kDepth * 5 * (33 + 40) + 2 * 4 * kDepth);
  check_same_clip(parse_bvh(written, "deep2.bvh"), clip);
}

TEST_CASE("a skeleton without channels: each frame an empty line", "[bvh]") {
  const std::string header =
      "HIERARCHY\nROOT A\n{\nOFFSET 0 0 0\nCHANNELS 0\nEnd Site\n{\nOFFSET 0 1 0\n}\n}\nMOTION\n";
  std::vector<std::string> warnings;
  Clip clip = parse_bvh(header + "Frames: 3\nFrame Time: 0.1\n\n\n\n", "empty.bvh", &warnings);
  CHECK(clip.frames() == 3);
  CHECK(warnings.empty());
  check_same_clip(parse_bvh(format_bvh(clip), "again.bvh"), clip);
  // An absurd declared count allocates nothing: the file holds no frame lines, and is refused.
  CHECK_THROWS_WITH(parse_bvh(header + "Frames: 100000000\nFrame Time: 0.1\n", "lie.bvh", &warnings),
                    Catch::StartsWith("lie.bvh:13: the file ends after 0 frame lines of the 100000000 that Frames: "
                                      "declares on line 12: it was cut short"));
  CHECK_THROWS_WITH(parse_bvh(header + "Frames: 1\nFrame Time: 0.1\n1\n", "x.bvh"),
                    "x.bvh:14: expected 0 values in frame 1, found '1'");
}

TEST_CASE("a file cut short is refused, naming where it ends and the frames declared", "[bvh]") {
  std::vector<std::string> warnings;
  SECTION("fewer frames than declared") {
    CHECK_THROWS_WITH(parse_bvh(replace_all(kSmall, "Frames: 2", "Frames: 5"), "w.bvh", &warnings),
                      "w.bvh:20: the file ends after 2 complete frames of the 5 that Frames: declares on line 17: "
                      "it was cut short; copy or export it again (or set Frames: to 2 to load what is there)");
  }
  SECTION("a cut last line") {
    const std::string text = kSmall.substr(0, kSmall.size() - std::string(" 0 0 0 0 0\n").size());
    CHECK_THROWS_WITH(parse_bvh(text, "w.bvh", &warnings),
                      Catch::StartsWith("w.bvh:20: the file ends after 1 complete frame of the 2 that Frames: declares "
                                        "on line 17, its last line cut (4 of 9 values): it was cut short"));
  }
  SECTION("a file cut inside a number") {
    for (const char* tail : {"4 5 6 9.5e", "4 5 6 9.5e-", "4 5 -", "4."}) {
      INFO(tail);
      const std::string text = kSmall.substr(0, kSmall.find("4 5 6 90")) + tail;
      CHECK_THROWS_WITH(parse_bvh(text, "w.bvh", &warnings), Catch::Contains("1 complete frame of the 2"));
    }
  }
  SECTION("a cut last line followed by blank lines") {
    const std::string text = replace_all(kSmall, "4 5 6 90 0 0 0 0 0\n", "4 5 6\n\n  \n");
    CHECK_THROWS_WITH(parse_bvh(text, "w.bvh", &warnings), Catch::Contains("cut short"));
  }
  CHECK(warnings.empty());
}

TEST_CASE("recoverable defects load the complete frames and warn", "[bvh]") {
  std::vector<std::string> warnings;
  SECTION("more frames than declared") {
    std::string text = replace_all(kSmall, "Frames: 2", "Frames: 1");
    for (int i = 0; i < 200; ++i) text += "7 8 9 0 0 0 0 0 0\n";
    const Clip clip = parse_bvh(text, "w.bvh", &warnings);
    CHECK(clip.frames() == 202);
    CHECK(clip.motion(201, 2) == 9);
    REQUIRE(warnings.size() == 1);
    CHECK(warnings[0] == "w.bvh:17: Frames: says 1 but the file has 202 complete frames; loaded 202");
  }
  SECTION("a file cut inside a number after the frames declared") {
    const std::string text = kSmall.substr(0, kSmall.find("4 5 6 90")) + "4 5 6 90 0 0 0 0 1.";
    const Clip clip = parse_bvh(text, "w.bvh", &warnings);
    CHECK(clip.frames() == 2);
  }
}

TEST_CASE("a large synthetic file loads (linear, no per-value reallocation)", "[bvh]") {
  // 20000 frames of the CMU layout, about 17 MB; the declared count too low loads them all, too
  // high (a file cut short) is refused without allocating for it.
  const Clip cmu = read_bvh_file(test::asset("motions/cmu142_walk_happy.bvh"));
  Clip big = cmu;
  big.motion.resize(20000, cmu.motion.cols());
  for (int f = 0; f < big.frames(); ++f) big.motion.row(f) = cmu.motion.row(f % cmu.frames());
  const std::string text = format_bvh(big);
  for (const char* frames : {"Frames: 20000", "Frames: 3"}) {
    INFO(frames);
    std::vector<std::string> warnings;
    const Clip back = parse_bvh(replace_all(text, "Frames: 20000", frames), "big.bvh", &warnings);
    CHECK(back.motion == big.motion);
    CHECK(warnings.size() == (std::string(frames) == "Frames: 20000" ? 0u : 1u));
  }
  CHECK_THROWS_WITH(parse_bvh(replace_all(text, "Frames: 20000", "Frames: 99999999"), "big.bvh"),
                    Catch::Contains("the file ends after 20000 complete frames of the 99999999"));
}
