#version 460
// "SSAA Resolve", forward path: a full-screen pass; the box filter is include/ssaa.glsl.
#extension GL_GOOGLE_include_directive : require
#include "include/ssaa.glsl"

layout(location = 0) in vec2 inUv;
layout(location = 0) out vec4 outColor;

void main() { outColor = ssaaBoxMean(ivec2(gl_FragCoord.xy)); }
