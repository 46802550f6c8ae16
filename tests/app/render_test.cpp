// Headless pictures through OSMesa, made by `bounce render` as a user
// would: golden images with stated tolerances, and exact radiance checks.
#include <sys/wait.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>

#include <gtest/gtest.h>

#include "cornell_files.h"
#include "image/image.h"
#include "image/image_metrics.h"
#include "picture_checks.h"
#include "scene/camera_math.h"
#include "scene/framing.h"
#include "test_files.h"

namespace bounce {
namespace {

using test_support::block_difference;
using test_support::scratch_dir;
using test_support::source_path;

int run(const std::string& args) {
  const std::string command = std::string(BOUNCE_EXE) + " " + args + " >/dev/null 2>&1 </dev/null";
  const int status = std::system(command.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

// Compares a rendered PNG with a golden one: mean and 99.9th percentile of
// the absolute difference in 8-bit units. On failure the rendered,
// reference and difference images stay in the build folder.
void expect_matches_golden(const std::string& rendered, const std::string& golden_name, double max_mean,
                           double max_p999) {
  const std::string golden = source_path("tests/golden/" + golden_name);
  int w = 0, h = 0, gw = 0, gh = 0;
  std::vector<unsigned char> a, b;
  std::string error;
  ASSERT_TRUE(read_png_rgb8(rendered, w, h, a, error)) << error;
  ASSERT_TRUE(read_png_rgb8(golden, gw, gh, b, error)) << error;
  ASSERT_EQ(w, gw);
  ASSERT_EQ(h, gh);
  std::vector<int> diff(a.size());
  double sum = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    diff[i] = std::abs(int(a[i]) - int(b[i]));
    sum += diff[i];
  }
  const double mean = sum / double(a.size());
  std::vector<int> sorted = diff;
  std::nth_element(sorted.begin(), sorted.begin() + std::ptrdiff_t(0.999 * (sorted.size() - 1)), sorted.end());
  const double p999 = sorted[std::size_t(0.999 * (sorted.size() - 1))];
  EXPECT_LE(mean, max_mean) << golden_name;
  EXPECT_LE(p999, max_p999) << golden_name;
  if (mean > max_mean || p999 > max_p999) {
    const std::filesystem::path out = std::filesystem::path(BOUNCE_BINARY_DIR) / "image_test_output";
    std::filesystem::create_directories(out);
    std::filesystem::copy_file(rendered, out / ("rendered_" + golden_name),
                               std::filesystem::copy_options::overwrite_existing);
    std::filesystem::copy_file(golden, out / ("reference_" + golden_name),
                               std::filesystem::copy_options::overwrite_existing);
    std::vector<unsigned char> d(diff.size());
    for (std::size_t i = 0; i < diff.size(); ++i) d[i] = static_cast<unsigned char>(std::min(255, diff[i] * 8));
    write_png((out / ("difference_" + golden_name)).string(), w, h, 3, d.data(), error);
    ADD_FAILURE() << "images written to " << out;
  }
}

// Tolerances: llvmpipe is deterministic on one machine; the margins allow
// other CPUs' float rounding and a few flipped shadow rays.
constexpr double max_mean = 1.0, max_p999 = 24.0;

// Renders the Cornell box as tests/update_goldens.sh does, with the given
// stopping point, and compares it with the named golden.
void expect_cornell_matches(const std::string& stop, const std::string& golden) {
  scratch_dir dir;
  ASSERT_EQ(run("render --size 128x128 --max-edge 60 --solver progressive " + stop + " --out " + dir.path("a.png")), 0);
  expect_matches_golden(dir.path("a.png"), golden, max_mean, max_p999);
}

TEST(HeadlessImages, CornellBoxAfterOneShot) {
  expect_cornell_matches("--max-steps 1", "cornell_1_shot.png");
}
TEST(HeadlessImages, CornellBoxAfterTenShots) {
  expect_cornell_matches("--max-steps 10", "cornell_10_shots.png");
}
TEST(HeadlessImages, CornellBoxConverged) {
  expect_cornell_matches("--until 0.001", "cornell_converged.png");
}
// The default solver, hierarchical, at its default element size.
TEST(HeadlessImages, CornellBoxHierarchical) {
  scratch_dir dir;
  ASSERT_EQ(run("render --size 128x128 --until 0.001 --out " + dir.path("a.png")), 0);
  expect_matches_golden(dir.path("a.png"), "cornell_hierarchical.png", max_mean, max_p999);
}

TEST(HeadlessImages, EmitterPixelsShowTheirRadiance) {
  // After the first shot the light has received nothing: its pixels are
  // exactly its Ke = (17, 12, 4) in the linear PFM.
  scratch_dir dir;
  ASSERT_EQ(run("render --size 256x256 --max-edge 60 --max-steps 1 --out " + dir.path("a.png") + " --pfm " +
                dir.path("a.pfm")),
            0);
  image img;
  std::string error;
  ASSERT_TRUE(read_pfm(dir.path("a.pfm"), img, error)) << error;
  camera c;
  c.eye = vec3(278, 273, -800);
  c.target = vec3(278, 273, 0);
  c.fov_y_degrees = 39.3;
  c.width = c.height = 256;
  const bounds3 box{vec3(0.0), vec3(556, 548.8, 559.2)};
  const glm::dvec4 q = projection_matrix(c, box) * view_matrix(c) * glm::dvec4(278, 548.8, 279.5, 1.0);
  const int x = int((q.x / q.w * 0.5 + 0.5) * 256), y = int((1 - (q.y / q.w * 0.5 + 0.5)) * 256);
  const rgb light = img.at(x, y);
  EXPECT_NEAR(light.r, 17.0, 17.0 * 1e-5);
  EXPECT_NEAR(light.g, 12.0, 12.0 * 1e-5);
  EXPECT_NEAR(light.b, 4.0, 4.0 * 1e-5);
}

// Pixels of the Cornell camera (256x256 or other) that see the light's
// rectangle (x 213..343, z 227..332) with a pixel of margin all round.
std::vector<std::pair<int, int>> light_pixels(int width, int height) {
  camera c;
  c.eye = vec3(278, 273, -800);
  c.target = vec3(278, 273, 0);
  c.fov_y_degrees = 39.3;
  c.width = width;
  c.height = height;
  auto on_light = [&](double x, double y) {
    const vec3 d = camera_ray_direction(c, x, y);
    if (d.y <= 0) return false;
    const vec3 p = c.eye + d * ((548.8 - c.eye.y) / d.y);
    return p.x > 213 && p.x < 343 && p.z > 227 && p.z < 332;
  };
  std::vector<std::pair<int, int>> out;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      if (on_light(x - 1, y - 1) && on_light(x + 2, y - 1) && on_light(x - 1, y + 2) && on_light(x + 2, y + 2))
        out.emplace_back(x, y);
  return out;
}

void expect_finite_and_non_negative(const image& img, const std::string& what) {
  int bad = 0;
  for (float v : img.pixels) bad += !(std::isfinite(v) && v >= 0.0f);
  EXPECT_EQ(bad, 0) << what;
}

TEST(HeadlessImages, LightInOrUnderTheCeilingPlaneShowsItsRadiance) {
  // The published Cornell box: the light in the plane of an uncut ceiling,
  // and 0.1 mm under it. The mesher cuts it out of the ceiling and the
  // depth range resolves 0.1 mm, so after the first shot every pixel of
  // the light is its Ke exactly, as for the embedded box (measured before:
  // in the plane, the ceiling showed over most of the light; 0.1 mm under,
  // blocks of ceiling along its rim).
  const std::vector<std::pair<int, int>> pixels = light_pixels(256, 256);
  ASSERT_GT(pixels.size(), 100u);
  for (const char* height : {"548.8", "548.7"}) {
    scratch_dir dir(height);
    const std::string json = test_support::write_official_cornell(dir, height);
    ASSERT_EQ(run("render " + json + " --max-edge 60 --max-steps 1 --out " + dir.path("a.png") + " --pfm " +
                  dir.path("a.pfm")),
              0);
    image img;
    std::string error;
    ASSERT_TRUE(read_pfm(dir.path("a.pfm"), img, error)) << error;
    int wrong = 0;
    for (const auto& [x, y] : pixels) {
      const rgb v = img.at(x, y);
      wrong += std::abs(v.r - 17.0) > 17e-5 || std::abs(v.g - 12.0) > 12e-5 || std::abs(v.b - 4.0) > 4e-5;
    }
    EXPECT_EQ(wrong, 0) << height << ": " << pixels.size() << " light pixels";
    expect_finite_and_non_negative(img, height);
  }
}

// The back of a one-sided surface is black in the view, as in the still:
// a lit floor seen from below. Before, the view drew it with its front's
// light, so the picture changed when the camera came to rest.
TEST(HeadlessImages, ABackFaceIsBlackAsInTheStill) {
  scratch_dir dir;
  const std::string scene = dir.write("below.json", R"({
  "camera": {"eye": [1, -2, 1.2], "target": [1, 0, 1], "up": [0, 0, 1], "fov": 40, "size": [64, 64]},
  "materials": {"floor": {"rho": [0.6, 0.6, 0.6]}, "lamp": {"ke": [4, 4, 4]}},
  "surfaces": [
    {"name": "floor", "polygon": [[0, 0, 0], [0, 0, 2], [2, 0, 2], [2, 0, 0]], "material": "floor"},
    {"name": "lamp", "polygon": [[0.7, 0.5, 0.7], [1.3, 0.5, 0.7], [1.3, 0.5, 1.3], [0.7, 0.5, 1.3]], "material": "lamp"}
  ]
})");
  ASSERT_EQ(run("render " + scene + " --max-edge 0.25 --out " + dir.path("view.pfm")), 0);
  ASSERT_EQ(run("trace " + scene + " --max-edge 0.25 --spp 4 --out " + dir.path("still.pfm")), 0);
  image view, still;
  std::string error;
  ASSERT_TRUE(read_pfm(dir.path("view.pfm"), view, error)) << error;
  ASSERT_TRUE(read_pfm(dir.path("still.pfm"), still, error)) << error;
  double view_sum = 0.0, still_sum = 0.0;
  for (const float v : view.pixels) view_sum += v;
  for (const float v : still.pixels) still_sum += v;
  EXPECT_EQ(still_sum, 0.0);  // the floor's back fills the view: black
  EXPECT_EQ(view_sum, 0.0);
}

TEST(HeadlessImages, NoNegativeOrWildPixelsAtAnySize) {
  // Radiosities are >= 0, and so is every convex combination of them: the
  // Gouraud view interpolates at the centroid (no extrapolation past a
  // triangle under MSAA). Measured before, after 10 shots: 32 pixels below
  // zero at 64x64 and 67 at 128x128 (down to -0.011), and at 1x1 and 64x1,
  // where triangles are smaller than a pixel, values like -211056.
  scratch_dir dir;
  double brightest = 0.0;
  for (const char* size : {"64x64", "128x128", "1x1", "64x1"}) {
    ASSERT_EQ(run(std::string("render --max-steps 10 --size ") + size + " --out " + dir.path("a.png") + " --pfm " +
                  dir.path("a.pfm")),
              0)
        << size;
    image img;
    std::string error;
    ASSERT_TRUE(read_pfm(dir.path("a.pfm"), img, error)) << error;
    expect_finite_and_non_negative(img, size);
    for (float v : img.pixels) {
      if (std::string(size) == "64x64") brightest = std::max(brightest, double(v));
      EXPECT_LE(v, 1.01 * brightest) << size;  // none brighter than the light
    }
  }
}

TEST(HeadlessImages, FurnaceRendersItsExactRadianceEverywhere) {
  // Ke = 1, rho = 0.5: radiance Ke / (1 - rho) = 2 on every pixel.
  scratch_dir dir;
  ASSERT_EQ(run("render " + source_path("assets/furnace/furnace.json") + " --size 64x64 --max-edge 0.5 --until 1e-6 " +
                "--out " + dir.path("a.png") + " --pfm " + dir.path("a.pfm")),
            0);
  image img;
  std::string error;
  ASSERT_TRUE(read_pfm(dir.path("a.pfm"), img, error)) << error;
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x)
      for (int c = 0; c < 3; ++c) ASSERT_NEAR(img.at(x, y)[c], 2.0, 2.0 * 0.005) << x << "," << y;
}

image read(const std::string& pfm) {
  image img;
  std::string error;
  EXPECT_TRUE(read_pfm(pfm, img, error)) << error;
  return img;
}

// Mean relative difference of two pictures away from the edges and
// emitters of `marks` (anti-aliased differently by the view and the
// tracer), both pictures left with those pixels excluded.
double difference_away_from_edges(image& a, image& b, const image& marks) {
  std::vector<bool> edges = contrast_edges(marks, 0.1);
  const std::vector<bool> emitters = bright_pixels(marks, 1.0);
  for (std::size_t i = 0; i < edges.size(); ++i) edges[i] = edges[i] || emitters[i];
  exclude_pixels(a, edges, 1);
  exclude_pixels(b, edges, 1);
  return mean_relative_error(a, b);
}

TEST(HeadlessImages, EyeInsideARoomWithBigTrianglesCrossingTheViewVolume) {
  // The eye inside a room, elements up to 2 m long: many triangles cross
  // the near plane and the sides of the view. GL's clipper, given values
  // already divided by w, made inf and NaN pixels (measured before the
  // fragment shader fell back to GL's own interpolation there: 218 at
  // 64x64 from the scene's camera, 2610 looking up from near the floor).
  // Every pixel is finite and >= 0, and away from edges the view agrees
  // with the ray-traced still of the same solution, as on the Cornell box
  // (so the clipped parts carry the right values, not merely finite ones).
  // Without multisampling (--msaa 0, the window on software GL) the shader
  // takes GL's own interpolation throughout: the same holds. The view adds
  // the ambient term as the still does: three steps may end just after the
  // links were refined, where the residual (87% here) is far from zero.
  scratch_dir dir;
  for (const std::string view : {"", " --eye 3,0.3,3 --target 3,3,4 --fov 100"}) {
    const std::string common = " generated:interior-10k --max-edge 2 --max-steps 3 --size 64x64" + view + " --out " +
                               dir.path("a.png") + " --pfm ";
    ASSERT_EQ(run("trace --direct radiosity --spp 4" + common + dir.path("traced.pfm")), 0) << view;
    for (const std::string samples : {"", " --msaa 0"}) {
      // --ambient: the still always adds the solution's ambient term.
      ASSERT_EQ(run("render --ambient" + samples + common + dir.path("gouraud.pfm")), 0) << view << samples;
      image gouraud = read(dir.path("gouraud.pfm")), traced = read(dir.path("traced.pfm"));
      expect_finite_and_non_negative(gouraud, "view" + view + samples);
      const image marks = traced;
      const double difference = difference_away_from_edges(traced, gouraud, marks);
      std::printf("view%s%s: mean relative difference %.5f away from edges\n", view.c_str(), samples.c_str(),
                  difference);
      EXPECT_LT(difference, 0.01) << view << samples;
    }
  }
}

TEST(RayTracedStills, WhittedSceneMatchesItsGolden) {
  // One-pass Whitted (checkerboard, mirror and glass spheres, point
  // light), as tests/update_goldens.sh makes it.
  scratch_dir dir;
  ASSERT_EQ(run("trace " + source_path("assets/whitted/whitted.json") +
                " --size 160x120 --spp 4 --no-radiosity --ambient 0.5 --out " + dir.path("a.png")),
            0);
  expect_matches_golden(dir.path("a.png"), "whitted_trace.png", max_mean, max_p999);
}

TEST(RayTracedStills, TwoPassMatchesTheGouraudViewOfTheSameSolution) {
  // Purely diffuse scene, diffuse term all from the solution: the traced
  // still and the Gouraud view interpolate the same vertex radiosities, so
  // away from edges (silhouettes, emitters: anti-aliased differently)
  // they agree to the interpolation's float round-off.
  scratch_dir dir;
  const std::string common = " --size 128x128 --max-edge 60 --until 1e-3 --out " + dir.path("a.png") + " --pfm ";
  ASSERT_EQ(run("render" + common + dir.path("gouraud.pfm")), 0);
  ASSERT_EQ(run("trace --direct radiosity --spp 4" + common + dir.path("traced.pfm")), 0);
  image gouraud = read(dir.path("gouraud.pfm")), traced = read(dir.path("traced.pfm"));
  const image marks = gouraud;
  const double difference = difference_away_from_edges(traced, gouraud, marks);
  std::printf("two-pass vs Gouraud: mean relative difference %.5f away from edges\n", difference);
  EXPECT_LT(difference, 0.01);
  EXPECT_NEAR(mean_radiance(traced) / mean_radiance(gouraud), 1.0, 0.005);
}

TEST(RayTracedStills, CornellRadiosityAgreesWithThePathTracer) {
  // The converged radiosity solution (Gouraud view) against the path
  // tracer at 256 samples per pixel, emitters left out, 4x downsampled:
  // on uniform meshes (no element split: --min-edge = --max-edge) the
  // error falls as the elements shrink from 100 to 30 mm; from 100 mm
  // with the elements split where links need them, it is about the 30 mm
  // mesh's (measured 0.0350 against 0.0315, the 100 mm uniform mesh
  // 0.0613; 0.0437 against 0.0417 before the floor under the blocks was
  // cut out of the mesh, 0.0473 against 0.0527 before clusters sent by
  // direction). The path tracer's own noise here is about 2%.
  scratch_dir dir;
  ASSERT_EQ(run("trace --integrator path --spp 256 --size 64x64 --pfm " + dir.path("path.pfm") + " --out " +
                dir.path("a.png")),
            0);
  auto error_of = [&](const std::string& args) {
    EXPECT_EQ(run("render --size 64x64 --until 1e-3 " + args + " --pfm " + dir.path("radiosity.pfm") + " --out " +
                  dir.path("a.png")),
              0);
    image path = read(dir.path("path.pfm")), radiosity = read(dir.path("radiosity.pfm"));
    const std::vector<bool> emitters = bright_pixels(path, 1.0);
    exclude_pixels(path, emitters, 1);
    exclude_pixels(radiosity, emitters, 1);
    const double error = relative_rmse(downsample(radiosity, 4), downsample(path, 4));
    std::printf("radiosity, %s, vs path traced: relative RMSE %.4f\n", args.c_str(), error);
    return error;
  };
  const double coarse = error_of("--max-edge 100 --min-edge 100");
  const double fine = error_of("--max-edge 30 --min-edge 30");
  const double split = error_of("--max-edge 100");
  EXPECT_LT(coarse, 0.16);
  EXPECT_LT(fine, 0.06);
  EXPECT_LT(fine, coarse);
  EXPECT_LT(split, 1.2 * fine);
}

TEST(RayTracedStills, CoplanarLightAgreesWithThePathTracerAsTheEmbeddedBoxDoes) {
  // Relative RMSE of the Gouraud view against the path tracer, emitters
  // included (4x downsampled, as `bounce compare --downsample 4`): the
  // published box with the light in the ceiling's plane or 0.1 mm under it
  // must do as well as the embedded box, whose ceiling is cut by hand
  // (measured: 0.274 for the embedded box; before the cut 2.4 in the plane
  // and 1.75 under it, after it 0.273 and 0.247).
  auto error_of = [&](const std::string& scene_args, const std::string& tag) {
    scratch_dir dir(tag);
    const std::string json = scene_args.empty() ? "" : test_support::write_official_cornell(dir, scene_args, 64, 64);
    const std::string common = json + " --size 64x64 --out " + dir.path("a.png") + " --pfm ";
    EXPECT_EQ(run("trace " + common + dir.path("path.pfm") + " --integrator path --spp 256"), 0);
    EXPECT_EQ(run("render " + common + dir.path("radiosity.pfm") + " --max-edge 40"), 0);
    const double error =
        relative_rmse(downsample(read(dir.path("radiosity.pfm")), 4), downsample(read(dir.path("path.pfm")), 4));
    std::printf("%s: relative RMSE %.4f against the path tracer\n", tag.c_str(), error);
    return error;
  };
  const double embedded = error_of("", "embedded");
  EXPECT_LT(error_of("548.8", "in_plane"), 1.15 * embedded);
  EXPECT_LT(error_of("548.7", "under"), 1.15 * embedded);
}

TEST(HeadlessImages, FramesAreWrittenDuringTheSolve) {
  scratch_dir dir;
  ASSERT_EQ(run("render --size 64x64 --max-edge 100 --solver progressive --max-steps 6 --frame-every 2 --frames " +
                dir.path("frames") + " --out " + dir.path("a.png")),
            0);
  for (const char* name : {"frame_000002.png", "frame_000004.png", "frame_000006.png"})
    EXPECT_TRUE(std::filesystem::exists(dir.path("frames/") + name)) << name;
  EXPECT_FALSE(std::filesystem::exists(dir.path("frames/frame_000001.png")));
  // Each frame shows more light than the one before.
  double previous = -1.0;
  for (const char* name : {"frame_000002.png", "frame_000004.png", "frame_000006.png"}) {
    int w = 0, h = 0;
    std::vector<unsigned char> rgb;
    std::string error;
    ASSERT_TRUE(read_png_rgb8(dir.path("frames/") + name, w, h, rgb, error)) << error;
    double sum = 0.0;
    for (unsigned char v : rgb) sum += v;
    EXPECT_GT(sum, previous) << name;
    previous = sum;
  }
}

TEST(HeadlessImages, PanelIsDrawnBesideThePictureNotOnIt) {
  scratch_dir dir;
  const std::string args = "render --size 512x512 --max-edge 80 --until 0.05 --out ";
  ASSERT_EQ(run(args + dir.path("plain.png")), 0);
  ASSERT_EQ(run(args + dir.path("panel.png") + " --panel"), 0);
  int w = 0, h = 0, pw = 0, ph = 0;
  std::vector<unsigned char> plain, panel;
  std::string error;
  ASSERT_TRUE(read_png_rgb8(dir.path("plain.png"), w, h, plain, error)) << error;
  ASSERT_TRUE(read_png_rgb8(dir.path("panel.png"), pw, ph, panel, error)) << error;
  // The panel is docked to the right of the whole picture: the PNG is wider
  // by the panel's width, and its left 512 columns are the plain picture.
  ASSERT_EQ(ph, h);
  ASSERT_GE(pw, w + 300);
  double view_difference = 0.0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int c = 0; c < 3; ++c)
        view_difference +=
            std::abs(int(plain[(std::size_t(y) * w + x) * 3 + c]) - int(panel[(std::size_t(y) * pw + x) * 3 + c]));
  EXPECT_LT(view_difference / (double(w) * h * 3), 0.01);
  // The panel's part holds its background and text: not black.
  double panel_level = 0.0;
  for (int y = 0; y < h; ++y)
    for (int x = w + 8; x < pw; ++x)
      for (int c = 0; c < 3; ++c) panel_level += panel[(std::size_t(y) * pw + x) * 3 + c];
  EXPECT_GT(panel_level / (double(pw - w - 8) * h * 3), 10.0);
}
TEST(HeadlessImages, NoArgumentsRendersTheDefaultScene) {
  scratch_dir dir;
  const std::string command = "cd " + dir.root.string() + " && env -u DISPLAY " + BOUNCE_EXE + " >out.txt 2>&1";
  ASSERT_EQ(std::system(command.c_str()), 0);
  EXPECT_TRUE(std::filesystem::exists(dir.path("bounce.png")));
  std::ifstream out(dir.path("out.txt"));
  std::string text((std::istreambuf_iterator<char>(out)), {});
  EXPECT_NE(text.find("wrote " + dir.path("bounce.png")), std::string::npos) << text;
}
// A floor with a checker and a back wall with an 8 x 8 image under a small
// lamp, open, with a black background: textured materials in the live view.
// `textured` false drops the textures (the same rho, untextured).
std::string write_textured_scene(const scratch_dir& dir, bool textured) {
  // The wall's image: gentle ramps, so that bilinear filtering is what the
  // comparison sees (no texel edges for it to leave out), and the still's 4
  // jittered samples a pixel average to about its centre's value.
  std::vector<unsigned char> texels;
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 8; ++x)
      for (int c : {100 + 12 * x, 100 + 12 * y, 184 - 6 * (x + y)}) texels.push_back(static_cast<unsigned char>(c));
  std::string error;
  EXPECT_TRUE(write_png(dir.path("wall.png"), 8, 8, 3, texels.data(), error)) << error;
  const std::string path = dir.path(textured ? "textured.json" : "plain.json");
  std::ofstream(path) << R"({
  "camera": {"eye": [1, 1.2, 3], "target": [1, 0.5, 0.6], "fov": 60, "size": [96, 96]},
  "textures": {
    "checks": {"checker": {"color0": [0.9, 0.9, 0.9], "color1": [0.2, 0.3, 0.1], "scale": 3}},
    "wall": {"image": "wall.png"}
  },
  "materials": {
    "floor": {"rho": [0.7, 0.7, 0.7])"
                      << (textured ? R"(, "texture": "checks")" : "") << R"(},
    "wall": {"rho": [0.6, 0.6, 0.6])"
                      << (textured ? R"(, "texture": "wall")" : "") << R"(},
    "lamp": {"ke": [5, 5, 5]}
  },
  "surfaces": [
    {"polygon": [[0, 0, 0], [0, 0, 2], [2, 0, 2], [2, 0, 0]], "uv": [[0, 0], [0, 2], [2, 2], [2, 0]], "material": "floor"},
    {"polygon": [[0, 0, 0], [2, 0, 0], [2, 1.5, 0], [0, 1.5, 0]], "uv": [[0, 0], [1, 0], [1, 1], [0, 1]], "material": "wall"},
    {"polygon": [[0.7, 1.5, 0.7], [1.3, 1.5, 0.7], [1.3, 1.5, 1.3], [0.7, 1.5, 1.3]], "material": "lamp"}
  ]
})";
  return path;
}

