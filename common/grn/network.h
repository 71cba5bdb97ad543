// The gene regulatory network a genome encodes (docs/model.md §2).
//
// A Network is immutable after Build and may be shared by any number of
// threads. It holds the nodes in the model's node order, the binding graph used
// for the viability check, and the weights the dynamics (GrnBatch) use.
#ifndef ANIMAT_COMMON_GRN_NETWORK_H_
#define ANIMAT_COMMON_GRN_NETWORK_H_

#include <array>
#include <span>
#include <string>
#include <vector>

#include "common/genome/genome.h"
#include "common/grn/grn_params.h"

namespace animat {

enum class NodeKind : uint8_t { kUnit, kInput, kOutput };

struct Node {
  NodeKind kind = NodeKind::kUnit;
  // Genome index of the node's first element (its first P, or its S).
  int first_element = 0;
  // InputChannel of an input node, OutputChannel of an output node, else -1.
  int channel = -1;
  // Genome indices of its regulatory regions: a unit's P elements, an output
  // node's own S_OUT; none for an input node.
  std::vector<int> regions;
  // Genome indices of the factors it makes that can bind: a unit's G
  // elements, an input node's own S_IN; none for an output node.
  std::vector<int> factors;
  bool makes_internal = false;   // Some G_INTERNAL factor.
  bool makes_morphogen = false;  // Some G_MORPHOGEN factor.
  int morphogen = -1;  // Index among the morphogen-making nodes, or -1.
};

// Where the concentration multiplying one row of weights comes from.
enum class SourceKind : uint8_t {
  kInput,      // An input node's value.
  kLevel,      // A unit's level L (its G_INTERNAL factors).
  kMorphogen,  // A unit's morphogen signal M (its G_MORPHOGEN factors).
};

struct Source {
  SourceKind kind;
  int node;
};

struct Viability {
  bool viable = false;
  std::string reason;  // Why not, when !viable.
};

// w(f, r) of model §2.2: sign(f) * sign(r) * weight_max * exp(-d /
// decay_length) when d < cutoff, else 0, with d = sqrt(dx*dx + dy*dy).
double Affinity(const Element& factor, const Element& region,
                const GrnParams& params);
// Whether factor f binds region r at all (d < cutoff), whatever the sign.
bool Binds(const Element& factor, const Element& region,
           const GrnParams& params);

class Network {
 public:
  // Any genome is accepted (even an empty one); validity is the caller's.
  static Network Build(const Genome& genome, const GrnParams& params);

  const std::vector<Node>& nodes() const { return nodes_; }
  int node_count() const { return static_cast<int>(nodes_.size()); }

  // Node indices of the morphogen-making units, in node order; a node's
  // `morphogen` field is its position here.
  const std::vector<int>& morphogen_nodes() const { return morphogen_nodes_; }
  int morphogen_count() const {
    return static_cast<int>(morphogen_nodes_.size());
  }
  // Input nodes of each input channel and output nodes of each output
  // channel (several elements of one channel are several nodes).
  const std::vector<int>& input_nodes(int channel) const {
    return input_nodes_[channel];
  }
  const std::vector<int>& output_nodes(int channel) const {
    return output_nodes_[channel];
  }

  // The dynamics as a sparse weight matrix. Targets are the units and
  // output nodes, in node order. Sources are the input nodes of the
  // channels other than CHEMICAL, then the CHEMICAL input nodes, then the
  // units making internal factors, then the units making morphogens, each
  // group in node order; a source whose weights are all zero is left out.
  // Source s has weights weight_value[k] onto targets weight_target[k] for
  // k in [row_begin[s], row_begin[s + 1]), targets increasing. Each weight
  // is the sum over the target's regions r (genome order) of the sum over
  // the source's factors f of that kind (genome order) of w(f, r).
  const std::vector<Source>& sources() const { return sources_; }
  const std::vector<int>& targets() const { return targets_; }
  const std::vector<int>& row_begin() const { return row_begin_; }
  const std::vector<int>& weight_target() const { return weight_target_; }
  const std::vector<double>& weight_value() const { return weight_value_; }
  // Number of leading sources that are input nodes.
  int input_source_count() const { return input_source_count_; }
  // Number of leading sources that are input nodes of channels other than
  // CHEMICAL (the inputs that stay constant during motion).
  int static_input_source_count() const { return static_input_source_count_; }
  // The total weight from source node `from` (as `kind`) onto node `to`,
  // 0 when none (for tests and tools; O(row length)).
  double Weight(SourceKind kind, int from, int to) const;

  // The binding graph: successors()[s] lists, in increasing order, the
  // nodes u with an element pair of s's factors binding u's regions.
  const std::vector<std::vector<int>>& successors() const {
    return successors_;
  }

  // model §2.5: a path from some input to a DIVIDE output, and one from some
  // input to an EXPAND or CONTRACT output.
  Viability CheckViability() const;

  // What an evaluation reads of the network, as bytes: the nodes' kinds,
  // channels and factor kinds, which of them can influence an output
  // (NodesReaching), the channel and morphogen lists, and, among the nodes
  // that can, the weights (their bits) and the binding graph. Left out:
  // where the nodes' elements sit in the genome, and the weights and
  // bindings of nodes that influence no output, which are never computed.
  // Two genomes whose networks have equal keys differ only where nothing
  // reads them (an element that binds nothing or only feeds such nodes,
  // elements moved), so, under one model configuration, they evaluate to
  // the same result bit for bit (EvaluationKey in
  // common/evaluation/evaluator.h).
  std::string Key() const;

  // Which nodes can influence an output node of one of `channels`: the
  // output nodes themselves and every node with a path to one in the
  // binding graph. Indexed by node.
  std::vector<bool> NodesReaching(
      std::span<const OutputChannel> channels) const;

 private:
  std::vector<Node> nodes_;
  std::vector<int> morphogen_nodes_;
  std::array<std::vector<int>, kInputChannels> input_nodes_;
  std::array<std::vector<int>, kOutputChannels> output_nodes_;
  std::vector<Source> sources_;
  std::vector<int> targets_;
  std::vector<int> row_begin_;
  std::vector<int> weight_target_;
  std::vector<double> weight_value_;
  int input_source_count_ = 0;
  int static_input_source_count_ = 0;
  std::vector<std::vector<int>> successors_;
};

}  // namespace animat

#endif  // ANIMAT_COMMON_GRN_NETWORK_H_
