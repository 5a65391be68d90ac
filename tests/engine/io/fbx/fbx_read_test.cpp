#include "engine/io/fbx/fbx_read.h"

#include <catch2/catch.hpp>
#include <cmath>

#include <filesystem>

#include "engine/io/bvh/bvh_read.h"
#include "engine/base/error.h"
#include "engine/io/motion_file.h"
#include "engine/kinematics/kinematics.h"
#include "engine/kinematics/resample.h"
#include "engine/kinematics/units.h"
#include "tests/engine/io/fbx/fbx_ascii.h"
#include "tests/engine/io/motion_compare.h"
#include "tests/engine/io/temp_dir.h"
#include "tests/test_data.h"

namespace fs = std::filesystem;
using namespace mostyle;
using Catch::Matchers::Contains;

namespace {

using test::kMaxBound;
using test::kMeanBound;
// What Blender's thinned FBX curves keep of the BVH (see the test on its files): measured 1.3e-3
// and 1.5e-2 on cmu142_walk_joy.fbx.
constexpr double kBlenderFbxMeanBound = 2e-3;
constexpr double kBlenderFbxMaxBound = 2.5e-2;

// A small ASCII FBX 7.4 file: Hips (not keyed) at (0, 90, 0); Spine 10 above it with a
// pre-rotation of 90 degrees about Z and a key curve turning it 0 -> 90 degrees more about Z over
// one second; Head 10 along Spine's Y (keyed, constant). Time mode 6: 30 fps.
const std::string kSmallFbx = R"FBX(; FBX 7.4.0 project file
FBXHeaderExtension:  {
	FBXHeaderVersion: 1003
	FBXVersion: 7400
}
GlobalSettings:  {
	Version: 1000
	Properties70:  {
		P: "UpAxis", "int", "Integer", "",1
		P: "UpAxisSign", "int", "Integer", "",1
		P: "FrontAxis", "int", "Integer", "",2
		P: "FrontAxisSign", "int", "Integer", "",1
		P: "CoordAxis", "int", "Integer", "",0
		P: "CoordAxisSign", "int", "Integer", "",1
		P: "UnitScaleFactor", "double", "Number", "",1
		P: "TimeMode", "enum", "", "",6
	}
}
Objects:  {
	Model: 1000, "Model::Hips", "LimbNode" {
		Version: 232
		Properties70:  {
			P: "Lcl Translation", "Lcl Translation", "", "A",0,90,0
		}
	}
	Model: 1001, "Model::Spine", "LimbNode" {
		Version: 232
		Properties70:  {
			P: "Lcl Translation", "Lcl Translation", "", "A",0,10,0
			P: "PreRotation", "Vector3D", "Vector", "",0,0,90
			P: "RotationActive", "bool", "", "",1
		}
	}
	Model: 1002, "Model::Head", "LimbNode" {
		Version: 232
		Properties70:  {
			P: "Lcl Translation", "Lcl Translation", "", "A",0,10,0
		}
	}
	AnimationStack: 2000, "AnimStack::nod", "" {
		Properties70:  {
			P: "LocalStop", "KTime", "Time", "",46186158000
		}
	}
	AnimationLayer: 2001, "AnimLayer::BaseLayer", "" {
	}
	AnimationCurveNode: 2002, "AnimCurveNode::R", "" {
		Properties70:  {
			P: "d|X", "Number", "", "A",0
			P: "d|Y", "Number", "", "A",0
			P: "d|Z", "Number", "", "A",0
		}
	}
	AnimationCurve: 2003, "AnimCurve::", "" {
		Default: 0
		KeyVer: 4008
		KeyTime: *2 {
			a: 0,46186158000
		}
		KeyValueFloat: *2 {
			a: 0,90
		}
	}
	AnimationCurveNode: 2004, "AnimCurveNode::T", "" {
		Properties70:  {
			P: "d|X", "Number", "", "A",0
			P: "d|Y", "Number", "", "A",10
			P: "d|Z", "Number", "", "A",0
		}
	}
	AnimationCurve: 2005, "AnimCurve::", "" {
		Default: 0
		KeyVer: 4008
		KeyTime: *2 {
			a: 0,46186158000
		}
		KeyValueFloat: *2 {
			a: 10,10
		}
	}
}
Connections:  {
	C: "OO",1000,0
	C: "OO",1001,1000
	C: "OO",1002,1001
	C: "OO",2001,2000
	C: "OO",2002,2001
	C: "OO",2004,2001
	C: "OP",2002,1001, "Lcl Rotation"
	C: "OP",2003,2002, "d|Z"
	C: "OP",2004,1002, "Lcl Translation"
	C: "OP",2005,2004, "d|Y"
}
)FBX";

using test::TempDir;

}  // namespace

TEST_CASE("FBX: an ASCII file with a pre-rotation, sampled at the file's time mode", "[fbx]") {
  const AnimatedScene scene = parse_fbx(kSmallFbx, "small.fbx");
  REQUIRE(scene.takes.size() == 1);
  CHECK(scene.takes[0].name == "nod");
  CHECK(scene.frame_rate == 30.0);
  const Clip clip = scene_take_to_clip(scene, 0);
  CHECK(clip.frames() == 31);
  REQUIRE(clip.skeleton.joints.size() == 2);  // Spine and Head move; Hips only places them
  CHECK(clip.skeleton.joints[0].name == "Spine");
  CHECK(clip.skeleton.joints[1].name == "Head");
  const Eigen::MatrixXd p = joint_positions(clip);
  for (int f : {0, 15, 30}) {
    // Spine's world rotation: Rz(90 + theta), theta = 90 f / 30 degrees. Head = Spine + R (0, 10, 0).
    const double a = (90.0 + 90.0 * f / 30.0) * M_PI / 180.0;
    CHECK(p(f, 0) == Approx(0.0).margin(1e-5));
    CHECK(p(f, 1) == Approx(100.0).margin(1e-5));
    CHECK(p(f, 3) == Approx(-10 * std::sin(a)).margin(1e-4));
    CHECK(p(f, 4) == Approx(100 + 10 * std::cos(a)).margin(1e-4));
  }
}