TEST(HeadlessImages, TexturedMaterialsShowTheStillsRule) {
  // The live view multiplies the vertex radiosity by texture(uv) /
  // mean(texture), as the two-pass still does per pixel, so away from edges
  // (the checker's among them) and emitters the two agree to the float
  // round-off of interpolation and texture filtering and the still's
  // jittered samples (measured: 0.0022). Without textures the same scene
  // differs by far more (measured: 0.30).
  scratch_dir dir;
  const std::string solve = " --solver progressive --max-edge 0.25 --until 1e-3 --out " + dir.path("a.png") + " --pfm ";
  const std::string textured = write_textured_scene(dir, true), plain = write_textured_scene(dir, false);
  ASSERT_EQ(run("render " + textured + solve + dir.path("gouraud.pfm")), 0);
  ASSERT_EQ(run("trace --direct radiosity --spp 4 " + textured + solve + dir.path("traced.pfm")), 0);
  ASSERT_EQ(run("render " + plain + solve + dir.path("plain.pfm")), 0);
  image gouraud = read(dir.path("gouraud.pfm")), traced = read(dir.path("traced.pfm"));
  image untextured = read(dir.path("plain.pfm")), traced_again = traced;
  const image marks = traced;
  const double difference = difference_away_from_edges(traced, gouraud, marks);
  const double without = difference_away_from_edges(traced_again, untextured, marks);
  std::printf("textured view vs still: mean relative difference %.5f away from edges; untextured view: %.5f\n",
              difference, without);
  EXPECT_LT(difference, 0.005);
  EXPECT_GT(without, 0.1);
}

