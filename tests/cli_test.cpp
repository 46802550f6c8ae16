// The `bounce` command line, run as a user would: exit codes and messages.
#include <sys/wait.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "test_files.h"

namespace {

using bounce::testing::scratch_dir;
using bounce::testing::source_path;

struct run_result {
  int code = -1;
  std::string out, err;
};

std::string slurp(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// Runs bounce with `args`, behind `prefix` (e.g. "env -u DISPLAY").
run_result run_env(const std::string& prefix, const std::string& args) {
  scratch_dir dir(".run");
  std::string out = dir.path("stdout"), err = dir.path("stderr");
  std::string command = prefix + " " + std::string(BOUNCE_EXE) + " " + args + " >" + out + " 2>" + err + " </dev/null";
  int status = std::system(command.c_str());
  run_result r;
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.out = slurp(out);
  r.err = slurp(err);
  return r;
}

run_result run(const std::string& args) {
  return run_env("", args);
}

TEST(Cli, HelpListsEveryCommand) {
  run_result r = run("--help");
  EXPECT_EQ(r.code, 0);
  for (const char* command : {"info", "view", "render", "trace", "solve", "bench"})
    EXPECT_NE(r.out.find(command), std::string::npos) << command;
  for (const char* command : {"info", "view", "render", "trace", "solve", "bench"})
    EXPECT_EQ(run(std::string(command) + " --help").code, 0) << command;
}

TEST(Cli, SolvingCommandsShareOptions) {
  for (const char* command : {"view", "render", "trace", "solve"}) {
    run_result r = run(std::string(command) + " --help");
    for (const char* option :
         {"--method", "--max-edge", "--until", "--max-shots", "--time", "--eye", "--target", "--up", "--fov", "--size"})
      EXPECT_NE(r.out.find(option), std::string::npos) << command << " " << option;
  }
}

// --stats is offered only where a file gets written, and every command that
// offers it writes one; the window has no statistics file to write.
TEST(Cli, StatsIsWrittenByEveryCommandThatOffersIt) {
  scratch_dir dir;
  const std::string fast = " --max-edge 150 --until 0.05";
  for (const char* command : {"solve", "render", "trace"}) {
    const std::string stats = dir.path(std::string(command) + ".json");
    const std::string out =
        std::string(command) == "solve" ? "" : " --size 16x16 --out " + dir.path(std::string(command) + ".png");
    run_result r = run(std::string(command) + fast + out + " --stats " + stats);
    ASSERT_EQ(r.code, 0) << command << ": " << r.err;
    nlohmann::json j = nlohmann::json::parse(slurp(stats), nullptr, false);
    ASSERT_FALSE(j.is_discarded()) << command << ": " << slurp(stats);
    const nlohmann::json& radiosity = std::string(command) == "trace" ? j["radiosity"] : j;
    EXPECT_GT(radiosity["shots"].get<int>(), 0) << command;
    EXPECT_GT(radiosity["elements"].get<int>(), 0) << command;
    EXPECT_LE(radiosity["unshot_fraction"].get<double>(), 0.05) << command;
    EXPECT_LT(radiosity["power_balance_error"].get<double>(), 1e-9) << command;
    if (std::string(command) == "trace") {
      EXPECT_EQ(j["trace"]["width"].get<int>(), 16);
    }
  }
  EXPECT_EQ(run("view --stats " + dir.path("view.json")).code, 2);
}

TEST(Cli, InfoJsonOnTheCornellBox) {
  run_result r = run("info " + source_path("assets/cornell_box/cornell_box.json") + " --json");
  ASSERT_EQ(r.code, 0) << r.err;
  nlohmann::json j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["emitting_surfaces"], 1);
  EXPECT_EQ(j["point_lights"], 0);
  EXPECT_EQ(j["surfaces"], j["polygon_meshes"]);
  EXPECT_GE(j["triangles"].get<int>(), 2 * j["polygons"].get<int>() - 8);
  EXPECT_DOUBLE_EQ(j["bounds"]["max"][1].get<double>(), 548.8);
  EXPECT_DOUBLE_EQ(j["camera"]["fov"].get<double>(), 39.3);
}

TEST(Cli, InfoOnEveryShippedScene) {
  for (const char* path : {"assets/furnace/furnace.json", "assets/whitted/whitted.json", "assets/teapot/teapot.json",
                           "assets/shapes/shapes.json", "assets/cornell_box/cornell_box.obj"}) {
    run_result r = run("info --json " + source_path(path));
    ASSERT_EQ(r.code, 0) << path << ": " << r.err;
    nlohmann::json j = nlohmann::json::parse(r.out);
    EXPECT_GT(j["triangles"].get<int>(), 0) << path;
    EXPECT_GT(j["emitting_surfaces"].get<int>() + j["point_lights"].get<int>(), 0) << path;
  }
  nlohmann::json teapot = nlohmann::json::parse(run("info --json " + source_path("assets/teapot/teapot.json")).out);
  EXPECT_EQ(teapot["bezier_surfaces"], 1);
  EXPECT_EQ(teapot["patches"].get<int>() >= 32, true);
  nlohmann::json whitted = nlohmann::json::parse(run("info --json " + source_path("assets/whitted/whitted.json")).out);
  EXPECT_EQ(whitted["spheres"], 2);
  EXPECT_EQ(whitted["point_lights"], 1);
}

TEST(Cli, FinerMaxEdgeMakesMoreTriangles) {
  std::string path = source_path("assets/teapot/teapot.json");
  nlohmann::json coarse = nlohmann::json::parse(run("info --json --max-edge 1 " + path).out);
  nlohmann::json fine = nlohmann::json::parse(run("info --json --max-edge 0.25 " + path).out);
  EXPECT_GT(fine["triangles"].get<int>(), coarse["triangles"].get<int>());
}

TEST(Cli, BadSceneExitsOneNamingTheFile) {
  run_result r = run("info /nonexistent/box.json");
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("/nonexistent/box.json"), std::string::npos) << r.err;

