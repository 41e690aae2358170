#include "spin.hpp"

#include <fgb/shaders/registry.hpp>

#include <algorithm>
#include <cmath>

namespace fgb::vulkan {
namespace {

constexpr uint32_t kInvocations = 64;  // spin.comp's local size; one workgroup

struct SpinPush {
  uint32_t iterations;
  uint32_t seed;
};

double median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  const std::size_t n = values.size();
  return n % 2 == 1 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

}  // namespace

SpinWork::SpinWork(VulkanDevice& device, double fraction) : device_(device), fraction_(fraction) {
  const VkDevice vk = device.device();
  // Not a device buffer (createBuffer): those are in the bindless tables, where every node's
  // shaders would be seen (by synchronization validation) reading it.
  auto bufferInfo = vkStruct<VkBufferCreateInfo>(VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO);
  bufferInfo.size = kInvocations * sizeof(uint32_t);
  bufferInfo.usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
  bufferInfo.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
  VkBuffer buffer = VK_NULL_HANDLE;
  check(vkCreateBuffer(vk, &bufferInfo, nullptr, &buffer), "vkCreateBuffer (slow pass)");
  scratch_ = Owned<VkBuffer>(vk, buffer, vkDestroyBuffer);
  VkMemoryRequirements requirements{};
  vkGetBufferMemoryRequirements(vk, buffer, &requirements);
  VkPhysicalDeviceMemoryProperties properties{};
  vkGetPhysicalDeviceMemoryProperties(device.physical(), &properties);
  uint32_t type = 0;
  while (type < properties.memoryTypeCount && (requirements.memoryTypeBits & (1u << type)) == 0) ++type;
  auto allocateInfo = vkStruct<VkMemoryAllocateInfo>(VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO);
  allocateInfo.allocationSize = requirements.size;
  allocateInfo.memoryTypeIndex = type;
  VkDeviceMemory memory = VK_NULL_HANDLE;
  check(vkAllocateMemory(vk, &allocateInfo, nullptr, &memory), "vkAllocateMemory (slow pass)");
  memory_ = Owned<VkDeviceMemory>(vk, memory, vkFreeMemory);
  check(vkBindBufferMemory(vk, buffer, memory, 0), "vkBindBufferMemory (slow pass)");
  {
    VkDescriptorSetLayoutBinding binding{};
    binding.binding = 0;
    binding.descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    binding.descriptorCount = 1;
    binding.stageFlags = VK_SHADER_STAGE_COMPUTE_BIT;
    auto setInfo = vkStruct<VkDescriptorSetLayoutCreateInfo>(VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO);
    setInfo.bindingCount = 1;
    setInfo.pBindings = &binding;
    VkDescriptorSetLayout setLayout = VK_NULL_HANDLE;
    check(vkCreateDescriptorSetLayout(vk, &setInfo, nullptr, &setLayout), "vkCreateDescriptorSetLayout (slow pass)");
    setLayout_ = Owned<VkDescriptorSetLayout>(vk, setLayout, vkDestroyDescriptorSetLayout);

    const VkDescriptorPoolSize size{VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1};
    auto poolInfo = vkStruct<VkDescriptorPoolCreateInfo>(VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO);
    poolInfo.maxSets = 1;
    poolInfo.poolSizeCount = 1;
    poolInfo.pPoolSizes = &size;
    VkDescriptorPool pool = VK_NULL_HANDLE;
    check(vkCreateDescriptorPool(vk, &poolInfo, nullptr, &pool), "vkCreateDescriptorPool (slow pass)");
    pool_ = Owned<VkDescriptorPool>(vk, pool, vkDestroyDescriptorPool);
    auto allocate = vkStruct<VkDescriptorSetAllocateInfo>(VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO);
    allocate.descriptorPool = pool;
    allocate.descriptorSetCount = 1;
    allocate.pSetLayouts = &setLayout;
    check(vkAllocateDescriptorSets(vk, &allocate, &set_), "vkAllocateDescriptorSets (slow pass)");
    const VkDescriptorBufferInfo scratchInfo{buffer, 0, VK_WHOLE_SIZE};
    auto write = vkStruct<VkWriteDescriptorSet>(VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET);
    write.dstSet = set_;
    write.descriptorCount = 1;
    write.descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    write.pBufferInfo = &scratchInfo;
    vkUpdateDescriptorSets(vk, 1, &write, 0, nullptr);

    const VkPushConstantRange range{VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(SpinPush)};
    layout_ = createPipelineLayout(vk, setLayout, range, "slow pass");

    auto info = vkStruct<VkComputePipelineCreateInfo>(VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO);
    info.stage = vkStruct<VkPipelineShaderStageCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO);
    info.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
    info.stage.module = device.shaderModule("common/spin.comp");
    info.stage.pName = "main";
    info.layout = layout_.get();
    VkPipeline pipeline = VK_NULL_HANDLE;
    check(vkCreateComputePipelines(vk, VK_NULL_HANDLE, 1, &info, nullptr, &pipeline),
          "vkCreateComputePipelines (slow pass)");
    pipeline_ = Owned<VkPipeline>(vk, pipeline, vkDestroyPipeline);
  }
}

void SpinWork::record(VkCommandBuffer cmd) const {
  // Everything the node recorded finishes first; the scratch buffer's previous write (the previous
  // execution's spin) is made available too, although executions already wait for each other.
  auto barrier = vkStruct<VkMemoryBarrier2>(VK_STRUCTURE_TYPE_MEMORY_BARRIER_2);
  barrier.srcStageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
  barrier.srcAccessMask = VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT;
  barrier.dstStageMask = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;
  barrier.dstAccessMask = VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT;
  auto dependency = vkStruct<VkDependencyInfo>(VK_STRUCTURE_TYPE_DEPENDENCY_INFO);
  dependency.memoryBarrierCount = 1;
  dependency.pMemoryBarriers = &barrier;
  vkCmdPipelineBarrier2(cmd, &dependency);
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline_.get());
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, layout_.get(), 0, 1, &set_, 0, nullptr);
  const SpinPush push{iterations_, 0x2545F491u};
  vkCmdPushConstants(cmd, layout_.get(), VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(push), &push);
  vkCmdDispatch(cmd, 1, 1, 1);
}

void SpinWork::observe(uint64_t execution, double ownMs, double spinMs, uint32_t iterations) {
  if (execution == 0 || execution > kCalibration || iterations == 0 || spinMs <= 0.0) return;
  ownMs_.push_back(ownMs);
  msPerIteration_.push_back(spinMs / iterations);
  const double wanted = fraction_ * median(ownMs_) / median(msPerIteration_);
  iterations_ = static_cast<uint32_t>(std::clamp(std::round(wanted), 1.0, 4.0e9));
}

}  // namespace fgb::vulkan
