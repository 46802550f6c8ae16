// The `bounce` command line, run as a user would: exit codes and messages.
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <csignal>
#include <cstdio>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <tuple>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "test_files.h"

namespace {

using bounce::test_support::read_text;
using bounce::test_support::scratch_dir;
using bounce::test_support::source_path;

struct run_result {
  int code = -1;
  std::string out, err;
};

// Runs bounce with `args`, behind `prefix` (e.g. "env -u DISPLAY").
run_result run_env(const std::string& prefix, const std::string& args) {
  scratch_dir dir(".run");
  std::string out = dir.path("stdout"), err = dir.path("stderr");
  std::string command = prefix + " " + std::string(BOUNCE_EXE) + " " + args + " >" + out + " 2>" + err + " </dev/null";
  int status = std::system(command.c_str());
  run_result r;
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.out = read_text(out);
  r.err = read_text(err);
  return r;
}

run_result run(const std::string& args) {
  return run_env("", args);
}

TEST(Cli, HelpListsEveryCommand) {
  run_result r = run("--help");
  EXPECT_EQ(r.code, 0);
  for (const char* command : {"info", "view", "render", "trace", "solve", "bake", "bench"})
    EXPECT_NE(r.out.find(command), std::string::npos) << command;
  for (const char* command : {"info", "view", "render", "trace", "solve", "bake", "bench"})
    EXPECT_EQ(run(std::string(command) + " --help").code, 0) << command;
}

TEST(Cli, SolvingCommandsShareOptions) {
  for (const char* command : {"view", "render", "trace", "solve"}) {
    run_result r = run(std::string(command) + " --help");
    for (const char* option : {"--method", "--max-edge", "--until", "--max-steps", "--time"})
      EXPECT_NE(r.out.find(option), std::string::npos) << command << " " << option;
    // The camera options where a picture is made; solve makes none.
    for (const char* option : {"--eye", "--target", "--up", "--fov", "--size"})
      EXPECT_EQ(r.out.find(option) != std::string::npos, std::string(command) != "solve") << command << " " << option;
  }
  EXPECT_EQ(run("solve --size 8x8").code, 2);
}

// --stats is offered only where a file gets written, and every command that
// offers it writes one; the window has no statistics file to write.
TEST(Cli, StatsIsWrittenByEveryCommandThatOffersIt) {
  scratch_dir dir;
  for (const char* solver : {"hierarchical", "progressive"})
    for (const char* command : {"solve", "render", "trace"}) {
      const std::string fast = std::string(" --max-edge 150 --until 0.05 --solver ") + solver +
                               (std::string(solver) == "hierarchical" ? " --link-tolerance 1e-3" : "");
      const std::string stats = dir.path(std::string(command) + ".json");
      const std::string out =
          std::string(command) == "solve" ? "" : " --size 16x16 --out " + dir.path(std::string(command) + ".png");
      run_result r = run(std::string(command) + fast + out + " --stats " + stats);
      ASSERT_EQ(r.code, 0) << command << ": " << r.err;
      nlohmann::json j = nlohmann::json::parse(read_text(stats), nullptr, false);
      ASSERT_FALSE(j.is_discarded()) << command << ": " << read_text(stats);
      const nlohmann::json& radiosity = std::string(command) == "trace" ? j["radiosity"] : j;
      EXPECT_GT(radiosity["steps"].get<int>(), 0) << command;
      EXPECT_GT(radiosity["elements"].get<int>(), 0) << command;
      EXPECT_LE(radiosity["remaining"].get<double>(), 0.05) << command;
      EXPECT_EQ(radiosity["solver"].get<std::string>(), solver) << command;
      if (std::string(solver) == "progressive") {
        EXPECT_LT(radiosity["power_balance_error"].get<double>(), 1e-9) << command;
      } else {
        EXPECT_GT(radiosity["hierarchical"]["links"].get<int>(), 0) << command;
        EXPECT_EQ(radiosity["hierarchical"]["link_bytes"].get<int>(),
                  16 * radiosity["hierarchical"]["links"].get<int>())
            << command;
        EXPECT_TRUE(radiosity["hierarchical"]["links_final"].get<bool>()) << command;
      }
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
  // The element sizes the solvers start from, as the window shows them:
  // 1/10 of the diagonal for the default (hierarchical), 1/24 progressive.
  double diagonal = 0.0;
  for (int axis = 0; axis < 3; ++axis) {
    const double extent = j["bounds"]["max"][axis].get<double>() - j["bounds"]["min"][axis].get<double>();
    diagonal += extent * extent;
  }
  diagonal = std::sqrt(diagonal);
  EXPECT_NEAR(j["element_size"]["hierarchical"].get<double>(), diagonal / 10.0, 1e-6 * diagonal);
  EXPECT_NEAR(j["element_size"]["progressive"].get<double>(), diagonal / 24.0, 1e-6 * diagonal);
  EXPECT_DOUBLE_EQ(j["max_edge"].get<double>(), j["element_size"]["hierarchical"].get<double>());
  // What a solve needs: 2 kB an element over a 64 MB base, the links' limit
  // (32 million of 16 bytes), and the room, with what bounds it.
  const nlohmann::json& memory = j["memory"];
  EXPECT_DOUBLE_EQ(memory["max_edge"].get<double>(), j["element_size"]["hierarchical"].get<double>());
  EXPECT_GT(memory["elements"].get<double>(), 500.0);
  EXPECT_DOUBLE_EQ(memory["solve_bytes"].get<double>(), 64e6 + 2000.0 * memory["elements"].get<double>());
  EXPECT_DOUBLE_EQ(memory["link_bytes_max"].get<double>(), 512e6);
  EXPECT_GT(memory["available_bytes"].get<double>(), 1e8);
  EXPECT_FALSE(memory["available_bound"].get<std::string>().empty());
  // The text says the same.
  r = run("info " + source_path("assets/cornell_box/cornell_box.json"));
  EXPECT_NE(r.out.find("memory:     at least 6"), std::string::npos) << r.out;
}

TEST(Cli, InfoOnEveryShippedScene) {
  for (const char* path :
       {"assets/furnace/furnace.json", "assets/whitted/whitted.json", "assets/teapot/teapot.json",
        "assets/shapes/shapes.json", "assets/cornell_box/cornell_box.obj", "assets/textured_room/textured_room.json",
        "assets/cornell_caustics/cornell_caustics.json", "assets/glass_on_table/glass_on_table.json"}) {
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

TEST(Cli, GeneratedScenesByName) {
  run_result r = run("info --json generated:interior-10k");
  ASSERT_EQ(r.code, 0) << r.err;
  nlohmann::json j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["scene"], "generated:interior-10k");
  EXPECT_NEAR(j["triangles"].get<double>(), 10'000.0, 100.0);
  EXPECT_GT(j["emitting_surfaces"].get<int>(), 0);
  scratch_dir dir;
  r = run("render generated:box-room-2 --size 16x16 --max-steps 3 --out " + dir.path("box.png"));
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(std::filesystem::exists(dir.path("box.png")));
  // An unknown name is an input error naming it, like a missing file.
  r = run("render generated:box-room-0 --size 16x16 --out " + dir.path("no.png"));
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("generated:box-room-0: procedural scene 'box-room-0'"), std::string::npos) << r.err;
  r = run("info generated:palace");
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("unknown procedural scene 'palace'"), std::string::npos) << r.err;
  EXPECT_NE(run("info --help").out.find("generated:NAME"), std::string::npos);
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
  EXPECT_NE(r.err.find("'Ka' is not used"), std::string::npos) << r.err;
}

// Warnings of one kind come as one line with their count, not one line each.
TEST(Cli, ManyWarningsOfAKindAreOneLine) {
  scratch_dir dir;
  std::string obj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 2 0 0\nf 1 2 3\n";
  for (int i = 0; i < 500; ++i) obj += "f 1 2 4\n";  // lines 6 to 505: zero area
  const std::string path = dir.write("many.obj", obj);
  run_result r = run("info " + path);
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.err.find("warning: degenerate face (zero area) dropped: 500 times (first at " + path + ":6, last at " +
                       path + ":505)"),
            std::string::npos)
      << r.err;
  EXPECT_LT(std::count(r.err.begin(), r.err.end(), '\n'), 5) << r.err;
}

TEST(Cli, UsageErrorsExitTwo) {
  // Neither a command nor a file: a typo, not a missing scene.
  run_result r = run("frobnicate");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("'frobnicate' is neither a command nor a scene file"), std::string::npos) << r.err;
  EXPECT_EQ(run("info --max-edge -1").code, 2);
  EXPECT_EQ(run("solve --method magic").code, 2);
  EXPECT_EQ(run("solve --until 2").code, 2);
  EXPECT_EQ(run("info a.json b.json").code, 2);
}

