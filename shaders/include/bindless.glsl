// The device-wide descriptor set (set 0) every pipeline shares; resources are addressed by index
// (push constants carry the indices); binding numbers and capacities: fgb/rhi/shared/bindless.h.
// Storage buffers are declared per use (many block types): FGB_READONLY_STORAGE_BUFFER for blocks
// the shader only reads (binding 0), FGB_STORAGE_BUFFER for blocks it may write (binding 4). Both
// bindings hold the same buffers at the same indices; per graph node the RHI exposes a buffer in
// binding 4 only if the node declared a write to it, so a shader reading a buffer it does not
// write must use a read-only block.
#ifndef FGB_BINDLESS_GLSL
#define FGB_BINDLESS_GLSL

#extension GL_EXT_samplerless_texture_functions : require

#include "fgb/rhi/shared/bindless.h"  // binding numbers and capacities, shared with the Vulkan backend

// FGB_STORAGE_BUFFER(Name, array, access) { members } array[...] -> writable blocks Name.
#define FGB_STORAGE_BUFFER(BlockName, arrayName, qualifiers) \
  layout(set = 0, binding = FGB_BINDING_WRITABLE_STORAGE_BUFFERS, std430) qualifiers buffer BlockName
// FGB_READONLY_STORAGE_BUFFER(Name, array) { members } array[...] -> read-only blocks Name.
#define FGB_READONLY_STORAGE_BUFFER(BlockName, arrayName) \
  layout(set = 0, binding = FGB_BINDING_STORAGE_BUFFERS, std430) readonly buffer BlockName

layout(set = 0, binding = FGB_BINDING_SAMPLED_TEXTURES) uniform texture2D fgbTextures[FGB_MAX_SAMPLED_TEXTURES];
layout(set = 0, binding = FGB_BINDING_SAMPLERS) uniform sampler fgbSamplers[FGB_MAX_SAMPLERS];

vec4 fgbSample(uint textureIndex, uint samplerIndex, vec2 uv) {
  return texture(sampler2D(fgbTextures[textureIndex], fgbSamplers[samplerIndex]), uv);
}

vec4 fgbFetch(uint textureIndex, ivec2 texel) {
  return texelFetch(fgbTextures[textureIndex], texel, 0);
}

#endif