// An open scene: a lit floor seen from above its far edge, so that the top
// of the picture sees nothing but what the scene puts beyond it.
std::string write_open_scene(const scratch_dir& dir, const std::string& beyond) {
  const std::string path = dir.path("open.json");
  std::ofstream(path) << R"({
  "camera": {"eye": [1, 0.6, 3], "target": [1, 0.6, 0], "fov": 60, "size": [64, 64]},)"
                      << beyond << R"(
  "materials": {"floor": {"rho": [0.6, 0.6, 0.6]}, "lamp": {"ke": [4, 4, 4]}},
  "surfaces": [
    {"polygon": [[0, 0, 0], [0, 0, 2], [2, 0, 2], [2, 0, 0]], "material": "floor"},
    {"polygon": [[0.7, 0.5, 0.7], [1.3, 0.5, 0.7], [1.3, 0.5, 1.3], [0.7, 0.5, 1.3]], "material": "lamp"}
  ]
})";
  return path;
}

TEST(HeadlessImages, BackgroundShowsWhereNothingIsHit) {
  // Where no surface is hit (the top rows here), the linear output holds
  // the background radiance itself, and the PNG shows it through the same
  // exposure and tone curve as the still's PNG (8-bit rounding apart).
  scratch_dir dir;
  const rgb background(0.25, 0.5, 1.5);
  const std::string scene = write_open_scene(dir, R"( "background": [0.25, 0.5, 1.5],)");
  const std::string common = scene + " --solver progressive --max-edge 0.5 --until 1e-2 --exposure 0.8 --out ";
  ASSERT_EQ(run("render " + common + dir.path("view.png") + " --pfm " + dir.path("view.pfm")), 0);
  ASSERT_EQ(run("trace --direct radiosity --spp 4 " + common + dir.path("still.png")), 0);
  const image view = read(dir.path("view.pfm"));
  int w = 0, h = 0;
  std::vector<unsigned char> view_png, still_png;
  std::string error;
  ASSERT_TRUE(read_png_rgb8(dir.path("view.png"), w, h, view_png, error)) << error;
  ASSERT_TRUE(read_png_rgb8(dir.path("still.png"), w, h, still_png, error)) << error;
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < view.width; ++x)
      for (int c = 0; c < 3; ++c) {
        ASSERT_EQ(view.at(x, y)[c], float(background[c])) << x << "," << y;
        const std::size_t i = (std::size_t(y) * w + x) * 3 + c;
        ASSERT_LE(std::abs(int(view_png[i]) - int(still_png[i])), 1) << x << "," << y;
      }
  // The floor is drawn over it: the bottom rows are not the background.
  EXPECT_NE(view.at(32, 60).r, float(background.r));
}

