// The Cornell box as published (Cornell University Program of Computer
// Graphics, millimetres): an uncut ceiling and the light in its plane
// (y = 548.8) or, as most Cornell OBJ files have it, a hair under it
// (548.7). Unlike assets/cornell_box, nothing is cut by hand.
#pragma once

#include <string>

#include "test_files.h"

namespace bounce::test_support {

inline const char* cornell_mtl =
    "newmtl white\nKd 0.725 0.71 0.68\n"
    "newmtl red\nKd 0.63 0.065 0.05\n"
    "newmtl green\nKd 0.14 0.45 0.091\n"
    "newmtl light\nKd 0.78 0.78 0.78\nKe 17 12 4\n";

// Light corners x 213..343, z 227..332 at height light_y; faces as in
// assets/cornell_box (counter-clockwise seen from the side they face).
inline std::string official_cornell_obj(const std::string& light_y) {
  const std::string l = " " + light_y + " ";
  return "mtllib cornell.mtl\n"
         "o floor\nusemtl white\nv 552.8 0 0\nv 0 0 0\nv 0 0 559.2\nv 549.6 0 559.2\nf 1 2 3 4\n"
         "o ceiling\nusemtl white\nv 556 548.8 0\nv 556 548.8 559.2\nv 0 548.8 559.2\nv 0 548.8 0\nf 5 6 7 8\n"
         "o back_wall\nusemtl white\nv 549.6 0 559.2\nv 0 0 559.2\nv 0 548.8 559.2\nv 556 548.8 559.2\nf 9 10 11 12\n"
         "o right_wall\nusemtl green\nv 0 0 559.2\nv 0 0 0\nv 0 548.8 0\nv 0 548.8 559.2\nf 13 14 15 16\n"
         "o left_wall\nusemtl red\nv 552.8 0 0\nv 549.6 0 559.2\nv 556 548.8 559.2\nv 556 548.8 0\nf 17 18 19\n"
         "f 17 19 20\n"
         "o light\nusemtl light\nv 343" +
         l + "227\nv 343" + l + "332\nv 213" + l + "332\nv 213" + l +
         "227\nf 21 22 23 24\n"
         "o short_block\nusemtl white\n"
         "v 130 165 65\nv 82 165 225\nv 240 165 272\nv 290 165 114\n"
         "v 130 0 65\nv 82 0 225\nv 240 0 272\nv 290 0 114\n"
         "f 25 26 27 28\nf 29 30 26 25\nf 30 31 27 26\nf 31 32 28 27\nf 32 29 25 28\n"
         "o tall_block\nusemtl white\n"
         "v 423 330 247\nv 265 330 296\nv 314 330 456\nv 472 330 406\n"
         "v 423 0 247\nv 265 0 296\nv 314 0 456\nv 472 0 406\n"
         "f 33 34 35 36\nf 37 38 34 33\nf 38 39 35 34\nf 39 40 36 35\nf 40 37 33 36\n";
}

// Writes the OBJ, its MTL and a JSON scene with the standard camera at
// width x height into `dir`; returns the JSON's path.
inline std::string write_official_cornell(const scratch_dir& dir, const std::string& light_y, int width = 256,
                                          int height = 256) {
  dir.write("cornell.mtl", cornell_mtl);
  dir.write("cornell_" + light_y + ".obj", official_cornell_obj(light_y));
  return dir.write("cornell_" + light_y + ".json",
                   "{\"camera\": {\"eye\": [278, 273, -800], \"target\": [278, 273, 0], \"up\": [0, 1, 0], "
                   "\"fov\": 39.3, \"size\": [" +
                       std::to_string(width) + ", " + std::to_string(height) +
                       "]},\n \"surfaces\": [{\"obj\": \"cornell_" + light_y + ".obj\"}]}\n");
}

}  // namespace bounce::test_support
