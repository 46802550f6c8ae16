#version 330 core
// Element edges drawn over the Gouraud view, as lines (GL_LINES, which
// polygon offset does not move): each fragment is pulled towards the eye
// by a few depth steps, by hand, so that the edges win against the
// surfaces they lie on.
uniform vec4 colour;
out vec4 fragment;
void main() {
  fragment = colour;
  gl_FragDepth = gl_FragCoord.z - 4.0 * fwidth(gl_FragCoord.z) - 1e-5;
}
