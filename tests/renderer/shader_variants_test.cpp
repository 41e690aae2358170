// Shader variants (shaders/CMakeLists.txt): the visibility buffer's image backing is the raster and
// shade shaders compiled again with FGB_VIS_BACKING_IMAGE. The variants must be embedded under
// "PATH:image" and must be the image code: only they declare the 64-bit image capability, which a
// device without VK_EXT_shader_image_atomic_int64 refuses.
#include <gtest/gtest.h>

#include <cstdint>
#include <fgb/shaders/registry.hpp>
#include <span>

namespace fgb::shaders {
namespace {

constexpr uint32_t kOpCapability = 17;
constexpr uint32_t kCapabilityInt64ImageEXT = 5016;

// Walks the module's instructions (after the 5-word header) looking for OpCapability `capability`.
bool declaresCapability(std::span<const uint32_t> words, uint32_t capability) {
  for (size_t at = 5; at < words.size();) {
    const uint32_t count = words[at] >> 16;
    if (count == 0) return false;  // malformed
    if ((words[at] & 0xffffu) == kOpCapability && at + 1 < words.size() && words[at + 1] == capability) return true;
    at += count;
  }
  return false;
}

TEST(ShaderVariants, VisibilityImageBackingIsEmbeddedWithImageAtomicsOnlyThere) {
  EXPECT_EQ(variantPath("renderer/visbuffer/visibility_raster.comp", "image"),
            "renderer/visbuffer/visibility_raster.comp:image");
  for (const char* shader : {"renderer/visbuffer/visibility_raster.comp", "renderer/visbuffer/material_shade.comp"}) {
    ASSERT_TRUE(contains(variantPath(shader, "image"))) << shader;
    EXPECT_TRUE(declaresCapability(spirv(variantPath(shader, "image")), kCapabilityInt64ImageEXT)) << shader;
    EXPECT_FALSE(declaresCapability(spirv(shader), kCapabilityInt64ImageEXT)) << shader;
  }
  EXPECT_TRUE(declaresCapability(spirv("renderer/visbuffer/vis_clear.comp"), kCapabilityInt64ImageEXT));
  EXPECT_FALSE(contains("renderer/visbuffer/triangle_filter.comp:image"));
}

}  // namespace
}  // namespace fgb::shaders
