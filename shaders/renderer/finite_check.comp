#version 460
// "Finite Check" of a single-sample float texture (see include/finite_check.glsl).
#extension GL_GOOGLE_include_directive : require
#include "include/finite_check.glsl"
