// fgbench devices [--json]: the Vulkan devices, with the index --device INDEX takes.
#include "verb.hpp"

#include <fgb/renderer/workload.hpp>

#include <nlohmann/json.hpp>

#include <iostream>

namespace fgb::app {
namespace {

nlohmann::json toJson(const render::DeviceDescription& d) {
  return {{"index", d.index},
          {"name", d.name},
          {"type", d.type},
          {"driver", d.driver},
          {"api_version", d.apiVersion},
          {"timestamp_period_ns", d.timestampPeriodNs},
          {"host_timestamps", d.hostTimestamps},
          {"queue_families", d.queueFamilies}};
}

void printText(const std::vector<render::DeviceDescription>& devices) {
  if (devices.empty()) std::cout << "no Vulkan devices\n";
  for (const auto& d : devices) {
    std::cout << "[" << d.index << "] " << d.name << "\n"
              << "    type:        " << d.type << (d.hostTimestamps ? " (timestamps are host clock)" : "") << "\n"
              << "    driver:      " << d.driver << "\n"
              << "    api version: " << d.apiVersion << "\n"
              << "    timestamp:   " << d.timestampPeriodNs << " ns/tick\n"
              << "    queue families:\n";
    for (const auto& family : d.queueFamilies) std::cout << "      " << family << "\n";
  }
}

int devicesVerb(bool json) {
  const auto devices = render::listDevices();
  if (json) {
    nlohmann::json list = nlohmann::json::array();
    for (const auto& d : devices) list.push_back(toJson(d));
    std::cout << list.dump(2) << "\n";
  } else {
    printText(devices);
  }
  return 0;
}

const VerbRegistrar reg(10, [](CLI::App& app) {
  auto json = std::make_shared<bool>(false);
  CLI::App* sub = app.add_subcommand("devices", "List Vulkan devices: index, name, type, driver, API version, queue families");
  sub->add_flag("--json", *json, "Machine-readable output on stdout");
  return Verb{sub, [json] { return devicesVerb(*json); }};
});

}  // namespace
}  // namespace fgb::app
