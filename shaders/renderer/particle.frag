#version 460
// Soft round particle, alpha blended over the opaque scene.
layout(location = 0) in vec4 inColor;
layout(location = 1) in vec2 inCorner;
layout(location = 0) out vec4 outColor;

void main() {
  float falloff = clamp(1.0 - dot(inCorner, inCorner), 0.0, 1.0);
  outColor = vec4(inColor.rgb, inColor.a * falloff * falloff);
}
