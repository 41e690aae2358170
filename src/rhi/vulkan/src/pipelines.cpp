// VulkanDevice: shader modules (embedded SPIR-V, see shaders/) and pipelines. Graphics pipelines
// use dynamic rendering (no render pass objects); every pipeline shares the bindless layout.
#include "device.hpp"
#include "translate.hpp"

#include <fgb/core/error.hpp>
#include <fgb/core/stopwatch.hpp>
#include <fgb/shaders/registry.hpp>

#include <array>
#include <vector>

namespace fgb::vulkan {

VkShaderModule VulkanDevice::shaderModule(const std::string& path) {
  if (const auto it = shaderModules_.find(path); it != shaderModules_.end()) return it->second.get();
  const auto words = shaders::spirv(path);
  auto info = vkStruct<VkShaderModuleCreateInfo>(VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO);
  info.codeSize = words.size_bytes();
  info.pCode = words.data();
  VkShaderModule module = VK_NULL_HANDLE;
  check(vkCreateShaderModule(device_, &info, nullptr, &module), "vkCreateShaderModule '" + path + "'");
  setName(VK_OBJECT_TYPE_SHADER_MODULE, reinterpret_cast<uint64_t>(module), path);
  shaderModules_.emplace(path, Owned<VkShaderModule>(device_, module, vkDestroyShaderModule));
  return module;
}

namespace {

// Adds the scope's wall time to `total` (pipeline creation is host time the harness reports).
class ScopedMilliseconds {
 public:
  explicit ScopedMilliseconds(double& total) : total_(total) {}
  ~ScopedMilliseconds() { total_ += stopwatch_.elapsedMs(); }
  ScopedMilliseconds(const ScopedMilliseconds&) = delete;
  ScopedMilliseconds& operator=(const ScopedMilliseconds&) = delete;

 private:
  double& total_;
  Stopwatch stopwatch_;
};

VkPipelineShaderStageCreateInfo stage(VkShaderStageFlagBits bit, VkShaderModule module) {
  auto info = vkStruct<VkPipelineShaderStageCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO);
  info.stage = bit;
  info.module = module;
  info.pName = "main";
  return info;
}

VkPipelineColorBlendAttachmentState blendState(rhi::BlendMode mode) {
  VkPipelineColorBlendAttachmentState state{};
  state.colorWriteMask = VK_COLOR_COMPONENT_R_BIT | VK_COLOR_COMPONENT_G_BIT | VK_COLOR_COMPONENT_B_BIT |
                         VK_COLOR_COMPONENT_A_BIT;
  if (mode == rhi::BlendMode::Opaque) return state;
  state.blendEnable = VK_TRUE;
  state.colorBlendOp = state.alphaBlendOp = VK_BLEND_OP_ADD;
  state.srcColorBlendFactor = mode == rhi::BlendMode::Alpha ? VK_BLEND_FACTOR_SRC_ALPHA : VK_BLEND_FACTOR_ONE;
  state.dstColorBlendFactor = mode == rhi::BlendMode::Alpha ? VK_BLEND_FACTOR_ONE_MINUS_SRC_ALPHA : VK_BLEND_FACTOR_ONE;
  state.srcAlphaBlendFactor = VK_BLEND_FACTOR_ONE;
  state.dstAlphaBlendFactor = mode == rhi::BlendMode::Alpha ? VK_BLEND_FACTOR_ONE_MINUS_SRC_ALPHA : VK_BLEND_FACTOR_ONE;
  return state;
}

}  // namespace

// The pre-rasterisation stages: the vertex shader, or a mesh pipeline's task (optional) and mesh shaders.
std::vector<VkPipelineShaderStageCreateInfo> VulkanDevice::geometryStages(const rhi::GraphicsPipelineDesc& desc) {
  if (desc.meshShader.empty()) return {stage(VK_SHADER_STAGE_VERTEX_BIT, shaderModule(desc.vertexShader))};
  if (!meshShaders_)
    throw std::logic_error("mesh pipeline '" + desc.name + "' on a device without mesh shaders (" + adapter_.name +
                           ")");
  std::vector<VkPipelineShaderStageCreateInfo> stages;
  if (!desc.taskShader.empty()) stages.push_back(stage(VK_SHADER_STAGE_TASK_BIT_EXT, shaderModule(desc.taskShader)));
  stages.push_back(stage(VK_SHADER_STAGE_MESH_BIT_EXT, shaderModule(desc.meshShader)));
  return stages;
}

