#version 460
// Indirect dispatch arguments from the culling counters: one invocation, run inside "Cluster Cull"
// (for "Triangle Filter") and inside "Triangle Filter" (for the two "Visibility Raster" passes).
// It writes a snapshot of the counters with the arguments filled in, which the next node reads as
// indirect arguments and as counts.
#extension GL_GOOGLE_include_directive : require
#include "../include/visbuffer.glsl"

layout(local_size_x = 1) in;

layout(push_constant) uniform Push { ArgsPush pc; };

void main() {
  VisCounters c = visCountersRead[pc.counters].c;
  uvec3 filterGroups = dispatchFor(c.visibleClusters, 1u);
  uvec3 small = dispatchFor(c.smallTriangles, pc.smallPerGroup);
  uint largeTriangles = uint(c.largeTotals >> 40);
  uint jobs = min(uint(c.largeTotals & 0xffffffffffUL), pc.tileJobCapacity);
  uvec3 tileGroups = dispatchFor(jobs, 1u);
  c.filterGroups = uint[3](filterGroups.x, filterGroups.y, filterGroups.z);
  c.smallGroups = uint[3](small.x, small.y, small.z);
  c.largeTriangles = largeTriangles;
  c.tileJobs = jobs;
  c.tileGroups = uint[3](tileGroups.x, tileGroups.y, tileGroups.z);
  visCounters[pc.args].c = c;
}
