// Error categories that map to the CLI's exit codes (see the contract):
//   CheckFailed -> 1, InputError/UsageError -> 2, DeviceError -> 3.
// Messages are one line and say what and where (file, field, line).
#pragma once

#include <stdexcept>
#include <string>

namespace fgb {

// Bad usage or bad input: missing/corrupt scene, model, texture, image; invalid option.
class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// A check failed: golden over threshold, budget exceeded, significant slowdown.
class CheckFailed : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Device or runtime failure: no Vulkan device, out of memory, device lost, validation error.
class DeviceError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

enum ExitCode : int { kExitOk = 0, kExitCheckFailed = 1, kExitBadInput = 2, kExitDevice = 3 };

}  // namespace fgb
