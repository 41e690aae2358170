// VulkanDevice: the rhi::Device of the Vulkan backend. One class, implemented by concern:
// device.cpp (creation, queues, features), resources.cpp (buffers, textures, samplers),
// pipelines.cpp, executor.cpp (running graphs), executable_graph.cpp (compiling them).
#pragma once

#include "descriptors.hpp"
#include "instance.hpp"
#include "memory.hpp"
#include "pipeline_cache.hpp"
#include "vk.hpp"

#include <fgb/rhi/device.hpp>

#include <array>
#include <deque>
#include <functional>
#include <memory>
#include <string>
#include <unordered_map>
#include <vector>

namespace fgb::vulkan {

class VulkanGraph;

struct BufferRecord {
  Owned<VkBuffer> buffer;
  Allocation allocation;
  bool ownsMemory = false;
  rhi::BufferDesc desc;
  uint32_t storageIndex = rhi::kInvalidId;
};

struct TextureRecord {
  Owned<VkImage> image;
  Owned<VkImageView> view;
  Allocation allocation;
  bool ownsMemory = false;
  rhi::TextureDesc desc;
  VkImageAspectFlags aspect = 0;
  uint32_t sampledIndex = rhi::kInvalidId;
  uint32_t storageIndex = rhi::kInvalidId;
  // Sampled and storage usage both: a second sampled descriptor, in the GENERAL layout, for nodes
  // that hold the image as storage and sample it too (graph::Access::StorageSampledWrite).
  uint32_t sampledGeneralIndex = rhi::kInvalidId;
};

struct SamplerRecord {
  Owned<VkSampler> sampler;
  uint32_t index = rhi::kInvalidId;
};

struct PipelineRecord {
  Owned<VkPipeline> pipeline;
  VkPipelineBindPoint bindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
};

// A device queue the logical graph queues map onto.
struct DeviceQueue {
  VkQueue queue = VK_NULL_HANDLE;
  uint32_t family = 0;
  VkQueueFlags flags = 0;  // the family's capabilities (which stages its barriers may name)
};

// A timeline semaphore value a submission can wait for.
struct TimelinePoint {
  VkSemaphore semaphore = VK_NULL_HANDLE;
  uint64_t value = 0;
};

class VulkanDevice final : public rhi::Device {
 public:
  explicit VulkanDevice(const rhi::DeviceOptions& options);
  ~VulkanDevice() override;

  // rhi::Device
  const rhi::AdapterInfo& adapter() const override { return adapter_; }
  uint32_t maxSamples() const override { return rhi::clampSampleCount(64, sampleCounts_); }
  uint32_t sampleCounts() const override { return sampleCounts_; }
  bool bindless() const override { return descriptors_->bindless(); }
  bool drawIndirectCount() const override { return drawIndirectCount_; }
  rhi::ShaderCapabilities shaderCapabilities() const override { return shaderCapabilities_; }
  bool meshShaders() const override { return meshShaders_; }
  bool standardSampleLocations() const override { return standardSampleLocations_; }
  rhi::BufferId createBuffer(const rhi::BufferDesc& desc) override;
  rhi::TextureId createTexture(const rhi::TextureDesc& desc) override;
  rhi::SamplerId createSampler(const rhi::SamplerDesc& desc) override;
  rhi::PipelineId createGraphicsPipeline(const rhi::GraphicsPipelineDesc& desc) override;
  rhi::PipelineId createComputePipeline(const rhi::ComputePipelineDesc& desc) override;
  rhi::PipelineStats pipelineStats() const override;
  std::span<std::byte> mapped(rhi::BufferId buffer) override;
  uint32_t storageBufferIndex(rhi::BufferId buffer) const override;
  uint32_t sampledTextureIndex(rhi::TextureId texture) const override;
  uint32_t storageTextureIndex(rhi::TextureId texture) const override;
  uint32_t samplerIndex(rhi::SamplerId sampler) const override;
  std::unique_ptr<rhi::ExecutableGraph> compile(graph::FrameGraph&& graph, const rhi::GraphOptions& options) override;
  rhi::RunTicket execute(rhi::ExecutableGraph& graph, rhi::RunMode mode, std::function<void()> onComplete) override;
  bool isComplete(const rhi::RunTicket& ticket) const override;
  void wait(const rhi::RunTicket& ticket) override;
  void poll() override;
  void waitIdle() override;
  uint64_t validationMessages() const override { return instance_->messages(); }
  std::vector<std::string> validationLog() const override { return instance_->log(); }

