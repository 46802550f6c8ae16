#version 330 core
// Centroid, perspective-corrected by hand: see gouraud.vert. Compiled in
// variants (mesh_renderer.cpp): as it stands for plain materials, with
// TEXTURED for textured ones (so that plain pixels pay nothing for
// textures), with TEXTURED and SPECULAR for mirrors, with GLASS as well
// for glass (so that mirrors skip refraction), and with BACKGROUND for what
// rays that miss the scene see; each but the last with and without
// SINGLE_SAMPLE (see gouraud.vert).
#ifndef SINGLE_SAMPLE
noperspective centroid in vec4 radiance_w;
noperspective centroid in vec4 unshot_w;
noperspective centroid in vec3 normal_w;
noperspective centroid in vec3 position_w;
#endif
flat in int has_back_side;           // see gouraud.vert
smooth centroid in vec3 radiance_s;  // the fallback, or with SINGLE_SAMPLE the values: see gouraud.vert
smooth centroid in vec4 unshot_s;
smooth centroid in vec3 normal_s;
smooth centroid in vec3 position_s;
#ifdef TEXTURED
#ifndef SINGLE_SAMPLE
noperspective centroid in vec2 uv_w;
#endif
smooth centroid in vec2 uv_s;
#endif

#ifdef BACKGROUND
// The ray tracer's escaped_radiance (core/scene/sky.cpp): the sky where the
// scene has one, else the background colour.
uniform vec3 background;
uniform int sky;  // 1: the sky below, not the background
uniform vec3 zenith;
uniform vec3 horizon;
uniform vec3 sky_up;  // unit
uniform mat4 inverse_view_projection;
uniform vec4 viewport;  // x, y, width, height
#endif

uniform float exposure;
uniform int tone_curve;        // 0: clamp + sRGB, 1: filmic (ACES fit) + sRGB, 2: linear radiance (PFM)
uniform int false_colour;      // 0: radiance, 1: unshot power (log scale), 2: element size (linear)
uniform float largest_element;  // element size that maps to the top of the scale
uniform int highlight_back_faces;
uniform vec3 eye;
#ifdef TEXTURED
// Textures, as the ray tracer applies them (core/scene/texture.cpp): the
// reflected part of B times texture(uv) / mean(texture).
uniform int texture_mode;  // 1: image, 2: checker
uniform sampler2D image;   // linear RGB, row 0 the image's top (v = 1), repeating
uniform vec3 checker0;
uniform vec3 checker1;
uniform float checker_scale;  // squares per unit of uv
uniform vec3 inverse_mean;    // 1 / mean(texture), 0 where the mean is 0
uniform vec3 emitted;         // the material's ke, the mean of its emission
uniform float alpha;         // a cut-out's: no surface where the texture's alpha x alpha < alpha_cutoff
uniform float alpha_cutoff;  // 0: opaque
uniform int emission_mode;    // 1: the emission follows emission_image (material::emission_texture)
uniform sampler2D emission_image;
uniform vec3 emission_inverse_mean;
#endif

#ifdef SPECULAR
// Mirrors and glass, approximated (docs/viewer.md, "Mirrors and glass"):
// the scene as seen from the surface's centre, in a cube map, looked up
// where the reflected or refracted ray meets the scene's bounding box.
uniform samplerCube environment;  // linear radiance
uniform vec3 scene_min;
uniform vec3 scene_max;
uniform vec3 probe_centre;
uniform float probe_radius;  // the surface's bounding sphere: its exit for solid glass
uniform int probe_thin;      // 1: a sheet, light goes straight through
uniform vec3 mirror_weight;    // kr
uniform vec3 transmit_weight;  // kt
uniform float ior;
uniform int fresnel_on;
// The point lights' Phong highlights (the still's, without its shadow rays).
uniform int light_count;
uniform vec4 light_position[4];   // w = 1: a point or spot light at xyz; w = 0: a sun, xyz toward it
uniform vec3 light_intensity[4];  // W/sr (a sun: W/m^2)
uniform vec3 light_axis[4];       // a spot's direction
uniform vec2 light_cone[4];       // cos outer cone, 1 / (cos inner - cos outer): lights.cpp's cone_share
uniform vec3 specular_colour;
uniform float shininess;
#endif

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

