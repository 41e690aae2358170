// Shared by C++ and GLSL (see prelude.h): the device-wide descriptor set (set 0) every pipeline
// shares, and the push-constant bytes of the one pipeline layout. The Vulkan backend builds the set
// from these (src/rhi/vulkan/src/descriptors.hpp); shaders declare their bindings with them
// (shaders/include/bindless.glsl). Macros, since GLSL needs them in layout qualifiers.
#ifndef FGB_RHI_SHARED_BINDLESS_H
#define FGB_RHI_SHARED_BINDLESS_H

// Capacities (descriptors per binding; storage buffers: per storage-buffer binding, 0 and 4).
#define FGB_MAX_STORAGE_BUFFERS 16384
#define FGB_MAX_SAMPLED_TEXTURES 4096
#define FGB_MAX_STORAGE_TEXTURES 1024
#define FGB_MAX_SAMPLERS 64
#define FGB_MAX_INT64_STORAGE_TEXTURES 64

// Binding numbers.
#define FGB_BINDING_STORAGE_BUFFERS 0  // read-only blocks
#define FGB_BINDING_SAMPLED_TEXTURES 1
#define FGB_BINDING_STORAGE_TEXTURES 2
#define FGB_BINDING_SAMPLERS 3
#define FGB_BINDING_WRITABLE_STORAGE_BUFFERS 4  // blocks the shader may write; same slots as binding 0
// R64Uint storage textures (u64image2D, 64-bit image atomics) have a binding of their own, so no
// shader aliases them with another format on binding 2 (validation would count each variable as
// accessing every descriptor of the binding).
#define FGB_BINDING_INT64_STORAGE_TEXTURES 5
#define FGB_BINDING_COUNT 6

// The index of no resource (rhi::kInvalidId), e.g. a push-constant slot left unused.
#define FGB_NONE 0xffffffffu

// Push-constant bytes of the shared pipeline layout (rhi::kPushConstantBytes).
#define FGB_PUSH_CONSTANT_BYTES 128

#endif
