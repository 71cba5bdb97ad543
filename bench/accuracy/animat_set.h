// The fixed set of animats the report measures: genome files stored in
// bench/data/accuracy/ (see its README.md for how they were chosen), so the
// set does not change when the random-genome or evolution code does. Files
// named evolved-*.json hold evolved genomes; every other one a random genome.
// An animat evolved under other model constants (a drag coefficient of its
// run) has them beside its genome in NAME.model.txtpb (animat.v1.Config):
// every configuration evaluates it with them.
#ifndef ANIMAT_BENCH_ACCURACY_ANIMAT_SET_H_
#define ANIMAT_BENCH_ACCURACY_ANIMAT_SET_H_

#include <string>
#include <vector>

#include "common/base/status.h"
#include "common/evaluation/model_config.h"
#include "common/genome/genome.h"

namespace animat::accuracy {

struct Animat {
  std::string name;  // The file name without extension: "seed-01198".
  Genome genome;
  bool evolved = false;  // IsEvolvedName(name).
  // The model constants it was evolved under, over the defaults (proto text
  // of animat.v1.Config; empty: the defaults). They may not name what the
  // report compares: integrator, sub-steps, drag update, backend, contacts,
  // precision.
  std::string model_text;
};

// `config` with the animat's model constants applied (ConfigFromProto
// over it). Fails with the reader's message.
Result<ModelConfig> ForAnimat(const ModelConfig& config, const Animat& animat);

// Whether an animat of this name is an evolved one: "evolved-..." (the
// other files are random genomes, "seed-...").
bool IsEvolvedName(const std::string& name);

// Reads every *.json genome in `dir`, in file-name order, with its
// NAME.model.txtpb if there is one. Fails (naming the file) if one cannot be
// read or is invalid, if a model file names a compared option, or if there
// is no genome.
Result<std::vector<Animat>> LoadAnimatSet(const std::string& dir);

// The --quick subset: the first `random` random and the first `evolved`
// evolved animats of `animats` (fewer if there are fewer), in their order.
std::vector<Animat> QuickSubset(const std::vector<Animat>& animats, int random,
                                int evolved);

}  // namespace animat::accuracy

#endif  // ANIMAT_BENCH_ACCURACY_ANIMAT_SET_H_
