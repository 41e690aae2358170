// Schedule invariants: steps, submits, timeline values, waits, and lifetimes.
#include "invariants.hpp"

#include <algorithm>

namespace fgb::graph::test {
namespace {

std::string name(uint32_t node) { return "node " + std::to_string(node); }

Problems checkSteps(const CompiledGraph& compiled) {
  Problems problems;
  if (compiled.steps.size() != compiled.order.size()) return {"steps and order differ in size"};
  std::vector<uint32_t> lastOrderOnQueue(compiled.queueCount, 0);
  std::vector<bool> seenQueue(compiled.queueCount, false);
  for (uint32_t s = 0; s < compiled.steps.size(); ++s) {
    const uint32_t node = compiled.steps[s].node;
    if (node >= compiled.nodes.size() || compiled.nodes[node].culled) return {"step names a bad or culled node"};
    const NodeInfo& info = compiled.nodes[node];
    if (info.step != s) problems.push_back(name(node) + ": NodeInfo::step does not point at its step");
    if (seenQueue[info.queue] && info.orderIndex <= lastOrderOnQueue[info.queue]) {
      problems.push_back(name(node) + ": steps of one queue not in global order");
    }
    seenQueue[info.queue] = true;
    lastOrderOnQueue[info.queue] = info.orderIndex;
  }
  return problems;
}

Problems checkSubmitLayout(const CompiledGraph& compiled) {
  Problems problems;
  if (compiled.submitsPerQueue.size() != compiled.queueCount) return {"submitsPerQueue size != queueCount"};
  std::vector<uint64_t> countOnQueue(compiled.queueCount, 0);
  uint32_t nextStep = 0;
  for (uint32_t i = 0; i < compiled.submits.size(); ++i) {
    const Submit& submit = compiled.submits[i];
    if (submit.queue >= compiled.queueCount) return {"submit on a bad queue"};
    if (i > 0 && compiled.submits[i - 1].queue > submit.queue) problems.push_back("submits not grouped by queue");
    if (submit.firstStep != nextStep || submit.stepCount == 0) problems.push_back("submits do not tile the steps");
    nextStep = submit.firstStep + submit.stepCount;
    if (submit.signalValue != ++countOnQueue[submit.queue]) problems.push_back("signal values not 1, 2, ... per queue");
    for (uint32_t s = submit.firstStep; s < nextStep && s < compiled.steps.size(); ++s) {
      const NodeInfo& info = compiled.nodes[compiled.steps[s].node];
      if (info.queue != submit.queue || info.submit != i) problems.push_back("step in a submit of another queue");
    }
    for (const SemaphoreWait& wait : submit.waits) {
      if (wait.queue >= compiled.queueCount || wait.queue == submit.queue || wait.value == 0 ||
          wait.value > compiled.submitsPerQueue[wait.queue]) {
        problems.push_back("submit " + std::to_string(i) + " waits on a bad (queue, value)");
      }
    }
  }
  if (nextStep != compiled.steps.size()) problems.push_back("submits do not cover every step");
  for (uint32_t q = 0; q < compiled.queueCount; ++q) {
    if (compiled.submitsPerQueue[q] != countOnQueue[q]) problems.push_back("submitsPerQueue wrong");
  }
  return problems;
}

// Thesis placement: a submit ends after every dependency level holding a node that another queue
// waits for, so the signalling node's submit holds nothing of a later level.
Problems checkPlacement(const CompiledGraph& compiled) {
  Problems problems;
  for (const Edge& e : compiled.syncEdges) {
    const NodeInfo& signaller = compiled.nodes[e.from];
    const Submit& submit = compiled.submits[signaller.submit];
    for (uint32_t s = submit.firstStep; s < submit.firstStep + submit.stepCount; ++s) {
      if (compiled.nodes[compiled.steps[s].node].level > signaller.level) {
        problems.push_back(name(e.from) + " signals another queue but its submit continues past its level");
        break;
      }
    }
  }
  return problems;
}

}  // namespace

Problems checkSubmits(const Reference& ref, const CompiledGraph& compiled) {
  Problems problems = checkSteps(compiled);
  if (!problems.empty()) return problems;
  problems = checkSubmitLayout(compiled);
  if (!problems.empty()) return problems;
  if (compiled.queueCount == 1) {
    if (compiled.submits.size() > 1) problems.push_back("Q = 1 needs one submit");
    for (const Submit& s : compiled.submits) {
      if (!s.waits.empty()) problems.push_back("Q = 1 submit with waits");
    }
  }
  const HappensBefore hb(compiled);
  if (!hb.submitsAcyclic()) return {"submit waits form a cycle (deadlock)"};
  for (const RequiredOrder& r : ref.required) {
    if (!hb.ordered(r.before, r.after)) {
      problems.push_back(name(r.before) + " -> " + name(r.after) + " not ordered by queue order or semaphores");
    }
  }
  for (const Edge& e : compiled.syncEdges) {
    if (!hb.ordered(e.from, e.to)) problems.push_back("G* edge not realised by a wait");
  }
  const Problems placement = checkPlacement(compiled);
  problems.insert(problems.end(), placement.begin(), placement.end());
  return problems;
}

Problems checkLifetimes(const GraphModel& model, const CompiledGraph& compiled) {
  Problems problems;
  const uint32_t count = model.resourceCount();
  if (compiled.lifetimes.size() != count || compiled.resourceAlive.size() != count) return {"lifetime arrays sized wrong"};
  std::vector<uint32_t> first(count, kInvalidIndex);
  std::vector<uint32_t> last(count, 0);
  for (const ModelUse& use : model.uses) {
    if (compiled.nodes[use.node].culled) continue;
    const uint32_t position = compiled.nodes[use.node].orderIndex;
    first[use.resource] = std::min(first[use.resource], position);
    last[use.resource] = std::max(last[use.resource], position);
  }
  for (uint32_t r = 0; r < count; ++r) {
    const Lifetime& life = compiled.lifetimes[r];
    const bool used = first[r] != kInvalidIndex;
    const std::string what = "resource '" + model.resourceName[r] + "'";
    if (compiled.resourceAlive[r] != used) problems.push_back(what + ": resourceAlive wrong");
    if (life.used() != used) {
      problems.push_back(what + ": lifetime used() wrong");
    } else if (used && (life.first != first[r] || life.last < last[r] || life.last >= compiled.order.size())) {
      problems.push_back(what + ": lifetime [" + std::to_string(life.first) + ", " + std::to_string(life.last) +
                         "] does not start at the first use " + std::to_string(first[r]) + " and cover the last " +
                         std::to_string(last[r]));
    }
  }
  return problems;
}

}  // namespace fgb::graph::test
