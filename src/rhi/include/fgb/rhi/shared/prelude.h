// The common subset of C++ and GLSL that the headers shared by both languages are written in
// (niagara's config.h, The Forge's shader defs): every shared header includes it first. In C++ it
// defines, in namespace fgb::gpu, the GLSL types shared structs use, with their std430 alignment
// (vec4 and mat4 16 bytes, vec2 8; glm's own are 4), so a struct declared once has the same
// offsets in both languages; in GLSL it only defines the macros below.
//
// Shared headers live in src/rhi/include/fgb/rhi/shared/ (the RHI's: bindings, capacities) and
// shaders/renderer/shared/ (the renderer features': their GPU structs, push blocks, flags, sizes).
// Both languages include them by the same path ("fgb/rhi/shared/x.h", "renderer/shared/x.h"):
// glslang is given src/rhi/include and shaders/ as include directories (shaders/CMakeLists.txt),
// C++ gets them through fgb_rhi and fgb_shader_shared. A shared header:
// - has an #ifndef include guard (glslang has no #pragma once) and includes this file first;
// - declares its structs and constants between FGB_GPU_BEGIN and FGB_GPU_END;
// - uses uint, int, float, uint64_t (GLSL: with its int64 extension enabled by the includer),
//   vec2, vec4, ivec2, ivec4, uvec2, uvec4, mat4 and arrays of them: no vec3, mat3 or bool, whose
//   C++ and std430 layouts differ, and no member initialisers;
// - spells constants `const uint kName = 1u;`, or #define where GLSL needs a literal (layout
//   qualifiers such as local_size_x: a constant there becomes LocalSizeId);
// - may define functions both languages compile (scalar uint/int/float arithmetic, loops), each
//   marked FGB_INLINE (C++ `constexpr inline`, nothing in GLSL), where the two sides must agree on
//   a computation (e.g. the HiZ pyramid's layout, renderer/shared/hiz.h);
// - follows each struct with FGB_CHECK_SIZE(Name, bytes), or FGB_CHECK_PUSH(Name, bytes) for a
//   push-constant block (a shader declares `layout(push_constant) uniform Push { Name pc; };`).
//
// The size checks: C++ static_asserts sizeof == bytes. GLSL: shaders/renderer/shared/check.comp
// expands every check (FGB_SHARED_LAYOUT_CHECK) to a std430 block with a member at offset `bytes`
// after the struct, which glslang refuses ("cannot lie in previous members") when the struct's
// std430 size exceeds `bytes`; it cannot be smaller, since std430 aligns every type above at least
// as strictly as C++ does here (so the two sizes are equal).
#ifndef FGB_RHI_SHARED_PRELUDE_H
#define FGB_RHI_SHARED_PRELUDE_H

#include "fgb/rhi/shared/bindless.h"

#ifdef __cplusplus

#include <cstddef>
#include <cstdint>
#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec4.hpp>

#define FGB_GPU_BEGIN namespace fgb::gpu {
#define FGB_GPU_END }
#define FGB_INLINE constexpr inline
#define FGB_CHECK_SIZE(T, bytes) static_assert(sizeof(T) == (bytes), #T ": the C++ size differs from the GPU's");
#define FGB_CHECK_PUSH(T, bytes) \
  FGB_CHECK_SIZE(T, bytes)       \
  static_assert((bytes) <= FGB_PUSH_CONSTANT_BYTES, #T ": larger than the push constants");

namespace fgb::gpu {

// A glm vector or matrix aligned like its GLSL type in std430.
template <class Glm, std::size_t Alignment>
struct alignas(Alignment) Std430 : Glm {
  using Glm::Glm;
  Std430() = default;
  constexpr Std430(const Glm& from) : Glm(from) {}  // NOLINT(google-explicit-constructor)
};

using uint = std::uint32_t;
using std::uint64_t;
using vec2 = Std430<glm::vec2, 8>;
using vec4 = Std430<glm::vec4, 16>;
using ivec2 = Std430<glm::ivec2, 8>;
using ivec4 = Std430<glm::ivec4, 16>;
using uvec2 = Std430<glm::uvec2, 8>;
using uvec4 = Std430<glm::uvec4, 16>;
using mat4 = Std430<glm::mat4, 16>;

}  // namespace fgb::gpu

#else  // GLSL

#define FGB_GPU_BEGIN
#define FGB_GPU_END
#define FGB_INLINE
#ifdef FGB_SHARED_LAYOUT_CHECK
#define FGB_CHECK_SIZE(T, bytes) \
  layout(std430, binding = 0) buffer FgbSizeOf##T { T value; layout(offset = bytes) uint end; } fgbSizeOf##T;
#define FGB_CHECK_PUSH(T, bytes) \
  FGB_CHECK_SIZE(T, bytes)       \
  layout(std430, binding = 0) buffer FgbPushFits##T { T value; layout(offset = FGB_PUSH_CONSTANT_BYTES) uint end; } fgbPushFits##T;
#else
#define FGB_CHECK_SIZE(T, bytes)
#define FGB_CHECK_PUSH(T, bytes)
#endif

#endif

#endif
