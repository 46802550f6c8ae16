#version 330 core
// Element edges drawn over the Gouraud view.
uniform vec4 colour;
out vec4 fragment;
void main() { fragment = colour; }