// The checker of texture_value: color0 where floor(u s) + floor(v s) is
// even. A pixel whose footprint lies inside one square takes that square's
// colour exactly; one that straddles edges takes the box-filtered mean of
// the footprint (no moire in the distance, where the still averages
// samples).
#ifdef TEXTURED
vec3 checker(vec2 uv) {
  vec2 p = uv * checker_scale;
  vec2 w = max(abs(dFdx(p)), abs(dFdy(p)));
  vec2 lo = floor(p - 0.5 * w), hi = floor(p + 0.5 * w);
  float t;
  if (lo == hi) {
    t = mod(lo.x + lo.y, 2.0);
  } else {
    // Integral of the square wave (0 on even squares, 1 on odd) over the footprint.
    w = max(w, vec2(1e-6));
    vec2 s = clamp(2.0 * (abs(fract((p - 0.5 * w) * 0.5) - 0.5) - abs(fract((p + 0.5 * w) * 0.5) - 0.5)) / w, -1.0, 1.0);
    t = 0.5 - 0.5 * s.x * s.y;
  }
  return mix(checker0, checker1, t);
}
#endif

#ifdef SPECULAR
// The environment along d from p: the direction from the probe's centre to
// where the ray meets the scene's box (exact for the box's own walls, a
// parallax error for what stands inside it; plain d when p is outside).
vec3 environment_along(vec3 p, vec3 d) {
  vec3 safe = mix(vec3(1e-8), d, greaterThan(abs(d), vec3(1e-8)));
  vec3 far_side = max((scene_max - p) / safe, (scene_min - p) / safe);
  float t = min(min(far_side.x, far_side.y), far_side.z);
  vec3 lookup = d;
  if (t > 0.0 && !isinf(t) && !isnan(t)) {
    vec3 from_centre = p + t * d - probe_centre;
    if (dot(from_centre, from_centre) > 0.0) lookup = from_centre;
  }
  return texture(environment, lookup).rgb;
}

#ifdef GLASS
// core/trace/optics.cpp's fresnel_dielectric.
float fresnel(float cos_incident, float n1, float n2) {
  float cos_i = clamp(abs(cos_incident), 0.0, 1.0);
  float sin_t = n1 / n2 * sqrt(max(0.0, 1.0 - cos_i * cos_i));
  if (sin_t >= 1.0) return 1.0;
  float cos_t = sqrt(max(0.0, 1.0 - sin_t * sin_t));
  float parallel = (n2 * cos_i - n1 * cos_t) / (n2 * cos_i + n1 * cos_t);
  float perpendicular = (n1 * cos_i - n2 * cos_t) / (n1 * cos_i + n2 * cos_t);
  return 0.5 * (parallel * parallel + perpendicular * perpendicular);
}

// What arrives through glass entered at p along r (refracted): a sheet
// passes the view ray's own direction on; a solid is left where r meets
// its bounding sphere, refracted out there (exact for a glass sphere but
// for the light reflected inside, which is left out).
vec3 transmitted(vec3 p, vec3 view, vec3 r, bool entering) {
  vec3 oc = p - probe_centre;
  float b = dot(oc, r);
  float t = -b + sqrt(max(b * b - (dot(oc, oc) - probe_radius * probe_radius), 0.0));
  vec3 q = p + max(t, 0.0) * r;
  vec3 m = normalize(q - probe_centre);  // out of the solid
  vec3 out_dir = refract(r, -m, ior);
  if (dot(out_dir, out_dir) == 0.0) out_dir = reflect(r, -m);  // total internal reflection: once more inside, roughly
  bool straight = probe_thin != 0 || !entering;
  vec3 from = straight ? p : q;
  vec3 along = probe_thin != 0 ? view : (entering ? out_dir : r);
  return environment_along(from, along);
}
#endif

// The Whitted tracer's specular terms (ray_tracer.cpp, describe and
// whitted): kr times the reflection, kt times the refraction, Fresnel
// moving weight from kt to kr where asked.
vec3 specular_radiance(vec3 p, vec3 normal) {
  vec3 view = normalize(p - eye);
  vec3 n = normalize(normal);
  bool front = dot(view, n) < 0.0;
  if (!front) n = -n;
  vec3 kr = mirror_weight;
  vec3 radiance = vec3(0.0);
#ifdef GLASS
  float n1 = front ? 1.0 : ior, n2 = front ? ior : 1.0;
  vec3 kt = transmit_weight;
  vec3 r = refract(view, n, n1 / n2);
  if (dot(r, r) == 0.0) {  // total internal reflection
    kr += kt;
  } else {
    float f = fresnel_on != 0 ? fresnel(-dot(view, n), n1, n2) : 0.0;
    kr += f * kt;
    radiance += (1.0 - f) * kt * transmitted(p, view, r, front);
  }
#endif
  radiance += kr * environment_along(p, reflect(view, n));
  if (shininess > 0.0) {
    for (int i = 0; i < light_count; ++i) {  // ray_tracer.cpp's phong(), front side only
      vec3 to = light_position[i].xyz - light_position[i].w * p;
      float d2 = light_position[i].w == 0.0 ? 1.0 : dot(to, to);
      vec3 l = to / sqrt(dot(to, to));
      float cone = clamp((dot(light_axis[i], -l) - light_cone[i].x) * light_cone[i].y, 0.0, 1.0);
      float cos_x = dot(n, l), c = dot(reflect(-l, n), -view);
      if (!front || cos_x <= 0.0 || c <= 0.0) continue;
      radiance += specular_colour * (shininess + 2.0) / (2.0 * 3.14159265358979) * pow(c, shininess) *
                  light_intensity[i] * cone * cone * cos_x / d2;
    }
  }
  return radiance;
}
#endif

