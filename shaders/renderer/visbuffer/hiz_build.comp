#version 460
// "HiZ Build" (render.occlusion=1): one pass of the HiZ pyramid (hiz_occlusion.glsl), i.e. the
// FGB_HIZ_PASS_LEVELS levels after HizPush::sourceLevel (those that exist; hizPassGroups sizes
// the dispatch). A workgroup reduces a tile of kTile x kTile texels of the source level through
// shared memory, one level after another, and writes each level's texels that lie inside it.
// Level 0, the first pass's source, is the visibility buffer's depth keys (the high 32 bits of
// each word; 0 where no triangle is, the farthest); later passes read the level the previous pass
// wrote last. Each texel keeps the smallest key (the farthest depth) of its 2 x 2 children, those
// outside the level below counting as kOutside, the identity of min. As min is exact and
// associative, this is the same pyramid as reducing level by level with the children clamped to
// the level below: a texel inside its level always has a child inside the level below (2i < S
// when i < ceil(S / 2)), and its key is the smallest of the viewport pixels it covers.
// The variant "depth" (FGB_HIZ_FROM_DEPTH, the meshlet path's) reads level 0 from a
// single-sampled depth texture instead (HizPush::words: its sampled index), the cleared depth
// (kDepthClear: 0, the far plane) as key 0, like a pixel with no triangle.
#extension GL_GOOGLE_include_directive : require
#ifdef FGB_HIZ_FROM_DEPTH
#include "../include/clusters.glsl"
#else
#include "../include/visbuffer.glsl"
#endif
#define FGB_HIZ_BUILD_ONLY
#include "hiz_occlusion.glsl"

layout(local_size_x = FGB_HIZ_GROUP_SIZE) in;

layout(push_constant) uniform Push { HizPush pc; };

const uint kTile = 1u << FGB_HIZ_PASS_LEVELS;  // source texels per tile side
const uint kOutside = 0xffffffffu;             // a texel outside its level: no key, min's identity

// The tile's levels ping-pong between two halves: the odd steps of the pass (the first output
// level, (kTile / 2)^2 texels, and every other one after it) in the first, the even in the second.
const uint kEvenSteps = (kTile / 2u) * (kTile / 2u);
shared uint tileKeys[kEvenSteps + (kTile / 4u) * (kTile / 4u)];

// A texel of the source level (0: the depths), kOutside outside it.
uint sourceKey(uvec2 viewport, uvec2 texel, uvec2 size, uint base) {
  if (any(greaterThanEqual(texel, size))) return kOutside;
  if (pc.sourceLevel > 0u) return fgbUintsRead[pc.hiz].values[base + texel.y * size.x + texel.x];
#ifdef FGB_HIZ_FROM_DEPTH
  float z = texelFetch(sampler2D(fgbTextures[pc.words], fgbSamplers[pc.fetchSampler]), ivec2(texel), 0).r;
  return z == 0.0 ? 0u : depthKey(z, pc.reversedZ != 0u);
#else
  return uint(visWordAt(pc.words, ivec2(texel), viewport.x) >> 32);
#endif
}

// The farthest of a step's 2 x 2 children (the tile-local texel `local` of a level `side` texels
// per tile side): from the source level at the first step, from the tile's previous level after.
uint farthestChild(uvec2 viewport, uint step, uvec2 local, uint side) {
  uint keys[4];
  if (step == 1u) {
    uvec2 size = hizLevelSize(viewport, pc.sourceLevel);
    uint base = pc.sourceLevel > 0u ? hizLevelOffset(viewport, pc.sourceLevel) : 0u;
    uvec2 first = gl_WorkGroupID.xy * kTile + 2u * local;
    for (uint i = 0u; i < 4u; ++i) keys[i] = sourceKey(viewport, first + uvec2(i & 1u, i >> 1u), size, base);
  } else {
    uint previous = (step & 1u) != 0u ? kEvenSteps : 0u;  // where step - 1 wrote
    uint first = previous + 2u * local.y * (2u * side) + 2u * local.x;
    for (uint i = 0u; i < 4u; ++i) keys[i] = tileKeys[first + (i >> 1u) * (2u * side) + (i & 1u)];
  }
  return min(min(keys[0], keys[1]), min(keys[2], keys[3]));
}

void main() {
  uvec2 viewport = uvec2(pc.width, pc.height);
  uint lastLevel = min(pc.sourceLevel + FGB_HIZ_PASS_LEVELS, hizLevels(viewport));
  // Uniform over the workgroup (push constants only), so every invocation meets each barrier.
  for (uint level = pc.sourceLevel + 1u; level <= lastLevel; ++level) {
    uint step = level - pc.sourceLevel;
    uint side = kTile >> step;
    uint written = (step & 1u) != 0u ? 0u : kEvenSteps;
    uvec2 size = hizLevelSize(viewport, level);
    uint base = hizLevelOffset(viewport, level);
    // Consecutive invocations take consecutive texels of a row: coalesced reads and writes.
    for (uint i = gl_LocalInvocationIndex; i < side * side; i += FGB_HIZ_GROUP_SIZE) {
      uvec2 local = uvec2(i % side, i / side);
      uint farthest = farthestChild(viewport, step, local, side);
      tileKeys[written + i] = farthest;
      uvec2 texel = gl_WorkGroupID.xy * side + local;
      if (all(lessThan(texel, size))) fgbUints[pc.hiz].values[base + texel.y * size.x + texel.x] = farthest;
    }
    memoryBarrierShared();
    barrier();  // the next step reads this one's keys (and overwrites the step's before)
  }
}