// A bad camera override is a bad command line: exit 2, the option named.
TEST(Cli, CameraOverridesAreChecked) {
  const std::pair<const char*, const char*> cases[] = {
      {"render --eye 1,2", "--eye: expected x,y,z"},
      {"render --eye 1,nan,3", "--eye: expected x,y,z (three finite numbers)"},
      {"render --target inf,0,0", "--target: expected x,y,z"},
      {"render --up 0,1e400,0", "--up: expected x,y,z"},
      {"render --eye 2e9,0,0", "--eye: coordinate 2e+09 is out of range (limit 1e+09"},
      {"render --size 640by480", "--size: expected WxH"},
      {"render --size 0x480", "--size: size 0x480 must be from 1 to 16384"},
      {"render --size 640x-1", "--size: size 640x-1 must be from 1 to 16384"},
      {"trace --size 20000x10", "--size: size 20000x10 must be from 1 to 16384"},
      {"view --size 16384x16384", "more than the limit of 33554432"},
      {"trace --fov 200", "--fov: 200 is out of range: must be in [0.001, 179]"},
      {"render --fov 1e-300", "--fov: 1e-300 is out of range: must be in [0.001, 179]"},
      {"trace --fov 0", "--fov: 0 is out of range"},
      {"trace --fov nan", "--fov: 'nan' is not a finite number"},
      {"view --eye 278,273,0 --target 278,273,0", "eye and target are the same point"},
  };
  for (const auto& [args, message] : cases) {
    run_result r = run(args);
    EXPECT_EQ(r.code, 2) << args;
    EXPECT_NE(r.err.find(message), std::string::npos) << args << ": " << r.err;
  }
}

// The limits apply to a scene file's own camera size too (it has no --size).
TEST(Cli, SceneCameraSizeIsLimited) {
  scratch_dir dir;
  const std::string path = dir.write("big.json", R"({"materials": {"w": {"rho": [0.5,0.5,0.5]}},
        "surfaces": [{"sphere": {"center": [0,0,0], "radius": 1}, "material": "w"}],
        "lights": [{"position": [0,5,0], "intensity": [1,1,1]}],
        "camera": {"eye": [0,0,5], "target": [0,0,0], "size": [16384, 16384]}})");
  run_result r = run("trace " + path + " --integrator path");
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find(path + ": camera.size: size 16384x16384 has 268435456 pixels"), std::string::npos) << r.err;
  // --size replaces it; the smallest picture is fine.
  r = run("trace " + path + " --integrator path --size 1x1 --out " + dir.path("a.png"));
  EXPECT_EQ(r.code, 0) << r.err;
}

// Every floating-point option refuses NaN, infinities and literals beyond
// a double (CLI11's own checks let NaN through: --exposure nan gave a black
// picture, --patch-edge nan an unsubdivided mesh).
TEST(Cli, EveryFloatingPointOptionRefusesNonFiniteNumbers) {
  const char* options[] = {"solve --max-edge",
                           "solve --until",
                           "solve --time",
                           "solve --patch-edge",
                           "render --exposure",
                           "trace --exposure",
                           "trace --fov",
                           "view --fov",
                           "info --max-edge",
                           "solve --adaptive --tolerance",
                           "solve --adaptive --min-edge",
                           "trace --no-radiosity --ambient",
                           "compare a.pfm b.pfm --exclude-above"};
  // Every option with NaN; every non-finite spelling with one of them (all
  // share one check, and a process costs seconds under the sanitizers).
  std::vector<std::pair<std::string, std::string>> cases;
  for (const char* option : options) cases.emplace_back(option, "nan");
  for (const char* value : {"inf", "-inf", "1e400", "NaN"}) cases.emplace_back("render --exposure", value);
  for (const auto& [option, value] : cases) {
    run_result r = run(option + " " + value);
    EXPECT_EQ(r.code, 2) << option << " " << value;
    const std::string name = option.substr(option.rfind(' ') + 1);
    EXPECT_NE(r.err.find(name + ": '" + value + "' is not a finite number"), std::string::npos)
        << option << " " << value << ": " << r.err;
  }
}

// Range errors are short: the limits in %g, not DBL_MAX's 309 digits.
TEST(Cli, RangeErrorsAreShort) {
  const std::pair<const char*, const char*> cases[] = {
      {"solve --max-edge -1", "--max-edge: -1 is out of range: must be > 0"},
      {"solve --time -1", "--time: -1 is out of range: must be >= 0"},
      {"solve --patch-edge -0.5", "--patch-edge: -0.5 is out of range: must be >= 0"},
      {"solve --until 2", "--until: 2 is out of range: must be in [0, 1]"},
      {"render --exposure 0", "--exposure: 0 is out of range: must be in [1e-09, 1e+09]"},
      {"render --exposure 1e10", "--exposure: 1e+10 is out of range: must be in [1e-09, 1e+09]"},
      {"trace --no-radiosity --ambient 1e10", "--ambient: 1e+10 is out of range: must be in [0, 1e+09]"},
      {"solve --max-steps -1", "--max-steps: '-1' is not a whole number"},
      {"trace --seed -1", "--seed: '-1' is not a whole number"},
  };
  for (const auto& [args, message] : cases) {
    run_result r = run(args);
    EXPECT_EQ(r.code, 2) << args;
    EXPECT_NE(r.err.find(message), std::string::npos) << args << ": " << r.err;
    EXPECT_LT(r.err.size(), 200u) << args << ": " << r.err;
  }
}

// An option that a combination would ignore is refused, naming it, before
// anything is loaded or solved.
TEST(Cli, OptionsThatWouldBeIgnoredAreRefused) {
  const std::pair<const char*, const char*> cases[] = {
      {"render --frame-every 3", "--frame-every requires --frames"},
      {"view --screenshot a.png", "--screenshot requires --frames"},
      {"view --still a.png", "--still requires --frames"},
      {"view --exit", "--exit requires --frames"},
      {"solve --tolerance 0.3", "--tolerance requires --adaptive"},
      {"render --solver progressive --min-edge 5", "--min-edge applies to --solver hierarchical or --adaptive only"},
      {"solve --method hemicube --rays 4", "--rays applies to --method raycast only"},
      {"trace --method hemicube --full-rays", "--full-rays applies to --method raycast only"},
      {"view --hemicube 64", "--hemicube applies to --method hemicube only"},
      {"solve --method hemicube --ray-baseline", "--ray-baseline applies to --method raycast only"},
      {"trace --integrator path --light-samples 3",
       "--light-samples applies to --integrator whitted, twopass and ppm only"},
      {"trace --integrator path --direct radiosity", "--direct applies to --integrator whitted only"},
      {"trace --integrator path --no-radiosity", "--no-radiosity applies to --integrator whitted only"},
      {"trace --integrator path --max-edge 100 --until 0.1", "--max-edge, --until: the path tracer makes no radiosity"},
      {"trace --ambient 0.5", "--ambient applies with --no-radiosity only"},
      {"trace --no-radiosity --direct rays", "--direct applies to two-pass stills only"},
      {"trace --no-radiosity --ambient 0.5 --max-steps 9", "--max-steps: with --no-radiosity and --ambient"},
      {"trace --spp 4 --adaptive-spp 4", "--adaptive-spp 4 must be more than --spp 4"},
      {"trace --passes 4", "--passes applies to --integrator ppm only"},
      {"trace --integrator twopass --passes 4", "--passes applies to --integrator ppm only"},
      {"trace --photons 1000", "--photons applies to --integrator twopass and ppm only"},
      {"trace --integrator path --gather-rays 64", "--gather-rays applies to --integrator twopass and ppm only"},
      {"trace --integrator twopass --direct radiosity", "--direct applies to --integrator whitted only (twopass"},
      {"trace --integrator ppm --no-radiosity", "--no-radiosity applies to --integrator whitted only (ppm"},
      {"trace --integrator ppm --adaptive-spp 64", "--adaptive-spp does not apply to --integrator ppm"},
      {"trace --integrator path --spp 8 --adaptive-spp 2", "--adaptive-spp 2 must be more than --spp 8"},
      {"bench --report-only --suite full", "--suite excludes --report-only"},
      {"solve --solver hierarchical --adaptive", "--adaptive applies to --solver progressive only"},
      {"render --solver hierarchical --rays 4 --patch-edge 50",
       "--patch-edge, --rays apply to --solver progressive only"},
      {"solve --solver progressive --link-tolerance 1e-4", "--link-tolerance applies to --solver hierarchical only"},
      {"trace --adaptive --link-tolerance 1e-4", "--link-tolerance applies to --solver hierarchical only"},
      {"solve --solver hierarchical --reference", "--reference applies to --solver progressive only"},
      {"solve --reference --link-tolerance 1e-4", "--link-tolerance applies to --solver hierarchical only"},
      {"render --solver progressive --view-independent", "--view-independent applies to --solver hierarchical only"},
      {"trace --adaptive --view-independent", "--view-independent applies to --solver hierarchical only"},
      {"view --solver progressive --view-independent", "--view-independent applies to --solver hierarchical only"},
  };
  for (const auto& [args, message] : cases) {
    run_result r = run(args);
    EXPECT_EQ(r.code, 2) << args;
    EXPECT_NE(r.err.find(message), std::string::npos) << args << ": " << r.err;
  }
}

