#version 330 core
// Gouraud view of the patch mesh: per-vertex radiosity, interpolated.
layout(location = 0) in vec3 position;
layout(location = 1) in vec3 normal;
layout(location = 2) in vec3 reflectance;  // rho, for the display ambient term
layout(location = 3) in vec3 radiosity;    // B, updated after every solver step
layout(location = 4) in vec3 unshot;       // mean unshot radiosity of the vertex's elements
layout(location = 5) in float element_size;  // square root of the mean area of the vertex's elements

uniform mat4 view_projection;
uniform vec3 ambient;        // Cohen 1988 ambient radiosity, zero when switched off

out vec3 vertex_radiance;    // W / (m^2 sr): B / pi
out vec3 vertex_unshot;
out vec3 world_normal;
out vec3 world_position;
out float vertex_element_size;

void main() {
  const float pi = 3.14159265358979;
  vertex_radiance = (radiosity + reflectance * ambient) / pi;
  vertex_unshot = unshot / pi;
  world_normal = normal;
  world_position = position;
  vertex_element_size = element_size;
  gl_Position = view_projection * vec4(position, 1.0);
}
