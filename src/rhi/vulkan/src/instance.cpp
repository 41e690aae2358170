#include "instance.hpp"

#include <fgb/core/error.hpp>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string_view>

namespace fgb::vulkan {
namespace {

constexpr const char* kValidationLayer = "VK_LAYER_KHRONOS_validation";
constexpr size_t kMaxLoggedMessages = 256;

void loadVulkanLoader() {
  // volkInitialize is idempotent; once the loader is found, later calls return immediately.
  static const VkResult result = volkInitialize();
  if (result != VK_SUCCESS) {
    throw DeviceError("Vulkan loader (libvulkan.so.1) not found: install a Vulkan driver (e.g. mesa-vulkan-drivers)");
  }
}

bool hasLayer(const char* name) {
  uint32_t count = 0;
  vkEnumerateInstanceLayerProperties(&count, nullptr);
  std::vector<VkLayerProperties> layers(count);
  vkEnumerateInstanceLayerProperties(&count, layers.data());
  for (const auto& layer : layers) {
    if (std::strcmp(layer.layerName, name) == 0) return true;
  }
  return false;
}

bool hasInstanceExtension(const char* layer, const char* name) {
  uint32_t count = 0;
  vkEnumerateInstanceExtensionProperties(layer, &count, nullptr);
  std::vector<VkExtensionProperties> extensions(count);
  vkEnumerateInstanceExtensionProperties(layer, &count, extensions.data());
  for (const auto& extension : extensions) {
    if (std::strcmp(extension.extensionName, name) == 0) return true;
  }
  return false;
}

// volkLoadDevice asks vkGetDeviceProcAddr for every function volk knows. Debian 12's volk
// (1.3.239) files a few instance-level functions among them (e.g.
// vkGetPhysicalDeviceVideoEncodeQualityLevelPropertiesKHR), and newer validation layers warn about
// each ask on drivers that expose them (NVIDIA). That is volk's table, not our use of Vulkan: the
// pointer is never called. Only this exact warning is dropped.
bool isVolkDeviceTableNoise(const VkDebugUtilsMessengerCallbackDataEXT& data) {
  const std::string_view message = data.pMessage ? data.pMessage : "";
  return message.starts_with("vkGetDeviceProcAddr(): pName is trying to grab ") &&
         message.ends_with(" which is an instance level function");
}

VKAPI_ATTR VkBool32 VKAPI_CALL onMessage(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                         VkDebugUtilsMessageTypeFlagsEXT /*types*/,
                                         const VkDebugUtilsMessengerCallbackDataEXT* data, void* user) {
  if (!isVolkDeviceTableNoise(*data)) static_cast<Instance*>(user)->record(severity, *data);
  return VK_FALSE;  // never abort the call that triggered the message
}

VkDebugUtilsMessengerCreateInfoEXT messengerInfo(Instance* instance) {
  auto info = vkStruct<VkDebugUtilsMessengerCreateInfoEXT>(VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT);
  // Warnings and errors are what validation reports; info/verbose are loader chatter.
  info.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
  info.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                     VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
  info.pfnUserCallback = onMessage;
  info.pUserData = instance;
  return info;
}

}  // namespace

bool validationRequestedByEnvironment() {
  const char* value = std::getenv("FGBENCH_VALIDATION");
  return value != nullptr && value[0] != '\0' && std::strcmp(value, "0") != 0;
}

Instance::Instance(bool validation) : validation_(validation) {
  loadVulkanLoader();
  if (validation_ && !hasLayer(kValidationLayer)) {
    throw DeviceError(std::string("validation requested but ") + kValidationLayer +
                      " is not installed (Debian: vulkan-validationlayers)");
  }
  // Debug utils gives object names and per-node labels (RenderDoc, validation messages) and the messenger.
  debugUtils_ = hasInstanceExtension(nullptr, VK_EXT_DEBUG_UTILS_EXTENSION_NAME) ||
                (validation_ && hasInstanceExtension(kValidationLayer, VK_EXT_DEBUG_UTILS_EXTENSION_NAME));

  std::vector<const char*> extensions;
  std::vector<const char*> layers;
  if (debugUtils_) extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);

