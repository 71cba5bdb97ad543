// The one-line progress report of a generation, shared by animat-master
// and animat evolve.
#ifndef ANIMAT_MASTER_PROGRESS_H_
#define ANIMAT_MASTER_PROGRESS_H_

#include <string>

#include "master/run/evolution_run.h"

namespace animat {

// "generation 12/100: best 0.4321 (id 3456), mean 0.1234, median 0.0987,
//  300 ok, 0 failed | 57.3 evaluations/s | ETA 00:12:34"
std::string FormatProgress(const GenerationReport& report);

}  // namespace animat

#endif  // ANIMAT_MASTER_PROGRESS_H_