  scratch_dir dir;
  std::string path = dir.write("bad.obj", "v 0 0 0\nv 1 x 0\n");
  r = run("info " + path);
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find(path + ":2:"), std::string::npos) << r.err;
}

TEST(Cli, WarningsGoToStandardError) {
  scratch_dir dir;
  dir.write("m.mtl", "newmtl e\nKe 1 1 1\nKa 0 0 0\n");
  std::string path =
      dir.write("w.obj", "mtllib m.mtl\nusemtl e\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 2 0 0\nf 1 2 3\nf 1 2 4\n");
  run_result r = run("info " + path);
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.err.find("warning: " + path + ":8: degenerate face"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("1 degenerate face(s) dropped"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("'Ka' is not used"), std::string::npos) << r.err;
}

TEST(Cli, UsageErrorsExitTwo) {
  EXPECT_EQ(run("frobnicate").code, 2);
  EXPECT_EQ(run("info --max-edge -1").code, 2);
  EXPECT_EQ(run("solve --method magic").code, 2);
  EXPECT_EQ(run("solve --until 2").code, 2);
  EXPECT_EQ(run("info a.json b.json").code, 2);
}

TEST(Cli, CameraOverridesAreChecked) {
  run_result r = run("render --eye 1,2");
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("--eye: expected x,y,z"), std::string::npos) << r.err;
  r = run("render --size 640by480");
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("--size: expected WxH"), std::string::npos) << r.err;
  r = run("render --size 0x480");
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("camera: size 0x480"), std::string::npos) << r.err;
  r = run("trace --fov 200");
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("--fov"), std::string::npos) << r.err;
  r = run("view --eye 278,273,0 --target 278,273,0");
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("eye and target are the same point"), std::string::npos) << r.err;
}