TEST_CASE("FBX: a CMU take written as ASCII FBX (Euler orders, time mode) reads as the same motion", "[fbx]") {
  const Clip bvh = read_bvh_file(test::asset("motions/cmu142_walk_clumsy.bvh"));
  const AnimatedScene scene = parse_fbx(test::format_fbx_ascii(bvh, "clumsy"), "clumsy.fbx");
  CHECK(scene.frame_rate == Approx(1.0 / bvh.frame_time).epsilon(1e-6));
  const Clip clip = scene_take_to_clip(scene, 0);
  CHECK(clip.frames() == bvh.frames());
  // No fit: the file's world is the BVH's (float32 keys: about 1e-7 of the height).
  const Eigen::MatrixXd a = joint_positions(bvh), b = joint_positions(clip);
  double worst = 0;
  for (size_t i = 0; i < bvh.skeleton.joints.size(); ++i) {
    if (bvh.skeleton.joints[i].end_site) continue;
    const int j = clip.skeleton.find(bvh.skeleton.joints[i].name);
    REQUIRE(j >= 0);
    worst = std::max(worst, (a.middleCols(3 * i, 3) - b.middleCols(3 * j, 3)).rowwise().norm().maxCoeff());
  }
  CHECK(worst / guess_units(bvh).height < 1e-5);
}

TEST_CASE("FBX: bad files are one sentence naming the file", "[fbx][errors]") {
  TempDir tmp;
  CHECK_THROWS_WITH(parse_fbx("not an fbx at all", "junk.fbx"), Contains("junk.fbx: not a readable FBX file"));
  CHECK_THROWS_WITH(parse_fbx(kSmallFbx.substr(0, kSmallFbx.size() / 3), "cut.fbx"), Contains("cut.fbx: "));
  std::string binary = "Kaydara FBX Binary  ";
  binary += '\0';
  binary += "\x1a\x00\xe8\x1c\x00\x00";
  binary += std::string(40, '\xff');
  CHECK_THROWS_WITH(parse_fbx(binary, "broken.fbx"), Contains("broken.fbx: not a readable FBX file"));
  // No animation stack: no take.
  const size_t stack = kSmallFbx.find("\tAnimationStack");
  const std::string still = kSmallFbx.substr(0, stack) + "}\nConnections:  {\n\tC: \"OO\",1000,0\n}\n";
  CHECK_THROWS_WITH(parse_fbx(still, "still.fbx"), Contains("still.fbx: has no animation"));
  const std::string file = tmp.write("small.fbx", kSmallFbx);
  CHECK_THROWS_WITH(read_motion_file(file + "#walk"), Contains("small.fbx: has no animation 'walk'; it has 'nod'"));
  CHECK_NOTHROW(read_motion_file(file + "#nod"));
}

TEST_CASE("FBX: Blender's files read as the BVHs they came from", "[fbx][shared]") {
  MOSTYLE_REQUIRE_SHARED_MOTIONS();
  struct Case {
    const char* fbx;
    const char* bvh;
    double rate;  // the file's own
  };
  for (const Case& c : {Case{"formats/cmu142_walk_joy.fbx", "cmu142_walk_joy.bvh", 120.0},
                        Case{"formats/cmu142_walk_happy_30fps.fbx", "cmu142_walk_happy.bvh", 30.0}}) {
    const Clip bvh = read_bvh_file(test::shared_motion(c.bvh));
    const Clip own = read_motion_file(test::shared_motion(c.fbx));
    CHECK(own.fps() == c.rate);
    for (double fps : {0.0, 30.0}) {
      MotionReadOptions o;
      o.fps = fps;
      const Clip clip = fps == 0 ? own : read_motion_file(test::shared_motion(c.fbx), nullptr, o);
      const Clip reference = fps == 0 && c.rate == 120.0 ? bvh : resample_clip(bvh, fps == 0 ? c.rate : fps);
      const test::MotionDifference d = test::motion_difference(reference, clip);
      INFO(c.fbx << " at " << clip.fps() << " fps: mean " << d.mean << ", max " << d.max << " of the height, "
                 << d.frames << " frames, " << d.joints << " joints");
      CHECK(d.joints == 31);
      CHECK(std::abs(clip.frames() - reference.frames()) <= 1);
      // Blender's FBX exporter thins each curve (its "simplify", on by default): a key is kept
      // only where the value moved enough since the last one kept, and the curves are LINEAR in
      // between (KeyAttrFlags 0x6104), so slow drifts are gone from the file itself: the joy
      // file's Hips X curve keeps 1966 of 2666 keys and holds 51.59 at frame 217 where the BVH
      // has 51.42 (0.7% of the height). No reader can give back what the file does not hold;
      // the same reader is exact on files that keep every key (the ASCII case above, 1e-7).
      // The general bounds (motion_compare.h) are reported (CHECK_NOFAIL); the file's own loss bounds the test.
      CHECK_NOFAIL(d.mean <= kMeanBound);
      CHECK_NOFAIL(d.max <= kMaxBound);
      CHECK(d.mean <= kBlenderFbxMeanBound);
      CHECK(d.max <= kBlenderFbxMaxBound);
      WARN(c.fbx << " at " << clip.fps() << " fps: mean " << d.mean << ", max " << d.max);
    }
  }
}
