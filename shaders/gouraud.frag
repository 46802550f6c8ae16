#version 330 core
// Centroid, perspective-corrected by hand: see gouraud.vert.
noperspective centroid in vec4 radiance_w;
noperspective centroid in vec4 unshot_w;
noperspective centroid in vec3 normal_w;
noperspective centroid in vec3 position_w;
smooth centroid in vec3 radiance_s;  // the fallback: see gouraud.vert
smooth centroid in vec4 unshot_s;
smooth centroid in vec3 normal_s;
smooth centroid in vec3 position_s;

uniform float exposure;
uniform int tone_curve;        // 0: clamp + sRGB, 1: filmic (ACES fit) + sRGB, 2: linear radiance (PFM)
uniform int false_colour;      // 0: radiance, 1: unshot power (log scale), 2: element size (linear)
uniform float largest_element;  // element size that maps to the top of the scale
uniform int highlight_back_faces;
uniform vec3 eye;

out vec4 fragment;

vec3 srgb(vec3 linear) {
  linear = clamp(linear, 0.0, 1.0);
  return mix(12.92 * linear, 1.055 * pow(linear, vec3(1.0 / 2.4)) - 0.055, step(vec3(0.0031308), linear));
}

// Narkowicz's fit of the ACES filmic curve.
vec3 filmic(vec3 x) {
  return clamp((x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14), 0.0, 1.0);
}

// Blue (0) to red (1).
vec3 heat(float t) {
  t = clamp(t, 0.0, 1.0);
  return clamp(vec3(1.5 - abs(4.0 * t - 3.0), 1.5 - abs(4.0 * t - 2.0), 1.5 - abs(4.0 * t - 1.0)), 0.0, 1.0);
}

void main() {
  float w = 1.0 / radiance_w.w;
  vec3 vertex_radiance = radiance_w.xyz * w;
  vec3 vertex_unshot = unshot_w.xyz * w;
  float vertex_element_size = unshot_w.w * w;
  vec3 world_normal = normal_w * w;
  vec3 world_position = position_w * w;
  // Where the clipper left no quotient (see gouraud.vert): GL's own values.
  vec4 check = vec4(vertex_radiance, vertex_element_size) + vec4(vertex_unshot, 0.0);
  if (!(radiance_w.w > 0.0) || any(isnan(check)) || any(isinf(check))) {
    vertex_radiance = radiance_s;
    vertex_unshot = unshot_s.xyz;
    vertex_element_size = unshot_s.w;
    world_normal = normal_s;
    world_position = position_s;
  }
  if (highlight_back_faces != 0 && dot(world_normal, eye - world_position) < 0.0) {
    fragment = vec4(1.0, 0.0, 1.0, 1.0);  // magenta: a flipped normal faces the camera
    return;
  }
  if (false_colour == 1) {  // unshot radiance over eight decades, 1e-6 to 1e2
    float value = max(dot(vertex_unshot, vec3(1.0)), 1e-30);
    fragment = vec4(srgb(heat((log(value) / log(10.0) + 6.0) / 8.0)), 1.0);
    return;
  }
  if (false_colour == 2) {
    fragment = vec4(srgb(heat(vertex_element_size / largest_element)), 1.0);
    return;
  }
  vec3 value = vertex_radiance * exposure;
  if (tone_curve == 2) {
    fragment = vec4(vertex_radiance, 1.0);  // linear radiance, unscaled
  } else if (tone_curve == 1) {
    fragment = vec4(srgb(filmic(value)), 1.0);
  } else {
    fragment = vec4(srgb(value), 1.0);
  }
}
