#include "common/grn/network.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>

#include "common/base/fast_math.h"

namespace animat {
namespace {

double Distance(const Element& a, const Element& b) {
  const double dx = a.x - b.x;
  const double dy = a.y - b.y;
  return std::sqrt(dx * dx + dy * dy);
}

// docs/model.md §2.3: G factors bind P and S_OUT regions; S_IN factors bind
// P only.
bool Compatible(const Element& factor, const Element& region) {
  if (factor.IsG()) return true;
  return factor.type == ElementType::kSIn && region.type == ElementType::kP;
}

struct Row {
  SourceKind kind;
  int node;
  std::vector<int> targets;
  std::vector<double> values;
};

}  // namespace

double Affinity(const Element& factor, const Element& region,
                const GrnParams& params) {
  const double d = Distance(factor, region);
  if (!(d < params.cutoff)) return 0.0;
  return static_cast<double>(factor.sign * region.sign) * params.weight_max *
         Exp(-d / params.decay_length);
}

bool Binds(const Element& factor, const Element& region,
           const GrnParams& params) {
  return Distance(factor, region) < params.cutoff;
}

namespace {

// The genome's elements parsed into nodes (model §2.1): a run of P
// followed by a run of G is a unit; an input or output element is a node
// of its own; a P run with no G after it, and a G run with no P before it,
// make nothing.
std::vector<Node> ParseNodes(const std::vector<Element>& el) {
  std::vector<Node> nodes;
  const int n = static_cast<int>(el.size());
  int i = 0;
  while (i < n) {
    const ElementType type = el[i].type;
    if (type == ElementType::kP) {
      int j = i;
      while (j < n && el[j].type == ElementType::kP) ++j;
      int k = j;
      while (k < n && el[k].IsG()) ++k;
      if (k > j) {
        Node node;
        node.kind = NodeKind::kUnit;
        node.first_element = i;
        for (int p = i; p < j; ++p) node.regions.push_back(p);
        for (int g = j; g < k; ++g) {
          node.factors.push_back(g);
          if (el[g].type == ElementType::kGInternal) node.makes_internal = true;
          if (el[g].type == ElementType::kGMorphogen) {
            node.makes_morphogen = true;
          }
        }
        nodes.push_back(std::move(node));
      }
      i = k;  // A P run with no G after it is ignored.
    } else if (el[i].IsG()) {
      while (i < n && el[i].IsG()) ++i;  // G run with no P before it.
    } else {
      Node node;
      node.first_element = i;
      node.channel = el[i].channel;
      if (type == ElementType::kSIn) {
        node.kind = NodeKind::kInput;
        node.factors.push_back(i);
      } else {
        node.kind = NodeKind::kOutput;
        node.regions.push_back(i);
      }
      nodes.push_back(std::move(node));
      ++i;
    }
  }
  return nodes;
}

// One source node's weights onto every target (indices into `targets`),
// by the kind of its binding factors, and the nodes it binds.
struct SourceRows {
  Row input, level, morphogen;
  std::vector<int> successors;
};

SourceRows RowsOf(int s, const std::vector<Node>& nodes,
                  const std::vector<int>& targets,
                  const std::vector<Element>& el, const GrnParams& params) {
  const Node& source = nodes[s];
  SourceRows rows{{SourceKind::kInput, s, {}, {}},
                  {SourceKind::kLevel, s, {}, {}},
                  {SourceKind::kMorphogen, s, {}, {}},
                  {}};
  for (size_t t = 0; t < targets.size(); ++t) {
    const int u = targets[t];
    bool bound = false;
    double w_input = 0.0, w_level = 0.0, w_morphogen = 0.0;
    for (int r : nodes[u].regions) {
      for (int f : source.factors) {
        if (!Compatible(el[f], el[r]) || !Binds(el[f], el[r], params)) {
          continue;
        }
        bound = true;
        const double w = Affinity(el[f], el[r], params);
        switch (el[f].type) {
          case ElementType::kSIn:
            w_input += w;
            break;
          case ElementType::kGInternal:
            w_level += w;
            break;
          default:
            w_morphogen += w;
            break;
        }
      }
    }
    if (bound) rows.successors.push_back(u);
    const int target = static_cast<int>(t);
    for (auto [row, w] :
         {std::pair{&rows.input, w_input}, std::pair{&rows.level, w_level},
          std::pair{&rows.morphogen, w_morphogen}}) {
      if (w == 0.0) continue;
      row->targets.push_back(target);
      row->values.push_back(w);
    }
  }
  return rows;
}

}  // namespace

Network Network::Build(const Genome& genome, const GrnParams& params) {
  Network net;
  const std::vector<Element>& el = genome.elements;
  net.nodes_ = ParseNodes(el);

  const int nodes = net.node_count();
  for (int v = 0; v < nodes; ++v) {
    Node& node = net.nodes_[v];
    if (node.makes_morphogen) {
      node.morphogen = static_cast<int>(net.morphogen_nodes_.size());
      net.morphogen_nodes_.push_back(v);
    }
    if (node.kind == NodeKind::kInput)
      net.input_nodes_[node.channel].push_back(v);
    if (node.kind == NodeKind::kOutput) {
      net.output_nodes_[node.channel].push_back(v);
    }
    if (node.kind != NodeKind::kInput) net.targets_.push_back(v);
  }

  // Weights and the binding graph, one source node at a time.
  std::vector<Row> input_rows, chemical_rows, level_rows, morphogen_rows;
  net.successors_.assign(nodes, {});
  for (int s = 0; s < nodes; ++s) {
    const Node& source = net.nodes_[s];
    if (source.factors.empty()) continue;
    SourceRows rows = RowsOf(s, net.nodes_, net.targets_, el, params);
    net.successors_[s] = std::move(rows.successors);
    if (!rows.input.targets.empty()) {
      (source.channel == static_cast<int>(InputChannel::kChemical)
           ? chemical_rows
           : input_rows)
          .push_back(std::move(rows.input));
    }
    if (!rows.level.targets.empty())
      level_rows.push_back(std::move(rows.level));
    if (!rows.morphogen.targets.empty()) {
      morphogen_rows.push_back(std::move(rows.morphogen));
    }
  }

  net.row_begin_.push_back(0);
  for (std::vector<Row>* group :
       {&input_rows, &chemical_rows, &level_rows, &morphogen_rows}) {
    for (Row& row : *group) {
      net.sources_.push_back({row.kind, row.node});
      net.weight_target_.insert(net.weight_target_.end(), row.targets.begin(),
                                row.targets.end());
      net.weight_value_.insert(net.weight_value_.end(), row.values.begin(),
                               row.values.end());
      net.row_begin_.push_back(static_cast<int>(net.weight_target_.size()));
    }
  }
  net.static_input_source_count_ = static_cast<int>(input_rows.size());
  net.input_source_count_ =
      static_cast<int>(input_rows.size() + chemical_rows.size());
  return net;
}

namespace {

template <typename T>
void Append(std::string* out, T value) {
  out->append(reinterpret_cast<const char*>(&value), sizeof(value));
}

void AppendInts(std::string* out, const std::vector<int>& values) {
  Append<uint64_t>(out, values.size());
  for (int v : values) Append<int32_t>(out, v);
}

}  // namespace

std::string Network::Key() const {
  // What no evaluation computes is left out: a node that cannot influence
  // any output is never updated (GrnBatch::Restrict; its level stays 0),
  // so neither its own weights nor the weights onto it are read, and no
  // path from an input to an output passes through it (CheckViability,
  // NodesReaching of any outputs).
  const std::vector<bool> needed = NodesReaching(kAllOutputChannels);
  std::string key;
  Append<uint64_t>(&key, nodes_.size());
  for (size_t v = 0; v < nodes_.size(); ++v) {
    const Node& n = nodes_[v];
    Append<uint8_t>(&key, static_cast<uint8_t>(n.kind));
    Append<int32_t>(&key, n.channel);
    Append<uint8_t>(&key, n.makes_internal);
    Append<uint8_t>(&key, n.makes_morphogen);
    Append<int32_t>(&key, n.morphogen);
    Append<uint8_t>(&key, n.regions.empty());
    Append<uint8_t>(&key, n.factors.empty());
    Append<uint8_t>(&key, needed[v]);
  }
  AppendInts(&key, morphogen_nodes_);
  for (const std::vector<int>& channel : input_nodes_)
    AppendInts(&key, channel);
  for (const std::vector<int>& channel : output_nodes_) {
    AppendInts(&key, channel);
  }
  AppendInts(&key, targets_);
  // The needed sources in order, each with its group and its weights onto
  // needed targets (their bits), as GrnBatch::Restrict keeps them.
  for (size_t s = 0; s < sources_.size(); ++s) {
    if (!needed[sources_[s].node]) continue;
    const int index = static_cast<int>(s);
    Append<uint8_t>(&key, static_cast<uint8_t>(sources_[s].kind));
    Append<int32_t>(&key, sources_[s].node);
    Append<uint8_t>(&key, index < static_input_source_count_);
    Append<uint8_t>(&key, index < input_source_count_);
    for (int k = row_begin_[s]; k < row_begin_[s + 1]; ++k) {
      const int t = weight_target_[k];
      if (!needed[targets_[t]]) continue;
      Append<int32_t>(&key, t);
      Append<double>(&key, weight_value_[k]);
    }
    Append<int32_t>(&key, -1);  // The row's end.
  }
  // The binding graph among needed nodes.
  for (size_t v = 0; v < successors_.size(); ++v) {
    if (!needed[v]) continue;
    Append<int32_t>(&key, static_cast<int32_t>(v));
    for (int u : successors_[v]) {
      if (needed[u]) Append<int32_t>(&key, u);
    }
    Append<int32_t>(&key, -1);
  }
  return key;
}

double Network::Weight(SourceKind kind, int from, int to) const {
  for (size_t s = 0; s < sources_.size(); ++s) {
    if (sources_[s].kind != kind || sources_[s].node != from) continue;
    for (int k = row_begin_[s]; k < row_begin_[s + 1]; ++k) {
      if (targets_[weight_target_[k]] == to) return weight_value_[k];
    }
  }
  return 0.0;
}

std::vector<bool> Network::NodesReaching(
    std::span<const OutputChannel> channels) const {
  // Reverse reachability: predecessors of each node.
  std::vector<std::vector<int>> predecessors(nodes_.size());
  for (size_t s = 0; s < successors_.size(); ++s) {
    for (int u : successors_[s]) predecessors[u].push_back(static_cast<int>(s));
  }
  std::vector<bool> reaches(nodes_.size(), false);
  std::vector<int> stack;
  for (OutputChannel channel : channels) {
    for (int v : output_nodes_[static_cast<int>(channel)]) {
      if (!reaches[v]) {
        reaches[v] = true;
        stack.push_back(v);
      }
    }
  }
  while (!stack.empty()) {
    const int v = stack.back();
    stack.pop_back();
    for (int p : predecessors[v]) {
      if (!reaches[p]) {
        reaches[p] = true;
        stack.push_back(p);
      }
    }
  }
  return reaches;
}

Viability Network::CheckViability() const {
  std::vector<bool> reached(nodes_.size(), false);
  std::vector<int> stack;
  for (int c = 0; c < kInputChannels; ++c) {
    for (int v : input_nodes_[c]) {
      reached[v] = true;
      stack.push_back(v);
    }
  }
  while (!stack.empty()) {
    const int v = stack.back();
    stack.pop_back();
    for (int u : successors_[v]) {
      if (!reached[u]) {
        reached[u] = true;
        stack.push_back(u);
      }
    }
  }
  auto any_reached = [&](int channel) {
    for (int v : output_nodes_[channel]) {
      if (reached[v]) return true;
    }
    return false;
  };
  const int divide = static_cast<int>(OutputChannel::kDivide);
  const int expand = static_cast<int>(OutputChannel::kExpand);
  const int contract = static_cast<int>(OutputChannel::kContract);
  Viability result;
  if (output_nodes_[divide].empty()) {
    result.reason = "the network has no DIVIDE output";
  } else if (!any_reached(divide)) {
    result.reason = "no path from an input to a DIVIDE output";
  } else if (output_nodes_[expand].empty() && output_nodes_[contract].empty()) {
    result.reason = "the network has no EXPAND or CONTRACT output";
  } else if (!any_reached(expand) && !any_reached(contract)) {
    result.reason = "no path from an input to an EXPAND or CONTRACT output";
  } else {
    result.viable = true;
  }
  return result;
}

}  // namespace animat
