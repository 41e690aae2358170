#version 460
// Bloom's smallest levels in one workgroup, the last dispatch of the "Bloom" node's downsamples
// and the first of its upsamples (bloom_feature.cpp): levels firstLevel .. lastLevel downsampled
// from the level before (bloom_down.comp's filter for levels after the first), then upsampled back
// onto firstLevel (bloom_up.comp's tent). Each level is a loop over its texels with a workgroup
// barrier after it. A dispatch and a barrier per level cost more than these levels' work (at
// 1080p, levels 4-6 hold 10k texels; about 11 us per level on an H200); the values are the same.
#extension GL_GOOGLE_include_directive : require
#define FGB_BLOOM_IMAGE_QUALIFIERS coherent
#include "include/bloom.glsl"
#include "renderer/shared/post.h"

layout(local_size_x = FGB_BLOOM_TAIL_GROUP_SIZE) in;

layout(push_constant) uniform Push { BloomTailPush pc; };

uint levelImage(uint level) { return pc.images[level]; }
ivec2 levelSize(uint level) { return max(pc.fullSize >> level, ivec2(1)); }

// Makes this invocation's image writes visible to the workgroup, then waits for all of it.
void levelDone() {
  memoryBarrierImage();
  barrier();
}

void main() {
  for (uint level = pc.firstLevel; level <= pc.lastLevel; ++level) {
    const ivec2 size = levelSize(level);
    for (int t = int(gl_LocalInvocationIndex); t < size.x * size.y; t += FGB_BLOOM_TAIL_GROUP_SIZE) {
      const ivec2 texel = ivec2(t % size.x, t / size.x);
      const vec3 sum = bloomDownsampleLevel(levelImage(level - 1u), levelSize(level - 1u), size, texel);
      imageStore(fgbImagesRgba16f[levelImage(level)], texel, vec4(clamp(sum, vec3(0.0), vec3(kHalfMax)), 1.0));
    }
    levelDone();
  }
  for (uint level = pc.lastLevel; level > pc.firstLevel; --level) {
    const ivec2 size = levelSize(level - 1u);
    for (int t = int(gl_LocalInvocationIndex); t < size.x * size.y; t += FGB_BLOOM_TAIL_GROUP_SIZE) {
      const ivec2 texel = ivec2(t % size.x, t / size.x);
      const vec3 sum = bloomUpsampleTent(levelImage(level), levelSize(level), size, texel, pc.radius);
      const vec4 below = imageLoad(fgbImagesRgba16f[levelImage(level - 1u)], texel);
      imageStore(fgbImagesRgba16f[levelImage(level - 1u)], texel, vec4(min(below.rgb + sum, vec3(kHalfMax)), 1.0));
    }
    levelDone();
  }
}
