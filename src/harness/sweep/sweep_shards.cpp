// Sweeps over several devices: `--shard K/N` cuts the grid along reference groups, and
// `sweep-merge` joins the shards' outputs into one sweep with one front.
#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fgb/core/error.hpp>
#include <fgb/harness/base/json_io.hpp>
#include <fgb/harness/image/image_io.hpp>
#include <fgb/harness/stats/stats.hpp>
#include <fgb/harness/sweep/sweep.hpp>
#include <limits>
#include <set>

namespace fgb::harness {
namespace {

constexpr uint32_t kMaxShards = 64;

std::optional<uint32_t> parseCount(std::string_view text) {
  uint32_t value = 0;
  const auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec != std::errc() || ptr != text.data() + text.size()) return std::nullopt;
  return value;
}

// --- reading a shard's sweep.json back ------------------------------------------------------

struct ShardFile {
  std::filesystem::path dir, file;
  nlohmann::json json;
  ShardInfo shard;
};

[[noreturn]] void bad(const ShardFile& s, const std::string& what) {
  throw InputError(s.file.string() + ": " + what);
}

const nlohmann::json& field(const ShardFile& s, const nlohmann::json& object, const char* key) {
  if (!object.is_object() || !object.contains(key)) bad(s, fmt::format("field '{}' is missing", key));
  return object[key];
}

double number(const ShardFile& s, const nlohmann::json& object, const char* key) {
  const auto& value = field(s, object, key);
  if (value.is_null()) return std::numeric_limits<double>::infinity();  // PSNR of identical images
  if (!value.is_number()) bad(s, fmt::format("field '{}' must be a number", key));
  return value.get<double>();
}

ImageMetrics metricsOf(const ShardFile& s, const nlohmann::json& j) {
  ImageMetrics m;
  m.width = static_cast<uint32_t>(number(s, j, "width"));
  m.height = static_cast<uint32_t>(number(s, j, "height"));
  m.domain = field(s, j, "domain").get<std::string>();
  m.maxAbsError = number(s, j, "max_abs_error");
  m.rmse = number(s, j, "rmse");
  m.psnr = number(s, j, "psnr_db");
  m.peak = number(s, j, "psnr_peak");
  m.channelThreshold = number(s, j, "channel_threshold");
  m.shareOverThreshold = number(s, j, "share_over_threshold");
  m.nonFiniteReference = static_cast<uint64_t>(number(s, j, "non_finite_reference"));
  m.nonFiniteTest = static_cast<uint64_t>(number(s, j, "non_finite_test"));
  if (j.contains("flip")) {
    const auto& f = j["flip"];
    m.flip = FlipStatistics{field(s, f, "mode").get<std::string>(),
                            number(s, f, "mean"),
                            number(s, f, "p50"),
                            number(s, f, "p95"),
                            number(s, f, "p99"),
                            number(s, f, "max")};
  }
  return m;
}

render::WorkloadConfig workloadOf(const ShardFile& s, const std::string& scene, const nlohmann::json& config) {
  render::WorkloadConfig w;
  w.scenePath = scene;
  w.width = config.contains("width") ? static_cast<uint32_t>(number(s, config, "width")) : 0;
  w.height = config.contains("height") ? static_cast<uint32_t>(number(s, config, "height")) : 0;
  w.msaa = static_cast<uint32_t>(number(s, config, "msaa_requested"));
  for (const auto& [k, v] : field(s, config, "knobs").items()) w.knobs[k] = v.get<std::string>();
  return w;
}

Image imageOf(const ShardFile& s, const std::string& name) {
  const auto path = s.dir / "images" / name;
  if (!std::filesystem::exists(path)) bad(s, "no " + ("images/" + name) + " beside it (was it written by --shard?)");
  return readPng(path);
}

ReferenceCheck checkOf(const ShardFile& s, const std::string& scene, const nlohmann::json& j) {
  ReferenceCheck check;
  check.label = field(s, j, "label").get<std::string>();
  check.workload = workloadOf(s, scene, field(s, j, "config"));
  check.display = metricsOf(s, field(s, j, "display"));
  check.hdr = metricsOf(s, field(s, j, "hdr"));
  const auto& wall = field(s, j, "wall_ms");
  check.wall = {number(s, wall, "open"), number(s, wall, "frames"), number(s, wall, "readback")};
  return check;
}

ReferenceOutcome referenceOf(const ShardFile& s, const std::string& scene, const nlohmann::json& j, std::size_t index) {
  ReferenceOutcome r;
  r.workload = workloadOf(s, scene, field(s, j, "config"));
  r.identical = field(s, j, "repeat_identical").get<bool>();
  r.repeatDisplay = metricsOf(s, field(s, field(s, j, "noise"), "display"));
  r.repeatHdr = metricsOf(s, field(s, field(s, j, "noise"), "hdr"));
  r.renderMs = number(s, j, "render_ms");
  for (const auto& w : field(s, j, "renders_ms"))
    r.renders.push_back({number(s, w, "open"), number(s, w, "frames"), number(s, w, "readback")});
  if (!field(s, j, "convergence").is_null()) r.convergence = checkOf(s, scene, j["convergence"]);
  for (const auto& b : field(s, j, "biases")) r.biases.push_back(checkOf(s, scene, b));
  r.images.display = imageOf(s, fmt::format("reference-{}.png", index + 1));
  return r;
}

ConfigurationOutcome configurationOf(const ShardFile& s, const SweepResult& merged, const nlohmann::json& j,
                                     std::size_t gridIndex, std::size_t referenceOffset) {
  ConfigurationOutcome c;
  c.configuration.label = field(s, j, "label").get<std::string>();
  const auto& point = field(s, j, "point");
  for (const auto& axis : merged.axes) {
    c.configuration.point.emplace_back(axis.key, field(s, point, axis.key.c_str()).get<std::string>());
  }
  c.configuration.workload = workloadOf(s, merged.scene, field(s, j, "config"));
  c.reference = referenceOffset + static_cast<std::size_t>(number(s, j, "reference"));
  c.run.device = merged.device;
  c.run.stats["msaa"] = number(s, field(s, j, "config"), "msaa");
  for (const auto& v : field(s, field(s, j, "samples"), "frame_gpu_ms")) c.run.frameGpuMs.push_back(v.get<double>());
  if (c.run.frameGpuMs.empty()) bad(s, c.configuration.label + ": no frame samples");
  c.run.frameGpu = summarize(c.run.frameGpuMs);
  c.frameGpu = medianConfidenceInterval(c.run.frameGpuMs);
  const auto& cpu = field(s, j, "frame_cpu_ms");
  c.run.frameCpu.median = number(s, cpu, "median");
  c.run.frameCpu.p5 = number(s, cpu, "p5");
  c.run.frameCpu.p95 = number(s, cpu, "p95");
  for (const auto& p : field(s, j, "passes")) {
    PassRecord pass;
    pass.name = field(s, p, "name").get<std::string>();
    pass.queue = field(s, p, "queue").get<std::string>();
    pass.culled = field(s, p, "culled").get<bool>();
    pass.gpu.median = number(s, p, "median_ms");
    pass.gpu.p5 = number(s, p, "p5_ms");
    pass.gpu.p95 = number(s, p, "p95_ms");
    pass.gpu.n = static_cast<std::size_t>(number(s, p, "n"));
    c.run.passes.push_back(std::move(pass));
  }
  c.stable = field(s, j, "stable").get<bool>();
  c.display = metricsOf(s, field(s, field(s, j, "error"), "display"));
  c.hdr = metricsOf(s, field(s, field(s, j, "error"), "hdr"));
  c.unresolved = field(s, j, "unresolved").get<bool>();
  // Along a camera path (absent in sweeps written before path times, null for a still scene).
  if (j.contains("path_error") && !j["path_error"].is_null()) {
    for (const auto& t : field(s, j["path_error"], "times")) {
      c.pathErrors.push_back(
          {number(s, t, "time_s"), metricsOf(s, field(s, t, "display")), metricsOf(s, field(s, t, "hdr"))});
    }
  }
  if (const auto& bias = field(s, j, "bias"); !bias.is_null()) {
    const std::string label = field(s, bias, "label").get<std::string>();
    c.bias = merged.references.at(c.reference).biasIndex(label);
    if (!c.bias) bad(s, c.configuration.label + ": its bias '" + label + "' is not among its reference's");
  }
  const auto& wall = field(s, j, "wall_ms");
  c.wall = {number(s, wall, "open"),
            number(s, wall, "warmup"),
            number(s, wall, "measure"),
            number(s, wall, "metrics"),
            static_cast<uint32_t>(number(s, wall, "warmup_frames")),
            static_cast<uint32_t>(number(s, wall, "rewarm_frames")),
            static_cast<uint32_t>(number(s, wall, "visits"))};
  c.images.display = imageOf(s, fmt::format("config-{}.png", gridIndex + 1));
  c.heatMap = imageOf(s, fmt::format("heat-{}.png", gridIndex + 1));
  return c;
}

ShardFile loadShard(const std::filesystem::path& dir) {
  ShardFile s;
  s.dir = dir;
  s.file = std::filesystem::is_directory(dir) ? dir / "sweep.json" : dir;
  if (!std::filesystem::is_directory(dir)) s.dir = dir.parent_path();
  if (!std::filesystem::exists(s.file)) throw InputError(s.file.string() + ": no such file (a sweep --shard's --out)");
  s.json = readJsonFile(s.file);
  if (!s.json.is_object() || s.json.value("schema", 0) != kSweepSchema) bad(s, "not a sweep.json of schema 1");
  if (!s.json.contains("shard") || s.json["shard"].is_null())
    bad(s, "not a shard (run `fgbench sweep ... --shard K/N` for each part)");
  const auto& shard = s.json["shard"];
  s.shard.index = static_cast<uint32_t>(number(s, shard, "index"));
  s.shard.count = static_cast<uint32_t>(number(s, shard, "count"));
  s.shard.gridSize = static_cast<std::size_t>(number(s, shard, "grid_size"));
  for (const auto& i : field(s, shard, "grid_indices")) s.shard.gridIndices.push_back(i.get<std::size_t>());
  if (s.shard.gridIndices.size() != field(s, s.json, "configurations").size())
    bad(s, "shard.grid_indices and configurations differ in length");
  return s;
}

// What every shard must share with the first: the same scene, build, device model, grid and method.
void checkCompatible(const ShardFile& first, const ShardFile& s) {
  auto same = [&](const nlohmann::json& a, const nlohmann::json& b, const std::string& what) {
    if (a != b) bad(s, fmt::format("{} {} differs from {}'s {}", what, b.dump(), first.file.string(), a.dump()));
  };
  same(first.json["scene_hash"], s.json["scene_hash"], "scene (hash)");
  same(first.json["tool_version"], s.json["tool_version"], "build (tool_version)");
  same(first.json["device"]["name"], s.json["device"]["name"], "device model");
  same(first.json["axes"], s.json["axes"], "grid (axes)");
  same(first.json["shard"]["count"], s.json["shard"]["count"], "shard count");
  same(first.json["shard"]["grid_size"], s.json["shard"]["grid_size"], "grid size");
  for (const char* key : {"alpha", "reference_ssaa", "frame_cap", "error", "path_times_s"})
    same(first.json["method"][key], s.json["method"][key], std::string("method.") + key);
}

}  // namespace

