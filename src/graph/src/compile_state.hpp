// Internal: state shared by the compiler stages (one file per stage, run in order by compiler.cpp).
#pragma once

#include <fgb/graph/compiler.hpp>

#include <array>
#include <cstdint>
#include <iterator>
#include <vector>

namespace fgb::graph::detail {

using QueueArray = std::array<uint32_t, kQueueClassCount>;

// A std::vector whose storage comes from, and goes back to, a per-thread pool. A frame graph is
// compiled every frame; keeping the compiler's temporary arrays between compiles saves their
// allocation and, for large graphs, the page faults of touching fresh memory (which cost more
// than the compile itself). Only for temporaries: results handed to the caller are plain vectors.
// Each thread keeps what its largest compile needed, in as many buffers as were alive at once.
template <typename T>
class ScratchVector : public std::vector<T> {
 public:
  ScratchVector() {
    auto& pool = pool_();
    if (!pool.empty()) {
      std::vector<T>::swap(pool.back());
      pool.pop_back();
    }
  }
  ScratchVector(size_t count, const T& value) : ScratchVector() { this->assign(count, value); }
  template <std::input_iterator It>
  ScratchVector(It first, It last) : ScratchVector() {
    this->assign(first, last);
  }
  ScratchVector(const ScratchVector&) = delete;
  ScratchVector& operator=(const ScratchVector&) = delete;
  ScratchVector(ScratchVector&& other) noexcept : std::vector<T>(std::move(other)) {}
  ScratchVector& operator=(ScratchVector&& other) noexcept {
    std::vector<T>::swap(other);
    return *this;
  }
  ~ScratchVector() {
    if (this->capacity() == 0) return;
    this->clear();
    try {
      pool_().push_back(std::move(static_cast<std::vector<T>&>(*this)));
    } catch (...) {  // out of memory growing the pool: just free this buffer
    }
  }

 private:
  static std::vector<std::vector<T>>& pool_() {
    thread_local std::vector<std::vector<T>> pool;
    return pool;
  }
};

// Compressed adjacency: the neighbours of node i are items[start[i] .. start[i+1]).
struct Adjacency {
  ScratchVector<uint32_t> start;
  ScratchVector<uint32_t> items;
  [[nodiscard]] uint32_t begin(uint32_t node) const { return start[node]; }
  [[nodiscard]] uint32_t end(uint32_t node) const { return start[node + 1]; }
};

// A node's use of one resource; a node that uses a resource twice (e.g. read + resolve) gets one
// combined use.
struct MergedUse {
  uint32_t node = kInvalidIndex;
  StageMask stages = kStageNone;
  AccessMask access = kAccessNone;
  Layout layout = Layout::Undefined;
  bool reads = false;
  bool writes = false;
};

// Per resource, its uses by alive nodes in execution order: uses[start[r] .. end[r]).
struct ResourceUses {
  ScratchVector<uint32_t> start;
  ScratchVector<uint32_t> end;
  ScratchVector<MergedUse> uses;
};

struct CompileState {
  CompileState(const FrameGraph& g, const CompileOptions& o, CompiledGraph& c)
      : graph(g), options(o), out(c), nodeCount(static_cast<uint32_t>(g.nodes().size())) {}

  const FrameGraph& graph;
  const CompileOptions& options;
  CompiledGraph& out;
  uint32_t nodeCount;

  ScratchVector<uint8_t> alive;        // per node
  bool anyCulled = false;
  ScratchVector<uint32_t> queueOf;     // per node: queue index
  Adjacency predecessors;            // per node: alive nodes it depends on (deduplicated)
  ScratchVector<uint32_t> sigma;       // per node: SSIS re-index σ(u) = order position + queue·V + 1
  ScratchVector<QueueArray> known;     // per node: per queue, the largest σ the node is ordered after
  ScratchVector<uint32_t> lastSigmaOnQueue;    // per resource × queue: largest σ of a user on that queue
  ScratchVector<StageMask> stagesOnQueue;      // per resource × queue: stages used on that queue
  ScratchVector<uint32_t> firstUser;           // per resource: node of the first alive use
  ResourceUses resourceUses;                 // built with the lifetimes, walked again by the barrier plan
};

// Readers of each version among the nodes selected by `alive`, in declaration order.
Adjacency collectVersionReaders(const FrameGraph& graph, const std::vector<uint8_t>& alive);

// Stages, in pipeline order.
void assignQueues(CompileState& state);
void detectCycles(const CompileState& state);          // over every declared node
// Throws GraphError naming a cycle among `left` (nodes Kahn's algorithm could not order).
[[noreturn]] void reportCycle(const CompileState& state, const Adjacency& preds, const std::vector<uint32_t>& left);
void cullNodes(CompileState& state);                    // fills alive + NodeInfo reasons
void buildDependencies(CompileState& state);            // RAW/WAR/WAW edges among alive nodes
void sortByLevel(CompileState& state);                  // levels + order
void pruneCrossQueueEdges(CompileState& state);         // SSIS → syncEdges, known
void placeSubmits(CompileState& state);                 // steps + submits + waits
void resolveResources(CompileState& state);             // dependent fields, requirements
void computeLifetimes(CompileState& state);             // also fills resourceUses
void placeTransients(CompileState& state);              // aliasing plan
void planBarriers(CompileState& state);

// Edges implied by resource versions among `alive` nodes, appended to `edges`.
inline void appendVersionEdges(const FrameGraph& graph, const std::vector<uint8_t>& alive,
                               const std::vector<uint32_t>& queueOf, const Adjacency& readers,
                               ScratchVector<Edge>& edges);

}  // namespace fgb::graph::detail

#include "version_edges.inl"