// render hands its camera to the solver, and the statistics say so;
// --view-independent keeps it out; solve has no camera to hand.
TEST(Cli, RenderSaysItsCameraLedTheSolve) {
  scratch_dir dir;
  for (const bool led : {false, true}) {
    const std::string stats = dir.path(led ? "led.json" : "plain.json");
    const run_result r = run(std::string("render --size 64x64 --until 0.05 --out ") + dir.path("x.png") + " --stats " +
                             stats + (led ? "" : " --view-independent"));
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_EQ(nlohmann::json::parse(read_text(stats))["hierarchical"]["view_led"], led);
  }
  const std::string stats = dir.path("solve.json");
  ASSERT_EQ(run("solve --until 0.05 --stats " + stats).code, 0);
  EXPECT_EQ(nlohmann::json::parse(read_text(stats))["hierarchical"]["view_led"], false);
}

// --mirror-depth sets how many planar mirrors the hierarchical solver's
// links pass: the hall's four mirror walls make 4 chains of one mirror,
// 4 + 4 x 3 of up to two and 4 + 12 + 36 of up to three; 0 leaves the
// mirrors to traced paths. Past the images' limit it is refused.
TEST(Cli, MirrorDepthSetsTheChainsOfPlanarMirrors) {
  scratch_dir dir;
  const std::string scene = source_path("assets/mirror_hall/mirror_hall.json");
  for (const auto& [depth, chains] : {std::pair{0, 0}, {1, 4}, {2, 16}, {3, 52}}) {
    const std::string stats = dir.path("d" + std::to_string(depth) + ".json");
    const run_result r = run("solve " + scene + " --mirror-depth " + std::to_string(depth) +
                             " --link-tolerance 1e-3 --until 0.2 --stats " + stats);
    ASSERT_EQ(r.code, 0) << r.err;
    const auto h = nlohmann::json::parse(read_text(stats))["hierarchical"];
    EXPECT_EQ(h["mirror_chains"], chains) << depth;
    EXPECT_EQ(h["mirror_links"].get<int>() > 0, depth > 0) << depth;
  }
  const run_result r = run("solve " + scene + " --mirror-depth 5");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("--mirror-depth"), std::string::npos) << r.err;
}

// --max-edge with --no-radiosity sets the coarse solution the ambient term
// comes from (it was replaced by twice the default). View-independent, as
// solve is: a camera-led solve splits other elements.
TEST(Cli, OnePassAmbientSolutionTakesTheMaxEdge) {
  scratch_dir dir;
  const std::string fast = " --view-independent --until 0.2 --size 8x8 --out " + dir.path("a.png");
  run_result r = run("trace --no-radiosity --max-edge 150" + fast + " --stats " + dir.path("a.json"));
  ASSERT_EQ(r.code, 0) << r.err;
  r = run("solve --max-edge 150 --until 0.2 --stats " + dir.path("b.json"));
  ASSERT_EQ(r.code, 0) << r.err;
  const auto one_pass = nlohmann::json::parse(read_text(dir.path("a.json")));
  const auto solved = nlohmann::json::parse(read_text(dir.path("b.json")));
  EXPECT_EQ(one_pass["radiosity"]["elements"], solved["elements"]);
  r = run("trace --no-radiosity" + fast + " --stats " + dir.path("c.json"));
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(nlohmann::json::parse(read_text(dir.path("c.json")))["radiosity"]["elements"], solved["elements"]);
}

// The element-count estimate of a tiny --max-edge is computed in double.
TEST(Cli, TinyMaxEdgeReportsAPositiveEstimate) {
  run_result r = run("solve --max-edge 1e-9");
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("max edge 1e-09 would make about "), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("about -"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("e+24 elements (limit 5000000)"), std::string::npos) << r.err;
  r = run("solve --max-edge 1e-200");
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("would make more than 1e+308 elements"), std::string::npos) << r.err;
}

// Warnings said before a failure come first, then the error.
TEST(Cli, WarningsBeforeTheError) {
  scratch_dir dir;
  dir.write("m.mtl", "newmtl e\nKe 1 1 1\nKa 0 0 0\n");
  const std::string path = dir.write("w.obj", "mtllib m.mtl\nusemtl e\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nv 1 x 0\n");
  run_result r = run("info " + path);
  EXPECT_EQ(r.code, 1);
  const std::size_t warning = r.err.find("warning: "), error = r.err.find("error: " + path + ":7:");
  ASSERT_NE(warning, std::string::npos) << r.err;
  ASSERT_NE(error, std::string::npos) << r.err;
  EXPECT_LT(warning, error) << r.err;
}

// An emitter facing away from everything: every command that loads says so.
TEST(Cli, EmitterFacingAwayIsWarnedAbout) {
  scratch_dir dir;
  const std::string path = dir.write("away.json", R"({"materials": {"w": {"rho": [0.5,0.5,0.5]}, "e": {"ke": [9,9,9]}},
      "surfaces": [{"name": "floor", "polygon": [[0,0,0],[0,0,1],[1,0,1],[1,0,0]], "material": "w"},
                   {"name": "lamp", "polygon": [[0.4,1,0.4],[0.4,1,0.6],[0.6,1,0.6],[0.6,1,0.4]], "material": "e"}]})");
  const std::string commands[] = {"info", "solve --max-steps 5",
                                  "render --max-steps 5 --size 8x8 --out " + dir.path("r.png"),
                                  "trace --max-steps 5 --size 8x8 --out " + dir.path("t.png")};
  for (const std::string& command : commands) {
    run_result r = run(command + " " + path);
    EXPECT_EQ(r.code, 0) << command << ": " << r.err;
    EXPECT_NE(r.err.find("warning: " + path +
                         ": surface 'lamp' emits (material 'e') but faces away from every other "
                         "surface: its light reaches nothing"),
              std::string::npos)
        << command << ": " << r.err;
  }
}

// compare refuses pictures it cannot measure instead of printing 0 or -nan.
TEST(Cli, CompareRefusesNonFinitePixelsAndOversizedDownsampling) {
  scratch_dir dir;
  // 4x2 PFM (rows bottom to top); the second value of the top row's first pixel is NaN.
  auto pfm = [&](const std::string& name, float bad) {
    std::string bytes = "PF\n4 2\n-1.0\n";
    std::vector<float> values(4 * 2 * 3, 0.5f);
    values[4 * 3 + 1] = bad;  // second row in the file: the top row
    bytes.append(reinterpret_cast<const char*>(values.data()), values.size() * sizeof(float));
    return dir.write(name, bytes);
  };
  const std::string good = pfm("good.pfm", 0.5f), nan = pfm("nan.pfm", NAN), inf = pfm("inf.pfm", INFINITY);
  run_result r = run("compare " + good + " " + good);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("relative RMSE 0.00000"), std::string::npos) << r.out;
  for (const std::string& bad : {nan, inf}) {
    r = run("compare " + bad + " " + good);
    EXPECT_EQ(r.code, 1);
    EXPECT_NE(r.err.find("error: " + bad + ": pixel (0,0) is not a finite number"), std::string::npos) << r.err;
    r = run("compare " + good + " " + bad);
    EXPECT_EQ(r.code, 1);
    EXPECT_NE(r.err.find("error: " + bad + ": pixel (0,0)"), std::string::npos) << r.err;
  }
  r = run("compare " + good + " " + good + " --downsample 3");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("--downsample 3 is larger than the pictures (4x2)"), std::string::npos) << r.err;
  EXPECT_EQ(run("compare " + good + " " + good + " --downsample 2").code, 0);
}

