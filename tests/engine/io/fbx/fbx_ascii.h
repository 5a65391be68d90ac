#pragma once
// A clip as an ASCII FBX 7.4 file, for tests and benchmarks of the FBX reader (no FBX writer ships:
// mostyle writes BVH and glTF). Each joint (End Sites left out) a LimbNode Model with its OFFSET
// as Lcl Translation and its Euler order as RotationOrder; one animation stack `take` whose
// curves key every frame: Lcl Rotation (degrees, unwrapped frame to frame as exporters write
// them: FBX curves interpolate Euler angles, so a jump of 360 degrees would be a turn) of every
// joint, Lcl Translation of joints with position channels. Time mode: custom, the clip's rate.
// Joints need 3 rotation channels.
#include <cmath>
#include <string>

#include "engine/base/clip.h"
#include "engine/kinematics/euler.h"
#include "engine/kinematics/kinematics.h"

namespace mostyle::test {

inline std::string format_fbx_ascii(const Clip& clip, const std::string& take) {
  constexpr long long kTicksPerSecond = 46186158000LL;
  const Skeleton& s = clip.skeleton;
  const int frames = clip.frames();
  MotionMatrix motion = clip.motion;  // rotation triples unwrapped
  for (const Joint& joint : s.joints) {
    std::vector<int> r;
    for (size_t c = 0; c < joint.channels.size(); ++c)
      if (is_rotation(joint.channels[c])) r.push_back(joint.first_channel + static_cast<int>(c));
    if (r.size() != 3) continue;
    for (int f = 1; f < frames; ++f) {
      const Eigen::Vector3d prev(motion(f - 1, r[0]), motion(f - 1, r[1]), motion(f - 1, r[2]));
      const Eigen::Vector3d near = euler_near(Eigen::Vector3d(motion(f, r[0]), motion(f, r[1]), motion(f, r[2])), prev);
      for (int a = 0; a < 3; ++a) motion(f, r[a]) = near(a);
    }
  }
  std::string out;
  out.reserve(4096 + static_cast<size_t>(frames) * s.channel_count * 24);
  const auto num = [](double v) {
    char b[32];
    std::snprintf(b, sizeof b, "%.9g", v);
    return std::string(b);
  };
  out += "; FBX 7.4.0 project file\nFBXHeaderExtension:  {\n\tFBXHeaderVersion: 1003\n\tFBXVersion: 7400\n}\n";
  out += "GlobalSettings:  {\n\tVersion: 1000\n\tProperties70:  {\n";
  out += "\t\tP: \"UpAxis\", \"int\", \"Integer\", \"\",1\n\t\tP: \"UpAxisSign\", \"int\", \"Integer\", \"\",1\n";
  out += "\t\tP: \"FrontAxis\", \"int\", \"Integer\", \"\",2\n\t\tP: \"FrontAxisSign\", \"int\", \"Integer\", \"\",1\n";
  out += "\t\tP: \"CoordAxis\", \"int\", \"Integer\", \"\",0\n\t\tP: \"CoordAxisSign\", \"int\", \"Integer\", \"\",1\n";
  out += "\t\tP: \"UnitScaleFactor\", \"double\", \"Number\", \"\",1\n";
  out += "\t\tP: \"TimeMode\", \"enum\", \"\", \"\",14\n";
  out += "\t\tP: \"CustomFrameRate\", \"double\", \"Number\", \"\"," + num(1.0 / clip.frame_time) + "\n\t}\n}\n";
  out += "Objects:  {\n";
  std::string connections = "Connections:  {\n";
  long long next_id = 1000000;
  const long long stack = next_id++, layer = next_id++;
  std::string times = "\t\tKeyTime: *" + std::to_string(frames) + " {\n\t\t\ta: ";
  for (int f = 0; f < frames; ++f)
    times += (f ? "," : "") + std::to_string(std::llround(f * clip.frame_time * kTicksPerSecond));
  times += "\n\t\t}\n";
  std::string curves;
  std::vector<long long> model_id(s.joints.size(), 0);
  for (size_t j = 0; j < s.joints.size(); ++j) {
    const Joint& joint = s.joints[j];
    if (joint.end_site) continue;
    const long long id = next_id++;
    model_id[j] = id;
    std::string order;  // BVH "ZYX" (R = Rz Ry Rx) is FBX's eEulerXYZ: the letters reversed
    std::vector<int> rotation_column(3, -1), position_column(3, -1);
    for (size_t c = 0; c < joint.channels.size(); ++c) {
      const int axis = channel_axis(joint.channels[c]);
      if (is_rotation(joint.channels[c])) {
        order.insert(order.begin(), static_cast<char>('X' + axis));
        rotation_column[axis] = joint.first_channel + static_cast<int>(c);
      } else {
        position_column[axis] = joint.first_channel + static_cast<int>(c);
      }
    }
    const char* const kOrders[] = {"XYZ", "XZY", "YZX", "YXZ", "ZXY", "ZYX"};
    int order_enum = 0;
    for (int o = 0; o < 6; ++o)
      if (order == kOrders[o]) order_enum = o;
    out += "\tModel: " + std::to_string(id) + ", \"Model::" + joint.name + "\", \"LimbNode\" {\n\t\tVersion: 232\n";
    out += "\t\tProperties70:  {\n\t\t\tP: \"RotationOrder\", \"enum\", \"\", \"\"," + std::to_string(order_enum) + "\n";
    const bool moves = position_column[0] >= 0 || position_column[1] >= 0 || position_column[2] >= 0;
    const Eigen::Vector3d t = moves ? Eigen::Vector3d::Zero() : joint.offset;
    out += "\t\t\tP: \"Lcl Translation\", \"Lcl Translation\", \"\", \"A\"," + num(t.x()) + "," + num(t.y()) + "," +
           num(t.z()) + "\n\t\t}\n\t}\n";
    connections += "\tC: \"OO\"," + std::to_string(id) + "," +
                   std::to_string(joint.parent < 0 ? 0 : model_id[joint.parent]) + "\n";
    for (int kind = 0; kind < 2; ++kind) {
      const std::vector<int>& columns = kind == 0 ? rotation_column : position_column;
      if (columns[0] < 0 && columns[1] < 0 && columns[2] < 0) continue;
      const long long node = next_id++;
      out += "\tAnimationCurveNode: " + std::to_string(node) + ", \"AnimCurveNode::" + (kind == 0 ? "R" : "T") +
             "\", \"\" {\n\t\tProperties70:  {\n";
      for (int a = 0; a < 3; ++a)
        out += std::string("\t\t\tP: \"d|") + static_cast<char>('X' + a) + "\", \"Number\", \"\", \"A\",0\n";
      out += "\t\t}\n\t}\n";
      connections += "\tC: \"OO\"," + std::to_string(node) + "," + std::to_string(layer) + "\n";
      connections += "\tC: \"OP\"," + std::to_string(node) + "," + std::to_string(id) + ", \"" +
                     (kind == 0 ? "Lcl Rotation" : "Lcl Translation") + "\"\n";
      for (int a = 0; a < 3; ++a) {
        if (columns[a] < 0) continue;
        const long long curve = next_id++;
        curves += "\tAnimationCurve: " + std::to_string(curve) + ", \"AnimCurve::\", \"\" {\n\t\tDefault: 0\n";
        curves += "\t\tKeyVer: 4008\n" + times + "\t\tKeyValueFloat: *" + std::to_string(frames) + " {\n\t\t\ta: ";
        for (int f = 0; f < frames; ++f) curves += (f ? "," : "") + num(motion(f, columns[a]));
        curves += "\n\t\t}\n\t}\n";
        connections += "\tC: \"OP\"," + std::to_string(curve) + "," + std::to_string(node) + ", \"d|" +
                       static_cast<char>('X' + a) + "\"\n";
      }
    }
  }
  out += "\tAnimationStack: " + std::to_string(stack) + ", \"AnimStack::" + take + "\", \"\" {\n";
  out += "\t\tProperties70:  {\n\t\t\tP: \"LocalStop\", \"KTime\", \"Time\", \"\"," +
         std::to_string(std::llround((frames - 1) * clip.frame_time * kTicksPerSecond)) + "\n\t\t}\n\t}\n";
  out += "\tAnimationLayer: " + std::to_string(layer) + ", \"AnimLayer::BaseLayer\", \"\" {\n\t}\n";
  out += curves;
  out += "}\n";
  connections += "\tC: \"OO\"," + std::to_string(layer) + "," + std::to_string(stack) + "\n}\n";
  return out + connections;
}

}  // namespace mostyle::test