  // Backend internals (used by VulkanGraph and the command buffer).
  VkDevice device() const { return device_; }
  VkPhysicalDevice physical() const { return physical_; }
  const std::vector<DeviceQueue>& queues() const { return queues_; }
  // Device queue for each queue class (graphics, compute, transfer).
  const std::array<uint32_t, 3>& queueOfClass() const { return queueOfClass_; }
  MemoryAllocator& memory() { return *memory_; }
  const Descriptors& descriptors() const { return *descriptors_; }
  Descriptors& descriptors() { return *descriptors_; }
  bool debugLabels() const { return debugLabels_; }
  bool validationEnabled() const { return instance_->validation(); }
  void setName(VkObjectType type, uint64_t handle, const std::string& name) const;

  const BufferRecord& buffer(rhi::BufferId id) const;
  const TextureRecord& texture(rhi::TextureId id) const;
  const PipelineRecord& pipeline(rhi::PipelineId id) const;

  // Resources of a graph: created unbound or placed at an offset of a given memory block.
  // (points into the device: use it while the device lives)
  VkBufferCreateInfo bufferInfo(const rhi::BufferDesc& desc) const;
  static VkImageCreateInfo imageInfo(const rhi::TextureDesc& desc);
  rhi::BufferId createBufferIn(const rhi::BufferDesc& desc, const Allocation* placement);
  rhi::TextureId createTextureIn(const rhi::TextureDesc& desc, const Allocation* placement);
  void destroyBuffer(rhi::BufferId id) override;
  void destroyTexture(rhi::TextureId id) override;

  uint32_t registerGraph(VulkanGraph* graph);
  void unregisterGraph(uint32_t id);
  // Waits for the previous sequential run; replaced by the points of the run just submitted.
  std::vector<TimelinePoint>& sequentialTail() { return sequentialTail_; }

 private:
  // A graphics pipeline's stages before rasterisation (pipelines.cpp).
  std::vector<VkPipelineShaderStageCreateInfo> geometryStages(const rhi::GraphicsPipelineDesc& desc);
  void createLogicalDevice();
  void createView(TextureRecord& record);
  void createDescriptors(bool forceFallback);
  void initialiseFallbackDescriptors();
  void waitForAllGraphs();
  void invokeFinishedCallbacks();

  std::unique_ptr<Instance> instance_;
  VkPhysicalDevice physical_ = VK_NULL_HANDLE;
  rhi::AdapterInfo adapter_;
  VkDevice device_ = VK_NULL_HANDLE;
  std::vector<DeviceQueue> queues_;
  std::vector<uint32_t> queueFamilies_;  // distinct families of queues_ (buffers are shared by them)
  std::array<uint32_t, 3> queueOfClass_{0, 0, 0};
  uint32_t sampleCounts_ = 1;  // rhi::Device::sampleCounts()
  bool debugLabels_ = false;
  bool drawIndirectCount_ = false;
  rhi::ShaderCapabilities shaderCapabilities_;
  bool standardSampleLocations_ = false;
  bool meshShaders_ = false;  // VK_EXT_mesh_shader enabled (task + mesh shaders, drawIndirectCount)
  uint32_t framesInFlight_ = 2;

  std::unique_ptr<MemoryAllocator> memory_;
  std::unique_ptr<Descriptors> descriptors_;
  std::vector<BufferRecord> buffers_;
  std::vector<TextureRecord> textures_;
  std::vector<SamplerRecord> samplers_;
  std::vector<PipelineRecord> pipelines_;
  std::unique_ptr<PipelineCache> pipelineCache_;
  double pipelineCreationMs_ = 0.0;
  std::vector<uint32_t> freeBuffers_;
  std::vector<uint32_t> freeTextures_;
  std::unordered_map<std::string, Owned<VkShaderModule>> shaderModules_;

  std::vector<VulkanGraph*> graphs_;  // by graph id; null once destroyed
  std::vector<TimelinePoint> sequentialTail_;
  struct Callback {
    rhi::RunTicket ticket;
    std::function<void()> function;
  };
  std::deque<Callback> callbacks_;
  bool submittedWork_ = false;

  friend class VulkanGraph;
  friend class SpinWork;
  VkShaderModule shaderModule(const std::string& path);
  // Names the pipeline and keeps it; its id is its index.
  rhi::PipelineId addPipeline(VkPipeline pipeline, VkPipelineBindPoint bindPoint, const std::string& name);
};

}  // namespace fgb::vulkan
