#pragma once
// A small BVH file in the most common layout, shared by the BVH tests; line numbers in the
// comments, so error messages can be checked to the line.
#include <string>

namespace mostyle::test {

inline const std::string kSmallBvh =
    "HIERARCHY\n"                                                               // 1
    "ROOT Hips\n"                                                               // 2
    "{\n"                                                                       // 3
    "  OFFSET 0 0 0\n"                                                          // 4
    "  CHANNELS 6 Xposition Yposition Zposition Zrotation Yrotation Xrotation\n"  // 5
    "  JOINT Spine\n"                                                           // 6
    "  {\n"                                                                     // 7
    "    OFFSET 0 10 0\n"                                                       // 8
    "    CHANNELS 3 Zrotation Xrotation Yrotation\n"                            // 9
    "    End Site\n"                                                            // 10
    "    {\n"                                                                   // 11
    "      OFFSET 0 5 0\n"                                                      // 12
    "    }\n"                                                                   // 13
    "  }\n"                                                                     // 14
    "}\n"                                                                       // 15
    "MOTION\n"                                                                  // 16
    "Frames: 2\n"                                                               // 17
    "Frame Time: 0.0333333\n"                                                   // 18
    "1 2 3 0 0 0 0 0 0\n"                                                       // 19
    "4 5 6 90 0 0 0 0 0\n";

}  // namespace mostyle::test
