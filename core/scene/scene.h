// The one scene model shared by the mesher, the solvers, the ray tracer and
// the renderer. Plain data: objects refer to each other by int index.
//
// Units: lengths in scene units (any); colours per RGB channel.
// Emission `ke` is radiance, as MTL's Ke; a Lambertian emitter's exitance is
// E = pi * ke. Reflectances are fractions of incident power.
#pragma once

#include <array>
#include <string>
#include <variant>
#include <vector>

#include "base/math_types.h"

namespace bounce {

enum class texture_kind { image, checker };

// A texture modulates a material's diffuse reflectance: rho(x) = rho * t(uv).
struct texture {
  std::string name;  // image path as written in the scene, or "checker"
  texture_kind kind = texture_kind::checker;
  // image: linear RGB texels, width*height*3, row 0 is the top (v = 1)
  int width = 0;
  int height = 0;
  std::vector<float> texels;
  std::vector<float> alpha;  // width*height coverage in [0, 1] when the image has it, else empty
  // checker: squares of color0/color1, `scale` squares per unit of uv
  rgb color0{1.0};
  rgb color1{0.0};
  double scale = 1.0;
};

struct material {
  std::string name;
  rgb rho{0.0};            // diffuse reflectance, each channel in [0, 1)
  rgb ke{0.0};             // emitted radiance, >= 0
  rgb kr{0.0};             // mirror reflectance (Whitted)
  rgb kt{0.0};             // specular transmittance (Whitted)
  double ior = 1.0;        // index of refraction, for kt
  bool fresnel = false;    // weight kr/kt by Fresnel's equations
  rgb specular{0.0};       // Phong highlight colour
  double shininess = 0.0;  // Phong exponent
  int texture = -1;        // index into scene::textures, or -1
  // Spreads the emission over the surface as a texture does: ke(x) =
  // ke * t(uv) / mean(t), so ke stays the mean radiance (the power) and the
  // glow follows the texture (a label, a screen). -1: uniform.
  int emission_texture = -1;
  // A cut-out (glTF's alphaMode MASK): where the texture's alpha times
  // `alpha` is below `alpha_cutoff`, there is no surface. 0: opaque.
  double alpha = 1.0;
  double alpha_cutoff = 0.0;
  bool two_sided = false;  // both sides receive, reflect and emit (two_sided.h)
};

// A polygon mesh as given: faces keep their vertex count (quads stay quads).
struct polygon_face {
  std::vector<int> position;  // indices into polygon_mesh::positions
  std::vector<int> normal;    // empty, or one per corner
  std::vector<int> uv;        // empty, or one per corner
  int material = 0;
  int line = 0;  // source line, for messages (0: not from a file)
};

struct polygon_mesh {
  std::vector<vec3> positions;
  std::vector<vec3> normals;
  std::vector<vec2> uvs;
  std::vector<polygon_face> faces;
};

// Analytic sphere; the normal points out of it.
struct sphere {
  vec3 center{0.0};
  double radius = 1.0;
  int material = 0;
};

// a x^2 + b y^2 + c z^2 + 2d xy + 2e yz + 2f xz + 2g x + 2h y + 2j z + k = 0,
// the part inside the axis-aligned box [box_min, box_max]. The normal is the
// gradient's direction: it points to where the polynomial is positive.
struct quadric {
  double a = 0, b = 0, c = 0, d = 0, e = 0, f = 0, g = 0, h = 0, j = 0, k = 0;
  vec3 box_min{-1.0};
  vec3 box_max{1.0};
  int material = 0;
};

// One smooth surface made of bicubic Bezier patches (the Utah teapot is 32).
// A patch's control points are row-major: control[4 * row + col], with u
// along a row (col) and v down the columns (row). Normal = dP/du x dP/dv.
struct bezier_surface {
  std::vector<std::array<vec3, 16>> patches;
  int material = 0;
};

// A uniform bicubic B-spline surface over a rows x cols control grid
// (rows, cols >= 4), row-major; it has (rows-3) x (cols-3) spans.
// u runs along a row, v down the columns. Normal = dP/du x dP/dv.
struct bspline_surface {
  int rows = 0;
  int cols = 0;
  std::vector<vec3> control;
  int material = 0;
};

using shape = std::variant<polygon_mesh, sphere, quadric, bezier_surface, bspline_surface>;

struct surface {
  std::string name;    // for messages: object name or "surfaces[3]"
  std::string source;  // file it was read from, for messages
  shape geometry;
  // Two-sided materials: the back of surface `back_of` (its faces with a
  // two-sided material, turned over), and its partner's index on the front.
  int back_of = -1;
  int back_side = -1;
};

struct camera {
  vec3 eye{0.0, 0.0, 1.0};
  vec3 target{0.0};
  vec3 up{0.0, 1.0, 0.0};
  double fov_y_degrees = 45.0;  // vertical field of view
  int width = 512;
  int height = 512;
};

enum class light_type { point, spot, sun };

// A light without area (the classic Whitted scenes' lamps, glTF's
// KHR_lights_punctual). point: radiant intensity `intensity` (W/sr) from
// `position` in every direction. spot: the same within a cone about
// `direction`, whole inside `inner_cone` and none beyond `outer_cone`
// (half-angles in radians), with glTF's smooth edge between (lights.h).
// sun: parallel light travelling along `direction` from beyond the scene,
// `intensity` being the irradiance (W/m^2) on a surface that faces it.
struct punctual_light {
  vec3 position{0.0};  // point and spot only
  rgb intensity{0.0};
  light_type type = light_type::point;
  vec3 direction{0.0, -1.0, 0.0};  // unit; spot and sun only
  double inner_cone = 0.0;
  double outer_cone = 0.7853981633974483;  // pi / 4, glTF's default
};

// An environment emitter at infinity around the whole scene: radiance
// `horizon` at and below the horizon, blending linearly in the cosine to
// `zenith` straight up (along `up`). Equal colours make a uniform sky.
// It lights an open scene; rays that leave the scene see it (sky.h).
struct sky_light {
  rgb zenith{0.0};
  rgb horizon{0.0};
  vec3 up{0.0, 1.0, 0.0};
  bool on() const { return zenith != rgb(0.0) || horizon != rgb(0.0); }
};

struct scene {
  std::string source;  // file it came from, for messages
  std::vector<material> materials;
  std::vector<texture> textures;
  std::vector<surface> surfaces;
  std::vector<punctual_light> lights;
  camera view;
  rgb background{0.0};  // radiance of rays that leave the scene, where there is no sky
  sky_light sky;        // off unless the scene has one (or a bare model file has no emitter)
};

// Light that does not come from the surfaces: punctual lights or a sky.
inline bool has_lights_beyond_surfaces(const scene& s) {
  return !s.lights.empty() || s.sky.on();
}

}  // namespace bounce