// The quick suite as a smoke test (its times are not checked): every
// output is written, parses, and holds every scene and method with a
// measured, finite error.
TEST(Cli, BenchQuickSuiteWritesEveryOutputForEveryMethod) {
  scratch_dir dir;
  run_result r = run("bench --suite quick --out " + dir.path("bench"));
  ASSERT_EQ(r.code, 0) << r.out << r.err;
  const nlohmann::json results = nlohmann::json::parse(slurp(dir.path("bench/bench.json")));
  std::set<std::string> methods, scenes;
  std::size_t points = 0;
  for (const auto& c : results["cases"]) {
    EXPECT_EQ(c["error"], "") << c.dump();
    EXPECT_GT(c["peak_mib"].get<double>(), 1.0);
    EXPECT_GT(c["cpu_seconds"].get<double>(), 0.0);
    scenes.insert(c["scene"].get<std::string>());
    for (const auto& curve : c["curves"]) {
      methods.insert(curve["method"].get<std::string>());
      ASSERT_FALSE(curve["points"].empty()) << curve["label"];
      for (const auto& p : curve["points"]) {
        ++points;
        EXPECT_GT(p["seconds"].get<double>(), 0.0);
        if (!c["growth"].get<bool>()) {
          ASSERT_TRUE(p["error"].is_number()) << curve["label"];
          EXPECT_GE(p["error"].get<double>(), 0.0);
          EXPECT_LT(p["error"].get<double>(), 10.0) << curve["label"];
        }
      }
    }
  }
  for (const char* m : {"raycast", "hemicube", "reference-lu", "gauss-seidel", "path", "two-pass"})
    EXPECT_TRUE(methods.count(m)) << m;
  for (const char* s :
       {"cornell", "occluders", "furnace", "furnace-0.99", "sphere", "squares-perpendicular", "squares-parallel"}) {
    EXPECT_TRUE(scenes.count(s)) << s;
    EXPECT_EQ(slurp(dir.path("bench/" + std::string(s) + ".svg")).rfind("<svg", 0), 0u) << s;
  }
  // One CSV row per measured point, under a header.
  const std::string csv = slurp(dir.path("bench/bench.csv"));
  EXPECT_EQ(std::size_t(std::count(csv.begin(), csv.end(), '\n')), points + 1);
  const std::string md = slurp(dir.path("bench/bench.md"));
  EXPECT_NE(md.find("## Targets"), std::string::npos);
  EXPECT_NE(md.find("## Growth with element count"), std::string::npos);
  EXPECT_NE(md.find("Fitted exponents"), std::string::npos);
  // The reference picture is cached and reused by the next run.
  EXPECT_TRUE(std::filesystem::exists(dir.path("bench/reference/cornell-64px-1024spp.pfm")));
}

TEST(Cli, BenchRejectsAnUnknownSuite) {
  run_result r = run("bench --suite huge");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("--suite"), std::string::npos) << r.err;
}

TEST(Cli, TraceWritesPngAndPfmAndReportsRays) {
  scratch_dir dir;
  run_result r = run("trace --size 48x36 --max-edge 150 --until 0.05 --spp 2 --out " + dir.path("a.png") + " --pfm " +
                     dir.path("a.pfm"));
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(std::filesystem::exists(dir.path("a.png")));
  EXPECT_TRUE(std::filesystem::exists(dir.path("a.pfm")));
  EXPECT_NE(r.out.find("radiosity: "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("3456 primary"), std::string::npos) << r.out;  // 48 x 36 x 2
  r = run("trace --integrator path --size 16x16 --spp 2 --out " + dir.path("b.png"));
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(r.out.find("radiosity: "), std::string::npos) << r.out;  // no radiosity pass
  r = run("trace --no-radiosity --size 16x16 --out " + dir.path("c.png"));
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("one pass: ambient irradiance"), std::string::npos) << r.out;
}

TEST(Cli, TraceRejectsBadOptionsAndFiles) {
  scratch_dir dir;
  EXPECT_EQ(run("trace --integrator photon").code, 2);
  EXPECT_EQ(run("trace --spp 0").code, 2);
  EXPECT_EQ(run("trace --direct maybe").code, 2);
  run_result r = run("trace " + dir.path("missing.json"));
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("missing.json"), std::string::npos) << r.err;
  r = run("trace --size 8x8 --max-edge 200 --until 0.5 --out " + dir.path("no/such/folder/a.png"));
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("a.png"), std::string::npos) << r.err;
}

TEST(Cli, CompareReportsErrorsBetweenPictures) {
  scratch_dir dir;
  ASSERT_EQ(
      run("trace --integrator path --size 16x16 --spp 4 --out " + dir.path("a.png") + " --pfm " + dir.path("a.pfm"))
          .code,
      0);
  run_result r = run("compare " + dir.path("a.pfm") + " " + dir.path("a.pfm") + " --downsample 2");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("relative RMSE 0.00000"), std::string::npos) << r.out;
  r = run("compare " + dir.path("a.pfm") + " " + dir.path("missing.pfm"));
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("missing.pfm"), std::string::npos) << r.err;
}

