// Shared declarations of the renderer's shaders: the scene's buffers, whose structs are declared
// once for C++ and GLSL in renderer/shared/scene.h, and common functions.
#ifndef FGB_RENDERER_COMMON_GLSL
#define FGB_RENDERER_COMMON_GLSL

#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_nonuniform_qualifier : require
#include "bindless.glsl"
#include "renderer/shared/scene.h"

const float PI = 3.14159265358979;

FGB_READONLY_STORAGE_BUFFER(FrameBlock, fgbFrames) { FrameConstants frame; } fgbFrames[FGB_MAX_STORAGE_BUFFERS];
FGB_READONLY_STORAGE_BUFFER(InstanceBlock, fgbInstances) { Instance instances[]; } fgbInstances[FGB_MAX_STORAGE_BUFFERS];
FGB_READONLY_STORAGE_BUFFER(MaterialBlock, fgbMaterials) { Material materials[]; } fgbMaterials[FGB_MAX_STORAGE_BUFFERS];
FGB_READONLY_STORAGE_BUFFER(LightBlock, fgbLights) { PointLight lights[]; } fgbLights[FGB_MAX_STORAGE_BUFFERS];
FGB_READONLY_STORAGE_BUFFER(ExposureBlock, fgbExposures) { Exposure state; } fgbExposures[FGB_MAX_STORAGE_BUFFERS];
FGB_STORAGE_BUFFER(CommandBlock, fgbCommands, ) { DrawCommand commands[]; } fgbCommands[FGB_MAX_STORAGE_BUFFERS];
FGB_STORAGE_BUFFER(UintBlock, fgbUints, ) { uint values[]; } fgbUints[FGB_MAX_STORAGE_BUFFERS];
FGB_STORAGE_BUFFER(Vec4Block, fgbVec4s, ) { vec4 values[]; } fgbVec4s[FGB_MAX_STORAGE_BUFFERS];
// Read-only views of the same buffers, for shaders that do not write them (see bindless.glsl).
FGB_READONLY_STORAGE_BUFFER(UintReadBlock, fgbUintsRead) { uint values[]; } fgbUintsRead[FGB_MAX_STORAGE_BUFFERS];
FGB_READONLY_STORAGE_BUFFER(Vec4ReadBlock, fgbVec4sRead) { vec4 values[]; } fgbVec4sRead[FGB_MAX_STORAGE_BUFFERS];

// Texture lookups whose index may differ between invocations of one draw (per-instance materials).
vec4 sampleMaterialTexture(int textureIndex, uint samplerIndex, vec2 uv) {
  return texture(sampler2D(fgbTextures[nonuniformEXT(uint(textureIndex))], fgbSamplers[samplerIndex]), uv);
}

float luminance(vec3 c) { return dot(c, vec3(0.2126, 0.7152, 0.0722)); }

// normalize() without the 0/0: a (near) zero-length vector gives `fallback` (already unit).
// Interpolated normals and tangents can cancel out, a fragment can sit on a light or the camera.
vec3 safeNormalize(vec3 v, vec3 fallback) {
  float lengthSquared = dot(v, v);
  return lengthSquared > 1e-20 ? v * inversesqrt(lengthSquared) : fallback;
}

// R16F's largest finite value: radiance written to the HDR target is clamped to it, so an
// out-of-range value saturates instead of becoming Inf (which bloom would spread).
const float kHalfMax = 65504.0;

// The factor radiance is multiplied by before it is written to the HDR target.
float preExposure(FrameConstants frame) { return fgbExposures[frame.buffers.x].state.preExposure; }

// Thesis attenuation max(1 - d/R, 0) / d^2, with d clamped to 5 cm against the singularity at
// the light, written without a division: it takes 1/d (unclamped) and 1/R, which the CPU writes into
// PointLight.color.w (gpu_upload.cpp; a light's radius is positive and finite there), since shading
// runs this for every light of every pixel.
float pointLightAttenuation(float distance, float inverseDistance, float inverseRadius) {
  float inverseClamped = min(inverseDistance, 20.0);  // 1 / max(d, 0.05)
  return max(1.0 - distance * inverseRadius, 0.0) * (inverseClamped * inverseClamped);
}

// Cluster of a fragment: 16x16-pixel tile and exponential depth slice.
uint clusterIndex(FrameConstants frame, vec2 fragCoord, float viewDepth) {
  uvec2 tile = min(uvec2(fragCoord) / frame.clusterGrid.w, frame.clusterGrid.xy - 1u);
  float slice = floor(log(max(viewDepth, 1e-6)) * frame.depthRange.z + frame.depthRange.w);
  uint z = uint(clamp(slice, 0.0, float(frame.clusterGrid.z - 1u)));
  return (z * frame.clusterGrid.y + tile.y) * frame.clusterGrid.x + tile.x;
}

// A blue-green-yellow-red ramp for heat maps, t in [0, 1].
vec3 heatRamp(float t) {
  t = clamp(t, 0.0, 1.0);
  return vec3(smoothstep(0.5, 1.0, t), sin(t * PI), 1.0 - smoothstep(0.0, 0.5, t));
}

#endif
