#version 330 core
// Gouraud view of the patch mesh: per-vertex radiosity, interpolated.
layout(location = 0) in vec3 position;
layout(location = 1) in vec3 normal;
layout(location = 2) in vec3 reflectance;  // rho, for the display ambient term
layout(location = 3) in vec3 radiosity;    // B, updated after every solver step
layout(location = 4) in vec3 unshot;       // mean unshot radiosity of the vertex's elements
layout(location = 5) in float element_size;  // square root of the mean area of the vertex's elements
#ifdef TEXTURED  // see gouraud.frag
layout(location = 6) in vec2 uv;  // texture coordinates
#endif

uniform mat4 view_projection;
uniform vec3 ambient;        // Cohen 1988 ambient radiosity, zero when switched off
uniform vec3 eye;
// The preview before the first solution (display_settings::headlight):
// rho times this radiance, shaded by a light at the eye. 0: off.
uniform float headlight;

// Interpolated at the centroid: under MSAA a pixel partly covered by a
// triangle is shaded at a covered sample, never at the pixel centre outside
// the triangle, where linear interpolation extrapolates (negative radiance
// at silhouettes, wild values where triangles are smaller than a pixel).
// Perspective is corrected by hand (each value over w, and 1 / w, linear in
// the screen, divided in gouraud.frag): Mesa's llvmpipe (22.3) takes w at
// the pixel centre for centroid inputs, so a constant came out up to 0.4%
// off; the quotient of two values interpolated at one point is exact.
// SINGLE_SAMPLE (a framebuffer without multisampling: the window on
// software GL, the mirrors' cube-map faces) leaves the quotients out: the
// centroid is then the pixel centre, GL's own interpolation below is
// exact, and half as many values to interpolate is a few milliseconds a
// frame on llvmpipe (docs/viewer.md, "Frame times").
#ifndef SINGLE_SAMPLE
noperspective centroid out vec4 radiance_w;  // (B / pi in W / (m^2 sr), 1) / w
noperspective centroid out vec4 unshot_w;    // (unshot / pi, element size) / w
noperspective centroid out vec3 normal_w;
noperspective centroid out vec3 position_w;
#endif
// The same values interpolated by GL itself (perspective-correct), for the
// few fragments where the quotients above are not finite: Mesa's clipper
// finds its blend factor for noperspective values from a difference of
// screen x (or y), 0 / 0 on an edge that is clipped where its two ends
// land in the same column, and a vertex at w = 0 has no quotient at all.
// 1 on surfaces that have a back (a two-sided material): their partner
// draws that side, so this one's back is not drawn (the sign of element_size).
flat out int has_back_side;
smooth centroid out vec3 radiance_s;
smooth centroid out vec4 unshot_s;
smooth centroid out vec3 normal_s;
smooth centroid out vec3 position_s;
#ifdef TEXTURED
#ifndef SINGLE_SAMPLE
noperspective centroid out vec2 uv_w;
#endif
smooth centroid out vec2 uv_s;
#endif

void main() {
  const float pi = 3.14159265358979;
#ifdef BACKGROUND  // see gouraud.frag
  // Corners (-1, -1), (3, -1), (-1, 3) cover the screen; z = w puts the
  // triangle on the far plane, where only samples no surface drew pass.
  vec2 corner = vec2(float((gl_VertexID & 1) << 2) - 1.0, float((gl_VertexID & 2) << 1) - 1.0);
  gl_Position = vec4(corner, 1.0, 1.0);
  return;
#endif
  gl_Position = view_projection * vec4(position, 1.0);
  has_back_side = element_size < 0.0 ? 1 : 0;
  vec3 lit = radiosity + reflectance * ambient;
  if (headlight > 0.0) {
    vec3 to_eye = eye - position;
    float facing = dot(to_eye, to_eye) > 0.0 ? abs(dot(normalize(normal), normalize(to_eye))) : 1.0;
    lit += pi * headlight * reflectance * (0.3 + 0.7 * facing);
  }
#ifndef SINGLE_SAMPLE
  float inv_w = 1.0 / gl_Position.w;
  radiance_w = vec4(lit / pi, 1.0) * inv_w;
  unshot_w = vec4(unshot / pi, abs(element_size)) * inv_w;
  normal_w = normal * inv_w;
  position_w = position * inv_w;
#endif
  radiance_s = lit / pi;
  unshot_s = vec4(unshot / pi, abs(element_size));
  normal_s = normal;
  position_s = position;
#ifdef TEXTURED
#ifndef SINGLE_SAMPLE
  uv_w = uv * inv_w;
#endif
  uv_s = uv;
#endif
}
