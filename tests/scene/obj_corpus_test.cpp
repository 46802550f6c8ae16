// OBJ and MTL files as real programs write them: each case is a small copy
// of what a model of Debian's assimp-testmodels corpus (models/OBJ and
// models/invalid) does, written by the test itself. Plain intent loads with
// one warning naming the file and line; unclear intent is refused by name.
#include <chrono>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <stb/stb_image_write.h>

#include "scene/reader_support.h"
#include "scene/scene_io.h"
#include "test_files.h"

namespace bounce {
namespace {

using test_support::scratch_dir;

const char* triangle = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";

struct loaded {
  bool ok = false;
  scene s;
  load_report report;

  // Warnings containing every one of `parts`.
  std::size_t warnings_with(std::initializer_list<std::string> parts) const {
    std::size_t n = 0;
    for (const std::string& w : report.warnings) {
      bool all = true;
      for (const std::string& p : parts) all = all && w.find(p) != std::string::npos;
      n += all;
    }
    return n;
  }
  std::string all_warnings() const {
    std::string out;
    for (const std::string& w : report.warnings) out += w + "\n";
    return out;
  }
  const material& material_of_face(std::size_t surface = 0, std::size_t face = 0) const {
    return s.materials[std::get<polygon_mesh>(s.surfaces.at(surface).geometry).faces.at(face).material];
  }
};

loaded load(const std::string& path) {
  loaded l;
  l.ok = load_scene(path, l.s, l.report);
  return l;
}

const material* find_material(const scene& s, const std::string& name) {
  for (const material& m : s.materials)
    if (m.name == name) return &m;
  return nullptr;
}

// box.obj, testmixed.obj, malformed2.obj: `usemtl Default` without any mtllib.
TEST(ObjCorpus, UndefinedMaterialGetsTheGreyDefaultWithOneWarning) {
  scratch_dir dir;
  std::string path = dir.write("box.obj", std::string(triangle) + "usemtl Default\nf 1 2 3\nusemtl Default\nf 3 2 1\n");
  loaded l = load(path);
  ASSERT_TRUE(l.ok) << l.report.error;
  EXPECT_EQ(l.warnings_with({path + ":5: material 'Default' is not defined", "rho 0.5"}), 1u) << l.all_warnings();
  EXPECT_EQ(l.warnings_with({"'Default'"}), 1u) << l.all_warnings();  // once, not per use
  EXPECT_EQ(l.material_of_face(0, 1).rho, rgb(0.5));
  EXPECT_EQ(l.material_of_face(0, 2).rho, rgb(0.5));
}

// Old Mac exporters end lines with a lone CR: the OBJ was "no faces" and
// the MTL one line, its lamp lost. Both read as with LF, line numbers too.
TEST(ObjCorpus, CrOnlyLineEndsReadAsLines) {
  scratch_dir dir;
  dir.write("mac.mtl", "newmtl white\rKd 0.5 0.5 0.5\rnewmtl lamp\rKe 4 4 4\r");
  const std::string path = dir.write(
      "mac.obj",
      "mtllib mac.mtl\rv 0 0 0\rv 1 0 0\rv 0 0 1\rv 0 1 0\rusemtl white\rf 1 3 2\rusemtl lamp\rf 1 2 4\rf 9 9 9\r");
  scene s;
  load_report report;
  EXPECT_FALSE(load_scene(path, s, report));
  EXPECT_NE(report.error.find(path + ":10:"), std::string::npos) << report.error;  // the bad face's line
  dir.write("mac.obj",
            "mtllib mac.mtl\rv 0 0 0\rv 1 0 0\rv 0 0 1\rv 0 1 0\r\nusemtl white\rf 1 3 2\rusemtl lamp\rf 1 2 4\r");
  loaded l = load(path);
  ASSERT_TRUE(l.ok) << l.report.error;
  EXPECT_EQ(l.material_of_face(0, 0).rho, rgb(0.5));
  EXPECT_EQ(l.material_of_face(0, 1).ke, rgb(4.0));
}

// Numbers as C writes them, "-2.e-1" and ".5" and "1e0" included, read as
// the numbers they are.
TEST(ObjCorpus, NumbersWithoutDigitsAfterThePointAreRead) {
  scratch_dir dir;
  loaded l = load(dir.write("n.obj", "v -2.e-1 .5 0\nv 1e0 0 0\nv 0 0 +1.\nf 1 2 3\n"));
  ASSERT_TRUE(l.ok) << l.report.error;
  const polygon_mesh& m = std::get<polygon_mesh>(l.s.surfaces.at(0).geometry);
  ASSERT_EQ(m.positions.size(), 3u);
  EXPECT_EQ(m.positions[0], vec3(-0.2, 0.5, 0.0));
  EXPECT_EQ(m.positions[1], vec3(1.0, 0.0, 0.0));
  EXPECT_EQ(m.positions[2], vec3(0.0, 0.0, 1.0));
}

// usemtl before the mtllib that defines it: names are looked up at the end.
TEST(ObjCorpus, UsemtlBeforeMtllibFindsTheMaterial) {
  scratch_dir dir;
  dir.write("m.mtl", "newmtl red\nKd 0.6 0.1 0.1\n");
  loaded l = load(dir.write("a.obj", std::string("usemtl red\n") + triangle + "mtllib m.mtl\n"));
  ASSERT_TRUE(l.ok) << l.report.error;
  EXPECT_EQ(l.material_of_face().rho, rgb(0.6, 0.1, 0.1));
}

// cube_usemtl.mtl, regr_3429812.mtl: Kd 1 1 1, the commonest white.
TEST(ObjCorpus, KdOfOneIsClampedWithAWarning) {
  scratch_dir dir;
  std::string mtl = dir.write("m.mtl", "newmtl white\nKa 1 1 1\nKd 1.000 1.000 0.5\n");
  loaded l = load(dir.write("a.obj", std::string("mtllib m.mtl\nusemtl white\n") + triangle));
  ASSERT_TRUE(l.ok) << l.report.error;
  EXPECT_EQ(l.material_of_face().rho, rgb(max_reflectance, max_reflectance, 0.5));
  EXPECT_EQ(l.warnings_with({mtl + ":3: Kd", "'white'", "clamped to 0.99"}), 1u) << l.all_warnings();
}

// A 0-255 colour is not a reflectance: refused rather than guessed.
TEST(ObjCorpus, KdFarAboveOneIsRefused) {
  scratch_dir dir;
  std::string mtl = dir.write("m.mtl", "newmtl c\nKd 255 128 0\n");
  loaded l = load(dir.write("a.obj", std::string("mtllib m.mtl\nusemtl c\n") + triangle));
  ASSERT_FALSE(l.ok);
  EXPECT_NE(l.report.error.find(mtl + ":2: Kd 255 128 0 is not a reflectance"), std::string::npos) << l.report.error;
}

// Kd + a mirror Ks (illum 3) over 1: all of rho, kr, kt scaled to sum 0.99.
TEST(ObjCorpus, EnergyCreatingMaterialIsScaledWithAWarning) {
  scratch_dir dir;
  std::string mtl = dir.write("m.mtl", "newmtl shiny\nKd 0.8 0.4 0.4\nKs 0.9 0.9 0.9\nillum 3\n");
  loaded l = load(dir.write("a.obj", std::string("mtllib m.mtl\nusemtl shiny\n") + triangle));
  ASSERT_TRUE(l.ok) << l.report.error;
  const material& m = l.material_of_face();
  const rgb sum = m.rho + m.kr + m.kt;
  EXPECT_NEAR(std::max({sum.r, sum.g, sum.b}), max_reflectance, 1e-12);
  EXPECT_NEAR(m.rho.r / m.kr.r, 0.8 / 0.9, 1e-12);  // scaled together
  EXPECT_EQ(l.warnings_with({mtl + ":1: material 'shiny' reflects more than it receives", "Kd at line 2",
                             "Ks at line 3", "scaled by"}),
            1u)
      << l.all_warnings();
}

// `d 0` / `Tr 1`: dissolve mixes the material with nothing, so a fully
// dissolved material transmits everything; the warning names the statement.
TEST(ObjCorpus, DissolveNamesItsLine) {
  scratch_dir dir;
  std::string mtl = dir.write("m.mtl",
                              "newmtl gone\nKd 0.8 0.8 0.8\nd 0\n"
                              "newmtl also_gone\nKd 0.8 0.8 0.8\nTr 1\n"
                              "newmtl half\nKd 0.8 0.6 0.4\nd 0.5\n");
  loaded l = load(dir.write("a.obj", std::string("mtllib m.mtl\nusemtl half\n") + triangle));
  ASSERT_TRUE(l.ok) << l.report.error;
  EXPECT_EQ(l.warnings_with({mtl + ":3: 'd 0' makes material 'gone' fully transparent"}), 1u) << l.all_warnings();
  EXPECT_EQ(l.warnings_with({mtl + ":6: 'Tr 1' makes material 'also_gone' fully transparent"}), 1u) << l.all_warnings();
  EXPECT_EQ(find_material(l.s, "gone")->kt, rgb(1.0));
  EXPECT_EQ(find_material(l.s, "gone")->rho, rgb(0.0));
  const material& half = l.material_of_face();
  EXPECT_EQ(half.rho, rgb(0.4, 0.3, 0.2));
  EXPECT_EQ(half.kt, rgb(0.5));
}

// cube_with_vertexcolors*.obj: `v x y z r g b`, no materials at all.
TEST(ObjCorpus, VertexColoursBecomeRhoOfFacesWithoutAMaterial) {
  scratch_dir dir;
  std::string path = dir.write("c.obj",
                               "v 0 0 0 0.2 0.4 0.6\nv 1 0 0 0.2 0.4 0.6\nv 0 1 0 0.2 0.4 0.6\n"
                               "v 1 1 0 1.0 0.0 0.0\n"
                               "f 1 2 3\nf 2 4 3\n");
  loaded l = load(path);
  ASSERT_TRUE(l.ok) << l.report.error;
  EXPECT_LT(glm::length(l.material_of_face(0, 0).rho - rgb(0.2, 0.4, 0.6)), 1.0 / 255);
  // (0.99 + 0.2 + 0.2) / 3 = 0.463 red: the 1.0 channel clamped first.
  EXPECT_LT(glm::length(l.material_of_face(0, 1).rho - rgb(1.39 / 3, 0.8 / 3, 1.2 / 3)), 1.0 / 255);
  EXPECT_EQ(l.warnings_with({path + ":5: faces without a material take their vertex colours"}), 1u) << l.all_warnings();
  EXPECT_EQ(l.warnings_with({path + ":4: vertex colour channels of 1 or more clamped to 0.99"}), 1u)
      << l.all_warnings();
  // Ambiguous lengths are refused.
  l = load(dir.write("seven.obj", "v 0 0 0 1 0.5 0.5 0.5\n"));
  EXPECT_NE(l.report.error.find("seven.obj:1: 'v' with 7 numbers is ambiguous"), std::string::npos) << l.report.error;
}

// number_formats.obj: `+1 +2. +3.0` are numbers; `3.1+e2` is not.
TEST(ObjCorpus, NumbersWithAPlusSign) {
  scratch_dir dir;
  loaded l = load(dir.write("n.obj", "v +1 +2. +3.0\nv -1 2.e1 +3.1e-2\nv 1E2 0 0\nf 1 2 3\n"));
  ASSERT_TRUE(l.ok) << l.report.error;
  const auto& mesh = std::get<polygon_mesh>(l.s.surfaces[0].geometry);
  EXPECT_EQ(mesh.positions[0], vec3(1, 2, 3));
  EXPECT_EQ(mesh.positions[1], vec3(-1, 20, 0.031));
  for (const char* bad : {"3.1+e2", "++1", "+-1", "+"}) {
    l = load(dir.write("bad.obj", std::string("v 0 0 ") + bad + "\n"));
    EXPECT_NE(l.report.error.find("bad.obj:1: '" + std::string(bad) + "' is not a number"), std::string::npos)
        << l.report.error;
  }
}

// space_in_material_name.obj, box_mat_with_spaces.obj, empty_mat.obj
// (Blender's unnamed material: `newmtl ` and `usemtl `).
TEST(ObjCorpus, MaterialNamesWithSpacesAndEmptyNames) {
  scratch_dir dir;
  dir.write("m.mtl",
            "newmtl Hard Shiny Plastic White \nKd 0.1 0.2 0.3\n"
            "newmtl \nKd 0.7 0.7 0.7\n");
  loaded l = load(dir.write("a.obj", std::string("mtllib m.mtl\n") + triangle +
                                         "usemtl  Hard Shiny Plastic White   \nf 1 2 3\nusemtl \nf 3 2 1\n"));
  ASSERT_TRUE(l.ok) << l.report.error;
  EXPECT_EQ(l.material_of_face(0, 1).name, "Hard Shiny Plastic White");
  EXPECT_EQ(l.material_of_face(0, 1).rho, rgb(0.1, 0.2, 0.3));
  EXPECT_EQ(l.material_of_face(0, 2).rho, rgb(0.7));
  EXPECT_EQ(l.warnings_with({"not defined"}), 0u) << l.all_warnings();
}

// cube_mtllib_after_g.obj names a .mat that is a .mtl; a library name may
// have a space; a library that is not there is a warning.
TEST(ObjCorpus, MtllibMisnamedSpacedOrMissing) {
  scratch_dir dir;
  std::string real = dir.write("cube.mtl", "newmtl MyMaterial\nKd 0.3 0.3 0.3\n");
  std::string path = dir.write("cube.obj", std::string("mtllib cube.mat\nusemtl MyMaterial\n") + triangle);
  loaded l = load(path);
  ASSERT_TRUE(l.ok) << l.report.error;
  EXPECT_EQ(l.material_of_face().rho, rgb(0.3));
  EXPECT_EQ(l.warnings_with({path + ":1: material library 'cube.mat' not found; reading '" + real + "'"}), 1u)
      << l.all_warnings();

  dir.write("my mats.mtl", "newmtl m\nKd 0.2 0.2 0.2\n");
  l = load(dir.write("spaced.obj", std::string("mtllib my mats.mtl\nusemtl m\n") + triangle));
  ASSERT_TRUE(l.ok) << l.report.error;
  EXPECT_EQ(l.material_of_face().rho, rgb(0.2));

  path = dir.write("missing.obj", std::string("mtllib gone.mtl\nusemtl m\n") + triangle);
  l = load(path);
  ASSERT_TRUE(l.ok) << l.report.error;
  EXPECT_EQ(l.warnings_with({path + ":1: cannot read material library", "gone.mtl"}), 1u) << l.all_warnings();
  EXPECT_EQ(l.material_of_face().rho, rgb(0.5));
}

// spider.mtl: `map_Kd .\wal67ar_small.jpg`.
TEST(ObjCorpus, BackslashesInTexturePaths) {
  scratch_dir dir;
  const unsigned char pixels[] = {255, 255, 255, 128, 0, 64};
  std::filesystem::create_directories(dir.root / "tex");
  ASSERT_TRUE(stbi_write_png(dir.path("tex/wal 67.png").c_str(), 2, 1, 3, pixels, 6));
  std::string mtl = dir.write("m.mtl", "newmtl skin\nKd 0.8 0.8 0.8\nmap_Kd -s 1 1 1 .\\tex\\wal 67.png\n");
  loaded l = load(dir.write("a.obj", std::string("mtllib m.mtl\nusemtl skin\n") + triangle));
  ASSERT_TRUE(l.ok) << l.report.error;
  ASSERT_EQ(l.s.textures.size(), 1u);
  EXPECT_EQ(l.s.textures[0].width, 2);
  EXPECT_EQ(l.warnings_with({mtl + ":3: backslashes in file names read as '/'"}), 1u) << l.all_warnings();
}

// WusonOBJ.obj and most of the corpus: no emitter at all. It loads; the
// warning says why the picture will be dark.
TEST(ObjCorpus, NoEmitterLoadsWithAWarning) {
  scratch_dir dir;
  std::string path = dir.write("w.obj", triangle);
  loaded l = load(path);
  ASSERT_TRUE(l.ok) << l.report.error;
  EXPECT_EQ(l.warnings_with({path + ": no emitter"}), 1u) << l.all_warnings();
}

// box_UTF16BE.obj; and a UTF-8 byte order mark (Windows editors).
TEST(ObjCorpus, Utf16IsRefusedByNameAndABomIsSkipped) {
  scratch_dir dir;
  const std::string ascii = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
  auto utf16 = [&](bool big_endian, bool mark) {
    std::string out = mark ? (big_endian ? "\xFE\xFF" : "\xFF\xFE") : "";
    for (char c : ascii) {
      if (big_endian) out += '\0';
      out += c;
      if (!big_endian) out += '\0';
    }
    return out;
  };
  for (bool big : {false, true})
    for (bool mark : {false, true}) {
      std::string path = dir.write("u.obj", utf16(big, mark));
      loaded l = load(path);
      EXPECT_EQ(l.report.error, path + ": UTF-16 text; save it as UTF-8") << big << mark;
    }
  dir.write("m.mtl", "\xEF\xBB\xBFnewmtl m\nKd 0.25 0.25 0.25\n");
  loaded l = load(dir.write("bom.obj", "\xEF\xBB\xBFmtllib m.mtl\nusemtl m\n" + ascii));
  ASSERT_TRUE(l.ok) << l.report.error;
  EXPECT_EQ(l.material_of_face().rho, rgb(0.25));
}

// invalid/empty.obj, point_cloud.obj, testpoints.obj, testline.obj: nothing
// with an area. Refused, saying what the file does have.
TEST(ObjCorpus, FilesWithoutFacesAreRefusedSayingWhatTheyHave) {
  scratch_dir dir;
  std::string path = dir.write("empty.obj", "");
  EXPECT_EQ(load(path).report.error, path + ": empty file");
  path = dir.write("points.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\np 1 2 3\nl 1 2\n");
  std::string e = load(path).report.error;
  EXPECT_NE(e.find(path + ": no faces ('f'); 3 vertices, 1 points ('p'), 1 lines ('l')"), std::string::npos) << e;
}

// spider.obj:1560: `vn 0 0 0`.
TEST(ObjCorpus, ZeroNormalIsReplacedByTheFaceNormal) {
  scratch_dir dir;
  std::string path = dir.write("z.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 0\nf 1//1 2//1 3//1\n");
  loaded l = load(path);
  ASSERT_TRUE(l.ok) << l.report.error;
  EXPECT_EQ(l.warnings_with({path + ":4: zero-length normals"}), 1u) << l.all_warnings();
}

// regr_3429812.mtl: `Ni 0` on an opaque material is harmless.
TEST(ObjCorpus, NiZeroIsIgnoredWhenOpaqueAndRefusedWhenTransparent) {
  scratch_dir dir;
  std::string mtl = dir.write("m.mtl", "newmtl trim\nNi 0\nKd 0.5 0.5 0.5\n");
  loaded l = load(dir.write("a.obj", std::string("mtllib m.mtl\nusemtl trim\n") + triangle));
  ASSERT_TRUE(l.ok) << l.report.error;
  EXPECT_EQ(l.material_of_face().ior, 1.0);
  EXPECT_EQ(l.warnings_with({mtl + ":2: Ni 0 of material 'trim' is not a refractive index; ignored"}), 1u)
      << l.all_warnings();
  mtl = dir.write("g.mtl", "newmtl glass\nNi 0\nd 0.2\n");
  l = load(dir.write("g.obj", std::string("mtllib g.mtl\nusemtl glass\n") + triangle));
  EXPECT_NE(l.report.error.find(mtl + ":2: Ni 0 of material 'glass' is not a refractive index"), std::string::npos)
      << l.report.error;
}

// `Ke 1e300` gave NaN pictures, a vertex at 1e13 blamed the fitted camera.
TEST(ObjCorpus, HugeNumbersAreRefusedAtTheirLine) {
  scratch_dir dir;
  std::string mtl = dir.write("m.mtl", "newmtl sun\nKe 1e300 1 1\n");
  loaded l = load(dir.write("a.obj", std::string("mtllib m.mtl\nusemtl sun\n") + triangle));
  EXPECT_NE(l.report.error.find(mtl + ":2: 1e300 is out of range"), std::string::npos) << l.report.error;
  EXPECT_NE(l.report.error.find("1e+09"), std::string::npos) << l.report.error;
  for (const char* far : {"1e13", "-2e9", "1e300", "1e400"}) {
    std::string path = dir.write("far.obj", std::string("v 0 0 0\nv ") + far + " 0 0\nv 0 1 0\nf 1 2 3\n");
    l = load(path);
    EXPECT_NE(l.report.error.find(path + ":2: "), std::string::npos) << l.report.error;
    EXPECT_NE(l.report.error.find("out of range"), std::string::npos) << l.report.error;
  }
  l = load(dir.write("ok.obj", "v 0 0 0\nv 1e9 0 0\nv 0 1e9 0\nf 1 2 3\n"));
  EXPECT_TRUE(l.ok) << l.report.error;
}

// A face with 200,000 corners hung the loader in ear clipping.
TEST(ObjCorpus, FaceWithTooManyCornersIsRefusedAtOnce) {
  scratch_dir dir;
  std::string text;
  const std::size_t n = max_face_corners + 1;
  for (std::size_t i = 0; i < n; ++i) {
    const double a = 6.283185307179586 * i / n;
    text += "v " + std::to_string(std::cos(a)) + " " + std::to_string(std::sin(a)) + " 0\n";
  }
  text += "f";
  for (std::size_t i = 1; i <= n; ++i) text += " " + std::to_string(i);
  text += "\n";
  std::string path = dir.write("big.obj", text);
  const auto start = std::chrono::steady_clock::now();
  loaded l = load(path);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_NE(l.report.error.find(path + ":" + std::to_string(n + 1) + ": face with " + std::to_string(n) +
                                " corners; Bounce takes at most " + std::to_string(max_face_corners)),
            std::string::npos)
      << l.report.error;
  EXPECT_LT(seconds, 5.0);
}

// Warnings said before a failure are kept: they often explain it.
TEST(ObjCorpus, WarningsBeforeAFailureAreKept) {
  scratch_dir dir;
  std::string path = dir.write("a.obj", "mtllib gone.mtl\nv 0 0 0\nv 1 0 0\nf 1 2 7\n");
  loaded l = load(path);
  EXPECT_FALSE(l.ok);
  EXPECT_NE(l.report.error.find(path + ":4: vertex index 7"), std::string::npos) << l.report.error;
  EXPECT_EQ(l.warnings_with({path + ":1: cannot read material library"}), 1u) << l.all_warnings();
}

}  // namespace
}  // namespace bounce