TEST(HeadlessImages, SkyShowsWhereNothingIsHit) {
  // With a sky, what rays that miss see depends on their direction: the
  // view's top rows hold the still's sky radiance (a linear blend from the
  // horizon up, evaluated per pixel) to float precision, and its PNG the
  // still's PNG (8-bit rounding apart).
  scratch_dir dir;
  const std::string scene = write_open_scene(
      dir, R"( "background": [9, 9, 9], "sky": {"zenith": [0.2, 0.4, 1.2], "horizon": [1, 0.8, 0.5]},)");
  const std::string common = scene + " --solver progressive --max-edge 0.5 --until 1e-2 --fov 120 --out ";
  ASSERT_EQ(run("render " + common + dir.path("view.png") + " --pfm " + dir.path("view.pfm")), 0);
  ASSERT_EQ(
      run("trace --direct radiosity --spp 4 " + common + dir.path("still.png") + " --pfm " + dir.path("still.pfm")), 0);
  const image view = read(dir.path("view.pfm")), still = read(dir.path("still.pfm"));
  int w = 0, h = 0;
  std::vector<unsigned char> view_png, still_png;
  std::string error;
  ASSERT_TRUE(read_png_rgb8(dir.path("view.png"), w, h, view_png, error)) << error;
  ASSERT_TRUE(read_png_rgb8(dir.path("still.png"), w, h, still_png, error)) << error;
  double sum = 0.0, largest = 0.0;
  for (int y = 0; y < 10; ++y)
    for (int x = 0; x < view.width; ++x)
      for (int c = 0; c < 3; ++c) {
        const double difference = std::abs(double(view.at(x, y)[c]) / still.at(x, y)[c] - 1.0);
        sum += difference;
        largest = std::max(largest, difference);
        const std::size_t i = (std::size_t(y) * w + x) * 3 + c;
        ASSERT_LE(std::abs(int(view_png[i]) - int(still_png[i])), 1) << x << "," << y;
      }
  const double mean = sum / (10 * view.width * 3);
  std::printf("sky: relative difference in the top rows %.6f (mean), %.6f (largest)\n", mean, largest);
  EXPECT_LT(mean, 2e-3);     // measured: 0.0005, the still's 4 jittered samples a pixel
  EXPECT_LT(largest, 1e-2);  // measured: 0.0035
  // The sky changes over those rows (the test sees a gradient, not a colour).
  EXPECT_GT(std::abs(view.at(32, 0).b - view.at(32, 9).b), 0.01);
}

