#version 460
// "HiZ Build" (render.occlusion=1): one level of the HiZ pyramid (hiz_occlusion.glsl) per
// dispatch, one invocation per texel. Level 1 reduces the visibility buffer's depth keys (the
// high 32 bits of each word; 0 where no triangle is, the farthest), every later level the one
// before it; each texel keeps the smallest key (the farthest depth) of its 2 x 2 children that lie
// inside the level below.
#extension GL_GOOGLE_include_directive : require
#include "../include/visbuffer.glsl"
#define FGB_HIZ_BUILD_ONLY
#include "hiz_occlusion.glsl"

layout(local_size_x = FGB_HIZ_GROUP_SIZE, local_size_y = FGB_HIZ_GROUP_SIZE) in;

layout(push_constant) uniform Push { HizPush pc; };

uint childKey(uvec2 viewport, uvec2 child, uint childBase, uvec2 childSize) {
  if (pc.level == 1u) return uint(visWordAt(pc.words, ivec2(child), viewport.x) >> 32);
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