// The quick suite as a smoke test (its times are not checked): every
// output is written, parses, and holds every scene, solver and method with
// a measured, finite error; --threads reaches every run.
TEST(Cli, BenchQuickSuiteWritesEveryOutputForEveryMethod) {
  scratch_dir dir;
  run_result r = run("bench --suite quick --threads 1 --out " + dir.path("bench"));
  ASSERT_EQ(r.code, 0) << r.out << r.err;
  const nlohmann::json results = nlohmann::json::parse(read_text(dir.path("bench/bench.json")));
  std::set<std::string> methods, scenes, solvers;
  std::size_t points = 0;
  for (const auto& c : results["cases"]) {
    EXPECT_EQ(c["error"], "") << c.dump();
    EXPECT_GT(c["peak_mib"].get<double>(), 1.0);
    EXPECT_GT(c["cpu_seconds"].get<double>(), 0.0);
    EXPECT_EQ(c["threads"], 1) << c["scene"];  // not the machine's default, where it has 2 cores or more
    scenes.insert(c["scene"].get<std::string>());
    solvers.insert(c["solver"].get<std::string>());
    for (const auto& curve : c["curves"]) {
      // Curves name their solver: the hierarchical and progressive ones are told apart.
      const std::string label = curve["label"].get<std::string>();
      if (c["solver"] == "hierarchical" || c["solver"] == "progressive") {
        EXPECT_EQ(label.rfind(c["solver"].get<std::string>(), 0), 0u) << label;
      }
      if (c["solver"] == "hierarchical") {
        EXPECT_GT(c["links"].get<std::uint64_t>(), 0u);
      }
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
        // Pictures carry their mean per material; closed forms are per vertex.
        if (!c["growth"].get<bool>() && c["truth"] == "path-traced picture") {
          EXPECT_FALSE(p["surfaces"].empty()) << curve["label"];
          for (const auto& m : p["surfaces"]) {
            EXPECT_GT(m["pixels"].get<std::size_t>(), 0u);
            EXPECT_GT(m["ratio"].get<double>(), 0.0) << curve["label"] << " " << m["material"];
          }
        }
      }
    }
  }
  // The path tracer's own pictures are unbiased: at their most samples,
  // every material's mean is the reference's within noise.
  for (const auto& c : results["cases"]) {
    if (c["solver"] != "path") continue;
    for (const auto& m : c["curves"][0]["points"].back()["surfaces"]) {
      EXPECT_NEAR(m["ratio"].get<double>(), 1.0, 0.1) << c["scene"] << " " << m["material"];
    }
  }
  for (const char* m : {"raycast", "hemicube", "hierarchical", "reference-lu", "gauss-seidel", "path", "two-pass"})
    EXPECT_TRUE(methods.count(m)) << m;
  for (const char* s : {"hierarchical", "progressive", "reference", "path"}) EXPECT_TRUE(solvers.count(s)) << s;
  for (const char* s :
       {"cornell", "occluders", "furnace", "furnace-0.99", "sphere", "squares-perpendicular", "squares-parallel"}) {
    EXPECT_TRUE(scenes.count(s)) << s;
    EXPECT_EQ(read_text(dir.path("bench/" + std::string(s) + ".svg")).rfind("<svg", 0), 0u) << s;
  }
  // One CSV row per measured point, under a header.
  const std::string csv = read_text(dir.path("bench/bench.csv"));
  EXPECT_EQ(std::size_t(std::count(csv.begin(), csv.end(), '\n')), points + 1);
  const std::string md = read_text(dir.path("bench/bench.md"));
  EXPECT_NE(md.find("## Targets"), std::string::npos);
  EXPECT_NE(md.find("## Growth with element count"), std::string::npos);
  EXPECT_NE(md.find("Fitted exponents"), std::string::npos);
  // The reference picture is cached and reused by the next run.
  EXPECT_TRUE(std::filesystem::exists(dir.path("bench/reference/cornell-64px-256spp.pfm")));
}

// The walkthrough's smoke run: one solve, every view judged for both
// methods, the path tracer's sample count a power of two that either
// reached the radiosity picture's error or is the cap; references cached.
TEST(Cli, BenchWalkthroughJudgesEveryViewForBothMethods) {
  scratch_dir dir;
  run_result r = run("bench --suite walkthrough-quick --out " + dir.path("walk"));
  ASSERT_EQ(r.code, 0) << r.out << r.err;
  const nlohmann::json results = nlohmann::json::parse(read_text(dir.path("walk/walkthrough.json")));
  ASSERT_EQ(results["scenes"].size(), 1u);
  const nlohmann::json& scene = results["scenes"][0];
  EXPECT_EQ(scene["scene"], "box-room-10");
  EXPECT_GT(scene["solve_seconds"].get<double>(), 0.0);
  EXPECT_GT(scene["links"].get<std::uint64_t>(), 0u);
  ASSERT_EQ(scene["views"].size(), 3u);
  double path_seconds = 0.0;
  for (const auto& v : scene["views"]) {
    const double radiosity = v["radiosity_error"].get<double>(), path = v["path_error"].get<double>();
    EXPECT_GT(radiosity, 0.0);
    EXPECT_LT(radiosity, 0.5) << v.dump();
    const int spp = v["path_spp"].get<int>();
    EXPECT_TRUE(spp >= 1 && spp <= 16 && (spp & (spp - 1)) == 0) << spp;
    EXPECT_EQ(v["path_reached"].get<bool>(), path <= radiosity) << v.dump();
    if (!v["path_reached"].get<bool>()) {
      EXPECT_EQ(spp, 16);
    }
    path_seconds += v["path_seconds"].get<double>();
  }
  EXPECT_NEAR(scene["path_seconds"].get<double>(), path_seconds + scene["path_bvh_seconds"].get<double>(), 1e-9);
  const std::string md = read_text(dir.path("walk/walkthrough.md"));
  EXPECT_NE(md.find("| radiosity: one solve, every view drawn |"), std::string::npos) << md;
  EXPECT_TRUE(std::filesystem::exists(dir.path("walk/reference/walk-box-room-10-2of3-64px-64spp.pfm")));
}

TEST(Cli, BenchRejectsAnUnknownSuite) {
  run_result r = run("bench --suite huge");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("--suite"), std::string::npos) << r.err;
}

TEST(Cli, TraceWritesPngAndPfmAndReportsRays) {
  scratch_dir dir;
  run_result r = run("trace --size 48x36 --max-edge 150 --until 0.05 --link-tolerance 1e-3 --spp 2 --out " +
                     dir.path("a.png") + " --pfm " + dir.path("a.pfm"));
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

TEST(Cli, TraceTwoPassAndPpmReportPhotonsAndTheCache) {
  scratch_dir dir;
  // The Whitted scene has a mirror ball and a glass ball: caustic photons.
  const std::string whitted = source_path("assets/whitted/whitted.json");
  run_result r = run("trace " + whitted + " --integrator twopass --size 24x18 --photons 20000 --gather-rays 32" +
                     " --max-edge 2 --until 0.05 --out " + dir.path("a.png") + " --stats " + dir.path("a.json"));
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("twopass: 20000 photons"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("(twopass, 4 spp)"), std::string::npos) << r.out;  // default_spp
  const nlohmann::json j = nlohmann::json::parse(read_text(dir.path("a.json")));
  EXPECT_EQ(j["trace"]["photons"]["emitted"].get<long>(), 20000);
  EXPECT_GT(j["trace"]["irradiance_cache"]["records"].get<long>(), 0);
  EXPECT_TRUE(j.contains("radiosity"));
  r = run("trace " + whitted + " --integrator ppm --passes 3 --size 16x12 --photons 5000 --gather-rays 16" +
          " --max-edge 2 --until 0.05 --out " + dir.path("b.png") + " --stats " + dir.path("b.json"));
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("ppm: 15000 photons"), std::string::npos) << r.out;
  EXPECT_EQ(nlohmann::json::parse(read_text(dir.path("b.json")))["trace"]["photons"]["passes"].get<int>(), 3);
}

TEST(Cli, TraceRejectsBadOptionsAndFiles) {
  scratch_dir dir;
  EXPECT_EQ(run("trace --integrator photon").code, 2);
  EXPECT_EQ(run("trace --spp 0").code, 2);
  EXPECT_EQ(run("trace --direct maybe").code, 2);
  run_result r = run("trace " + dir.path("missing.json"));
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("missing.json"), std::string::npos) << r.err;
  // A usage error, found before the solve (Cli.OutputPathsAreCheckedBeforeAnyWork).
  r = run("trace --size 8x8 --max-edge 200 --until 0.5 --out " + dir.path("no/such/folder/a.png"));
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("a.png: the folder"), std::string::npos) << r.err;
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