ShardSpec parseShard(const std::string& text) {
  const auto slash = text.find('/');
  const auto k = slash == std::string::npos ? std::nullopt : parseCount(std::string_view(text).substr(0, slash));
  const auto n = slash == std::string::npos ? std::nullopt : parseCount(std::string_view(text).substr(slash + 1));
  if (!k || !n || *k < 1 || *k > *n || *n > kMaxShards)
    throw InputError(fmt::format("--shard {}: expected K/N with 1 <= K <= N <= {}, e.g. 1/2", text, kMaxShards));
  return {*k, *n};
}

std::vector<std::size_t> shardConfigurations(const std::vector<SweepConfiguration>& grid, const ReferenceRules& rules,
                                             ShardSpec spec) {
  // Reference groups in grid order (by their first configuration).
  std::vector<render::WorkloadConfig> references;
  std::vector<std::vector<std::size_t>> groups;
  for (std::size_t i = 0; i < grid.size(); ++i) {
    const render::WorkloadConfig reference = referenceOf(grid[i], rules);
    const auto it =
        std::find_if(references.begin(), references.end(), [&](const auto& r) { return sameWorkload(r, reference); });
    if (it == references.end()) {
      references.push_back(reference);
      groups.push_back({i});
    } else {
      groups[static_cast<std::size_t>(it - references.begin())].push_back(i);
    }
  }
  if (groups.size() < spec.count) {
    throw InputError(fmt::format(
        "--shard {}/{}: the grid has {} reference group(s) (configurations sharing a reference stay together); "
        "use at most {} shards",
        spec.index, spec.count, groups.size(), groups.size()));
  }
  // Largest groups first (ties: grid order), each to the least loaded shard (ties: the lowest).
  std::vector<std::size_t> order(groups.size());
  for (std::size_t g = 0; g < order.size(); ++g) order[g] = g;
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return groups[a].size() > groups[b].size(); });
  std::vector<std::size_t> load(spec.count, 0);
  std::vector<std::size_t> mine;
  for (std::size_t g : order) {
    const auto shard = static_cast<std::size_t>(std::min_element(load.begin(), load.end()) - load.begin());
    load[shard] += groups[g].size();
    if (shard + 1 == spec.index) mine.insert(mine.end(), groups[g].begin(), groups[g].end());
  }
  std::sort(mine.begin(), mine.end());
  return mine;
}

