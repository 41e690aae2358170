#include "reference.hpp"

#include <algorithm>
#include <map>
#include <utility>

namespace fgb::graph::test {
namespace {

using ChainSlot = std::pair<uint32_t, int>;  // (resource, position)

std::map<ChainSlot, uint32_t> producers(const GraphModel& model) {
  std::map<ChainSlot, uint32_t> producerOf;
  for (const ModelUse& use : model.uses) {
    if (use.writes()) producerOf[{use.resource, use.writePos}] = use.node;
  }
  return producerOf;
}

void addEdge(std::vector<Edge>& edges, uint32_t from, uint32_t to) {
  if (from == to) return;
  const Edge edge{from, to};
  if (std::find(edges.begin(), edges.end(), edge) == edges.end()) edges.push_back(edge);
}

std::vector<Edge> versionEdges(const GraphModel& model) {
  const auto producerOf = producers(model);
  std::vector<Edge> edges;
  for (const ModelUse& use : model.uses) {
    if (use.reads() && use.readPos > 0) addEdge(edges, producerOf.at({use.resource, use.readPos}), use.node);  // RAW
    if (use.writes() && use.writePos > 1) {
      addEdge(edges, producerOf.at({use.resource, use.writePos - 1}), use.node);  // WAW
    }
  }
  for (const ModelUse& reader : model.uses) {  // WAR: reader of k -> producer of k + 1
    if (!reader.reads()) continue;
    const auto next = producerOf.find({reader.resource, reader.readPos + 1});
    if (next != producerOf.end()) addEdge(edges, reader.node, next->second);
  }
  return edges;
}

// Iterative-enough DFS (graphs are small): returns the nodes of the first cycle found.
bool findCycle(uint32_t node, const std::vector<std::vector<uint32_t>>& out, std::vector<int>& state,
               std::vector<uint32_t>& stack, std::vector<uint32_t>& cycle) {
  state[node] = 1;
  stack.push_back(node);
  for (uint32_t next : out[node]) {
    if (state[next] == 1) {
      cycle.assign(std::find(stack.begin(), stack.end(), next), stack.end());
      return true;
    }
    if (state[next] == 0 && findCycle(next, out, state, stack, cycle)) return true;
  }
  stack.pop_back();
  state[node] = 2;
  return false;
}

std::vector<uint32_t> cycleOf(uint32_t nodeCount, const std::vector<Edge>& edges) {
  std::vector<std::vector<uint32_t>> out(nodeCount);
  for (const Edge& e : edges) out[e.from].push_back(e.to);
  std::vector<int> state(nodeCount, 0);
  std::vector<uint32_t> stack;
  std::vector<uint32_t> cycle;
  for (uint32_t n = 0; n < nodeCount; ++n) {
    if (state[n] == 0 && findCycle(n, out, state, stack, cycle)) break;
  }
  return cycle;
}

// Frostbite-style liveness as reverse reachability: outputs are side-effect nodes and writers of
// imported resources; a producer is alive when an alive node reads what it wrote.
std::vector<bool> aliveNodes(const GraphModel& model, bool cull) {
  std::vector<bool> alive(model.nodeCount(), !cull);
  if (!cull) return alive;
  for (uint32_t n = 0; n < model.nodeCount(); ++n) alive[n] = model.sideEffect[n];
  for (const ModelUse& use : model.uses) {
    if (use.writes() && model.imported[use.resource]) alive[use.node] = true;
  }
  const auto producerOf = producers(model);
  for (bool changed = true; changed;) {
    changed = false;
    for (const ModelUse& use : model.uses) {
      if (!alive[use.node] || !use.reads() || use.readPos == 0) continue;
      const uint32_t producer = producerOf.at({use.resource, use.readPos});
      if (!alive[producer]) alive[producer] = changed = true;
    }
  }
  return alive;
}

std::vector<RequiredOrder> requiredOrders(const GraphModel& model, const std::vector<bool>& alive) {
  std::vector<RequiredOrder> required;
  for (const ModelUse& a : model.uses) {
    for (const ModelUse& b : model.uses) {
      if (a.resource != b.resource || a.node == b.node || !alive[a.node] || !alive[b.node]) continue;
      if (!a.writes() && !b.writes()) continue;
      if (chainKey(a) < chainKey(b)) required.push_back({a.node, b.node, a.resource});
    }
  }
  return required;
}

std::vector<uint32_t> longestPathLevels(uint32_t nodeCount, const std::vector<RequiredOrder>& required) {
  std::vector<uint32_t> level(nodeCount, 0);
  // Bellman-Ford style relaxation; converges in at most nodeCount rounds on a DAG.
  for (uint32_t round = 0; round < nodeCount; ++round) {
    bool changed = false;
    for (const RequiredOrder& r : required) {
      if (level[r.after] < level[r.before] + 1) {
        level[r.after] = level[r.before] + 1;
        changed = true;
      }
    }
    if (!changed) break;
  }
  return level;
}

}  // namespace

int chainKey(const ModelUse& use) { return use.writes() ? 2 * use.writePos : 2 * use.readPos + 1; }

Reference computeReference(const GraphModel& model, bool cull) {
  Reference ref;
  ref.declaredEdges = versionEdges(model);
  ref.cycle = cycleOf(model.nodeCount(), ref.declaredEdges);
  if (!ref.cycle.empty()) return ref;
  ref.alive = aliveNodes(model, cull);
  ref.required = requiredOrders(model, ref.alive);
  ref.level = longestPathLevels(model.nodeCount(), ref.required);
  return ref;
}

Reachability::Reachability(uint32_t nodeCount, const std::vector<Edge>& edges)
    : reach_(nodeCount, std::vector<char>(nodeCount, 0)) {
  std::vector<std::vector<uint32_t>> out(nodeCount);
  for (const Edge& e : edges) out[e.from].push_back(e.to);
  for (uint32_t source = 0; source < nodeCount; ++source) {
    std::vector<uint32_t> frontier = out[source];
    while (!frontier.empty()) {
      const uint32_t node = frontier.back();
      frontier.pop_back();
      if (reach_[source][node] != 0) continue;
      reach_[source][node] = 1;
      frontier.insert(frontier.end(), out[node].begin(), out[node].end());
    }
  }
}

}  // namespace fgb::graph::test