// An output that would overwrite an input (the scene, its MTL, a texture,
// through a symbolic link too) or another output of the same command is
// refused before any work, naming both; the files stay as they were.
TEST(Cli, OutputsNeverOverwriteInputsOrEachOther) {
  scratch_dir dir;
  dir.write("wood.ppm", "P6\n2 2\n255\n" + std::string(12, char(128)));  // a grey 2 x 2 texture
  const std::string scene = dir.write("scene.json", R"({"textures": {"wood": {"image": "wood.ppm"}},
    "materials": {"floor": {"rho": [0.5, 0.5, 0.5], "texture": "wood"}, "lamp": {"ke": [5, 5, 5]}},
    "surfaces": [{"polygon": [[-1, 0, -1], [-1, 0, 1], [1, 0, 1], [1, 0, -1]], "material": "floor"},
                 {"polygon": [[-0.2, 1, -0.2], [0.2, 1, -0.2], [0.2, 1, 0.2], [-0.2, 1, 0.2]], "material": "lamp"}],
    "camera": {"eye": [0, 2, 3], "target": [0, 0, 0], "size": [32, 32]}})");
  const std::string scene_text = read_text(scene), texture_bytes = read_text(dir.path("wood.ppm"));
  std::filesystem::create_symlink(scene, dir.path("alias.json"));
  dir.write("base.obj", "mtllib base.mtl\nv 0 0 0\nv 1 0 0\nv 1 0 1\nusemtl lamp\nf 1 3 2\n");
  dir.write("base.mtl", "newmtl lamp\nKe 1 1 1\n");
  const std::string mtl_text = read_text(dir.path("base.mtl"));
  const std::string common = " --max-edge 1 --until 0.1 --link-tolerance 1e-2";
  for (const auto& [args, message] : std::vector<std::pair<std::string, std::string>>{
           {"render " + scene + " --stats " + scene, "--stats " + scene + " would overwrite " + scene},
           {"trace " + scene + " --stats " + dir.path("alias.json"), "which the scene is read from"},
           {"render " + scene + " --pfm " + dir.path("wood.ppm"), "would overwrite " + dir.path("wood.ppm")},
           {"solve " + dir.path("base.obj") + " --stats " + dir.path("base.mtl"),
            "would overwrite " + dir.path("base.mtl")},
           {"bake " + scene + " --out " + dir.path("x.glb") + " --stats " + dir.path("x.glb"), "name the same file"},
           {"render " + scene + " --out " + dir.path("x.png") + " --stats " + dir.path("x.png"), "name the same file"},
           {"render " + scene + " --pfm /dev/null", "not a regular file"}}) {
    const run_result r = run(args + common);
    EXPECT_EQ(r.code, 2) << args << "\n" << r.err;
    EXPECT_NE(r.err.find(message), std::string::npos) << args << ": " << r.err;
  }
  EXPECT_EQ(read_text(scene), scene_text);
  EXPECT_EQ(read_text(dir.path("wood.ppm")), texture_bytes);
  EXPECT_EQ(read_text(dir.path("base.mtl")), mtl_text);
  EXPECT_FALSE(std::filesystem::exists(dir.path("x.png")));
}

// Reproducers of arguments and files that crashed, hung or silently fell
// back: each is refused at once with its reason.
TEST(Cli, BadArgumentsAndFilesAreRefusedWithTheirReason) {
  scratch_dir dir;
  // A PFM whose header claims 65536 x 65536 over 192 floats: no 48 GiB
  // allocation, no abort.
  const std::string big = dir.write("big.pfm", "PF\n65536 65536\n-1.0\n" + std::string(192 * sizeof(float), '\0'));
  const std::string small = dir.write("small.pfm", "PF\n1 1\n-1.0\n" + std::string(3 * sizeof(float), '\0'));
  const std::string fifo = dir.path("buffer.bin");
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  const std::string gltf = dir.write("fifo.gltf", R"({"asset": {"version": "2.0"},
    "buffers": [{"uri": "buffer.bin", "byteLength": 36}],
    "bufferViews": [{"buffer": 0, "byteLength": 36}],
    "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3"}],
    "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}], "nodes": [{"mesh": 0}], "scenes": [{"nodes": [0]}]})");
  for (const auto& [args, code, message] : std::vector<std::tuple<std::string, int, std::string>>{
           {"render \"\"", 2, "SCENE: is empty (an unset shell variable?)"},
           {"compare " + big + " " + small, 1, "truncated PFM: its header says 65536x65536"},
           {"compare " + dir.path("missing.pfm") + " " + small, 1, "missing.pfm: no such file"},
           {"trace --integrator twopass --photons 2147483647", 2, "must be at most 50000000"},
           {"info " + gltf, 1, "is not a regular file"}}) {
    const run_result r = run_env("timeout 20", args);
    EXPECT_EQ(r.code, code) << args << "\n" << r.err;
    EXPECT_NE(r.err.find(message), std::string::npos) << args << ": " << r.err;
  }
}

// Memory. A scene whose mesh alone needs more than the process may use
// (here a million elements, at least 2 GB, under a 1.5 GB address-space
// limit) is refused before meshing, with both figures. What the estimate
// cannot foresee (links growing to 7 million at link tolerance 1e-9 under
// 400 MB) is an error that says so, exit 1, not "terminate called after
// throwing std::bad_alloc" and an abort. AddressSanitizer reserves more
// address space than any such limit: not under it.
TEST(Cli, OutOfMemoryIsAnErrorNotAnAbort) {
#if defined(__SANITIZE_ADDRESS__)
  GTEST_SKIP() << "AddressSanitizer cannot run under an address-space limit";
#endif
  const run_result refused = run_env("ulimit -v 1500000;", "solve generated:interior-1m --until 0.5");
  EXPECT_EQ(refused.code, 1) << refused.err;
  EXPECT_NE(refused.err.find("error: generated:interior-1m: solving needs at least 2.06 GB (about 1 million "
                             "elements at max edge 4.03, 2 kB each), more than the "),
            std::string::npos)
      << refused.err;
  EXPECT_NE(refused.err.find("(the address-space limit (ulimit -v) less what is mapped); use a larger --max-edge"),
            std::string::npos)
      << refused.err;
  const run_result ran_out = run_env("ulimit -v 400000;", "solve --link-tolerance 1e-9 --time 30 " +
                                                              source_path("assets/cornell_box/cornell_box.json"));
  EXPECT_EQ(ran_out.code, 1) << ran_out.err;
  EXPECT_NE(ran_out.err.find("error: out of memory"), std::string::npos) << ran_out.err;
  // 50 million photons could take 5.6 GB, were all to land in a caustic.
  const run_result photons =
      run_env("ulimit -v 3000000;", "trace --integrator twopass --photons 50000000 --size 32x32");
  EXPECT_EQ(photons.code, 1) << photons.err;
  EXPECT_NE(photons.err.find("the still, were every photon to land in a caustic (50000000 photons, a 32x32 "
                             "picture), needs at least 5.6 GB, more than the"),
            std::string::npos)
      << photons.err;
  // A picture of 32 million pixels at 4 samples: 1.48 GB before solving.
  scratch_dir dir;
  const run_result picture =
      run_env("ulimit -v 1000000;", "render --size 16384x2048 --msaa 4 --out " + dir.path("big.png"));
  EXPECT_EQ(picture.code, 1) << picture.err;
  EXPECT_NE(picture.err.find("the 16384x2048 picture at 4 samples needs at least 1.48 GB, more than the"),
            std::string::npos)
      << picture.err;
}

// The same command gives the same picture, bit for bit, run twice and on
// one thread or two: the solvers' sums run in a fixed order, rays are
// seeded by what they sample, and photons by their index.
TEST(Cli, PicturesAreBitIdenticalRunToRunAndOverThreads) {
  scratch_dir dir;
  const char* commands[] = {
      "render --size 40x40 --until 0.1 --link-tolerance 1e-4",
      "trace --size 24x24 --link-tolerance 1e-4",
      "trace --size 24x24 --integrator path --spp 4",
      "trace --size 24x24 --integrator twopass --photons 20000 "
      "--gather-rays 16 --link-tolerance 1e-4",
  };
  for (const char* command : commands) {
    std::string first;
    int run_index = 0;
    for (const char* threads : {"2", "2", "1"}) {
      const std::string pfm = dir.path("p" + std::to_string(run_index++) + ".pfm");
      const run_result r =
          run(std::string(command) + " --threads " + threads + " --out " + dir.path("p.png") + " --pfm " + pfm);
      ASSERT_EQ(r.code, 0) << command << ": " << r.err;
      const std::string picture = read_text(pfm);
      ASSERT_GT(picture.size(), 24u * 24u * 12u) << command;
      if (first.empty())
        first = picture;
      else
        EXPECT_TRUE(picture == first) << command << " --threads " << threads << " differs from the first run";
    }
  }
}