rhi::PipelineId VulkanDevice::createGraphicsPipeline(const rhi::GraphicsPipelineDesc& desc) {
  std::vector<VkPipelineShaderStageCreateInfo> stages = geometryStages(desc);
  if (!desc.fragmentShader.empty()) stages.push_back(stage(VK_SHADER_STAGE_FRAGMENT_BIT, shaderModule(desc.fragmentShader)));
  const bool meshPipeline = !desc.meshShader.empty();

  std::vector<VkVertexInputBindingDescription> bindings;
  for (const auto& b : desc.vertexBindings) {
    bindings.push_back({b.binding, b.stride, b.perInstance ? VK_VERTEX_INPUT_RATE_INSTANCE : VK_VERTEX_INPUT_RATE_VERTEX});
  }
  std::vector<VkVertexInputAttributeDescription> attributes;
  for (const auto& a : desc.vertexAttributes) attributes.push_back({a.location, a.binding, toVk(a.format), a.offset});
  auto vertexInput = vkStruct<VkPipelineVertexInputStateCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO);
  vertexInput.vertexBindingDescriptionCount = static_cast<uint32_t>(bindings.size());
  vertexInput.pVertexBindingDescriptions = bindings.data();
  vertexInput.vertexAttributeDescriptionCount = static_cast<uint32_t>(attributes.size());
  vertexInput.pVertexAttributeDescriptions = attributes.data();

  auto assembly = vkStruct<VkPipelineInputAssemblyStateCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO);
  assembly.topology = toVk(desc.topology);
  auto viewport = vkStruct<VkPipelineViewportStateCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO);
  viewport.viewportCount = 1;
  viewport.scissorCount = 1;
  auto raster = vkStruct<VkPipelineRasterizationStateCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO);
  raster.polygonMode = VK_POLYGON_MODE_FILL;
  raster.cullMode = toVk(desc.cullMode);
  raster.frontFace = desc.frontFaceCounterClockwise ? VK_FRONT_FACE_COUNTER_CLOCKWISE : VK_FRONT_FACE_CLOCKWISE;
  raster.lineWidth = 1.0f;
  auto multisample = vkStruct<VkPipelineMultisampleStateCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO);
  multisample.rasterizationSamples = toVkSamples(desc.samples);
  auto depth = vkStruct<VkPipelineDepthStencilStateCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO);
  depth.depthTestEnable = desc.depthTest;
  depth.depthWriteEnable = desc.depthWrite;
  depth.depthCompareOp = toVk(desc.depthCompare);
  std::vector<VkPipelineColorBlendAttachmentState> blends;
  for (size_t i = 0; i < desc.colorFormats.size(); ++i) {
    blends.push_back(blendState(i < desc.blend.size() ? desc.blend[i] : rhi::BlendMode::Opaque));
  }
  auto blend = vkStruct<VkPipelineColorBlendStateCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO);
  blend.attachmentCount = static_cast<uint32_t>(blends.size());
  blend.pAttachments = blends.data();
  const std::array<VkDynamicState, 2> dynamicStates{VK_DYNAMIC_STATE_VIEWPORT, VK_DYNAMIC_STATE_SCISSOR};
  auto dynamic = vkStruct<VkPipelineDynamicStateCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO);
  dynamic.dynamicStateCount = static_cast<uint32_t>(dynamicStates.size());
  dynamic.pDynamicStates = dynamicStates.data();

  std::vector<VkFormat> colorFormats;
  for (const auto format : desc.colorFormats) colorFormats.push_back(toVk(format));
  auto rendering = vkStruct<VkPipelineRenderingCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_RENDERING_CREATE_INFO);
  rendering.colorAttachmentCount = static_cast<uint32_t>(colorFormats.size());
  rendering.pColorAttachmentFormats = colorFormats.data();
  rendering.depthAttachmentFormat = toVk(desc.depthFormat);
  if (graph::hasStencil(desc.depthFormat)) rendering.stencilAttachmentFormat = toVk(desc.depthFormat);

  auto info = vkStruct<VkGraphicsPipelineCreateInfo>(VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO);
  info.pNext = &rendering;
  info.stageCount = static_cast<uint32_t>(stages.size());
  info.pStages = stages.data();
  // A mesh pipeline has neither (its mesh shader emits the primitives).
  info.pVertexInputState = meshPipeline ? nullptr : &vertexInput;
  info.pInputAssemblyState = meshPipeline ? nullptr : &assembly;
  info.pViewportState = &viewport;
  info.pRasterizationState = &raster;
  info.pMultisampleState = &multisample;
  info.pDepthStencilState = &depth;
  info.pColorBlendState = &blend;
  info.pDynamicState = &dynamic;
  info.layout = descriptors_->pipelineLayout();
  VkPipeline pipeline = VK_NULL_HANDLE;
  {
    const ScopedMilliseconds timer(pipelineCreationMs_);
    check(vkCreateGraphicsPipelines(device_, pipelineCache_->get(), 1, &info, nullptr, &pipeline),
          "vkCreateGraphicsPipelines '" + desc.name + "'");
  }
  return addPipeline(pipeline, VK_PIPELINE_BIND_POINT_GRAPHICS, desc.name);
}

rhi::PipelineId VulkanDevice::createComputePipeline(const rhi::ComputePipelineDesc& desc) {
  auto info = vkStruct<VkComputePipelineCreateInfo>(VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO);
  info.stage = stage(VK_SHADER_STAGE_COMPUTE_BIT, shaderModule(desc.shader));
  info.layout = descriptors_->pipelineLayout();
  VkPipeline pipeline = VK_NULL_HANDLE;
  {
    const ScopedMilliseconds timer(pipelineCreationMs_);
    check(vkCreateComputePipelines(device_, pipelineCache_->get(), 1, &info, nullptr, &pipeline),
          "vkCreateComputePipelines '" + desc.name + "'");
  }
  return addPipeline(pipeline, VK_PIPELINE_BIND_POINT_COMPUTE, desc.name);
}

rhi::PipelineId VulkanDevice::addPipeline(VkPipeline pipeline, VkPipelineBindPoint bindPoint, const std::string& name) {
  setName(VK_OBJECT_TYPE_PIPELINE, reinterpret_cast<uint64_t>(pipeline), name);
  pipelines_.push_back({Owned<VkPipeline>(device_, pipeline, vkDestroyPipeline), bindPoint});
  return rhi::PipelineId{static_cast<uint32_t>(pipelines_.size() - 1)};
}

rhi::PipelineStats VulkanDevice::pipelineStats() const {
  return {static_cast<uint32_t>(pipelines_.size()), pipelineCreationMs_, pipelineCache_->state()};
}

const PipelineRecord& VulkanDevice::pipeline(rhi::PipelineId id) const {
  if (id.index >= pipelines_.size()) throw std::out_of_range("no pipeline with id " + std::to_string(id.index));
  return pipelines_[id.index];
}

}  // namespace fgb::vulkan
