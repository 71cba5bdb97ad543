// The fixed set of animats the report measures: genome files stored in
// bench/data/accuracy/ (see its README.md for how they were chosen), so the
// set does not change when the random-genome code does.
#ifndef ANIMAT_BENCH_ACCURACY_ANIMAT_SET_H_
#define ANIMAT_BENCH_ACCURACY_ANIMAT_SET_H_

#include <string>
#include <vector>

#include "common/base/status.h"
#include "common/genome/genome.h"

namespace animat::accuracy {

struct Animat {
  std::string name;  // The file name without extension: "seed-01198".
  Genome genome;
};

// Reads every *.json genome in `dir`, in file-name order. Fails (naming the
// file) if one cannot be read or is invalid, or if there is none.
Result<std::vector<Animat>> LoadAnimatSet(const std::string& dir);

}  // namespace animat::accuracy

#endif  // ANIMAT_BENCH_ACCURACY_ANIMAT_SET_H_
