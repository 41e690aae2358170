#version 460
// "HiZ Build" (render.occlusion=1): one pass of the HiZ pyramid (hiz_occlusion.glsl), i.e. the
// FGB_HIZ_PASS_LEVELS levels after HizPush::sourceLevel (those that exist; hizPassGroups sizes
// the dispatch). A workgroup reduces a tile of kTile x kTile texels of the source level, the first
// two levels in registers (4 x 4 texels an invocation), the others through shared memory with a
// barrier between levels, and writes each level's texels that lie inside it. (One dispatch per
// level, 11 at 1080p, was latency-bound on an H200: 0.050 ms a build.)
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

// One invocation per texel of the pass's second level (reduceBlock).
#if FGB_HIZ_GROUP_SIZE != (1 << (2 * (FGB_HIZ_PASS_LEVELS - 2)))
#error "FGB_HIZ_GROUP_SIZE must be (2^(FGB_HIZ_PASS_LEVELS - 2))^2"
#endif
layout(local_size_x = FGB_HIZ_GROUP_SIZE) in;

layout(push_constant) uniform Push { HizPush pc; };

const uint kTile = 1u << FGB_HIZ_PASS_LEVELS;  // source texels per tile side
const uint kOutside = 0xffffffffu;             // a texel outside its level: no key, min's identity
const uint kQuarter = kTile / 4u;              // the pass's second level: texels per tile side

// The tile's levels from the second on ping-pong between two halves: the even steps of the pass
// (2, 4, 6; the second level has kQuarter^2 texels) in the first, the odd ones (3, 5) in the second.
const uint kOddSteps = kQuarter * kQuarter;
shared uint tileKeys[kOddSteps + (kTile / 8u) * (kTile / 8u)];

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

// The farthest of the 2 x 2 source texels from `first`.
uint quadKey(uvec2 viewport, uvec2 first, uvec2 size, uint base) {
  return min(min(sourceKey(viewport, first, size, base), sourceKey(viewport, first + uvec2(1u, 0u), size, base)),
             min(sourceKey(viewport, first + uvec2(0u, 1u), size, base), sourceKey(viewport, first + 1u, size, base)));
}

// Writes a texel of a level written by the pass, unless it lies outside the level.
void writeKey(uvec2 viewport, uint level, uvec2 texel, uint key) {
  uvec2 size = hizLevelSize(viewport, level);
  if (any(greaterThanEqual(texel, size))) return;
  fgbUints[pc.hiz].values[hizLevelOffset(viewport, level) + texel.y * size.x + texel.x] = key;
}

// The pass's first two levels in registers: each invocation reduces a 4 x 4 block of source
// texels to 2 x 2 texels of the first level and one of the second (no barrier between them).
// Returns the latter.
uint reduceBlock(uvec2 viewport, uint lastLevel, uvec2 local) {
  uvec2 size = hizLevelSize(viewport, pc.sourceLevel);
  uint base = pc.sourceLevel > 0u ? hizLevelOffset(viewport, pc.sourceLevel) : 0u;
  uvec2 block = gl_WorkGroupID.xy * kTile + 4u * local;
  uint farthest = kOutside;
  for (uint q = 0u; q < 4u; ++q) {
    uvec2 child = 2u * local + uvec2(q & 1u, q >> 1u);  // in the first level's tile
    uint key = quadKey(viewport, block + 2u * uvec2(q & 1u, q >> 1u), size, base);
    writeKey(viewport, pc.sourceLevel + 1u, gl_WorkGroupID.xy * (kTile / 2u) + child, key);
    farthest = min(farthest, key);
  }
  uint second = pc.sourceLevel + 2u;
  if (second <= lastLevel) writeKey(viewport, second, gl_WorkGroupID.xy * kQuarter + local, farthest);
  return farthest;
}

void main() {
  uvec2 viewport = uvec2(pc.width, pc.height);
  uint lastLevel = min(pc.sourceLevel + FGB_HIZ_PASS_LEVELS, hizLevels(viewport));
  uint thread = gl_LocalInvocationIndex;
  tileKeys[thread] = reduceBlock(viewport, lastLevel, uvec2(thread % kQuarter, thread / kQuarter));
  // Uniform over the workgroup (push constants only), so every invocation meets each barrier.
  for (uint level = pc.sourceLevel + 3u; level <= lastLevel; ++level) {
    memoryBarrierShared();
    barrier();  // this step reads the previous one's keys (and overwrites those of the one before)
    uint step = level - pc.sourceLevel;
    uint side = kTile >> step;
    uint written = (step & 1u) != 0u ? kOddSteps : 0u, previous = kOddSteps - written;
    if (thread < side * side) {
      uvec2 local = uvec2(thread % side, thread / side);
      uint first = previous + 2u * local.y * (2u * side) + 2u * local.x;
      uint farthest = min(min(tileKeys[first], tileKeys[first + 1u]),
                          min(tileKeys[first + 2u * side], tileKeys[first + 2u * side + 1u]));
      tileKeys[written + thread] = farthest;
      writeKey(viewport, level, gl_WorkGroupID.xy * side + local, farthest);
    }
  }
}