// What the pixel shows of a radiance: exposed and tone mapped, or as it is.
vec4 displayed(vec3 radiance) {
  vec3 value = radiance * exposure;
  if (tone_curve == 2) return vec4(radiance, 1.0);  // linear radiance, unscaled
  if (tone_curve == 1) return vec4(srgb(filmic(value)), 1.0);
  return vec4(srgb(value), 1.0);
}

void main() {
#ifdef BACKGROUND
  vec3 radiance = background;
  if (sky != 0) {
    vec2 ndc = (gl_FragCoord.xy - viewport.xy) / viewport.zw * 2.0 - 1.0;
    vec4 far = inverse_view_projection * vec4(ndc, 1.0, 1.0);
    vec3 dir = normalize(far.xyz / far.w - eye);
    radiance = horizon + (zenith - horizon) * max(0.0, dot(dir, sky_up));
  }
  fragment = displayed(radiance);
  return;
#endif
  // A two-sided surface seen from behind: its back, drawn in the same place, shows that side.
  if (has_back_side != 0 && !gl_FrontFacing) discard;
#ifdef SINGLE_SAMPLE
  vec3 vertex_radiance = radiance_s;
  vec3 vertex_unshot = unshot_s.xyz;
  float vertex_element_size = unshot_s.w;
  vec3 world_normal = normal_s;
  vec3 world_position = position_s;
#ifdef TEXTURED
  vec2 uv = uv_s;
#endif
#else
  float w = 1.0 / radiance_w.w;
  vec3 vertex_radiance = radiance_w.xyz * w;
  vec3 vertex_unshot = unshot_w.xyz * w;
  float vertex_element_size = unshot_w.w * w;
  vec3 world_normal = normal_w * w;
  vec3 world_position = position_w * w;
  // Where the clipper left no quotient (see gouraud.vert): GL's own values.
  vec4 check = vec4(vertex_radiance, vertex_element_size) + vec4(vertex_unshot, 0.0);
  bool quotients = radiance_w.w > 0.0 && !any(isnan(check)) && !any(isinf(check));
  if (!quotients) {
    vertex_radiance = radiance_s;
    vertex_unshot = unshot_s.xyz;
    vertex_element_size = unshot_s.w;
    world_normal = normal_s;
    world_position = position_s;
  }
#ifdef TEXTURED
  vec2 uv = uv_w * w;
  if (!quotients || any(isnan(uv)) || any(isinf(uv))) uv = uv_s;
#endif
#endif
  // Radiosities are >= 0, but next to a vertex at 0 (a block's foot) the
  // weights' rounding can dip a hair below it.
  vertex_radiance = max(vertex_radiance, vec3(0.0));
#ifdef TEXTURED
  // Outside any divergent return, so that the derivatives are defined.
  // The solution holds the mean emission; the glow is drawn where the
  // emission texture puts it.
  vec3 glow = emitted;
  if (emission_mode == 1) glow *= texture(emission_image, vec2(uv.x, 1.0 - uv.y)).rgb * emission_inverse_mean;
  if (texture_mode == 1) {
    vec4 texel = texture(image, vec2(uv.x, 1.0 - uv.y));
    if (alpha_cutoff > 0.0 && texel.a * alpha < alpha_cutoff) discard;  // RGB textures read alpha 1
    vec3 detail = texel.rgb * inverse_mean;
    vertex_radiance = glow + (vertex_radiance - emitted) * detail;
  } else if (texture_mode == 2) {
    vertex_radiance = glow + (vertex_radiance - emitted) * checker(uv) * inverse_mean;
  } else {
    vertex_radiance = glow + (vertex_radiance - emitted);
  }
#endif
  // The back of a one-sided surface has no light of its own: black, as the
  // still shows it (the radiosity drawn is its front's).
  if (!gl_FrontFacing) vertex_radiance = vec3(0.0);
#ifdef SPECULAR
  vertex_radiance += specular_radiance(world_position, world_normal);
#endif
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
  fragment = displayed(vertex_radiance);
}