TEST(Cli, ViewWithoutADisplaySaysSo) {
  run_result r = run_env("env -u DISPLAY", "view --max-edge 200");
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("no display"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("bounce render"), std::string::npos) << r.err;
}

TEST(Cli, SolveWritesStatsAndPly) {
  scratch_dir dir;
  const std::string stats = dir.path("stats.json"), ply = dir.path("box.ply");
  run_result r = run("solve --max-edge 150 --until 0.05 --stats " + stats + " --ply " + ply);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("mesh: "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("done: "), std::string::npos) << r.out;
  nlohmann::json j = nlohmann::json::parse(slurp(stats));
  for (const char* key : {"elements", "vertices", "shots", "unshot_fraction", "seconds", "rays"})
    EXPECT_TRUE(j.contains(key)) << key;
  EXPECT_LE(j["unshot_fraction"].get<double>(), 0.05);
  EXPECT_GT(j["rays"].get<double>(), 0.0);
  // The PLY header names the radiosity and colour properties, and the
  // counts match the statistics.
  const std::string text = slurp(ply);
  for (const char* line : {"ply", "format ascii 1.0", "property float radiosity_r", "property float radiosity_g",
                           "property float radiosity_b", "property uchar red", "property uchar green",
                           "property uchar blue", "end_header"})
    EXPECT_NE(text.find(std::string(line) + "\n"), std::string::npos) << line;
  EXPECT_NE(text.find("element vertex " + std::to_string(j["vertices"].get<int>()) + "\n"), std::string::npos);
  EXPECT_NE(text.find("element face " + std::to_string(j["elements"].get<int>()) + "\n"), std::string::npos);
}

TEST(Cli, AdaptiveMeshingRefinesInSolveRenderAndTrace) {
  scratch_dir dir;
  const std::string stats = dir.path("stats.json"), ply = dir.path("refined.ply");
  run_result r = run("solve --adaptive --max-edge 150 --until 0.02 --stats " + stats + " --ply " + ply);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("a priori refinement: "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("refinement at unshot "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("adaptive mesh: "), std::string::npos) << r.out;
  nlohmann::json j = nlohmann::json::parse(slurp(stats));
  EXPECT_TRUE(j["adaptive"].get<bool>());
  ASSERT_FALSE(j["refinement_passes"].empty());
  const auto& first = j["refinement_passes"][0];
  EXPECT_GT(first["elements_after"].get<int>(), first["elements_before"].get<int>());
  EXPECT_EQ(j["elements"].get<int>(), j["refinement_passes"].back()["elements_after"].get<int>());
  // The PLY is the refined mesh.
  EXPECT_NE(slurp(ply).find("element face " + std::to_string(j["elements"].get<int>()) + "\n"), std::string::npos);

  r = run("render --adaptive --max-edge 150 --until 0.02 --wireframe --size 64x64 --out " + dir.path("a.png"));
  ASSERT_EQ(r.code, 0) << r.err;
  r = run("trace --adaptive --max-edge 150 --until 0.02 --size 32x32 --out " + dir.path("t.png"));
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("radiosity: "), std::string::npos) << r.out;

  // A minimum edge the mesher cannot honour is a clear error, not a hang.
  r = run("solve --adaptive --max-edge 150 --min-edge 0.01");
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("--min-edge"), std::string::npos) << r.err;
}

TEST(Cli, SolveStopsAtTheShotLimitAndComparesWithTheReference) {
  scratch_dir dir;
  const std::string stats = dir.path("stats.json");
  run_result r = run("solve --max-edge 200 --max-shots 7 --stats " + stats);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(nlohmann::json::parse(slurp(stats))["shots"], 7);
  r = run("solve " + source_path("assets/furnace/furnace.json") + " --max-edge 1 --until 1e-7 --reference --stats " +
          stats);
  ASSERT_EQ(r.code, 0) << r.err;
  nlohmann::json j = nlohmann::json::parse(slurp(stats));
  EXPECT_LT(j["reference"]["max_relative_difference"].get<double>(), 1e-5);
  EXPECT_LT(j["reference"]["residual_lu"].get<double>(), 1e-12);
}

TEST(Cli, SolveRefusesAbsurdMeshes) {
  run_result r = run("solve --max-edge 0.001");
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("use a larger --max-edge"), std::string::npos) << r.err;
}

}  // namespace
