#version 460
// Proof scene, draw node: vertices come from the buffer the compute node wrote (vertex input).
layout(location = 0) in vec4 inPosition;
layout(location = 1) in vec4 inColor;
layout(location = 0) out vec4 outColor;

void main() {
  outColor = inColor;
  gl_Position = inPosition;
}
