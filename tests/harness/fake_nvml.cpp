// A stand-in for NVIDIA's libnvidia-ml.so.1 with one device, for the device probe's tests: the
// entry points DeviceProbe loads, with C linkage and NVML's signatures, plus setters the test
// reaches through dlsym on the same loaded library.
#include <cstring>

namespace {
unsigned smClock = 1980;
unsigned temperature = 41;
int initialised = 0;
int devicePlaceholder = 0;
}  // namespace

extern "C" {
void fakeNvmlSetSmClock(unsigned mhz) {
  smClock = mhz;
}
int fakeNvmlInitialised() {
  return initialised;
}

int nvmlInit_v2() {
  ++initialised;
  return 0;
}
int nvmlShutdown() {
  --initialised;
  return 0;
}
int nvmlDeviceGetCount_v2(unsigned* count) {
  *count = 1;
  return 0;
}
int nvmlDeviceGetHandleByIndex_v2(unsigned index, void** device) {
  if (index != 0) return 2;  // NVML_ERROR_INVALID_ARGUMENT
  *device = &devicePlaceholder;
  return 0;
}
int nvmlDeviceGetUUID(void*, char* uuid, unsigned length) {
  const char* text = "GPU-00112233-4455-6677-8899-AABBCCDDEEFF";
  if (length <= std::strlen(text)) return 7;  // NVML_ERROR_INSUFFICIENT_SIZE
  std::strcpy(uuid, text);
  return 0;
}
int nvmlDeviceGetClockInfo(void*, int type, unsigned* mhz) {
  *mhz = type == 1 ? smClock : 2619;
  return 0;
}
int nvmlDeviceGetTemperature(void*, int, unsigned* celsius) {
  *celsius = temperature;
  return 0;
}
int nvmlDeviceGetPowerUsage(void*, unsigned* milliwatts) {
  *milliwatts = 123456;
  return 0;
}
int nvmlDeviceGetCurrentClocksEventReasons(void*, unsigned long long* reasons) {
  *reasons = 0;
  return 0;
}
}