// --time counts from the command's start. Meshing a million triangles
// takes far longer than a second: the command stops at the limit, exit 1,
// saying so, with nothing written. A run whose steps pass the limit (at
// link tolerance 1e-9 one refinement took 21 s here) ends with its picture:
// a link refinement under way stops splitting (and warns; whether the
// limit falls in one depends on the clock, so only the picture is checked).
TEST(Cli, TheTimeLimitCoversMeshingAndLinkRefinement) {
  scratch_dir dir;
  const run_result meshing = run("solve generated:interior-1m --time 1 --stats " + dir.path("s.json"));
  EXPECT_EQ(meshing.code, 1) << meshing.err;
  EXPECT_NE(meshing.err.find("error: --time 1 s ran out while loading and meshing the scene"), std::string::npos)
      << meshing.err;
  EXPECT_FALSE(std::filesystem::exists(dir.path("s.json")));
  const run_result linking = run("render --size 32x32 --link-tolerance 1e-9 --time 3 --out " + dir.path("a.png"));
  EXPECT_EQ(linking.code, 0) << linking.err;
  EXPECT_TRUE(std::filesystem::exists(dir.path("a.png")));
}

// A run killed (SIGKILL: nothing can be tidied) while it renders or
// writes a large picture leaves the old picture byte for byte; a run that
// finished first has put a whole new one in its place. One kill lands in
// the solve; another as soon as the picture's partial file appears, in the
// write (201 MB of PFM: about half a second here).
TEST(Cli, AKilledRunLeavesTheOldPictureWhole) {
  scratch_dir dir;
  const std::string picture = dir.path("pic.pfm");
  const std::string old(1 << 16, 'o');
  auto partial_exists = [&] {
    for (const auto& entry : std::filesystem::directory_iterator(dir.root))
      if (entry.path().filename().string().starts_with("pic.pfm.partial")) return true;
    return false;
  };
  int killed_solving = 0, killed_writing = 0;
  for (const bool in_the_write : {false, true}) {
    dir.write("pic.pfm", old);
    for (const auto& entry : std::filesystem::directory_iterator(dir.root))
      if (entry.path().filename().string().starts_with("pic.pfm.partial")) std::filesystem::remove(entry.path());
    const pid_t child = fork();
    ASSERT_GE(child, 0);
    if (child == 0) {
      std::freopen("/dev/null", "w", stdout);
      std::freopen("/dev/null", "w", stderr);
      execl(BOUNCE_EXE, BOUNCE_EXE, "render", "--quiet", "--max-edge", "150", "--until", "0.05", "--size", "4096x4096",
            "--out", picture.c_str(), static_cast<char*>(nullptr));
      _exit(127);
    }
    int status = 0;
    bool reaped = false;
    if (in_the_write) {
      // Until the partial file appears or the run ends (at most a minute).
      for (int i = 0; i < 60000 && !reaped; ++i) {
        reaped = waitpid(child, &status, WNOHANG) == child;
        if (!reaped && partial_exists()) {
          kill(child, SIGKILL);
          break;
        }
        usleep(1000);
      }
    } else {
      usleep(300000);
      kill(child, SIGKILL);
    }
    if (!reaped) {
      ASSERT_EQ(waitpid(child, &status, 0), child);
    }
    const std::string now = read_text(picture);
    if (WIFSIGNALED(status)) {
      ++(in_the_write ? killed_writing : killed_solving);
      EXPECT_EQ(now, old) << (in_the_write ? "killed while writing" : "killed while solving");
    } else {
      ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0);
      EXPECT_EQ(now.size(), std::string("PF\n4096 4096\n-1.0\n").size() + 4096ull * 4096 * 12);
    }
  }
  EXPECT_EQ(killed_solving, 1);
  std::printf("killed while solving: %d, while writing: %d\n", killed_solving, killed_writing);
}

TEST(Cli, SolveWritesStatsAndPly) {
  scratch_dir dir;
  const std::string stats = dir.path("stats.json"), ply = dir.path("box.ply");
  run_result r = run("solve --max-edge 150 --until 0.05 --link-tolerance 1e-3 --stats " + stats + " --ply " + ply);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("mesh: "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("done: "), std::string::npos) << r.out;
  nlohmann::json j = nlohmann::json::parse(read_text(stats));
  for (const char* key : {"elements", "vertices", "steps", "remaining", "seconds", "rays"})
    EXPECT_TRUE(j.contains(key)) << key;
  EXPECT_LE(j["remaining"].get<double>(), 0.05);
  EXPECT_GT(j["rays"].get<double>(), 0.0);
  // The PLY header names the radiosity and colour properties, and the
  // counts match the statistics.
  const std::string text = read_text(ply);
  for (const char* line : {"ply", "format ascii 1.0", "property float radiosity_r", "property float radiosity_g",
                           "property float radiosity_b", "property uchar red", "property uchar green",
                           "property uchar blue", "end_header"})
    EXPECT_NE(text.find(std::string(line) + "\n"), std::string::npos) << line;
  EXPECT_NE(text.find("element vertex " + std::to_string(j["vertices"].get<int>()) + "\n"), std::string::npos);
  EXPECT_NE(text.find("element face " + std::to_string(j["elements"].get<int>()) + "\n"), std::string::npos);
}

// bake: solve, then the meshes with their light, in the format --out names;
// what the files hold is tested in tests/radiosity/bake_test.cpp.
TEST(Cli, BakeWritesTheFormatItsOutputNames) {
  scratch_dir dir;
  const std::string glb = dir.path("lit.glb");
  run_result r = run("bake --max-edge 150 --until 0.05 --link-tolerance 1e-3 --parts --exposure 3 --out " + glb);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("wrote " + glb), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("colours at exposure 3"), std::string::npos) << r.out;
  EXPECT_EQ(read_text(glb).substr(0, 4), "glTF");
  const std::string obj = dir.path("lit.obj");
  ASSERT_EQ(run("bake --max-edge 150 --until 0.05 --link-tolerance 1e-3 --out " + obj).code, 0);
  EXPECT_NE(read_text(obj).find("\no floor\nv "), std::string::npos);
  for (const auto& [args, message] : std::vector<std::pair<std::string, std::string>>{
           {"bake --out " + dir.path("lit.png"), "--out: expected a .glb, .gltf, .ply or .obj file"},
           {"bake --parts --out " + dir.path("lit.ply"), "--parts applies to glTF output only"},
           {"bake --exposure 0 --out " + glb, "--exposure: must be above 0"},
           {"bake", "--out is required"},
           {"solve --ply " + dir.path("lit.obj"), "--ply: expected a .ply file"}}) {
    const run_result bad = run(args);
    EXPECT_EQ(bad.code, 2) << args;
    EXPECT_NE(bad.err.find(message), std::string::npos) << args << ": " << bad.err;
  }
}

TEST(Cli, ShadowOutlinesAreCutOnRequestForEitherSolver) {
  // The embedded Cornell box: the short block's shadow under the lamp has
  // a penumbra narrower than a 150 mm element, and is outlined.
  scratch_dir dir;
  const std::string stats = dir.path("stats.json");
  for (const char* solver : {"--link-tolerance 1e-3", "--solver progressive"}) {
    run_result r = run(std::string("solve ") + solver + " --max-edge 150 --until 0.05 --stats " + stats);
    ASSERT_EQ(r.code, 0) << r.err;
    nlohmann::json j = nlohmann::json::parse(read_text(stats));
    EXPECT_EQ(j["shadow_outlines"].get<int>(), 0) << solver;
    r = run(std::string("solve ") + solver + " --shadow-outlines --max-edge 150 --until 0.05 --stats " + stats);
    ASSERT_EQ(r.code, 0) << r.err;
    j = nlohmann::json::parse(read_text(stats));
    EXPECT_EQ(j["shadow_outline_lights"].get<int>(), 1) << solver;
    EXPECT_GE(j["shadow_outlines"].get<int>(), 1) << solver;
    EXPECT_GT(j["shadow_triangles_split"].get<int>(), 0) << solver;
  }
}

