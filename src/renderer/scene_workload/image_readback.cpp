#include "image_readback.hpp"

#include <fgb/core/error.hpp>
#include <fgb/rhi/job_context.hpp>

#include <cmath>
#include <cstring>

namespace fgb::render {
namespace {

float halfToFloat(uint16_t half) {
  const uint32_t sign = (half >> 15) & 1u;
  const uint32_t exponent = (half >> 10) & 0x1fu;
  const uint32_t mantissa = half & 0x3ffu;
  float value = 0.0f;
  if (exponent == 0) value = std::ldexp(float(mantissa), -24);
  else if (exponent == 31) value = mantissa == 0 ? INFINITY : NAN;
  else value = std::ldexp(float(mantissa | 0x400u), int(exponent) - 25);
  return sign ? -value : value;
}

float srgbToLinear(uint8_t encoded) {
  const float c = float(encoded) / 255.0f;
  return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}

}  // namespace

ImageReadback::ImageReadback(rhi::Device& device, rhi::TextureId texture, graph::Format format, graph::Extent extent,
                             graph::ImportState finalState)
    : device_(device), format_(format), extent_(extent) {
  const uint64_t size = uint64_t{extent.width} * extent.height * graph::bytesPerPixel(format);
  buffer_ = device.createBuffer({"image readback", size, rhi::kBufferTransferDst, rhi::MemoryUsage::Readback});
  const graph::ImportState hostState{graph::kStageHost, graph::kAccessHostRead, graph::Layout::Undefined,
                                     graph::QueueClass::Graphics};
  graph::FrameGraph graph;
  auto source = graph.importTexture("frame image", {format, extent, 1, 1, 1, {}, 0}, rhi::external(texture),
                                    finalState, finalState);
  auto target = graph.importBuffer("image readback", {size, {}}, rhi::external(buffer_), hostState, hostState);
  // On the graphics queue, where the frame graph leaves the image: a transfer-queue copy would
  // acquire it from graphics with no matching release (the frame graph keeps it on graphics).
  auto node = graph.addNode("Image Readback", graph::NodeType::Transfer, graph::QueueClass::Graphics);
  node.read(source, graph::Access::TransferSrc);
  target = node.write(target, graph::Access::TransferDst);
  node.sideEffect();
  node.setJob([source, target](graph::JobContext& context) {
    auto& ctx = rhi::rhiContext(context);
    ctx.cmd().copyTextureToBuffer(ctx.texture(source), ctx.buffer(target));
  });
  node.recordingFixed();
  rhi::GraphOptions options;
  options.name = "image readback";
  options.timestamps = false;
  graph_ = device.compile(std::move(graph), options);
}

ImageRGBA32F ImageReadback::read() {
  device_.waitIdle();
  device_.wait(device_.execute(*graph_));
  return decodeTexels(format_, extent_, device_.mapped(buffer_));
}

ImageRGBA32F decodeTexels(graph::Format format, graph::Extent extent, std::span<const std::byte> bytes) {
  ImageRGBA32F image{extent.width, extent.height, {}};
  const size_t pixels = size_t{extent.width} * extent.height;
  image.pixels.assign(pixels * 4, 0.0f);
  const auto half = [&](size_t index) {
    uint16_t value = 0;
    std::memcpy(&value, bytes.data() + 2 * index, 2);
    return halfToFloat(value);
  };
  const auto single = [&](size_t index) {
    float value = 0;
    std::memcpy(&value, bytes.data() + 4 * index, 4);
    return value;
  };
  switch (format) {
    case graph::Format::R16G16B16A16Sfloat:
      for (size_t i = 0; i < pixels * 4; ++i) image.pixels[i] = half(i);
      break;
    case graph::Format::R32G32B32A32Sfloat:
      for (size_t i = 0; i < pixels * 4; ++i) image.pixels[i] = single(i);
      break;
    case graph::Format::R16G16Sfloat:
      for (size_t i = 0; i < pixels; ++i) image.pixels[i * 4] = half(2 * i), image.pixels[i * 4 + 1] = half(2 * i + 1);
      break;
    case graph::Format::R32Sfloat:
    case graph::Format::D32Sfloat:  // depth: the value in every colour channel, opaque
      for (size_t i = 0; i < pixels; ++i) {
        const float value = single(i);
        image.pixels[i * 4] = image.pixels[i * 4 + 1] = image.pixels[i * 4 + 2] = value;
        image.pixels[i * 4 + 3] = 1.0f;
      }
      break;
    case graph::Format::R8G8B8A8Srgb:
    case graph::Format::R8G8B8A8Unorm:
      // 8-bit images read back are display images: sRGB-encoded bytes, encoded by the hardware (sRGB
      // format) or by the compute tone mapping (UNORM, which storage images can be).
      for (size_t i = 0; i < pixels * 4; ++i) {
        const auto encoded = uint8_t(bytes[i]);
        image.pixels[i] = i % 4 == 3 ? float(encoded) / 255.0f : srgbToLinear(encoded);
      }
      break;
    default:
      throw DeviceError("image readback: unsupported format " + std::string(graph::toString(format)));
  }
  return image;
}

}  // namespace fgb::render
