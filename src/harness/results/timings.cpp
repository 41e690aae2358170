#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <fgb/core/error.hpp>
#include <fgb/harness/base/json_io.hpp>
#include <fgb/harness/results/compare_runs.hpp>
#include <fgb/harness/results/timings.hpp>

namespace fgb::harness {
namespace {

nlohmann::json toJson(const render::NonFiniteCounts& counts) {
  return {{"nan", counts.nan}, {"inf", counts.inf}, {"over_half_max", counts.overHalfMax}};
}

nlohmann::json toJson(const Summary& s) {
  return {{"median", s.median}, {"p5", s.p5},   {"p95", s.p95}, {"p99", s.p99},
          {"mean", s.mean},     {"min", s.min}, {"max", s.max}, {"n", s.n}};
}

// A camera path's frames: the time of each, and the slowest (by GPU time) with their CPU time, so a
// reader finds the worst frames along the path and can render one alone with camera.time.
nlohmann::json pathJson(const RunResult& run) {
  nlohmann::json slowest = nlohmann::json::array();
  for (const std::size_t f : run.slowestFrames(3)) {
    slowest.push_back({{"frame", f},
                       {"path_time_s", run.framePathTimeS[f]},
                       {"gpu_ms", run.frameGpuMs[f]},
                       {"cpu_ms", f < run.frameCpuMs.size() ? run.frameCpuMs[f] : 0.0}});
  }
  return {{"frames", run.framePathTimeS.size()},
          {"start_s", run.framePathTimeS.front()},
          {"end_s", run.framePathTimeS.back()},
          {"slowest", slowest}};
}

std::string csvField(const std::string& text) {
  if (text.find_first_of(",\"\n") == std::string::npos) return text;
  std::string quoted = "\"";
  for (char c : text) {
    if (c == '"') quoted += '"';
    quoted += c;
  }
  return quoted + "\"";
}

std::vector<double> readSamples(const nlohmann::json& object, const std::string& key, const std::filesystem::path& file,
                                const std::string& where) {
  const auto& array = requireField(object, key, file, where);
  const std::string field = where.empty() ? key : where + "." + key;
  if (!array.is_array()) throw InputError(file.string() + ": field '" + field + "' must be an array of milliseconds");
  std::vector<double> samples;
  samples.reserve(array.size());
  for (std::size_t i = 0; i < array.size(); ++i) {
    if (!array[i].is_number() || !std::isfinite(array[i].get<double>())) {
      throw InputError(file.string() + ": field '" + field + "[" + std::to_string(i) + "]' must be a finite number");
    }
    samples.push_back(array[i].get<double>());
  }
  return samples;
}

nlohmann::json toJson(const HarnessOverhead& o) {
  const render::StartupTimes& s = o.startup;
  return {{"open_ms", o.openMs},
          {"startup", {{"scene_ms", s.sceneMs},
                       {"device_ms", s.deviceMs},
                       {"upload_ms", s.uploadMs},
                       {"graph_ms", s.graphMs},
                       {"graph_compile_ms", s.graphCompileMs},
                       {"pipelines_ms", s.pipelinesMs},
                       {"pipelines", s.pipelines},
                       {"pipeline_cache", s.pipelineCache}}},
          {"loop_wall_ms", o.loopWallMs},
          {"workload_calls_ms", o.workloadCallsMs},
          {"harness_ms", o.harnessMs},
          {"harness_us_per_frame", o.perFrameUs},
          {"readback_ms", o.readbackMs},
          {"encode_ms", o.encodeMs}};
}

}  // namespace

const PassRecord* RunResult::findPass(const std::string& name) const {
  for (const auto& p : passes) {
    if (p.name == name) return &p;
  }
  return nullptr;
}

const render::NonFiniteCounts* RunResult::firstNonFinite() const {
  for (const auto& counts : nonFinite)
    if (counts.bad()) return &counts;
  return nullptr;
}

std::vector<std::size_t> RunResult::slowestFrames(std::size_t count) const {
  if (framePathTimeS.size() != frameGpuMs.size()) return {};
  std::vector<std::size_t> order(frameGpuMs.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(), [&](auto a, auto b) { return frameGpuMs[a] > frameGpuMs[b]; });
  order.resize(std::min(count, order.size()));
  return order;
}

MeasuredMedians RunResult::medians() const {
  MeasuredMedians m;
  for (const auto& p : passes) {
    if (p.culled || p.gpu.n == 0) continue;
    m.passMs[p.name] = p.hasIsolated() ? p.isolated.median : p.gpu.median;
    if (p.hasIsolated()) m.passCost = "isolated";
  }
  if (frameGpu.n > 0) m.frameMs = frameGpu.median;
  if (frameGpu.n > 0) m.frameP99Ms = frameGpu.p99;
  m.width = config.width;
  m.height = config.height;
  m.msaa = config.msaa;
  return m;
}

void summarizeRun(RunResult& run, double unstableSpread) {
  for (auto& pass : run.passes) {
    pass.gpu = summarize(pass.samplesMs);
    pass.unstable = isUnstable(pass.gpu, unstableSpread);
  }
  run.frameGpu = summarize(run.frameGpuMs);
  run.frameCpu = summarize(run.frameCpuMs);
  run.frameSubmit = summarize(run.frameSubmitMs);
  if (!run.nodesRecorded.empty()) {
    run.stats["nodes_recorded"] = summarize(run.nodesRecorded).median;
    run.stats["nodes_reused"] = summarize(run.nodesReused).median;
  }
}

nlohmann::json toJson(const RunResult& run) {
  nlohmann::json passes = nlohmann::json::array();
  for (const auto& p : run.passes) {
    nlohmann::json entry{{"name", p.name}, {"queue", p.queue}, {"culled", p.culled}, {"gpu_ms", toJson(p.gpu)},
                         {"unstable", p.unstable}, {"samples_ms", p.samplesMs}};
    if (const double detectable = detectableFromFrames(p.samplesMs); std::isfinite(detectable))
      entry["detectable_relative"] = detectable;
    if (!p.startMs.empty()) entry["start_ms"] = p.startMs;
    if (p.hasIsolated()) {
      entry["isolated_ms"] = toJson(p.isolated);
      entry["isolated_samples_ms"] = p.isolatedMs;
    }
    if (p.criticalShare >= 0.0) entry["critical_path_share"] = p.criticalShare;
    if (p.nonFinite) entry["non_finite"] = toJson(*p.nonFinite);
    passes.push_back(std::move(entry));
  }
  nlohmann::json knobs = nlohmann::json::object();
  for (const auto& [k, v] : run.config.knobs) knobs[k] = v;
  nlohmann::json stats = nlohmann::json::object();
  for (const auto& [k, v] : run.stats) stats[k] = v;
  nlohmann::json j{
      {"schema", kTimingsSchema},
      {"tool_version", run.toolVersion},
      {"scene", run.scene},
      {"scene_hash", run.sceneHash},
      {"device", {{"name", run.device.name}, {"driver", run.device.driver}, {"type", run.device.type},
                  {"api_version", run.device.apiVersion}, {"timestamp_period_ns", run.device.timestampPeriodNs},
                  {"host_timestamps", run.device.hostTimestamps}}},
      {"config", {{"width", run.config.width}, {"height", run.config.height}, {"msaa", run.config.msaa},
                  {"frames", run.config.frames}, {"warmup", run.config.warmup}, {"knobs", knobs}}},
      {"stats", stats},
      {"passes", passes},
      {"frame_gpu_ms", toJson(run.frameGpu)},
      {"frame_cpu_ms", toJson(run.frameCpu)},
      {"frame_submit_ms", toJson(run.frameSubmit)},
      {"samples", {{"frame_gpu_ms", run.frameGpuMs}, {"frame_cpu_ms", run.frameCpuMs},
                   {"frame_submit_ms", run.frameSubmitMs}, {"nodes_recorded", run.nodesRecorded},
                   {"nodes_reused", run.nodesReused}}},
      {"harness", toJson(run.overhead)},
      {"isolation", {{"frames", run.isolatedFrames}, {"calibration_ms", run.overhead.calibrationMs}}},
      {"wall_clock", toJson(run.wallClock)},
      {"device_state", toJson(run.deviceState)},
  };
  if (run.asyncCompute.queues > 0) j["async_compute"] = toJson(run.asyncCompute);
  if (!run.slowestFrames(1).empty()) {
    j["samples"]["path_time_s"] = run.framePathTimeS;
    j["path"] = pathJson(run);
  }
  j["budget"] = run.budget ? toJson(*run.budget)
                           : nlohmann::json{{"file", ""}, {"verdict", "none"}, {"over", nlohmann::json::array()}};
  const auto* firstBad = run.firstNonFinite();
  j["check_finite"] = {{"enabled", run.checkedFinite},
                       {"checked_passes", run.nonFinite.size()},
                       {"first_bad_pass", firstBad ? nlohmann::json(firstBad->pass) : nlohmann::json(nullptr)}};
  j["golden"] = run.golden ? toJson(*run.golden)
                           : nlohmann::json{{"file", ""}, {"verdict", "none"}, {"metrics", nlohmann::json::object()}};
  if (!run.passesGolden.is_null()) j["passes_golden"] = run.passesGolden;
  return j;
}

std::string toCsv(const RunResult& run) {
  std::string csv = "frame,pass,queue,culled,gpu_ms,frame_gpu_ms,frame_cpu_ms\n";
  for (std::size_t f = 0; f < run.frameGpuMs.size(); ++f) {
    const double cpu = f < run.frameCpuMs.size() ? run.frameCpuMs[f] : 0.0;
    for (const auto& p : run.passes) {
      const double ms = f < p.samplesMs.size() ? p.samplesMs[f] : 0.0;
      csv += fmt::format("{},{},{},{},{:.6f},{:.6f},{:.6f}\n", f, csvField(p.name), p.queue, p.culled ? 1 : 0, ms,
                         run.frameGpuMs[f], cpu);
    }
  }
  return csv;
}

LoadedTimings loadTimings(const std::filesystem::path& path) {
  const nlohmann::json j = readJsonFile(path);
  LoadedTimings t;
  t.file = path.string();
  const double schema = requireNumber(j, "schema", path);
  if (schema != kTimingsSchema) {
    throw InputError(path.string() + ": field 'schema' is " + fmt::format("{}", schema) + ", expected " +
                     std::to_string(kTimingsSchema));
  }
  t.scene = optionalString(j, "scene", "", path);
  if (j.contains("device")) {
    t.deviceName = optionalString(j["device"], "name", "", path, "device");
    t.deviceType = optionalString(j["device"], "type", "", path, "device");
  }
  const auto& passes = requireField(j, "passes", path);
  if (!passes.is_array()) throw InputError(path.string() + ": field 'passes' must be an array");
  for (std::size_t i = 0; i < passes.size(); ++i) {
    const std::string where = "passes[" + std::to_string(i) + "]";
    PassRecord p;
    p.name = requireString(passes[i], "name", path, where);
    p.queue = optionalString(passes[i], "queue", "", path, where);
    p.culled = passes[i].value("culled", false);
    if (!p.culled) {
      if (!passes[i].contains("samples_ms")) {
        throw InputError(path.string() + ": field '" + where + ".samples_ms' is missing (per-frame samples are needed to test significance)");
      }
      p.samplesMs = readSamples(passes[i], "samples_ms", path, where);
      if (passes[i].contains("isolated_samples_ms")) {
        p.isolatedMs = readSamples(passes[i], "isolated_samples_ms", path, where);
        p.isolated = summarize(p.isolatedMs);
      }
    }
    p.gpu = summarize(p.samplesMs);
    t.passes.push_back(std::move(p));
  }
  if (j.contains("samples") && j["samples"].contains("frame_gpu_ms")) {
    t.frameGpuMs = readSamples(j["samples"], "frame_gpu_ms", path, "samples");
    if (j["samples"].contains("path_time_s")) t.framePathTimeS = readSamples(j["samples"], "path_time_s", path, "samples");
  }
  return t;
}

}  // namespace fgb::harness
