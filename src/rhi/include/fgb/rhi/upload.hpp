// Uploads are transfer nodes too: these helpers build a one-node graph that copies from a staging
// buffer into the destination, run it, and wait. For setup-time data (meshes, textures), not for
// per-frame streaming (declare a transfer node in the frame's graph for that).
#pragma once

#include <fgb/rhi/device.hpp>

#include <cstddef>
#include <cstdint>
#include <span>

namespace fgb::rhi {

// `dst` receives `bytes` at offset 0 and is left readable by any later stage on any queue (buffers
// are shared by every queue family: no ownership to hand over).
void uploadBuffer(Device& device, BufferId dst, std::span<const std::byte> bytes);
// Mip level 0 of `dst` (tightly packed texels) is filled and left shader-readable.
void uploadTexture(Device& device, TextureId dst, const TextureDesc& desc, std::span<const std::byte> texels);

}  // namespace fgb::rhi
