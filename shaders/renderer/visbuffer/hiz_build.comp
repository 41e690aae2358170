#version 460
// "HiZ Build" (render.occlusion=1): one level of the HiZ pyramid (hiz_occlusion.glsl) per
// dispatch, one invocation per texel. Level 1 reduces the visibility buffer's depth keys (the
// high 32 bits of each word; 0 where no triangle is, the farthest), every later level the one
// before it; each texel keeps the smallest key (the farthest depth) of its 2 x 2 children that lie
// inside the level below. The variant "depth" (FGB_HIZ_FROM_DEPTH, the meshlet path's) reads level
// 1's children from a single-sampled depth texture instead (HizPush::words: its sampled index),
// the cleared depth (kDepthClear: 0, the far plane) as key 0, like a pixel with no triangle.
#extension GL_GOOGLE_include_directive : require
#ifdef FGB_HIZ_FROM_DEPTH
#include "../include/clusters.glsl"
#else
#include "../include/visbuffer.glsl"
#endif
#define FGB_HIZ_BUILD_ONLY
#include "hiz_occlusion.glsl"

layout(local_size_x = FGB_HIZ_GROUP_SIZE, local_size_y = FGB_HIZ_GROUP_SIZE) in;

layout(push_constant) uniform Push { HizPush pc; };

uint childKey(uvec2 viewport, uvec2 child, uint childBase, uvec2 childSize) {
#ifdef FGB_HIZ_FROM_DEPTH
  if (pc.level == 1u) {
    float z = texelFetch(sampler2D(fgbTextures[pc.words], fgbSamplers[pc.fetchSampler]), ivec2(child), 0).r;
    return z == 0.0 ? 0u : depthKey(z, pc.reversedZ != 0u);
  }
#else
  if (pc.level == 1u) return uint(visWordAt(pc.words, ivec2(child), viewport.x) >> 32);
#endif
  return fgbUintsRead[pc.hiz].values[childBase + child.y * childSize.x + child.x];
}

void main() {
  uvec2 viewport = uvec2(pc.width, pc.height);
  uvec2 size = hizLevelSize(viewport, pc.level);
  uvec2 texel = gl_GlobalInvocationID.xy;
  if (any(greaterThanEqual(texel, size))) return;
  uvec2 childSize = pc.level == 1u ? viewport : hizLevelSize(viewport, pc.level - 1u);
  uint childBase = pc.level == 1u ? 0u : hizLevelOffset(viewport, pc.level - 1u);
  uvec2 first = 2u * texel;
  uvec2 last = min(first + 1u, childSize - 1u);
  uint farthest = 0xffffffffu;
  for (uint y = first.y; y <= last.y; ++y)
    for (uint x = first.x; x <= last.x; ++x) farthest = min(farthest, childKey(viewport, uvec2(x, y), childBase, childSize));
  fgbUints[pc.hiz].values[hizLevelOffset(viewport, pc.level) + texel.y * size.x + texel.x] = farthest;
}