  VkDebugUtilsMessengerCreateInfoEXT messenger = messengerInfo(this);
  const VkValidationFeatureEnableEXT enables[] = {VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT};
  auto features = vkStruct<VkValidationFeaturesEXT>(VK_STRUCTURE_TYPE_VALIDATION_FEATURES_EXT);
  features.enabledValidationFeatureCount = 1;
  features.pEnabledValidationFeatures = enables;

  const void* next = nullptr;
  if (validation_) {
    layers.push_back(kValidationLayer);
    if (!hasInstanceExtension(kValidationLayer, VK_EXT_VALIDATION_FEATURES_EXTENSION_NAME)) {
      throw DeviceError("validation layer lacks VK_EXT_validation_features: synchronization validation unavailable");
    }
    extensions.push_back(VK_EXT_VALIDATION_FEATURES_EXTENSION_NAME);
    if (debugUtils_) features.pNext = &messenger;  // also report messages of vkCreate/DestroyInstance
    next = &features;
  }

  auto app = vkStruct<VkApplicationInfo>(VK_STRUCTURE_TYPE_APPLICATION_INFO);
  app.pApplicationName = "fgbench";
  app.pEngineName = "fgbench";
  app.apiVersion = VK_API_VERSION_1_3;

  auto info = vkStruct<VkInstanceCreateInfo>(VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO);
  info.pNext = next;
  info.pApplicationInfo = &app;
  info.enabledLayerCount = static_cast<uint32_t>(layers.size());
  info.ppEnabledLayerNames = layers.data();
  info.enabledExtensionCount = static_cast<uint32_t>(extensions.size());
  info.ppEnabledExtensionNames = extensions.data();
  check(vkCreateInstance(&info, nullptr, &instance_), "vkCreateInstance");
  volkLoadInstanceOnly(instance_);

  if (debugUtils_ && validation_) {
    messenger.pNext = nullptr;
    const VkResult result = vkCreateDebugUtilsMessengerEXT(instance_, &messenger, nullptr, &messenger_);
    if (result != VK_SUCCESS) {
      vkDestroyInstance(instance_, nullptr);
      check(result, "vkCreateDebugUtilsMessengerEXT");
    }
  }
}

Instance::~Instance() {
  if (messenger_ != VK_NULL_HANDLE) vkDestroyDebugUtilsMessengerEXT(instance_, messenger_, nullptr);
  vkDestroyInstance(instance_, nullptr);
}

void Instance::record(VkDebugUtilsMessageSeverityFlagBitsEXT severity, const VkDebugUtilsMessengerCallbackDataEXT& data) {
  messages_.fetch_add(1);
  const char* level = (severity & VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT) != 0 ? "error" : "warning";
  std::string line = std::string("validation ") + level + ": " + (data.pMessage ? data.pMessage : "(no message)");
  std::fprintf(stderr, "fgbench: %s\n", line.c_str());
  const std::lock_guard lock(logMutex_);
  if (log_.size() < kMaxLoggedMessages) log_.push_back(std::move(line));
}

std::vector<std::string> Instance::log() const {
  const std::lock_guard lock(logMutex_);
  return log_;
}

std::vector<VkPhysicalDevice> Instance::physicalDevices() const {
  uint32_t count = 0;
  check(vkEnumeratePhysicalDevices(instance_, &count, nullptr), "vkEnumeratePhysicalDevices");
  std::vector<VkPhysicalDevice> devices(count);
  check(vkEnumeratePhysicalDevices(instance_, &count, devices.data()), "vkEnumeratePhysicalDevices");
  devices.resize(count);
  return devices;
}

}  // namespace fgb::vulkan
