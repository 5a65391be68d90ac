#pragma once
// Which take a warning speaks of, so that each is listed under its own take: the readers name
// the file at the start of theirs ("walk.bvh:12: ...", "walk.glb: read animation ..."), and an
// alignment's are about the take aligned onto the reference, unless they say that only the
// reference's frames match ("only A's frames ...").
#include <string>
#include <vector>

namespace mostyle::ui {

// paths: the takes' files (N, FILE#ANIMATION too); load: every load's warnings; aligned: per take,
// its alignment's warnings (the reference's own: empty; shorter than N: none for the rest);
// names: how those name each take ("A", "B", or its file's name in a palette). Returns N lists,
// each in the order given. A load warning naming no take's file goes under the reference (0).
// O(warnings x N).
std::vector<std::vector<std::string>> warnings_by_take(const std::vector<std::string>& paths,
                                                       const std::vector<std::string>& load,
                                                       const std::vector<std::vector<std::string>>& aligned,
                                                       const std::vector<std::string>& names);

}  // namespace mostyle::ui
