// The --device rule, on made-up adapter lists (no Vulkan device needed).
#include "adapters.hpp"

#include <fgb/core/error.hpp>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

using fgb::rhi::AdapterInfo;
using fgb::vulkan::selectAdapter;

namespace {

AdapterInfo adapter(uint32_t index, const char* name, const char* type, bool usable = true) {
  AdapterInfo a;
  a.index = index;
  a.name = name;
  a.type = type;
  a.usable = usable;
  if (!usable) a.unusableReason = "Vulkan 1.1 < 1.3";
  return a;
}

template <class E>
std::string messageOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const E& e) {
    return e.what();
  }
  return "(no exception)";
}

}  // namespace

TEST(AdapterSelection, AutoPrefersDiscreteThenIntegratedThenCpu) {
  const std::vector<AdapterInfo> all = {adapter(0, "llvmpipe", "cpu"), adapter(1, "iGPU", "integrated"),
                                        adapter(2, "H100", "discrete")};
  EXPECT_EQ(selectAdapter(all, "auto"), 2u);
  EXPECT_EQ(selectAdapter({all[0], all[1]}, "auto"), 1u);
  EXPECT_EQ(selectAdapter({all[0]}, "auto"), 0u);
  EXPECT_EQ(selectAdapter(all, "gpu"), 2u);
  EXPECT_EQ(selectAdapter(all, "lavapipe"), 0u);
  EXPECT_EQ(selectAdapter(all, "1"), 1u);
}

TEST(AdapterSelection, SkipsUnusableAdapters) {
  const std::vector<AdapterInfo> all = {adapter(0, "old GPU", "discrete", false), adapter(1, "llvmpipe", "cpu")};
  EXPECT_EQ(selectAdapter(all, "auto"), 1u);
  EXPECT_THROW(selectAdapter(all, "gpu"), fgb::DeviceError);
  EXPECT_THAT(messageOf<fgb::DeviceError>([&] { selectAdapter(all, "0"); }), testing::HasSubstr("unusable"));
}

TEST(AdapterSelection, MissingDeviceIsADeviceErrorNamingWhatExists) {
  const std::vector<AdapterInfo> cpuOnly = {adapter(0, "llvmpipe", "cpu")};
  const std::string message = messageOf<fgb::DeviceError>([&] { selectAdapter(cpuOnly, "99"); });
  EXPECT_THAT(message, testing::HasSubstr("--device 99"));
  EXPECT_THAT(message, testing::HasSubstr("llvmpipe"));
  EXPECT_THROW(selectAdapter(cpuOnly, "gpu"), fgb::DeviceError);
  EXPECT_THROW(selectAdapter({}, "auto"), fgb::DeviceError);
}

TEST(AdapterSelection, MalformedSelectorIsAnInputError) {
  const std::vector<AdapterInfo> cpuOnly = {adapter(0, "llvmpipe", "cpu")};
  EXPECT_THROW(selectAdapter(cpuOnly, "fastest"), fgb::InputError);
  EXPECT_THROW(selectAdapter(cpuOnly, "-1"), fgb::InputError);
  EXPECT_THROW(selectAdapter(cpuOnly, ""), fgb::InputError);
}
