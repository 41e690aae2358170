#version 460
// Writes a constant colour (push constants): used by tests and debug passes.
layout(push_constant) uniform Push { vec4 color; } pc;
layout(location = 0) out vec4 outColor;

void main() { outColor = pc.color; }
