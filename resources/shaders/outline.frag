#version 410 core
// A flat colour in the linear HDR target (before exposure and the tone map).
uniform vec3 uColour;
layout(location = 0) out vec4 fragColour;
void main() { fragColour = vec4(uColour, 1.0); }
