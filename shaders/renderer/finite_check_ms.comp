#version 460
// "Finite Check" of a multisampled float texture: every sample (see include/finite_check.glsl).
#extension GL_GOOGLE_include_directive : require
#define FGB_MULTISAMPLE 1
#include "include/finite_check.glsl"
