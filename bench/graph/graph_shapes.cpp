#include "graph_shapes.hpp"

#include <random>

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace fgb::graph::bench {
namespace {

constexpr uint32_t kLayerWidth = 8;

NodeType typeOf(uint32_t node) {
  static constexpr NodeType kMix[] = {NodeType::Graphics, NodeType::Compute, NodeType::Graphics, NodeType::Transfer};
  return kMix[node % 4];
}

Access writeAccess(NodeType type) {
  switch (type) {
    case NodeType::Graphics:
      return Access::ColorAttachmentWrite;
    case NodeType::Compute:
      return Access::StorageWrite;
    case NodeType::Transfer:
      return Access::TransferDst;
  }
  return Access::StorageWrite;
}

Access readAccess(NodeType type) {
  return type == NodeType::Transfer ? Access::TransferSrc : Access::Sampled;
}

TextureDesc targetDesc() {
  TextureDesc desc;
  desc.format = Format::R16G16B16A16Sfloat;
  desc.extent = {256, 256, 1};
  return desc;
}

// Declares node `i` reading `reads` and writing a fresh transient; returns what it wrote.
TextureHandle declareNode(FrameGraph& graph, const ShapeInputs& inputs, uint32_t i, const TextureHandle* reads,
                          uint32_t readCount, bool sideEffect) {
  const TextureHandle target = graph.createTexture(inputs.resources[i], targetDesc());
  const NodeType type = typeOf(i);
  NodeBuilder builder = graph.addNode(inputs.nodes[i], type);
  for (uint32_t k = 0; k < readCount; ++k) builder.read(reads[k], readAccess(type));
  const TextureHandle written = builder.write(target, writeAccess(type));
  if (sideEffect) builder.sideEffect();
  return written;
}

}  // namespace

ShapeInputs::ShapeInputs(uint32_t nodeCount) : count(nodeCount) {
  for (uint32_t i = 0; i < nodeCount; ++i) {
    nodes.push_back("node" + std::to_string(i));
    resources.push_back("tex" + std::to_string(i));
  }
  std::mt19937 rng(42);
  for (uint32_t layer = 1; layer < nodeCount / kLayerWidth; ++layer) {
    for (uint32_t slot = 0; slot < kLayerWidth; ++slot) {
      const uint32_t first = rng() % kLayerWidth;
      uint32_t second = rng() % kLayerWidth;
      while (second == first) second = rng() % kLayerWidth;  // two distinct outputs
      layeredInputs.push_back({first, second});
    }
  }
}

void declareChain(FrameGraph& graph, const ShapeInputs& inputs) {
  TextureHandle previous{};
  for (uint32_t i = 0; i < inputs.count; ++i) {
    previous = declareNode(graph, inputs, i, &previous, i == 0 ? 0 : 1, i + 1 == inputs.count);
  }
}

void declareLayered(FrameGraph& graph, const ShapeInputs& inputs) {
  std::array<TextureHandle, kLayerWidth> previousLayer{};
  std::array<TextureHandle, kLayerWidth> currentLayer{};
  const uint32_t layers = inputs.count / kLayerWidth;
  const std::array<uint32_t, 2>* chosen = inputs.layeredInputs.data();
  for (uint32_t layer = 0; layer < layers; ++layer) {
    const bool last = layer + 1 == layers;
    for (uint32_t slot = 0; slot < kLayerWidth; ++slot) {
      const uint32_t i = layer * kLayerWidth + slot;
      TextureHandle reads[2];
      uint32_t readCount = 0;
      if (layer > 0) {
        reads[0] = previousLayer[(*chosen)[0]];
        reads[1] = previousLayer[(*chosen)[1]];
        readCount = 2;
        ++chosen;
      }
      currentLayer[slot] = declareNode(graph, inputs, i, reads, readCount, last);
    }
    std::swap(previousLayer, currentLayer);
  }
}

CompileOptions optionsFor(uint32_t queues) {
  CompileOptions options;
  options.queueCount = queues;
  options.queueOfClass = queues == 1 ? std::array<uint32_t, 3>{0, 0, 0} : std::array<uint32_t, 3>{0, 1, 2};
  return options;
}

void keepFreedMemory() {
#if defined(__GLIBC__)
  mallopt(M_MMAP_THRESHOLD, 256 << 20);  // large arrays from the heap, not from fresh mappings...
  mallopt(M_TRIM_THRESHOLD, 1 << 30);    // ...and the heap not trimmed after each graph
#endif
}

}  // namespace fgb::graph::bench
