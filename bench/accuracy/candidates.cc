#include "bench/accuracy/candidates.h"

#include <google/protobuf/util/message_differencer.h>

#include "animat/v1/config.pb.h"
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
  }
  std::string label(1, letter);
  label += std::to_string(substeps);
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
  } else {
    name += "euler";
  }
  name += std::string(" ×") + std::to_string(substeps);
  name += drag_update == "STABLE" ? ", stable" : ", explicit";
  name += precision == "FLOAT" ? ", float" : ", double";
  return name;
}

std::string Candidate::Group() const {
  if (backend == "BULLET") return "Bullet";
  if (integrator == "VELOCITY_VERLET") return "velocity Verlet";
  if (integrator == "RK4") return "RK4";
  return "semi-implicit Euler";
}

std::string Candidate::ConfigText() const {
  std::string text = "physics { integrator: " + integrator +
                     " substeps: " + std::to_string(substeps) +
                     " drag_update: " + drag_update + " backend: " + backend +
                     " }";
  // Always spelled out: the default precision has changed before.
  text += " grn { precision: " + precision + " }";
  return text;
}

Candidate ReferenceCandidate() {
  return Make("RK4", 16, "EXPLICIT", "DOUBLE", "NATIVE");
}

Candidate DefaultCandidate() {
  return Make("RK4", 1, "EXPLICIT", "FLOAT", "NATIVE");
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
  for (int substeps : {1, 2}) {
    for (const char* precision : {"DOUBLE", "FLOAT"}) {
      set.push_back(Make("SEMI_IMPLICIT_EULER", substeps, "EXPLICIT", precision,
                         "BULLET"));
    }
  }
  return set;
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
