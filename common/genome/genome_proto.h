// Conversion between Genome and its protobuf message (animat.v1.Genome).
//
// Thread-safe pure functions.
#ifndef ANIMAT_COMMON_GENOME_GENOME_PROTO_H_
#define ANIMAT_COMMON_GENOME_GENOME_PROTO_H_

#include "animat/v1/genome.pb.h"
#include "common/base/status.h"
#include "common/genome/genome.h"

namespace animat {

// Converts and validates; errors name the element and field
// ("elements[2].channel: an S_IN element needs an input channel ...").
Result<Genome> GenomeFromProto(const v1::Genome& message);

v1::Genome GenomeToProto(const Genome& genome);

// The proto channel of an InputChannel (MATERNAL_0..UNIFORM are 1..4,
// CHEMICAL 11) and of an OutputChannel (DIVIDE..CONTRACT are 5..10).
// Precondition: a valid channel of its kind.
v1::Element::Channel InputChannelToProto(int channel);
v1::Element::Channel OutputChannelToProto(int channel);

}  // namespace animat

#endif  // ANIMAT_COMMON_GENOME_GENOME_PROTO_H_
