#include "bench/accuracy/candidates.h"

#include <google/protobuf/util/message_differencer.h>

#include <utility>

#include "animat/v1/config.pb.h"
#include "common/base/text.h"
#include "common/io/proto_file.h"

namespace animat::accuracy {
namespace {

Candidate Make(std::string integrator, int substeps, std::string drag,
               std::string precision, std::string backend) {
  Candidate c;
  c.integrator = std::move(integrator);
  c.substeps = substeps;
  c.drag_update = std::move(drag);
  c.precision = std::move(precision);
  c.backend = std::move(backend);
  return c;
}

}  // namespace

std::string Candidate::Label() const {
  char letter = 'E';
  if (backend == "BULLET") {
    letter = 'B';
  } else if (integrator == "VELOCITY_VERLET") {
    letter = 'V';
  } else if (integrator == "RK4") {
    letter = 'R';
  } else if (integrator == "SSPRK3") {
    letter = 'S';
  } else if (integrator == "RALSTON3") {
    letter = 'L';
  }
  std::string label(1, letter);
  label += std::to_string(substeps);
  if (contact_substeps > 0) {
    label += 'c';
    label += std::to_string(contact_substeps);
  }
  if (contact_inner_substeps > 0) {
    label += 'i';
    label += std::to_string(contact_inner_substeps);
  }
  if (drag_update == "STABLE") label += 's';
  if (precision == "FLOAT") label += 'f';
  return label;
}

std::string Candidate::Name() const {
  std::string name = backend == "BULLET" ? "bullet " : "";
  if (integrator == "VELOCITY_VERLET") {
    name += "verlet";
  } else if (integrator == "RK4") {
    name += "rk4";
  } else if (integrator == "SSPRK3") {
    name += "ssprk3";
  } else if (integrator == "RALSTON3") {
    name += "ralston3";
  } else {
    name += "euler";
  }
  name += std::string(" ×") + std::to_string(substeps);
  if (contact_substeps > 0) {
    name += " (×" + std::to_string(contact_substeps) + " within n " +
            ShortestDouble(contact_near) + " of a contact)";
  }
  if (contact_inner_substeps > 0) {
    name += " (contacts ×" + std::to_string(contact_inner_substeps) +
            " within each)";
  }
  name += drag_update == "STABLE" ? ", stable" : ", explicit";
  name += precision == "FLOAT" ? ", float" : ", double";
  return name;
}

std::string Candidate::Group() const {
  if (backend == "BULLET") return "Bullet";
  if (integrator == "VELOCITY_VERLET") return "velocity Verlet";
  if (integrator == "RK4") return "RK4";
  if (integrator == "SSPRK3" || integrator == "RALSTON3") {
    return "third-order Runge-Kutta";
  }
  return "semi-implicit Euler";
}

std::string Candidate::ConfigText() const {
  std::string text =
      "physics { integrator: " + integrator +
      " substeps: " + std::to_string(substeps) +
      " contact_substeps: " + std::to_string(contact_substeps) +
      " contact_inner_substeps: " + std::to_string(contact_inner_substeps) +
      " drag_update: " + drag_update + " backend: " + backend;
  if (contact_substeps > 0) {
    text += " contact_near: " + ShortestDouble(contact_near);
  }
  if (contact_stiffness >= 0.0) {
    text += " contact_stiffness: " + ShortestDouble(contact_stiffness);
  }
  text += " }";
  // Always spelled out: the default precision has changed before.
  text += " grn { precision: " + precision + " }";
  return text;
}

Candidate ReferenceCandidate() {
  return Make("RK4", 16, "EXPLICIT", "DOUBLE", "NATIVE");
}

Candidate DefaultCandidate() {
  return Make("VELOCITY_VERLET", 4, "EXPLICIT", "FLOAT", "NATIVE");
}

std::vector<Candidate> CandidateSet() {
  std::vector<Candidate> set;
  for (const char* integrator :
       {"SEMI_IMPLICIT_EULER", "VELOCITY_VERLET", "RK4"}) {
    for (int substeps : {1, 2, 4}) {
      for (const char* drag : {"EXPLICIT", "STABLE"}) {
        for (const char* precision : {"DOUBLE", "FLOAT"}) {
          set.push_back(Make(integrator, substeps, drag, precision, "NATIVE"));
        }
      }
    }
  }
  // Velocity Verlet with three sub-steps, explicit drag: between 2 and 4,
  // where stiff contacts put the cheapest that meets the rule.
  for (const char* precision : {"DOUBLE", "FLOAT"}) {
    set.push_back(Make("VELOCITY_VERLET", 3, "EXPLICIT", precision, "NATIVE"));
  }
  // Velocity Verlet with 1 or 2 sub-steps, but 3 or 4 in a step that
  // starts with a contact near: the fine steps stiff contacts need only
  // where they act.
  for (const auto& [substeps, near] : {std::pair{1, 4}, {2, 3}, {2, 4}}) {
    for (const char* precision : {"DOUBLE", "FLOAT"}) {
      Candidate c =
          Make("VELOCITY_VERLET", substeps, "EXPLICIT", precision, "NATIVE");
      c.contact_substeps = near;
      set.push_back(c);
    }
  }
  // Velocity Verlet with 1 or 2 sub-steps for every force but contacts,
  // which take 2 to 4 inner sub-steps within each (multiple time
  // stepping): the fine steps stiff contacts need, only for them.
  for (const auto& [substeps, inner] :
       {std::pair{1, 4}, {2, 2}, {2, 3}, {2, 4}}) {
    for (const char* precision : {"DOUBLE", "FLOAT"}) {
      Candidate c =
          Make("VELOCITY_VERLET", substeps, "EXPLICIT", precision, "NATIVE");
      c.contact_inner_substeps = inner;
      set.push_back(c);
    }
  }
  // The third-order schemes with explicit drag only: the stable drag
  // update's splitting is at most second order (docs/accuracy.md).
  for (const char* integrator : {"SSPRK3", "RALSTON3"}) {
    for (int substeps : {1, 2}) {
      for (const char* precision : {"DOUBLE", "FLOAT"}) {
        set.push_back(
            Make(integrator, substeps, "EXPLICIT", precision, "NATIVE"));
      }
    }
  }
  for (int substeps : {1, 2}) {
    for (const char* precision : {"DOUBLE", "FLOAT"}) {
      set.push_back(Make("SEMI_IMPLICIT_EULER", substeps, "EXPLICIT", precision,
                         "BULLET"));
    }
  }
  return set;
}

int Counterpart(const std::vector<Candidate>& set, const Candidate& c) {
  if (c.backend != "BULLET" && c.precision != "FLOAT") return -1;
  for (size_t i = 0; i < set.size(); ++i) {
    const Candidate& o = set[i];
    const bool other_options =
        c.backend == "BULLET"
            ? o.backend == "NATIVE" && o.precision == c.precision
            : o.backend == c.backend && o.precision == "DOUBLE";
    if (other_options && o.integrator == c.integrator &&
        o.substeps == c.substeps && o.contact_substeps == c.contact_substeps &&
        o.contact_inner_substeps == c.contact_inner_substeps &&
        o.drag_update == c.drag_update) {
      return static_cast<int>(i);
    }
  }
  return -1;
}

Result<std::vector<Candidate>> SelectCandidates(
    const std::vector<std::string>& labels) {
  const std::vector<Candidate> set = CandidateSet();
  if (labels.empty()) return set;
  for (const std::string& label : labels) {
    bool known = false;
    for (const Candidate& c : set) known = known || c.Label() == label;
    if (!known) {
      return Status::InvalidArgument("no candidate labelled \"" + label +
                                     "\" (labels: E1, V2f, R1f, S1f, ...)");
    }
  }
  std::vector<Candidate> selected;
  for (const Candidate& c : set) {
    for (const std::string& label : labels) {
      if (c.Label() == label) {
        selected.push_back(c);
        break;
      }
    }
  }
  return selected;
}

Result<ModelConfig> CandidateConfig(const Candidate& candidate) {
  v1::Config requested;
  Status status =
      ParseProto(candidate.ConfigText(), ProtoFormat::kText, &requested);
  if (!status.ok()) return status.WithPrefix("config text");
  ModelConfig config;
  status = ConfigFromProto(requested, &config);
  if (!status.ok()) return status;

  // Every requested field must read back as requested.
  const v1::Config applied = ConfigToProto(config);
  v1::Config expected = applied;
  expected.MergeFrom(requested);
  google::protobuf::util::MessageDifferencer differencer;
  std::string differences;
  differencer.ReportDifferencesToString(&differences);
  if (!differencer.Compare(applied, expected)) {
    while (!differences.empty() && differences.back() == '\n') {
      differences.pop_back();
    }
    return Status::InvalidArgument(
        "requested but not applied by the config reader (not implemented?): " +
        differences);
  }
  return config;
}

}  // namespace animat::accuracy
