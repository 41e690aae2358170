// The device-wide descriptor set (set 0) every pipeline shares; resources are addressed by index
// (push constants carry the indices). Capacities must match src/rhi/vulkan/src/descriptors.hpp.
// Storage buffers are declared per use (many block types): FGB_READONLY_STORAGE_BUFFER for blocks
// the shader only reads (binding 0), FGB_STORAGE_BUFFER for blocks it may write (binding 4). Both
// bindings hold the same buffers at the same indices; per graph node the RHI exposes a buffer in
// binding 4 only if the node declared a write to it, so a shader reading a buffer it does not
// write must use a read-only block.
#ifndef FGB_BINDLESS_GLSL
#define FGB_BINDLESS_GLSL

#extension GL_EXT_samplerless_texture_functions : require

#define FGB_MAX_STORAGE_BUFFERS 16384
#define FGB_MAX_SAMPLED_TEXTURES 4096
#define FGB_MAX_STORAGE_TEXTURES 1024
#define FGB_MAX_SAMPLERS 64
#define FGB_MAX_INT64_STORAGE_TEXTURES 64

#define FGB_BINDING_STORAGE_BUFFERS 0
#define FGB_BINDING_SAMPLED_TEXTURES 1
#define FGB_BINDING_STORAGE_TEXTURES 2
#define FGB_BINDING_SAMPLERS 3
#define FGB_BINDING_WRITABLE_STORAGE_BUFFERS 4
// R64Uint storage textures (u64image2D, 64-bit image atomics) have a binding of their own, so no
// shader aliases them with another format on binding 2 (validation would count each variable as
// accessing every descriptor of the binding).
#define FGB_BINDING_INT64_STORAGE_TEXTURES 5

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