TEST(Cli, AdaptiveMeshingRefinesInSolveRenderAndTrace) {
  scratch_dir dir;
  const std::string stats = dir.path("stats.json"), ply = dir.path("refined.ply");
  run_result r = run("solve --adaptive --max-edge 150 --until 0.02 --stats " + stats + " --ply " + ply);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("a priori refinement: "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("refinement at unshot "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("adaptive mesh: "), std::string::npos) << r.out;
  nlohmann::json j = nlohmann::json::parse(read_text(stats));
  EXPECT_TRUE(j["adaptive"].get<bool>());
  ASSERT_FALSE(j["refinement_passes"].empty());
  const auto& first = j["refinement_passes"][0];
  EXPECT_GT(first["elements_after"].get<int>(), first["elements_before"].get<int>());
  EXPECT_EQ(j["elements"].get<int>(), j["refinement_passes"].back()["elements_after"].get<int>());
  // The PLY is the refined mesh.
  EXPECT_NE(read_text(ply).find("element face " + std::to_string(j["elements"].get<int>()) + "\n"), std::string::npos);

  r = run("render --adaptive --max-edge 150 --until 0.02 --wireframe --size 64x64 --out " + dir.path("a.png"));
  ASSERT_EQ(r.code, 0) << r.err;
  r = run("trace --adaptive --max-edge 150 --until 0.02 --size 32x32 --out " + dir.path("t.png"));
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("radiosity: "), std::string::npos) << r.out;

  // A minimum edge the mesher cannot honour is a clear error, not a hang,
  // with either solver.
  for (const char* solver : {"--adaptive", "--solver hierarchical"}) {
    r = run(std::string("solve ") + solver + " --max-edge 150 --min-edge 0.01");
    EXPECT_EQ(r.code, 1) << solver;
    EXPECT_NE(r.err.find("--min-edge"), std::string::npos) << solver << ": " << r.err;
  }
}

TEST(Cli, SolveStopsAtTheShotLimitAndComparesWithTheReference) {
  scratch_dir dir;
  const std::string stats = dir.path("stats.json");
  run_result r = run("solve --max-edge 200 --max-steps 7 --stats " + stats);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(nlohmann::json::parse(read_text(stats))["steps"], 7);
  r = run("solve " + source_path("assets/furnace/furnace.json") + " --max-edge 1 --until 1e-7 --reference --stats " +
          stats);
  ASSERT_EQ(r.code, 0) << r.err;
  nlohmann::json j = nlohmann::json::parse(read_text(stats));
  EXPECT_LT(j["reference"]["max_relative_difference"].get<double>(), 1e-5);
  EXPECT_LT(j["reference"]["residual_lu"].get<double>(), 1e-12);
}

TEST(Cli, SolveRefusesAbsurdMeshes) {
  run_result r = run("solve --max-edge 0.001");
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("use a larger --max-edge"), std::string::npos) << r.err;
}

// --- Conventions of pbrt, Mitsuba and Blender's command lines ---------------

std::string head(const std::string& path, std::size_t n) {
  return read_text(path).substr(0, n);
}

TEST(Cli, VersionNamesTheProgram) {
  run_result r = run("--version");
  EXPECT_EQ(r.code, 0);
  EXPECT_EQ(r.out.rfind("bounce ", 0), 0u) << r.out;
  EXPECT_NE(r.out.find_first_of("0123456789"), std::string::npos) << r.out;
}

TEST(Cli, QuietLeavesOnlyWarningsAndErrors) {
  scratch_dir dir;
  const std::string fast = " --size 16x16 --max-edge 150 --until 0.05 --link-tolerance 1e-3";
  // Before or after the command's name, as pbrt and Blender accept.
  for (const std::string& line :
       {"--quiet render" + fast + " --out " + dir.path("a.png"), "render -q" + fast + " --out " + dir.path("b.png"),
        "trace --quiet --spp 1" + fast + " --out " + dir.path("c.png"),
        std::string("solve --quiet --max-edge 150 --until 0.05 --link-tolerance 1e-3")}) {
    // The sanitizers' list of suppressions used is not the program's output.
    run_result r = run_env("LSAN_OPTIONS=\"$LSAN_OPTIONS:print_suppressions=0\"", line);
    EXPECT_EQ(r.code, 0) << line << ": " << r.err;
    EXPECT_EQ(r.out, "") << line;
    EXPECT_EQ(r.err, "") << line;
  }
  EXPECT_TRUE(std::filesystem::exists(dir.path("a.png")));
  EXPECT_TRUE(std::filesystem::exists(dir.path("c.png")));
  // Errors still speak.
  run_result r = run("render --quiet --out " + dir.path("a.jpg"));
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("unknown picture format"), std::string::npos) << r.err;
}

TEST(Cli, HierarchicalSolverStatsSayHowDiffuseLightPassedMirrors) {
  // The Cornell box with mirrors: the hierarchical solver's passes of
  // diffuse light through mirrors and glass show in --stats; a scene
  // without them has none to make.
  scratch_dir dir;
  const std::string fast = " --max-edge 150 --until 0.005 --link-tolerance 1e-3 --stats " + dir.path("s.json");
  run_result r = run("solve " + source_path("assets/cornell_caustics/cornell_caustics.json") + fast);
  ASSERT_EQ(r.code, 0) << r.err;
  nlohmann::json stats = nlohmann::json::parse(read_text(dir.path("s.json")));
  EXPECT_EQ(stats["hierarchical"]["specular_passes"], 2) << stats.dump(2);
  EXPECT_EQ(stats["hierarchical"]["specular_shot_fraction"], 1.0) << "a small scene: every patch within the budget";
  r = run("solve" + fast);
  ASSERT_EQ(r.code, 0) << r.err;
  stats = nlohmann::json::parse(read_text(dir.path("s.json")));
  EXPECT_EQ(stats["hierarchical"]["specular_passes"], 0) << stats.dump(2);
}

// Progress bars redraw one line on a terminal and stay out of pipes and logs.
TEST(Cli, ProgressBarsOnATerminalOnly) {
  scratch_dir dir;
  const std::string args = "trace --size 96x96 --max-edge 100 --until 0.01 --spp 4 --out " + dir.path("a.png");
  run_result piped = run(args);
  ASSERT_EQ(piped.code, 0) << piped.err;
  EXPECT_EQ(piped.err.find('\r'), std::string::npos) << piped.err;
  EXPECT_EQ(piped.err.find("solving ["), std::string::npos) << piped.err;
  // script(1) gives the command a pseudo-terminal; both streams land in its output.
  const std::string log = dir.path("tty.log");
  const std::string command = "script -qec '" + std::string(BOUNCE_EXE) + " " + args + "' " + log + " >/dev/null";
  ASSERT_EQ(std::system(command.c_str()), 0);
  const std::string seen = read_text(log);
  EXPECT_NE(seen.find("\rsolving ["), std::string::npos) << seen;
  // The bar is erased before the report, which starts on a clean line.
  EXPECT_NE(seen.find("\r\x1b[Kradiosity: "), std::string::npos) << seen;
  const std::string quiet = "script -qec '" + std::string(BOUNCE_EXE) + " --quiet " + args + "' " + log + " >/dev/null";
  ASSERT_EQ(std::system(quiet.c_str()), 0);
  EXPECT_EQ(read_text(log).find("solving ["), std::string::npos) << read_text(log);
}

TEST(Cli, ThreadsLimitsTheWorkers) {
  scratch_dir dir;
  const std::string stats = dir.path("s.json");
  ASSERT_EQ(run("solve --max-edge 150 --until 0.05 --link-tolerance 1e-3 --threads 1 --stats " + stats).code, 0);
  EXPECT_EQ(nlohmann::json::parse(read_text(stats))["threads"], 1);
  ASSERT_EQ(run("--threads 2 solve --max-edge 150 --until 0.05 --link-tolerance 1e-3 --stats " + stats).code, 0);
  EXPECT_EQ(nlohmann::json::parse(read_text(stats))["threads"], 2);
  ASSERT_EQ(run("solve --max-edge 150 --until 0.05 --link-tolerance 1e-3 --stats " + stats).code, 0);
  EXPECT_GE(nlohmann::json::parse(read_text(stats))["threads"].get<int>(), 1);
  for (const char* bad : {"--threads 0 solve", "--threads x solve", "solve --threads -2"})
    EXPECT_EQ(run(bad).code, 2) << bad;
}

// `bounce SCENE` is `bounce view SCENE`: the window, or headless without a display.
TEST(Cli, ASceneAloneOpensIt) {
  scratch_dir dir;
  run_result r = run_env("cd " + dir.root.string() + " && env -u DISPLAY",
                         source_path("assets/cornell_box/cornell_box.json") + " --quiet");
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(std::filesystem::exists(dir.path("bounce.png")));
  r = run_env("env -u DISPLAY", dir.path("missing.json"));
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("missing.json"), std::string::npos) << r.err;
  r = run("render " + source_path("assets/cornell_box/cornell_box.json") + " extra.json");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("unexpected argument 'extra.json'"), std::string::npos) << r.err;
}

