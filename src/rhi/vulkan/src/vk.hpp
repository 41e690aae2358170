// Vulkan through volk (no prototypes; every entry point is loaded at run time), error checking
// and a small owning handle for every device-level object.
#pragma once

#include <volk.h>

#include <string>
#include <string_view>
#include <utility>

namespace fgb::vulkan {

std::string_view toString(VkResult result);

// A device's 16-byte UUID (pipelineCacheUUID, deviceUUID) as 32 lowercase hex digits.
std::string hexUuid(const uint8_t (&uuid)[VK_UUID_SIZE]);

// A zero-initialised Vulkan structure with its sType set.
template <class T>
T vkStruct(VkStructureType type) {
  T value{};
  value.sType = type;
  return value;
}

// Throws fgb::DeviceError "<what>: <VkResult>" unless result is VK_SUCCESS.
void check(VkResult result, std::string_view what);

// Owns one device-level Vulkan object and destroys it with the function it was created for
// (vkDestroyBuffer, vkFreeMemory, ...). Move-only.
template <class T>
class Owned;

// A pipeline layout of one descriptor set layout and one push-constant range; `what` names it in
// the error ("vkCreatePipelineLayout (what) failed: ...").
Owned<VkPipelineLayout> createPipelineLayout(VkDevice device, VkDescriptorSetLayout setLayout,
                                             const VkPushConstantRange& push, std::string_view what);

template <class T>
class Owned {
 public:
  using Destroy = void(VKAPI_PTR*)(VkDevice, T, const VkAllocationCallbacks*);

  Owned() = default;
  Owned(VkDevice device, T handle, Destroy destroy) : device_(device), handle_(handle), destroy_(destroy) {}
  Owned(Owned&& other) noexcept { swap(other); }
  Owned& operator=(Owned&& other) noexcept {
    Owned moved(std::move(other));
    swap(moved);
    return *this;
  }
  Owned(const Owned&) = delete;
  Owned& operator=(const Owned&) = delete;
  ~Owned() { reset(); }

  void reset() {
    if (handle_ != VK_NULL_HANDLE) destroy_(device_, handle_, nullptr);
    handle_ = VK_NULL_HANDLE;
  }
  [[nodiscard]] T get() const { return handle_; }
  [[nodiscard]] explicit operator bool() const { return handle_ != VK_NULL_HANDLE; }

 private:
  void swap(Owned& other) noexcept {
    std::swap(device_, other.device_);
    std::swap(handle_, other.handle_);
    std::swap(destroy_, other.destroy_);
  }

  VkDevice device_ = VK_NULL_HANDLE;
  T handle_ = VK_NULL_HANDLE;
  Destroy destroy_ = nullptr;
};

}  // namespace fgb::vulkan
