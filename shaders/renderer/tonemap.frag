#version 460
// "Tone mapping", forward path: a full-screen pass into the sRGB display target (the hardware
// applies the sRGB curve). The maths is include/tonemap.glsl, shared with tonemap.comp.
#extension GL_GOOGLE_include_directive : require
#include "include/tonemap.glsl"

layout(location = 0) in vec2 inUv;
layout(location = 0) out vec4 outColor;

void main() { outColor = vec4(tonemapPixel(ivec2(gl_FragCoord.xy), inUv), 1.0); }
