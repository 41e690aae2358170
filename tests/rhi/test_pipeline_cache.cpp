// The on-disk pipeline cache: written when the device goes, named after the device and driver,
// read back by the next device; a file that is not a pipeline cache of this device is ignored
// (the run compiles from scratch), never passed to the driver.
#include "gpu_support.hpp"

#include <filesystem>
#include <fstream>

#include <unistd.h>

namespace fgb::test {
namespace {

// VkPipelineCacheHeaderVersionOne: size, version (1), vendor, device (uint32 each), 16-byte UUID.
constexpr uintmax_t kHeaderBytes = 32;

std::filesystem::path freshDirectory(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() / ("fgbench-" + name + "-" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  return dir;
}

std::vector<std::filesystem::path> cacheFiles(const std::filesystem::path& dir) {
  std::vector<std::filesystem::path> files;
  if (!std::filesystem::exists(dir)) return files;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) files.push_back(entry.path());
  return files;
}

rhi::PipelineStats createOnePipeline(const std::filesystem::path& dir) {
  auto device = makeValidatedDevice({.pipelineCacheDir = dir.string()});
  device->createComputePipeline({"fill", "common/fill.comp"});
  const rhi::PipelineStats stats = device->pipelineStats();
  EXPECT_EQ(device->validationMessages(), 0u);
  return stats;
}

TEST(PipelineCache, SavedWhenTheDeviceGoesAndFoundByTheNextOne) {
  const auto dir = freshDirectory("pipeline-cache");
  const rhi::PipelineStats first = createOnePipeline(dir);
  EXPECT_EQ(first.cache, "cold");
  EXPECT_EQ(first.created, 1u);
  EXPECT_GT(first.creationMs, 0.0);
  const auto files = cacheFiles(dir);
  ASSERT_EQ(files.size(), 1u);
  EXPECT_GE(std::filesystem::file_size(files[0]), kHeaderBytes);

  // Drivers that keep pipeline data in the cache report it warm the second time; lavapipe keeps
  // only the header, which is no warm cache.
  const rhi::PipelineStats second = createOnePipeline(dir);
  const bool hasData = std::filesystem::file_size(files[0]) > kHeaderBytes;
  EXPECT_EQ(second.cache, hasData ? "warm" : "cold");
  std::filesystem::remove_all(dir);
}

TEST(PipelineCache, AFileOfAnotherDeviceOrGarbageIsIgnored) {
  const auto dir = freshDirectory("pipeline-cache-bad");
  createOnePipeline(dir);
  const auto files = cacheFiles(dir);
  ASSERT_EQ(files.size(), 1u);
  {
    std::ofstream garbage(files[0], std::ios::binary | std::ios::trunc);
    garbage << std::string(4096, '\x7f');
  }
  const rhi::PipelineStats stats = createOnePipeline(dir);
  EXPECT_EQ(stats.cache, "cold");
  // The corrupt file was replaced by a valid one.
  std::ifstream in(files[0], std::ios::binary);
  uint32_t header[2] = {};
  in.read(reinterpret_cast<char*>(header), sizeof(header));
  EXPECT_EQ(header[0], kHeaderBytes);
  EXPECT_EQ(header[1], 1u);
  std::filesystem::remove_all(dir);
}

TEST(PipelineCache, OffWithoutADirectory) {
  auto device = makeValidatedDevice();
  EXPECT_EQ(device->pipelineStats().cache, "off");
  EXPECT_EQ(device->pipelineStats().created, 0u);
}

}  // namespace
}  // namespace fgb::test