// A floor modelled upside down under a lamp: black in the live view when
// one-sided; two-sided, its back shows the light as the right way up would,
// and the one-sided front it lies on does not show through.
TEST(HeadlessImages, TwoSidedUpsideDownFloorShowsItsLitSide) {
  scratch_dir dir;
  auto scene_file = [&](const std::string& name, bool upside_down, bool two_sided) {
    const std::string floor = upside_down ? "[[-1, 0, -1], [1, 0, -1], [1, 0, 1], [-1, 0, 1]]"
                                          : "[[-1, 0, -1], [-1, 0, 1], [1, 0, 1], [1, 0, -1]]";
    return dir.write(name, std::string(R"({"materials": {"white": {"rho": [0.5, 0.5, 0.5], "two_sided": )") +
                               (two_sided ? "true" : "false") + R"(}, "lamp": {"ke": [5, 5, 5]}},
      "surfaces": [{"polygon": )" +
                               floor + R"(, "material": "white"},
        {"polygon": [[-0.2, 1, -0.2], [0.2, 1, -0.2], [0.2, 1, 0.2], [-0.2, 1, 0.2]], "material": "lamp"}],
      "camera": {"eye": [0, 2, 2], "target": [0, 0, 0], "size": [64, 64]}})");
  };
  double mean[3] = {0, 0, 0};
  const std::string names[3] = {"right.json", "upside_down.json", "two_sided.json"};
  const bool flags[3][2] = {{false, false}, {true, false}, {true, true}};
  image pictures[3];
  for (int i = 0; i < 3; ++i) {
    const std::string file = scene_file(names[i], flags[i][0], flags[i][1]);
    ASSERT_EQ(run("render " + file + " --quiet --until 1e-4 --out " + dir.path("x.pfm")), 0) << names[i];
    std::string error;
    ASSERT_TRUE(read_pfm(dir.path("x.pfm"), pictures[i], error)) << error;
    for (float v : pictures[i].pixels)
      mean[i] += v < 2.0f ? v / double(pictures[i].pixels.size()) : 0.0;  // not the lamp
  }
  EXPECT_LT(mean[1], 0.05 * mean[0]);  // one-sided, upside down: black
  EXPECT_NEAR(mean[2], mean[0], 0.02 * mean[0]);
  // Pixel by pixel, not just on average: no z-fighting with the dark front.
  int dark = 0;
  for (std::size_t i = 0; i < pictures[0].pixels.size(); ++i)
    dark += pictures[0].pixels[i] > 0.05f && pictures[0].pixels[i] < 2.0f &&
            pictures[2].pixels[i] < 0.5f * pictures[0].pixels[i];
  EXPECT_EQ(dark, 0);
}

