#include "engine/kinematics/convert.h"

#include "engine/kinematics/kinematics.h"

namespace mostyle {

bool joint_euler_order(const Joint& joint, EulerOrder* order) {
  std::string axes;
  for (Channel c : joint.channels) {
    if (is_rotation(c)) axes += static_cast<char>('X' + channel_axis(c));
  }
  return axes.size() == 3 && parse_euler_order(axes, order);
}

Clip convert_euler_order(const Clip& clip, EulerOrder order) {
  const auto axes = euler_axes(order);
  Clip out;
  out.source = clip.source;
  out.frame_time = clip.frame_time;
  out.skeleton = clip.skeleton;
  // New channel layout: position channels first (file order), then the three rotations.
  int next = 0;
  for (size_t i = 0; i < out.skeleton.joints.size(); ++i) {
    Joint& j = out.skeleton.joints[i];
    j.first_channel = next;
    if (j.end_site) continue;
    std::vector<Channel> channels;
    bool rotates = false;
    for (Channel c : j.channels) {
      if (is_position(c)) channels.push_back(c);
      rotates = rotates || is_rotation(c);
    }
    if (rotates) {
      for (int a : axes) channels.push_back(static_cast<Channel>(static_cast<int>(Channel::kXrotation) + a));
    }
    j.channels = channels;
    next += static_cast<int>(channels.size());
  }
  out.skeleton.channel_count = next;
  out.motion.resize(clip.frames(), next);

  // Joints already in `order` keep their own values (unwrapped only), bit for bit.
  std::vector<char> same_order(clip.skeleton.joints.size(), 0);
  for (size_t i = 0; i < clip.skeleton.joints.size(); ++i) {
    EulerOrder o;
    const Joint& j = clip.skeleton.joints[i];
    same_order[i] = !j.end_site && joint_euler_order(j, &o) && o == order;
  }

  std::vector<Eigen::Vector3d> previous(clip.skeleton.joints.size(), Eigen::Vector3d::Zero());
  for (int f = 0; f < clip.frames(); ++f) {
    const double* in = clip.motion.row(f).data();
    double* row = out.motion.row(f).data();
    for (size_t i = 0; i < clip.skeleton.joints.size(); ++i) {
      const Joint& src = clip.skeleton.joints[i];
      const Joint& dst = out.skeleton.joints[i];
      if (src.end_site) continue;
      int k = dst.first_channel;
      for (size_t c = 0; c < src.channels.size(); ++c) {
        if (is_position(src.channels[c])) row[k++] = in[src.first_channel + c];
      }
      if (k == dst.first_channel + static_cast<int>(dst.channels.size())) continue;
      Eigen::Vector3d angles;
      if (same_order[i]) {
        int d = 0;
        for (size_t c = 0; c < src.channels.size(); ++c) {
          if (is_rotation(src.channels[c])) angles[d++] = in[src.first_channel + c];
        }
        if (f > 0) angles = euler_near(angles, previous[i]);
      } else {
        const Eigen::Matrix3d r = joint_local_rotation(src, in);
        angles = f == 0 ? matrix_to_euler(order, r) : matrix_to_euler_near(order, r, previous[i]);
      }
      previous[i] = angles;
      for (int d = 0; d < 3; ++d) row[k++] = angles[d];
    }
  }
  return out;
}

}  // namespace mostyle
