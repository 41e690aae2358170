#version 460
// "HiZ Build (late)"'s indirect arguments, one invocation, run at the end of "Triangle Filter
// (late)" (render.occlusion=1): a group count per pass of the build (hizPasses), or none at all
// when phase 2 rasterises no triangle. Then the visibility buffer is as phase 1 left it, and so is the pyramid
// "HiZ Build" made of it, which the next frame can use as it is (with a still camera, phase 2
// usually has nothing to draw).
#extension GL_GOOGLE_include_directive : require
#include "../include/visbuffer.glsl"
#define FGB_HIZ_BUILD_ONLY
#include "hiz_occlusion.glsl"

layout(local_size_x = 1) in;

layout(push_constant) uniform Push { HizArgsPush pc; };

void main() {
  VisCounters c = visCountersRead[pc.rasterArgs].c;
  bool drew = c.smallTriangles + c.tileJobs > 0u;
  uvec2 viewport = uvec2(pc.width, pc.height);
  uint passes = hizPasses(viewport);
  for (uint pass = 0u; pass < passes; ++pass) {
    uvec2 groups = drew ? hizPassGroups(viewport, pass) : uvec2(0u);
    fgbUints[pc.args].values[3u * pass] = groups.x;
    fgbUints[pc.args].values[3u * pass + 1u] = groups.y;
    fgbUints[pc.args].values[3u * pass + 2u] = 1u;
  }
}
