#include <fgb/core/atomic_file.hpp>

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <stdexcept>

namespace {

std::string readAll(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

class AtomicFileTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() /
           ("fgb_atomic_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  std::filesystem::path dir_;
};

TEST_F(AtomicFileTest, WritesWholeContent) {
  fgb::writeFileAtomic(dir_ / "a.txt", std::string_view("hello"));
  EXPECT_EQ(readAll(dir_ / "a.txt"), "hello");
}

TEST_F(AtomicFileTest, FailedWriterLeavesOldFileAndNoTemporary) {
  fgb::writeFileAtomic(dir_ / "a.txt", std::string_view("old"));
  EXPECT_THROW(fgb::writeViaTemporary(dir_ / "a.txt",
                                      [](const std::filesystem::path& tmp) {
                                        std::ofstream(tmp) << "half";
                                        throw std::runtime_error("encoder failed");
                                      }),
               std::runtime_error);
  EXPECT_EQ(readAll(dir_ / "a.txt"), "old");
  int files = 0;
  for ([[maybe_unused]] const auto& entry : std::filesystem::directory_iterator(dir_)) ++files;
  EXPECT_EQ(files, 1);
}

TEST_F(AtomicFileTest, UnwritableDirectoryThrows) {
  EXPECT_THROW(fgb::writeFileAtomic(dir_ / "missing" / "a.txt", std::string_view("x")), std::runtime_error);
}

}  // namespace
