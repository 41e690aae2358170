#version 460
// Compiled at build time (shaders/CMakeLists.txt), never embedded: the GLSL side of the shared
// headers' size checks. FGB_SHARED_LAYOUT_CHECK turns each FGB_CHECK_SIZE / FGB_CHECK_PUSH into a
// std430 block that glslang refuses when the struct's GLSL size exceeds the declared one or the
// push-constant bytes (see fgb/rhi/shared/prelude.h). Compiled for OpenGL, not Vulkan: glslang
// checks explicit member offsets against the previous members only there. A new shared header
// is included here.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#define FGB_SHARED_LAYOUT_CHECK
#include "renderer/shared/lighting.h"
#include "renderer/shared/meshes.h"
#include "renderer/shared/meshlets.h"
#include "renderer/shared/opaque_depth.h"
#include "renderer/shared/particles.h"
#include "renderer/shared/debug.h"
#include "renderer/shared/post.h"
#include "renderer/shared/scene.h"
#include "renderer/shared/transparent.h"
#include "renderer/shared/visbuffer.h"

layout(local_size_x = 1) in;
void main() {}