// A closed room with a red wall on one side and a green one on the other,
// and a sphere of `sphere_material` at its centre.
std::string write_room_with_sphere(const scratch_dir& dir, const std::string& sphere_material) {
  return dir.write("room_sphere.json", R"({
  "camera": {"eye": [1, 1, 2.9], "target": [1, 1, 1], "fov": 40, "size": [96, 96]},
  "materials": {
    "white": {"rho": [0.7, 0.7, 0.7]}, "red": {"rho": [0.7, 0.1, 0.1]}, "green": {"rho": [0.1, 0.7, 0.1]},
    "lamp": {"ke": [6, 6, 6]}, "ball": )" + sphere_material +
                                           R"(
  },
  "surfaces": [
    {"polygon": [[0, 0, 3], [2, 0, 3], [2, 0, 0], [0, 0, 0]], "material": "white"},
    {"polygon": [[2, 2, 0], [2, 2, 3], [0, 2, 3], [0, 2, 0]], "material": "white"},
    {"polygon": [[2, 0, 0], [2, 2, 0], [0, 2, 0], [0, 0, 0]], "material": "white"},
    {"polygon": [[0, 2, 3], [2, 2, 3], [2, 0, 3], [0, 0, 3]], "material": "white"},
    {"polygon": [[0, 2, 0], [0, 2, 3], [0, 0, 3], [0, 0, 0]], "material": "red"},
    {"polygon": [[2, 0, 3], [2, 2, 3], [2, 2, 0], [2, 0, 0]], "material": "green"},
    {"polygon": [[1.2, 1.99, 1.3], [1.2, 1.99, 1.7], [0.8, 1.99, 1.7], [0.8, 1.99, 1.3]], "material": "lamp"},
    {"sphere": {"center": [1, 1, 1], "radius": 0.5}, "material": "ball"}
  ]
})");
}