SweepResult mergeSweepShards(const std::vector<std::filesystem::path>& directories) {
  if (directories.empty()) throw InputError("sweep-merge: no shard directories given");
  std::vector<ShardFile> shards;
  for (const auto& dir : directories) shards.push_back(loadShard(dir));
  const ShardFile& first = shards.front();
  std::set<uint32_t> seen;
  for (const ShardFile& s : shards) {
    checkCompatible(first, s);
    if (!seen.insert(s.shard.index).second)
      bad(s, fmt::format("shard {}/{} given twice", s.shard.index, s.shard.count));
  }
  for (uint32_t k = 1; k <= first.shard.count; ++k) {
    if (!seen.count(k))
      throw InputError(fmt::format("sweep-merge: shard {}/{} is missing (given: {} director(ies))", k,
                                   first.shard.count, shards.size()));
  }

  SweepResult merged;
  const nlohmann::json& j = first.json;
  merged.toolVersion = j["tool_version"].get<std::string>();
  merged.scene = j["scene"].get<std::string>();
  merged.sceneHash = j["scene_hash"].get<std::string>();
  const auto& device = j["device"];
  merged.device.name = device["name"].get<std::string>();
  merged.device.driver = device.value("driver", "");
  merged.device.type = device.value("type", "");
  merged.device.apiVersion = device.value("api_version", "");
  merged.device.hostTimestamps = device.value("host_timestamps", false);
  for (const auto& a : j["axes"]) merged.axes.push_back({a["key"].get<std::string>(), a["values"]});
  const auto& method = j["method"];
  merged.alpha = method["alpha"].get<double>();
  merged.seed = method.value("seed", uint64_t{1});
  merged.frameCap = method.value("frame_cap", 0u);
  merged.warmupFrames = method.value("warmup_frames", 0u);
  merged.rewarmFrames = method.value("rewarm_frames", 0u);
  merged.referenceRules.ssaa = method.value("reference_ssaa", 4u);
  merged.lookKeys = method.value("look_knobs", std::vector<std::string>{});
  merged.roles = method.value("roles", std::map<std::string, std::string>{});
  merged.stopReason = method.value("stop_reason", "");
  merged.pathTimes = method.value("path_times_s", std::vector<double>{});
  merged.mergedShards = shards.size();

  std::vector<std::optional<ConfigurationOutcome>> placed(first.shard.gridSize);
  for (const ShardFile& s : shards) {
    const std::size_t referenceOffset = merged.references.size();
    const auto& references = field(s, s.json, "references");
    for (std::size_t r = 0; r < references.size(); ++r)
      merged.references.push_back(referenceOf(s, merged.scene, references[r], r));
    const auto& configurations = field(s, s.json, "configurations");
    for (std::size_t c = 0; c < configurations.size(); ++c) {
      const std::size_t g = s.shard.gridIndices[c];
      if (g >= placed.size() || placed[g]) bad(s, fmt::format("grid index {} out of range or measured twice", g));
      placed[g] = configurationOf(s, merged, configurations[c], g, referenceOffset);
    }
    merged.rounds = std::max(merged.rounds, static_cast<uint32_t>(s.json["method"].value("rounds", 0u)));
    merged.errorFloor = std::max(merged.errorFloor, s.json["method"].value("error_floor", 0.0));
    const auto& wall = field(s, s.json, "wall_ms");
    SweepOverhead& o = merged.overhead;
    o.openMs += number(s, wall, "open");
    o.referenceMs += number(s, wall, "references");
    o.warmupMs += number(s, wall, "warmup");
    o.measureMs += number(s, wall, "measure");
    o.closeMs += number(s, wall, "close");
    o.metricsMs += number(s, wall, "metrics");
    o.totalMs = std::max(o.totalMs, number(s, wall, "total"));  // shards run side by side
  }
  for (std::size_t g = 0; g < placed.size(); ++g) {
    if (!placed[g]) throw InputError(fmt::format("sweep-merge: no shard measured configuration {} of the grid", g + 1));
    merged.configurations.push_back(std::move(*placed[g]));
  }
  markFront(merged);
  return merged;
}

}  // namespace fgb::harness
