#pragma once
// Which take a warning speaks of, so that each is listed under its own take: the readers name
// the file at the start of theirs ("walk.bvh:12: ...", "walk.glb: read animation ..."), and an
// alignment's are about the take aligned onto the reference, unless they say that only the
// reference's frames match ("only A's frames ...").
#include <string>
#include <vector>

namespace mostyle::ui {

// What is said of one take, kept apart: the file reader's repairs and omissions (load), and how
// the take was aligned onto the reference where that changes what plays (alignment).
struct TakeMessages {
  std::vector<std::string> load;
  std::vector<std::string> alignment;
  bool operator==(const TakeMessages& o) const { return load == o.load && alignment == o.alignment; }
};

// paths: the takes' files (N, FILE#ANIMATION too); load: every load's warnings; aligned: per take,
// its alignment's warnings (the reference's own: empty; shorter than N: none for the rest);
// names: how those name each take ("A", "B", or its file's name in a palette). Returns N lists,
// each in the order given. A load warning naming no take's file goes under the reference (0).
// An alignment sentence given for several takes (the same words: about the reference, say) is
// said once, under the first of them, with how many takes it holds for. O(warnings x N).
std::vector<TakeMessages> warnings_by_take(const std::vector<std::string>& paths, const std::vector<std::string>& load,
                                           const std::vector<std::vector<std::string>>& aligned,
                                           const std::vector<std::string>& names);

}  // namespace mostyle::ui