// The mean relative difference of two pictures over the pixels that see
// the sphere of write_room_with_sphere well inside its outline.
double difference_on_sphere(const image& a, const image& b) {
  camera c;
  c.eye = vec3(1, 1, 2.9);
  c.target = vec3(1, 1, 1);
  c.fov_y_degrees = 40;
  c.width = a.width;
  c.height = a.height;
  double sum = 0.0;
  int count = 0;
  for (int y = 0; y < a.height; ++y)
    for (int x = 0; x < a.width; ++x) {
      const vec3 d = camera_ray_direction(c, x + 0.5, y + 0.5);
      const vec3 to_centre = vec3(1, 1, 1) - c.eye;
      const double miss = glm::length(to_centre - glm::dot(to_centre, d) * d);  // ray's distance from the centre
      if (miss > 0.4) continue;                                                 // the outline (radius 0.5) is left out
      for (int k = 0; k < 3; ++k) {
        sum += std::abs(double(a.at(x, y)[k]) - b.at(x, y)[k]) / std::max(1e-3, double(b.at(x, y)[k]));
        ++count;
      }
    }
  return count ? sum / count : 1.0;
}

// Curved surfaces look the same in the live view (`render`) as in the
// still (`trace`): the teapot round, not an octagon with dark wedges
// where the spout and handle enter the body; the vase's rim round.
// Measured (10 x 10 blocks, levels of 255, 240 x 180): teapot 11.7 before
// the curvature bound and the buried vertices, 1.4 after; shapes 0.93 and 0.48.
TEST(HeadlessImages, CurvedSurfacesLookTheSameLiveAndInTheStill) {
  scratch_dir dir;
  for (const std::string name : {"teapot", "shapes"}) {
    const std::string common = source_path("assets/" + name + "/" + name + ".json") + " --size 240x180 --out ";
    ASSERT_EQ(run("render --quiet " + common + dir.path(name + "-live.png")), 0);
    ASSERT_EQ(run("trace --quiet --spp 4 " + common + dir.path(name + "-still.png")), 0);
    const double difference = block_difference(dir.path(name + "-live.png"), dir.path(name + "-still.png"));
    std::printf("%s: live view against the still, %.2f of 255 over 10 x 10 blocks\n", name.c_str(), difference);
    EXPECT_LT(difference, 2.0) << name;
  }
}

