// Hand-made genomes for tests: one short function per element type.
#ifndef ANIMAT_TESTS_GENOME_BUILDER_H_
#define ANIMAT_TESTS_GENOME_BUILDER_H_

#include <initializer_list>

#include "common/genome/genome.h"

namespace animat::testing {

inline Element MakeElement(ElementType type, int sign, double x, double y,
                           int channel = -1) {
  Element e;
  e.type = type;
  e.sign = sign;
  e.x = x;
  e.y = y;
  e.channel = channel;
  return e;
}
inline Element P(double x, double y, int sign = 1) {
  return MakeElement(ElementType::kP, sign, x, y);
}
inline Element GInt(double x, double y, int sign = 1) {
  return MakeElement(ElementType::kGInternal, sign, x, y);
}
inline Element GMor(double x, double y, int sign = 1) {
  return MakeElement(ElementType::kGMorphogen, sign, x, y);
}
inline Element In(InputChannel channel, double x, double y, int sign = 1) {
  return MakeElement(ElementType::kSIn, sign, x, y, static_cast<int>(channel));
}
inline Element Out(OutputChannel channel, double x, double y, int sign = 1) {
  return MakeElement(ElementType::kSOut, sign, x, y, static_cast<int>(channel));
}
inline Genome MakeGenome(std::initializer_list<Element> elements) {
  Genome genome;
  genome.elements = elements;
  return genome;
}

}  // namespace animat::testing

#endif  // ANIMAT_TESTS_GENOME_BUILDER_H_