// --out's extension picks the format; the linear formats hold the same
// radiance as --pfm.
TEST(Cli, OutputFormatFollowsTheExtension) {
  scratch_dir dir;
  const std::string fast = " --size 24x16 --max-edge 150 --until 0.05 --link-tolerance 1e-3 --quiet";
  for (const char* command : {"render", "trace --spp 1"}) {
    const std::string c = command;
    ASSERT_EQ(run(c + fast + " --out " + dir.path("a.png")).code, 0) << c;
    EXPECT_EQ(head(dir.path("a.png"), 4), "\x89PNG") << c;
    ASSERT_EQ(run(c + fast + " --out " + dir.path("a.exr") + " --pfm " + dir.path("ref.pfm")).code, 0) << c;
    EXPECT_EQ(head(dir.path("a.exr"), 4), std::string("\x76\x2f\x31\x01", 4)) << c;
    ASSERT_EQ(run(c + fast + " --out " + dir.path("A.HDR")).code, 0) << c;
    EXPECT_EQ(head(dir.path("A.HDR"), 10), "#?RADIANCE") << c;
    ASSERT_EQ(run(c + fast + " --out " + dir.path("a.pfm")).code, 0) << c;
    EXPECT_EQ(read_text(dir.path("a.pfm")), read_text(dir.path("ref.pfm")))
        << c << ": --out x.pfm is the --pfm picture";
    run_result r = run(c + fast + " --out " + dir.path("a.jpg"));
    EXPECT_EQ(r.code, 2) << c;
    EXPECT_NE(r.err.find("unknown picture format '.jpg' (use .png, .pfm, .exr or .hdr)"), std::string::npos) << r.err;
  }
  // Display transforms do not apply to radiance files.
  for (const char* png_only : {"render --panel", "render --tone filmic", "render --exposure 2", "trace --exposure 2"}) {
    run_result r = run(std::string(png_only) + " --out " + dir.path("x.exr"));
    EXPECT_EQ(r.code, 2) << png_only;
    EXPECT_NE(r.err.find("applies to PNG output only"), std::string::npos) << r.err;
  }
}

// A bad output path is reported before the scene is even loaded: nothing
// else gets written.
TEST(Cli, OutputPathsAreCheckedBeforeAnyWork) {
  scratch_dir dir;
  const std::string stats = dir.path("stats.json");
  const std::string missing = dir.path("no/such/folder/");
  const std::pair<std::string, std::string> cases[] = {
      {"render --stats " + stats + " --out " + missing + "a.png", "does not exist"},
      {"render --stats " + stats + " --pfm " + missing + "a.pfm", "does not exist"},
      {"render --stats " + missing + "s.json --out " + dir.path("a.png"), "does not exist"},
      {"render --stats " + stats + " --frames " + missing + "frames", "does not exist"},
      {"trace --stats " + stats + " --out " + dir.root.string(), "is a folder"},
      {"trace --stats " + stats + " --out " + dir.path("a.tiff"), "unknown picture format"},
      {"solve --stats " + stats + " --ply " + missing + "m.ply", "does not exist"},
      {"view --frames 1 --screenshot " + missing + "w.png", "does not exist"},
  };
  for (const auto& [line, message] : cases) {
    run_result r = run(line);
    EXPECT_EQ(r.code, 2) << line;
    EXPECT_NE(r.err.find(message), std::string::npos) << line << ": " << r.err;
    EXPECT_EQ(r.out, "") << line;
    EXPECT_FALSE(std::filesystem::exists(stats)) << line << ": the solve ran";
  }
}

TEST(Cli, TraceDefaultsToACleanSampleCount) {
  scratch_dir dir;
  const std::string stats = dir.path("s.json");
  ASSERT_EQ(run("trace --quiet --size 8x8 --max-edge 150 --until 0.05 --link-tolerance 1e-3 --stats " + stats).code, 0);
  EXPECT_EQ(nlohmann::json::parse(read_text(stats))["trace"]["spp"], 16);
  ASSERT_EQ(run("trace --quiet --integrator path --size 8x8 --stats " + stats).code, 0);
  EXPECT_EQ(nlohmann::json::parse(read_text(stats))["trace"]["spp"], 256);
  EXPECT_NE(run("trace --help").out.find("Default: whitted 16"), std::string::npos);
}

// Frames at 1, 2, 4, 8, ... shots and the last, not one per shot.
TEST(Cli, FramesComeAtDoublingShotCounts) {
  scratch_dir dir;
  ASSERT_EQ(run("render --quiet --size 16x16 --solver progressive --max-edge 150 --max-steps 20 --until 0 --frames " +
                dir.path("f"))
                .code,
            0);
  std::set<std::string> names;
  for (const auto& e : std::filesystem::directory_iterator(dir.path("f"))) names.insert(e.path().filename().string());
  const std::set<std::string> expected = {"frame_000001.png", "frame_000002.png", "frame_000004.png",
                                          "frame_000008.png", "frame_000016.png", "frame_000020.png"};
  EXPECT_EQ(names, expected);
}

// OpenMesh's own complaints ("complex edge") become one Bounce warning.
TEST(Cli, LibraryWarningsBecomeBouncesOwn) {
  scratch_dir dir;
  run_result r = run("render --quiet --size 16x16 --until 0.05 " + source_path("assets/teapot/teapot.json") +
                     " --out " + dir.path("t.png"));
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(r.err.find("PolyMeshT"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("non-manifold face(s) kept with vertices of their own"), std::string::npos) << r.err;
}

// A camera file (as the window's panel saves it) gives the same picture as
// the same camera typed as options; options typed over it win.
TEST(Cli, CameraFileRendersTheSameViewAsOptions) {
  scratch_dir dir;
  const std::string file = dir.write("cam.json", R"({"camera": {"eye": [278, 200, -700], "target": [300, 250, 300],
    "up": [0, 1, 0], "fov": 35, "size": [40, 30]}})");
  const std::string fast = " --quiet --max-edge 150 --until 0.05 --link-tolerance 1e-3 --pfm ";
  ASSERT_EQ(run("render --camera " + file + fast + dir.path("a.pfm") + " --out " + dir.path("a.png")).code, 0);
  ASSERT_EQ(run("render --eye 278,200,-700 --target 300,250,300 --up 0,1,0 --fov 35 --size 40x30" + fast +
                dir.path("b.pfm") + " --out " + dir.path("b.png"))
                .code,
            0);
  EXPECT_EQ(read_text(dir.path("a.pfm")), read_text(dir.path("b.pfm")));
  ASSERT_EQ(
      run("render --camera " + file + " --size 20x10" + fast + dir.path("c.pfm") + " --out " + dir.path("c.png")).code,
      0);
  EXPECT_EQ(head(dir.path("c.pfm"), 9), "PF\n20 10\n");
  // A bad camera file is a file that cannot be used: exit 1, named.
  run_result r = run("render --camera " + dir.write("bad.json", R"({"camera": {"eye": [0, 0], "target": [0, 0, 1]}})"));
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("bad.json: camera.eye"), std::string::npos) << r.err;
  r = run("trace --camera " + dir.path("missing.json"));
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("missing.json: cannot read file"), std::string::npos) << r.err;
  // Keys left out keep the scene's values, as docs/cli.md says: a fov alone.
  const std::string narrow = dir.write("narrow.json", R"({"camera": {"fov": 30, "size": [24, 16]}})");
  ASSERT_EQ(run("render --camera " + narrow + fast + dir.path("d.pfm") + " --out " + dir.path("d.png")).code, 0);
  EXPECT_EQ(head(dir.path("d.pfm"), 9), "PF\n24 16\n");
  // A bad fov or an absurd size in a camera file is the file's fault (exit
  // 1, the file named), not the command line's or the scene's.
  r = run("render --camera " + dir.write("wide.json", R"({"camera": {"fov": 200}})"));
  EXPECT_EQ(r.code, 1) << r.err;
  EXPECT_NE(r.err.find("wide.json: camera file: fov must be from 0.001 to 179 degrees"), std::string::npos) << r.err;
  r = run("render --camera " + dir.write("huge.json", R"({"camera": {"size": [16000, 16000]}})"));
  EXPECT_EQ(r.code, 1) << r.err;
  EXPECT_NE(r.err.find("huge.json: camera.size"), std::string::npos) << r.err;
}

}  // namespace
