// Uploads are transfer nodes too: these helpers build a one-node graph that copies from a staging
// buffer into the destination, run it, and wait. For setup-time data (meshes, textures), not for
// per-frame streaming (declare a transfer node in the frame's graph for that).
#pragma once

#include <fgb/rhi/device.hpp>

#include <cstddef>
#include <cstdint>
#include <span>

namespace fgb::rhi {

// `dst` receives `bytes` at offset 0 and is left readable by any later stage. The copy runs on
// (and `dst` ends up owned by the family of) the queue class `owner`.
void uploadBuffer(Device& device, BufferId dst, std::span<const std::byte> bytes,
                  graph::QueueClass owner = graph::QueueClass::Graphics);
// Queue-family ownership release of `buffer` from queue class `from` to `to` (nothing where they
// share a family). For a buffer a frame graph imports with initial queue `from` and first uses on
// `to`: that graph acquires it on every execution, and each execution releases it back at its end
// (final queue `to`); this supplies the release the first execution's acquire pairs with.
void releaseBuffer(Device& device, BufferId buffer, uint64_t size, graph::QueueClass from, graph::QueueClass to);
// Mip level 0 of `dst` (tightly packed texels) is filled and left shader-readable.
void uploadTexture(Device& device, TextureId dst, const TextureDesc& desc, std::span<const std::byte> texels);

}  // namespace fgb::rhi
