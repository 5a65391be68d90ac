#include "engine/base/clip.h"

#include <cmath>

namespace mostyle {

const char* channel_name(Channel c) {
  switch (c) {
    case Channel::kXposition: return "Xposition";
    case Channel::kYposition: return "Yposition";
    case Channel::kZposition: return "Zposition";
    case Channel::kXrotation: return "Xrotation";
    case Channel::kYrotation: return "Yrotation";
    case Channel::kZrotation: return "Zrotation";
  }
  return "?";
}

int Skeleton::find(const std::string& name) const {
  for (int i = 0; i < static_cast<int>(joints.size()); ++i) {
    if (!joints[i].end_site && joints[i].name == name) return i;
  }
  return -1;
}

int Skeleton::joint_count_without_end_sites() const {
  int n = 0;
  for (const Joint& j : joints) n += j.end_site ? 0 : 1;
  return n;
}

std::vector<int> Skeleton::children(int joint) const {
  std::vector<int> out;
  for (int i = 0; i < static_cast<int>(joints.size()); ++i) {
    if (joints[i].parent == joint) out.push_back(i);
  }
  return out;
}

double frame_rate_from_frame_time(double frame_time) {
  if (!(frame_time > 0.0)) return 0.0;
  const double rate = 1.0 / frame_time;
  const double whole = std::round(rate);
  // 0.05% snaps 120.005 (from 0.008333) to 120 and keeps 29.97 as it is.
  if (whole > 0.0 && std::abs(rate - whole) <= 5e-4 * whole) return whole;
  return rate;
}

}  // namespace mostyle
