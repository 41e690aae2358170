#include "device.hpp"

#include "adapters.hpp"
#include "executable_graph.hpp"

#include <fgb/core/error.hpp>
#include <fgb/vulkan/backend.hpp>

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <string_view>
#include <vector>

namespace fgb::vulkan {
namespace {

struct FamilyChoice {
  uint32_t graphics = UINT32_MAX;
  uint32_t compute = UINT32_MAX;
  uint32_t transfer = UINT32_MAX;
};

// Graphics: a family with graphics+compute. Compute and transfer nodes go to dedicated families
// where the device has them (async compute, copy engines), else share the graphics family.
FamilyChoice chooseFamilies(VkPhysicalDevice physical) {
  uint32_t count = 0;
  vkGetPhysicalDeviceQueueFamilyProperties(physical, &count, nullptr);
  std::vector<VkQueueFamilyProperties> families(count);
  vkGetPhysicalDeviceQueueFamilyProperties(physical, &count, families.data());
  FamilyChoice choice;
  for (uint32_t i = 0; i < count; ++i) {
    const VkQueueFlags flags = families[i].queueFlags;
    const bool graphics = flags & VK_QUEUE_GRAPHICS_BIT;
    const bool compute = flags & VK_QUEUE_COMPUTE_BIT;
    const bool transfer = flags & VK_QUEUE_TRANSFER_BIT;
    if (graphics && compute && choice.graphics == UINT32_MAX) choice.graphics = i;
    if (compute && !graphics && choice.compute == UINT32_MAX) choice.compute = i;
    if (transfer && !graphics && !compute && choice.transfer == UINT32_MAX) choice.transfer = i;
  }
  if (choice.graphics == UINT32_MAX) throw DeviceError("device has no graphics+compute queue family");
  if (choice.compute == UINT32_MAX) choice.compute = choice.graphics;
  if (choice.transfer == UINT32_MAX) choice.transfer = choice.compute;
  return choice;
}

// R64 storage images with 64-bit atomics: the extension, its image feature, and R64_UINT optimal
// images with storage and storage atomics (the extension promises them; checked all the same).
bool supportsImageInt64Atomics(VkPhysicalDevice physical) {
  uint32_t count = 0;
  vkEnumerateDeviceExtensionProperties(physical, nullptr, &count, nullptr);
  std::vector<VkExtensionProperties> extensions(count);
  vkEnumerateDeviceExtensionProperties(physical, nullptr, &count, extensions.data());
  const bool listed = std::any_of(extensions.begin(), extensions.end(), [](const VkExtensionProperties& e) {
    return std::string_view(e.extensionName) == VK_EXT_SHADER_IMAGE_ATOMIC_INT64_EXTENSION_NAME;
  });
  if (!listed) return false;
  auto image = vkStruct<VkPhysicalDeviceShaderImageAtomicInt64FeaturesEXT>(
      VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SHADER_IMAGE_ATOMIC_INT64_FEATURES_EXT);
  auto features = vkStruct<VkPhysicalDeviceFeatures2>(VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2);
  features.pNext = &image;
  vkGetPhysicalDeviceFeatures2(physical, &features);
  if (image.shaderImageInt64Atomics != VK_TRUE) return false;
  VkFormatProperties format{};
  vkGetPhysicalDeviceFormatProperties(physical, VK_FORMAT_R64_UINT, &format);
  constexpr VkFormatFeatureFlags kNeeded =
      VK_FORMAT_FEATURE_STORAGE_IMAGE_BIT | VK_FORMAT_FEATURE_STORAGE_IMAGE_ATOMIC_BIT;
  return (format.optimalTilingFeatures & kNeeded) == kNeeded;
}

// VK_EXT_mesh_shader with task and mesh shaders (the meshlet path's), unless the environment
// hides it: FGBENCH_HIDE_MESH_SHADERS=1 opens the device without the extension, as on a device
// that lacks it (how the tests reach "needs VK_EXT_mesh_shader" on a device that has it).
bool supportsMeshShaders(VkPhysicalDevice physical) {
  if (const char* hide = std::getenv("FGBENCH_HIDE_MESH_SHADERS"); hide != nullptr && std::string_view(hide) == "1")
    return false;
  uint32_t count = 0;
  vkEnumerateDeviceExtensionProperties(physical, nullptr, &count, nullptr);
  std::vector<VkExtensionProperties> extensions(count);
  vkEnumerateDeviceExtensionProperties(physical, nullptr, &count, extensions.data());
  const bool listed = std::any_of(extensions.begin(), extensions.end(), [](const VkExtensionProperties& e) {
    return std::string_view(e.extensionName) == VK_EXT_MESH_SHADER_EXTENSION_NAME;
  });
  if (!listed) return false;
  auto mesh =
      vkStruct<VkPhysicalDeviceMeshShaderFeaturesEXT>(VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_MESH_SHADER_FEATURES_EXT);
  auto features = vkStruct<VkPhysicalDeviceFeatures2>(VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2);
  features.pNext = &mesh;
  vkGetPhysicalDeviceFeatures2(physical, &features);
  return mesh.taskShader == VK_TRUE && mesh.meshShader == VK_TRUE;
}

}  // namespace

VulkanDevice::VulkanDevice(const rhi::DeviceOptions& options) : framesInFlight_(std::max(1u, options.framesInFlight)) {
  instance_ = std::make_unique<Instance>(options.validation || validationRequestedByEnvironment());
  const auto physicals = instance_->physicalDevices();
  std::vector<rhi::AdapterInfo> adapters;
  for (uint32_t i = 0; i < physicals.size(); ++i) adapters.push_back(describeAdapter(physicals[i], i));
  const uint32_t chosen = selectAdapter(adapters, options.selector);
  physical_ = physicals[chosen];
  adapter_ = adapters[chosen];

  VkPhysicalDeviceProperties properties{};
  vkGetPhysicalDeviceProperties(physical_, &properties);
  // Counts up to 8 (the harness's range); 1 is always supported.
  sampleCounts_ = (properties.limits.framebufferColorSampleCounts & properties.limits.framebufferDepthSampleCounts &
                   (VK_SAMPLE_COUNT_2_BIT | VK_SAMPLE_COUNT_4_BIT | VK_SAMPLE_COUNT_8_BIT)) |
                  VK_SAMPLE_COUNT_1_BIT;
  standardSampleLocations_ = properties.limits.standardSampleLocations == VK_TRUE;
  debugLabels_ = options.debugLabels && instance_->debugUtils();

  createLogicalDevice();
  memory_ = std::make_unique<MemoryAllocator>(physical_, device_);
  createDescriptors(options.forceDescriptorFallback);
  pipelineCache_ = std::make_unique<PipelineCache>(device_, properties, options.pipelineCacheDir);
}

VulkanDevice::~VulkanDevice() {
  if (device_ == VK_NULL_HANDLE) return;
  vkDeviceWaitIdle(device_);
  callbacks_.clear();
  pipelines_.clear();
  pipelineCache_.reset();  // saved to disk here
  samplers_.clear();
  textures_.clear();
  buffers_.clear();
  shaderModules_.clear();
  descriptors_.reset();
  memory_.reset();
  vkDestroyDevice(device_, nullptr);
}

void VulkanDevice::createLogicalDevice() {
  const FamilyChoice families = chooseFamilies(physical_);
  std::vector<uint32_t> distinct;
  for (uint32_t family : {families.graphics, families.compute, families.transfer}) {
    if (std::find(distinct.begin(), distinct.end(), family) == distinct.end()) distinct.push_back(family);
  }
  const float priority = 1.0f;
  std::vector<VkDeviceQueueCreateInfo> queueInfos;
  for (uint32_t family : distinct) {
    auto info = vkStruct<VkDeviceQueueCreateInfo>(VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO);
    info.queueFamilyIndex = family;
    info.queueCount = 1;
    info.pQueuePriorities = &priority;
    queueInfos.push_back(info);
  }

  // Query what the device has, then enable what we need plus the optional features it offers.
  auto has13 = vkStruct<VkPhysicalDeviceVulkan13Features>(VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES);
  auto has12 = vkStruct<VkPhysicalDeviceVulkan12Features>(VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES);
  auto has11 = vkStruct<VkPhysicalDeviceVulkan11Features>(VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_1_FEATURES);
  has12.pNext = &has13;
  has11.pNext = &has12;
  auto has = vkStruct<VkPhysicalDeviceFeatures2>(VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2);
  has.pNext = &has11;
  vkGetPhysicalDeviceFeatures2(physical_, &has);

  auto v13 = vkStruct<VkPhysicalDeviceVulkan13Features>(VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES);
  v13.dynamicRendering = VK_TRUE;
  v13.synchronization2 = VK_TRUE;
  v13.maintenance4 = has13.maintenance4;
  auto v12 = vkStruct<VkPhysicalDeviceVulkan12Features>(VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES);
  v12.pNext = &v13;
  v12.timelineSemaphore = VK_TRUE;
  v12.hostQueryReset = VK_TRUE;
  v12.drawIndirectCount = has12.drawIndirectCount;
  v12.shaderBufferInt64Atomics = has12.shaderBufferInt64Atomics;
  v12.shaderSharedInt64Atomics = has12.shaderSharedInt64Atomics;
  drawIndirectCount_ = has12.drawIndirectCount == VK_TRUE;
  v12.descriptorIndexing = has12.descriptorIndexing;
  v12.descriptorBindingPartiallyBound = has12.descriptorBindingPartiallyBound;
  v12.descriptorBindingUpdateUnusedWhilePending = has12.descriptorBindingUpdateUnusedWhilePending;
  v12.descriptorBindingStorageBufferUpdateAfterBind = has12.descriptorBindingStorageBufferUpdateAfterBind;
  v12.descriptorBindingSampledImageUpdateAfterBind = has12.descriptorBindingSampledImageUpdateAfterBind;
  v12.descriptorBindingStorageImageUpdateAfterBind = has12.descriptorBindingStorageImageUpdateAfterBind;
  v12.shaderSampledImageArrayNonUniformIndexing = has12.shaderSampledImageArrayNonUniformIndexing;
  v12.shaderStorageBufferArrayNonUniformIndexing = has12.shaderStorageBufferArrayNonUniformIndexing;
  v12.runtimeDescriptorArray = has12.runtimeDescriptorArray;
  auto v11 = vkStruct<VkPhysicalDeviceVulkan11Features>(VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_1_FEATURES);
  v11.pNext = &v12;
  v11.shaderDrawParameters = has11.shaderDrawParameters;
  auto features = vkStruct<VkPhysicalDeviceFeatures2>(VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2);
  features.pNext = &v11;
  const VkPhysicalDeviceFeatures& core = has.features;
  features.features.samplerAnisotropy = core.samplerAnisotropy;
  features.features.multiDrawIndirect = core.multiDrawIndirect;
  features.features.drawIndirectFirstInstance = core.drawIndirectFirstInstance;
  features.features.independentBlend = core.independentBlend;
  features.features.fragmentStoresAndAtomics = core.fragmentStoresAndAtomics;
  features.features.vertexPipelineStoresAndAtomics = core.vertexPipelineStoresAndAtomics;
  features.features.shaderStorageImageWriteWithoutFormat = core.shaderStorageImageWriteWithoutFormat;
  features.features.shaderSampledImageArrayDynamicIndexing = core.shaderSampledImageArrayDynamicIndexing;
  features.features.shaderStorageBufferArrayDynamicIndexing = core.shaderStorageBufferArrayDynamicIndexing;
  features.features.shaderStorageImageArrayDynamicIndexing = core.shaderStorageImageArrayDynamicIndexing;
  features.features.shaderInt64 = core.shaderInt64;
  shaderCapabilities_.int64 = core.shaderInt64 == VK_TRUE;
  shaderCapabilities_.bufferInt64Atomics =
      shaderCapabilities_.int64 && has12.shaderBufferInt64Atomics == VK_TRUE && has12.shaderSharedInt64Atomics == VK_TRUE;
  shaderCapabilities_.imageInt64Atomics = shaderCapabilities_.int64 && supportsImageInt64Atomics(physical_);
  // The only device extensions, both optional: everything else the backend uses is Vulkan 1.3 core.
  std::vector<const char*> extensions;
  auto imageAtomics = vkStruct<VkPhysicalDeviceShaderImageAtomicInt64FeaturesEXT>(
      VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SHADER_IMAGE_ATOMIC_INT64_FEATURES_EXT);
  if (shaderCapabilities_.imageInt64Atomics) {
    extensions.push_back(VK_EXT_SHADER_IMAGE_ATOMIC_INT64_EXTENSION_NAME);
    imageAtomics.shaderImageInt64Atomics = VK_TRUE;
    imageAtomics.pNext = v13.pNext;
    v13.pNext = &imageAtomics;
  }
  // Mesh pipelines are drawn with drawMeshTasksIndirectCount, which needs drawIndirectCount, and
  // their task shaders find their draw by gl_DrawID (shaderDrawParameters).
  auto mesh =
      vkStruct<VkPhysicalDeviceMeshShaderFeaturesEXT>(VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_MESH_SHADER_FEATURES_EXT);
  meshShaders_ = drawIndirectCount_ && has11.shaderDrawParameters == VK_TRUE && supportsMeshShaders(physical_);
  if (meshShaders_) {
    extensions.push_back(VK_EXT_MESH_SHADER_EXTENSION_NAME);
    mesh.taskShader = VK_TRUE;
    mesh.meshShader = VK_TRUE;
    mesh.pNext = v13.pNext;
    v13.pNext = &mesh;
  }

  auto info = vkStruct<VkDeviceCreateInfo>(VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO);
  info.pNext = &features;
  info.enabledExtensionCount = static_cast<uint32_t>(extensions.size());
  info.ppEnabledExtensionNames = extensions.data();
  info.queueCreateInfoCount = static_cast<uint32_t>(queueInfos.size());
  info.pQueueCreateInfos = queueInfos.data();
  check(vkCreateDevice(physical_, &info, nullptr, &device_), "vkCreateDevice on " + adapter_.name);
  volkLoadDevice(device_);

  uint32_t familyCount = 0;
  vkGetPhysicalDeviceQueueFamilyProperties(physical_, &familyCount, nullptr);
  std::vector<VkQueueFamilyProperties> familyProperties(familyCount);
  vkGetPhysicalDeviceQueueFamilyProperties(physical_, &familyCount, familyProperties.data());
  for (uint32_t family : distinct) {
    DeviceQueue queue;
    queue.family = family;
    queue.flags = familyProperties[family].queueFlags;
    vkGetDeviceQueue(device_, family, 0, &queue.queue);
    queues_.push_back(queue);
    queueFamilies_.push_back(family);
  }
  const auto indexOf = [&](uint32_t family) {
    return static_cast<uint32_t>(std::find(distinct.begin(), distinct.end(), family) - distinct.begin());
  };
  queueOfClass_ = {indexOf(families.graphics), indexOf(families.compute), indexOf(families.transfer)};
  for (uint32_t i = 0; i < queues_.size(); ++i) {
    setName(VK_OBJECT_TYPE_QUEUE, reinterpret_cast<uint64_t>(queues_[i].queue),
            "queue family " + std::to_string(queues_[i].family));
  }
}

void VulkanDevice::createDescriptors(bool forceFallback) {
  const bool bindless = !forceFallback && supportsBindless(physical_);
  descriptors_ = std::make_unique<Descriptors>(device_, bindless, [this] {
    // Fallback sets cannot change while a command buffer using them is pending.
    if (submittedWork_) vkDeviceWaitIdle(device_);
  });
  if (!bindless) initialiseFallbackDescriptors();
}

void VulkanDevice::setName(VkObjectType type, uint64_t handle, const std::string& name) const {
  if (!instance_->debugUtils() || vkSetDebugUtilsObjectNameEXT == nullptr) return;
  auto info = vkStruct<VkDebugUtilsObjectNameInfoEXT>(VK_STRUCTURE_TYPE_DEBUG_UTILS_OBJECT_NAME_INFO_EXT);
  info.objectType = type;
  info.objectHandle = handle;
  info.pObjectName = name.c_str();
  vkSetDebugUtilsObjectNameEXT(device_, &info);
}

std::unique_ptr<rhi::Device> createDevice(const rhi::DeviceOptions& options) {
  return std::make_unique<VulkanDevice>(options);
}

std::vector<rhi::AdapterInfo> enumerateAdapters() {
  const Instance instance(false);
  const auto physicals = instance.physicalDevices();
  std::vector<rhi::AdapterInfo> adapters;
  for (uint32_t i = 0; i < physicals.size(); ++i) adapters.push_back(describeAdapter(physicals[i], i));
  return adapters;
}

}  // namespace fgb::vulkan
