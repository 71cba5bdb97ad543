// The configurations the report compares: the reference and the
// candidates, each a set of fields over the default configuration.
//
// A configuration is written as proto text (what a user would put in a
// config file) and read by the project's own config reader, so an option
// the reader rejects or ignores shows up as a load error, not as a silently
// wrong measurement.
#ifndef ANIMAT_BENCH_ACCURACY_CANDIDATES_H_
#define ANIMAT_BENCH_ACCURACY_CANDIDATES_H_

#include <string>
#include <vector>

#include "common/base/status.h"
#include "common/evaluation/model_config.h"

namespace animat::accuracy {

struct Candidate {
  // Proto enum value names (animat.v1.PhysicsConfig, GrnConfig).
  // "SEMI_IMPLICIT_EULER", "VELOCITY_VERLET", "RK4", "SSPRK3", "RALSTON3".
  std::string integrator;
  int substeps = 1;
  // Sub-steps in a step that starts with a contact near (0: `substeps` in
  // every step; physics.contact_substeps).
  int contact_substeps = 0;
  // physics.contact_near (n) for contact sub-steps; written only with
  // contact_substeps > 0.
  double contact_near = PhysicsParams{}.contact_near;
  // Contact sub-steps within each sub-step, the other forces once
  // (physics.contact_inner_substeps; 0: none).
  int contact_inner_substeps = 0;
  // physics.contact_stiffness (k_c); negative: the model's default, not
  // written. A whole report runs at one k_c, so it is not in the label.
  double contact_stiffness = -1.0;
  std::string drag_update;  // "EXPLICIT", "STABLE".
  std::string precision;    // "DOUBLE", "FLOAT".
  std::string backend;      // "NATIVE", "BULLET".

  // Compact label for plots: integrator letter (E semi-implicit Euler,
  // V velocity Verlet, R RK4, S SSPRK3, L Ralston's third order, B Bullet),
  // sub-steps, "c" and the sub-steps near contacts when they differ,
  // "i" and the contacts' inner sub-steps when they have them, "s" for the
  // stable drag update, "f" for float network arithmetic: "E1", "R4s", "B2f",
  // "V2c4f".
  std::string Label() const;
  // Readable name: "euler ×1, explicit, double" ("bullet euler ×2, ...",
  // "verlet ×2 (×4 within n 0.1 of a contact), explicit, float").
  std::string Name() const;
  // The group a plot colours it by: "semi-implicit Euler", "velocity
  // Verlet", "RK4", "third-order Runge-Kutta", "Bullet".
  std::string Group() const;
  // The fields it sets over the defaults, as proto text of animat.v1.Config.
  // Every field the candidate names is written, precision included, so a
  // change of the defaults does not change the candidate.
  std::string ConfigText() const;
};

// RK4, 16 sub-steps, explicit drag, double, native.
Candidate ReferenceCandidate();
// The default configuration: velocity Verlet, 4 sub-steps, explicit drag,
// float network arithmetic, native ("V4f").
Candidate DefaultCandidate();

// Every native integrator x sub-steps {1, 2, 4} x drag update {explicit,
// stable} x precision {double, float} for Euler, Verlet and RK4; the two
// third-order schemes with sub-steps {1, 2}, explicit drag, both
// precisions; velocity Verlet with 3 sub-steps, and with 1 or 2 sub-steps
// but 4 in steps near a contact, explicit drag, both precisions; velocity
// Verlet with (sub-steps, contact inner sub-steps) (1, 4), (2, 2), (2, 3),
// (2, 4), explicit drag, both precisions; then the
// Bullet backend (semi-implicit Euler, 1 and 2 sub-steps, explicit drag, both
// precisions).
std::vector<Candidate> CandidateSet();

// The index in `set` of the candidate that differs from `c` in one option
// only, for the float-against-double and Bullet-against-native tables: the
// native one of the same precision for a Bullet candidate, the double one
// for a native float one; every other option (integrator, sub-steps,
// contact sub-steps, inner contact sub-steps, drag update) the same. -1
// when `c` is neither or its counterpart is not in `set`.
int Counterpart(const std::vector<Candidate>& set, const Candidate& c);

// The candidates of CandidateSet() with these labels, in the set's order;
// all of them when `labels` is empty. Fails naming a label that is not in
// the set.
Result<std::vector<Candidate>> SelectCandidates(
    const std::vector<std::string>& labels);

// The configuration of `candidate`: the defaults with ConfigText() read by
// ConfigFromProto. Fails with the reader's message if it rejects the text,
// or if a requested field does not survive the round trip to the model's
// structs and back (ConfigToProto): the option is not implemented.
Result<ModelConfig> CandidateConfig(const Candidate& candidate);

}  // namespace animat::accuracy

#endif  // ANIMAT_BENCH_ACCURACY_CANDIDATES_H_