// An emissive texture (ClearCoatTest's labels): the view draws the glow
// where the texture puts it, as the still does, not the mean it solves with
// (the label, 10 x 10 blocks: 20.6 of 255 with the mean glow, 0.81 now).
TEST(HeadlessImages, EmissiveTexturesGlowAsInTheStill) {
  const std::string model = "/usr/share/assimp/models/glTF2/ClearCoat-glTF/ClearCoatTest.gltf";
  if (!std::filesystem::exists(model)) GTEST_SKIP() << "assimp-testmodels is not installed";
  scratch_dir dir;
  const std::string common = model + " --eye -2.087,6.616,4 --target -2.087,6.616,0 --fov 10 --size 160x80 --out ";
  ASSERT_EQ(run("render --quiet " + common + dir.path("live.png")), 0);
  ASSERT_EQ(run("trace --quiet --spp 4 " + common + dir.path("still.png")), 0);
  const double difference = block_difference(dir.path("live.png"), dir.path("still.png"));
  std::printf("label: live view against the still, %.2f of 255 over 10 x 10 blocks\n", difference);
  EXPECT_LT(difference, 4.0);
}

// A cut-out (material alpha_cutoff over a texture's alpha): the view draws
// nothing in its holes, as the still, and shows what is behind them.
TEST(HeadlessImages, CutOutsAreHolesInTheViewAsInTheStill) {
  scratch_dir dir;
  // 2 x 2 texels, white; the right column clear.
  const unsigned char texels[] = {255, 255, 255, 255, 255, 255, 255, 0, 255, 255, 255, 255, 255, 255, 255, 0};
  std::string error;
  ASSERT_TRUE(write_png(dir.path("leaf.png"), 2, 2, 4, texels, error)) << error;
  const std::string scene = dir.write("leaf.json", R"({
  "camera": {"eye": [0.5, 0.5, 3], "target": [0.5, 0.5, 0], "fov": 18.9246, "size": [64, 64]},
  "textures": {"leaf": {"image": "leaf.png"}},
  "materials": {"leaf": {"rho": [0.5, 0.5, 0.5], "ke": [1, 1, 1], "texture": "leaf", "alpha_cutoff": 0.5},
                "wall": {"rho": [0, 0, 0], "ke": [0, 0, 1]}},
  "surfaces": [{"polygon": [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]], "uv": [[0, 0], [1, 0], [1, 1], [0, 1]], "material": "leaf"},
               {"polygon": [[-1, -1, -1], [2, -1, -1], [2, 2, -1], [-1, 2, -1]], "material": "wall"}]})");
  ASSERT_EQ(run("render " + scene + " --out " + dir.path("view.pfm")), 0);
  ASSERT_EQ(run("trace --spp 1 " + scene + " --out " + dir.path("still.pfm")), 0);
  for (const char* name : {"view.pfm", "still.pfm"}) {
    const image picture = read(dir.path(name));
    // A quarter in from each side, mid-height: the leaf, then the wall.
    const rgb leaf = rgb(picture.at(16, 32)), hole = rgb(picture.at(48, 32));
    EXPECT_NEAR(leaf.r, 1.0, 0.05) << name;
    EXPECT_NEAR(hole.r, 0.0, 0.02) << name;
    EXPECT_NEAR(hole.b, 1.0, 0.05) << name;
  }
}

// Every --msaa the option accepts draws the picture: more samples than the
// GL offers (llvmpipe: 4) are drawn with the most it offers, not black.
TEST(HeadlessImages, EveryMsaaDrawsThePicture) {
  scratch_dir dir;
  double reference = 0.0;
  for (const int samples : {4, 8, 0, 1, 2}) {
    const std::string out = dir.path("msaa" + std::to_string(samples) + ".pfm");
    ASSERT_EQ(run("render --quiet --size 48x48 --max-edge 150 --until 0.05 --msaa " + std::to_string(samples) +
                  " --out " + out),
              0);
    const image picture = read(out);
    double mean = 0.0;
    for (float v : picture.pixels) mean += v / double(picture.pixels.size());
    if (samples == 4) reference = mean;
    // Without multisampling (0, 1) the mean is 7% higher (measured): the
    // same picture, drawn another way; black would be 100% off.
    EXPECT_NEAR(mean, reference, 0.15 * reference) << "--msaa " << samples;
  }
  EXPECT_GT(reference, 0.0);
}

TEST(HeadlessImages, MirrorAndGlassShowWhatTheStillShows) {
  // The live view draws mirrors and glass from cube maps taken at the
  // object's centre and looked up where the ray meets the room's box
  // (docs/viewer.md, "Mirrors and glass"). In a box room with a sphere at
  // its centre that is exact for a mirror, so the view agrees with the
  // Whitted still of the same solution (measured: 0.0??); for glass, the
  // view leaves out the light reflected inside the sphere (measured:
  // 0.0??). Without reflections the sphere is black: a difference of 1.
  scratch_dir dir;
  const std::string materials[2] = {R"({"rho": [0, 0, 0], "kr": [0.9, 0.9, 0.9]})",
                                    R"({"rho": [0, 0, 0], "kt": [0.95, 0.95, 0.95], "ior": 1.5, "fresnel": true})"};
  const double tolerance[2] = {0.05, 0.1};
  for (int i = 0; i < 2; ++i) {
    const std::string scene = write_room_with_sphere(dir, materials[i]);
    const std::string common =
        scene + " --solver progressive --max-edge 0.25 --until 1e-3 --out " + dir.path("a.png") + " --pfm ";
    ASSERT_EQ(run("render " + common + dir.path("view.pfm")), 0);
    ASSERT_EQ(run("trace --direct radiosity --spp 4 " + common + dir.path("still.pfm")), 0);
    const double difference = difference_on_sphere(read(dir.path("view.pfm")), read(dir.path("still.pfm")));
    std::printf("%s sphere: view vs still, mean relative difference %.4f\n", i == 0 ? "mirror" : "glass", difference);
    EXPECT_LT(difference, tolerance[i]) << materials[i];
  }
}

}  // namespace
}  // namespace bounce
