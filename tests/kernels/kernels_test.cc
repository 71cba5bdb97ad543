// Every instruction-set path of the kernels gives the baseline's bits:
// kernel by kernel on random and extreme inputs, and for whole evaluations.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <limits>
#include <string>
#include <vector>

#include "common/base/fast_math.h"
#include "common/base/rng.h"
#include "common/evaluation/evaluator.h"
#include "common/genome/genome_proto.h"
#include "common/io/proto_file.h"
#include "common/kernels/isa.h"
#include "common/kernels/kernels.h"
#include "tests/test_util.h"

namespace animat {
namespace {

// Restores the path in use when it goes out of scope.
class IsaGuard {
 public:
  IsaGuard() : saved_(ActiveIsa()) {}
  ~IsaGuard() { EXPECT_TRUE(SelectIsa(saved_).ok()); }

 private:
  Isa saved_;
};

// The paths beyond the baseline that this machine runs; the test says
// which it could not check.
std::vector<Isa> WiderPaths() {
  std::vector<Isa> paths;
  for (Isa isa : {Isa::kAvx2, Isa::kAvx512}) {
    if (IsaSupported(isa)) {
      paths.push_back(isa);
    } else {
      std::printf("note: path %s not supported here, not checked\n",
                  IsaName(isa));
    }
  }
  return paths;
}

// The bits of x, every NaN mapped to one pattern: which NaN an operation
// on two NaNs returns depends on the order of its operands, which no
// compiler keeps for + and * (kernels.h). A NaN is a numerical failure of
// the evaluation on every path, so its sign and payload never reach a
// result.
template <typename S>
uint64_t Bits(S x) {
  if (std::isnan(x)) return ~uint64_t{0};
  if constexpr (sizeof(S) == 4) {
    return std::bit_cast<uint32_t>(x);
  } else {
    return std::bit_cast<uint64_t>(x);
  }
}

// A network update on random rows, `cells` lanes, some values extreme.
template <typename S>
struct GrnCase {
  int cells, capacity, sources, targets;
  std::vector<S> source_values, weights, activation, levels;
  std::vector<int> row_begin, row_target, target_activation;

  GrnCase(int n, uint64_t seed) : cells(n), capacity(32) {
    RandomStream rng(seed, 0, StreamPurpose::kRandomGenome);
    sources = 1 + static_cast<int>(rng.NextU64() % 6);
    targets = 1 + static_cast<int>(rng.NextU64() % 8);
    const int activation_rows = targets + 2;
    auto value = [&](bool extreme) -> S {
      if (extreme) {
        switch (rng.NextU64() % 6) {
          case 0:
            return std::numeric_limits<S>::quiet_NaN();
          case 1:
            return std::numeric_limits<S>::infinity();
          case 2:
            return -std::numeric_limits<S>::infinity();
          case 3:
            return S{-0.0};
          case 4:
            return std::numeric_limits<S>::denorm_min();
          default:
            return S{1e30};
        }
      }
      return static_cast<S>(rng.Uniform(-3.0, 3.0));
    };
    const bool extreme = seed % 3 == 0;
    for (int i = 0; i < sources * capacity; ++i) {
      source_values.push_back(value(extreme && rng.NextU64() % 7 == 0));
    }
    row_begin.push_back(0);
    for (int r = 0; r < sources; ++r) {
      const int weights_here = static_cast<int>(rng.NextU64() % 5);
      for (int k = 0; k < weights_here; ++k) {
        row_target.push_back(static_cast<int>(rng.NextU64() % activation_rows));
        weights.push_back(static_cast<S>(rng.Uniform(-10.0, 10.0)));
      }
      row_begin.push_back(static_cast<int>(row_target.size()));
    }
    for (int i = 0; i < activation_rows * capacity; ++i) {
      activation.push_back(value(extreme && rng.NextU64() % 9 == 0));
    }
    for (int t = 0; t < targets; ++t) {
      target_activation.push_back(
          static_cast<int>(rng.NextU64() % activation_rows));
    }
    for (int i = 0; i < targets * capacity; ++i) {
      levels.push_back(extreme && rng.NextU64() % 9 == 0
                           ? value(true)
                           : static_cast<S>(rng.Uniform(0.0, 1.0)));
    }
  }

  // Runs the kernel on `isa` over a copy; returns activation then levels.
  std::vector<S> Run(Isa isa) const {
    std::vector<S> act = activation, lev = levels;
    std::vector<const S*> source_rows;
    for (int r = 0; r < sources; ++r) {
      source_rows.push_back(&source_values[static_cast<size_t>(r) * capacity]);
    }
    std::vector<S*> level_rows;
    for (int t = 0; t < targets; ++t) {
      level_rows.push_back(&lev[static_cast<size_t>(t) * capacity]);
    }
    kernels::GrnStepArgs<S> args;
    args.cells = cells;
    args.capacity = capacity;
    args.sources = sources;
    args.source = source_rows.data();
    args.row_begin = row_begin.data();
    args.row_target = row_target.data();
    args.row_weight = weights.data();
    args.activation = act.data();
    args.targets = targets;
    args.target_activation = target_activation.data();
    args.level = level_rows.data();
    args.dt = static_cast<S>(0.05);
    kernels::GrnStep(isa, args);
    act.insert(act.end(), lev.begin(), lev.end());
    return act;
  }
};

template <typename S>
void ExpectGrnPathsAgree() {
  testing::FpTrapsOff traps_off;  // Some cases hold NaN and infinity.
  for (Isa isa : WiderPaths()) {
    for (uint64_t seed = 1; seed <= 60; ++seed) {
      const int cells = 1 + static_cast<int>(seed % 32);
      const GrnCase<S> c(cells, seed);
      const std::vector<S> base = c.Run(Isa::kBaseline);
      const std::vector<S> wide = c.Run(isa);
      ASSERT_EQ(base.size(), wide.size());
      for (size_t i = 0; i < base.size(); ++i) {
        ASSERT_EQ(Bits(base[i]), Bits(wide[i]))
            << IsaName(isa) << " seed " << seed << " value " << i << ": "
            << base[i] << " against " << wide[i];
      }
    }
  }
}

TEST(KernelsTest, NetworkStepGivesTheBaselinesBitsOnEveryPathInFloat) {
  ExpectGrnPathsAgree<float>();
}

TEST(KernelsTest, NetworkStepGivesTheBaselinesBitsOnEveryPathInDouble) {
  ExpectGrnPathsAgree<double>();
}

TEST(KernelsTest, NetworkStepComputesTheModelsUpdate) {
  // One cell, one weight: A = 2 * 0.5 + 0.25 (starting sum), L = 0.5.
  const float value = 0.5f;
  const float* source = &value;
  const int row_begin[] = {0, 1};
  const int row_target[] = {0};
  const float weight[] = {2.0f};
  float activation[32] = {0.25f};
  float level = 0.5f;
  float* level_row = &level;
  const int target_activation[] = {0};
  kernels::GrnStepArgs<float> args;
  args.cells = 1;
  args.capacity = 32;
  args.sources = 1;
  args.source = &source;
  args.row_begin = row_begin;
  args.row_target = row_target;
  args.row_weight = weight;
  args.activation = activation;
  args.targets = 1;
  args.target_activation = target_activation;
  args.level = &level_row;
  args.dt = 0.05f;
  kernels::GrnStep(Isa::kBaseline, args);
  EXPECT_EQ(activation[0], 1.25f);
  EXPECT_NEAR(level, 0.5 + (std::tanh(0.625) - 0.5) * 0.05, 1e-6);
}

TEST(KernelsTest, PairKernelsGiveTheBaselinesBitsOnEveryPath) {
  testing::FpTrapsOff traps_off;
  std::vector<double> distance = {0.0,
                                  0.125,
                                  0.25,
                                  0.375,
                                  1.0,
                                  3.0,
                                  31.6,
                                  31.75,
                                  1e3,
                                  1e300,
                                  std::numeric_limits<double>::infinity(),
                                  std::numeric_limits<double>::quiet_NaN()};
  RandomStream rng(5, 0, StreamPurpose::kRandomGenome);
  for (int i = 0; i < 500; ++i) distance.push_back(rng.Uniform(0.0, 40.0));
  auto run = [&](Isa isa, size_t pairs) {
    std::vector<double> kernel(pairs), delay(pairs);
    kernels::PairKernelArgs args;
    args.pairs = pairs;
    args.distance = distance.data();
    args.kernel_length = 3.0;
    args.delay_length = 0.25;
    args.max_delay = 127.0;
    args.kernel = kernel.data();
    args.delay = delay.data();
    kernels::PairKernels(isa, args);
    kernel.insert(kernel.end(), delay.begin(), delay.end());
    return kernel;
  };
  for (Isa isa : WiderPaths()) {
    for (size_t pairs : {size_t{1}, size_t{7}, size_t{12}, distance.size()}) {
      const std::vector<double> base = run(Isa::kBaseline, pairs);
      const std::vector<double> wide = run(isa, pairs);
      for (size_t i = 0; i < base.size(); ++i) {
        ASSERT_EQ(Bits(base[i]), Bits(wide[i]))
            << IsaName(isa) << " pairs " << pairs << " value " << i;
      }
    }
  }
  // Every path against the model's formulas written with std::floor,
  // including values just below and above the integers and beyond 2^52.
  for (double y : {1.0, 2.0, 126.0, 127.0, 128.0, 0x1p52, 0x1p53, 1e300}) {
    for (double e : {-1e-12, 0.0, 1e-12}) {
      distance.push_back((y + e - 0.5) * 0.25);
    }
    distance.push_back(std::nextafter(y - 0.5, 0.0) * 0.25);
  }
  for (Isa isa : SupportedIsas()) {
    const std::vector<double> got = run(isa, distance.size());
    const size_t n = distance.size();
    for (size_t p = 0; p < n; ++p) {
      const double d = distance[p];
      const double steps = std::floor(d / 0.25 + 0.5);
      const double delay = steps < 127.0 ? steps : 127.0;
      ASSERT_EQ(Bits(got[n + p]), Bits(delay))
          << IsaName(isa) << " d " << d << ": " << got[n + p];
      ASSERT_EQ(Bits(got[p]), Bits(Exp(-d / 3.0))) << IsaName(isa);
    }
  }
  const std::vector<double> some = run(Isa::kBaseline, 12);
  EXPECT_EQ(some[0], 1.0);         // K(0).
  EXPECT_EQ(some[12 + 1], 1.0);    // 0.125 / 0.25 + 0.5 = 1.
  EXPECT_EQ(some[12 + 6], 126.0);  // floor(126.9).
  EXPECT_EQ(some[12 + 7], 127.0);  // floor(127.5), the cap.
  EXPECT_EQ(some[12 + 9], 127.0);  // Far beyond: the cap.
}

// NearPairs on every path against its rule written out here: rows of
// every length from 0 to 40 (whole vectors and tails), starting anywhere,
// with bounds that exclude (negative), admit and refuse, and coordinates
// that make the distance NaN or infinite.
TEST(KernelsTest, NearPairsKeepsWhatItsRuleKeepsOnEveryPath) {
  testing::FpTrapsOff traps_off;  // Some cases hold NaN and infinity.
  RandomStream rng(9, 0, StreamPurpose::kRandomGenome);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  for (int trial = 0; trial < 400; ++trial) {
    const int first = static_cast<int>(rng.NextU64() % 5);
    const int last = first + static_cast<int>(rng.NextU64() % 41);
    std::vector<double> x(last), y(last), bound2(last - first);
    for (int j = 0; j < last; ++j) {
      x[j] = rng.Uniform(-4.0, 4.0);
      y[j] = rng.Uniform(-4.0, 4.0);
      const uint64_t odd = rng.NextU64() % 40;
      if (odd == 0) x[j] = nan;
      if (odd == 1) y[j] = inf;
    }
    for (double& b : bound2) {
      const uint64_t kind = rng.NextU64() % 6;
      b = kind == 0 ? -1.0 : (kind == 1 ? 0.0 : rng.Uniform(0.0, 20.0));
    }
    const double xi = trial % 7 == 0 ? nan : rng.Uniform(-4.0, 4.0);
    const double yi = rng.Uniform(-4.0, 4.0);
    std::vector<int> expected;
    for (int j = first; j < last; ++j) {
      const double dx = x[j] - xi;
      const double dy = y[j] - yi;
      const double d2 = dx * dx + dy * dy;
      const double b = bound2[j - first];
      if (b >= 0.0 && !(d2 > b)) expected.push_back(j);
    }
    for (Isa isa : SupportedIsas()) {
      std::vector<int> out(last - first + 8, -7);
      kernels::NearPairsArgs args;
      args.first = first;
      args.last = last;
      args.x = x.data();
      args.y = y.data();
      args.xi = xi;
      args.yi = yi;
      args.bound2 = bound2.data();
      args.out = out.data();
      const int count = kernels::NearPairs(isa, args);
      ASSERT_EQ(std::vector<int>(out.begin(), out.begin() + count), expected)
          << IsaName(isa) << " trial " << trial << ", row [" << first << ", "
          << last << ")";
    }
  }
}

// WithinMove on every path against its rule written out here: point
// counts from 0 to 40, moves on both sides of the limit (and exactly at
// it), coordinates at and beyond the bound, NaN and infinity anywhere.
TEST(KernelsTest, WithinMoveSaysWhatItsRuleSaysOnEveryPath) {
  testing::FpTrapsOff traps_off;  // Some cases hold NaN and infinity.
  RandomStream rng(10, 0, StreamPurpose::kRandomGenome);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  const double bound = 0x1p20;
  const double limit2 = 0.225 * 0.225;
  int within = 0, outside = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    const size_t points = rng.NextU64() % 41;
    std::vector<Vec2> built(points), position(points);
    for (size_t k = 0; k < points; ++k) {
      built[k] = {rng.Uniform(-50.0, 50.0), rng.Uniform(-50.0, 50.0)};
      // Mostly small moves, so that whole lists pass.
      const double reach = rng.NextU64() % 50 == 0 ? 0.4 : 0.15;
      position[k] = built[k] + Vec2{rng.Uniform(-reach, reach),
                                    rng.Uniform(-reach, reach)};
      switch (rng.NextU64() % 400) {
        case 0:
          position[k].x = nan;
          break;
        case 1:
          position[k].y = inf;
          break;
        case 2:
          position[k] = {bound, 0.0};
          built[k] = position[k];
          break;
        case 3:
          built[k].y = nan;
          break;
        case 4:
          position[k] = built[k] + Vec2{0.225, 0.0};
          break;  // At it.
        default:
          break;
      }
    }
    bool expected = true;
    for (size_t k = 0; k < points; ++k) {
      const Vec2 p = position[k];
      const Vec2 move = p - built[k];
      expected = expected && std::fabs(p.x) < bound && std::fabs(p.y) < bound &&
                 move.x * move.x + move.y * move.y <= limit2;
    }
    (expected ? within : outside) += 1;
    for (Isa isa : SupportedIsas()) {
      kernels::WithinMoveArgs args;
      args.points = points;
      args.position = position.data();
      args.built = built.data();
      args.bound = bound;
      args.limit2 = limit2;
      ASSERT_EQ(kernels::WithinMove(isa, args), expected)
          << IsaName(isa) << " trial " << trial << ", " << points << " points";
    }
  }
  EXPECT_GT(within, 200);  // Both answers are tested.
  EXPECT_GT(outside, 200);
}

// The Verlet predictor and corrector on every path against Vec2's
// operators written out here, bit for bit, for 0 to 40 points.
TEST(KernelsTest, VerletPredictorAndCorrectorGiveTheOperatorsBitsOnEveryPath) {
  RandomStream rng(11, 0, StreamPurpose::kRandomGenome);
  auto random = [&](size_t n, double scale) {
    std::vector<Vec2> v(n);
    for (Vec2& p : v) {
      p = {rng.Uniform(-scale, scale), rng.Uniform(-scale, scale)};
    }
    return v;
  };
  for (size_t points = 0; points <= 40; ++points) {
    const std::vector<Vec2> x = random(points, 30.0), v = random(points, 3.0),
                            a0 = random(points, 500.0),
                            a1 = random(points, 500.0);
    const double h = 0.05 / 4;
    const double half_h2 = 0.5 * h * h;
    for (Isa isa : SupportedIsas()) {
      std::vector<Vec2> stage_x(points), stage_v(points);
      kernels::VerletPredictArgs predict;
      predict.points = points;
      predict.x = x.data();
      predict.v = v.data();
      predict.a = a0.data();
      predict.stage_x = stage_x.data();
      predict.stage_v = stage_v.data();
      predict.h = h;
      predict.half_h2 = half_h2;
      kernels::VerletPredict(isa, predict);
      std::vector<Vec2> end_x(points), end_v = v;
      kernels::VerletCorrectArgs correct;
      correct.points = points;
      correct.stage_x = stage_x.data();
      correct.a0 = a0.data();
      correct.a1 = a1.data();
      correct.x = end_x.data();
      correct.v = end_v.data();
      correct.half_h = 0.5 * h;
      kernels::VerletCorrect(isa, correct);
      auto same = [](Vec2 got, Vec2 want) {
        return Bits(got.x) == Bits(want.x) && Bits(got.y) == Bits(want.y);
      };
      for (size_t i = 0; i < points; ++i) {
        const Vec2 sx = x[i] + v[i] * h + a0[i] * half_h2;
        const Vec2 sv = v[i] + a0[i] * h;
        const Vec2 ev = v[i] + (a0[i] + a1[i]) * (0.5 * h);
        ASSERT_TRUE(same(stage_x[i], sx)) << IsaName(isa) << " point " << i;
        ASSERT_TRUE(same(stage_v[i], sv)) << IsaName(isa) << " point " << i;
        ASSERT_TRUE(same(end_x[i], sx)) << IsaName(isa) << " point " << i;
        ASSERT_TRUE(same(end_v[i], ev)) << IsaName(isa) << " point " << i;
      }
    }
  }
}

// Whole evaluations: the test genomes and random genomes that develop,
// under the default configuration, in both precisions.
std::vector<Genome> EvaluationGenomes() {
  std::vector<Genome> genomes;
  for (const char* name : {"seed-1198.json", "seed-139.json", "seed-1203.json",
                           "example.json", "folding-dn1-seed3.json"}) {
    v1::Genome message;
    if (!ReadProtoFile(testing::TestData(std::string("genomes/") + name),
                       &message)
             .ok()) {
      ADD_FAILURE() << name;
      continue;
    }
    Result<Genome> genome = GenomeFromProto(message);
    if (genome.ok()) genomes.push_back(*genome);
  }
  return genomes;
}

TEST(KernelsTest, EvaluationsGiveTheSameBitsOnEveryPath) {
  IsaGuard guard;
  const std::vector<Isa> wider = WiderPaths();
  for (Precision precision : {Precision::kFloat, Precision::kDouble}) {
    ModelConfig config;
    config.grn.precision = precision;
    config.evaluation.min_chambers = 0;  // Chains too (seed-1203).
    for (const Genome& genome : EvaluationGenomes()) {
      ASSERT_TRUE(SelectIsa(Isa::kBaseline).ok());
      const EvaluationResult base = Evaluate(genome, config);
      for (Isa isa : wider) {
        ASSERT_TRUE(SelectIsa(isa).ok());
        const EvaluationResult wide = Evaluate(genome, config);
        EXPECT_EQ(wide.status, base.status) << IsaName(isa);
        EXPECT_EQ(wide.reason, base.reason) << IsaName(isa);
        EXPECT_EQ(wide.cells, base.cells) << IsaName(isa);
        EXPECT_EQ(wide.steps, base.steps) << IsaName(isa);
        EXPECT_EQ(wide.state_hash, base.state_hash) << IsaName(isa);
        ASSERT_EQ(wide.fitness.has_value(), base.fitness.has_value());
        if (base.fitness) {
          EXPECT_EQ(Bits(*wide.fitness), Bits(*base.fitness)) << IsaName(isa);
        }
        ASSERT_EQ(wide.max_overlap.has_value(), base.max_overlap.has_value());
        if (base.max_overlap) {
          EXPECT_EQ(Bits(*wide.max_overlap), Bits(*base.max_overlap))
              << IsaName(isa);
        }
      }
    }
  }
}

TEST(IsaTest, NamesReadBackAndUnknownNamesAreRefused) {
  for (Isa isa : {Isa::kBaseline, Isa::kAvx2, Isa::kAvx512}) {
    Result<Isa> parsed = ParseIsa(IsaName(isa));
    ASSERT_TRUE(parsed.ok());
    EXPECT_EQ(*parsed, isa);
  }
  Result<Isa> bad = ParseIsa("sse9");
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(bad.status().message().find("baseline, avx2 or avx512"),
            std::string::npos);
}

TEST(IsaTest, TheBaselineIsAlwaysSupportedAndFirst) {
  const std::vector<Isa> supported = SupportedIsas();
  ASSERT_FALSE(supported.empty());
  EXPECT_EQ(supported.front(), Isa::kBaseline);
  EXPECT_TRUE(IsaSupported(Isa::kBaseline));
}

TEST(IsaTest, TheEnvironmentVariableChoosesOrIsRefused) {
  const char* saved = std::getenv("ANIMAT_ISA");
  const std::string saved_value = saved ? saved : "";
  setenv("ANIMAT_ISA", "baseline", 1);
  Result<Isa> chosen = IsaFromEnvironment();
  ASSERT_TRUE(chosen.ok());
  EXPECT_EQ(*chosen, Isa::kBaseline);
  setenv("ANIMAT_ISA", "", 1);
  chosen = IsaFromEnvironment();
  ASSERT_TRUE(chosen.ok());
  EXPECT_EQ(*chosen, SupportedIsas().back());
  setenv("ANIMAT_ISA", "mmx", 1);
  chosen = IsaFromEnvironment();
  ASSERT_FALSE(chosen.ok());
  EXPECT_NE(chosen.status().message().find("ANIMAT_ISA"), std::string::npos);
  for (Isa isa : {Isa::kAvx2, Isa::kAvx512}) {
    if (IsaSupported(isa)) continue;
    setenv("ANIMAT_ISA", IsaName(isa), 1);
    chosen = IsaFromEnvironment();
    ASSERT_FALSE(chosen.ok());
    EXPECT_NE(chosen.status().message().find("not supported"),
              std::string::npos);
  }
  if (saved) {
    setenv("ANIMAT_ISA", saved_value.c_str(), 1);
  } else {
    unsetenv("ANIMAT_ISA");
  }
}

TEST(IsaTest, SelectingAnUnsupportedPathIsRefused) {
  IsaGuard guard;
  for (Isa isa : {Isa::kBaseline, Isa::kAvx2, Isa::kAvx512}) {
    const Status status = SelectIsa(isa);
    EXPECT_EQ(status.ok(), IsaSupported(isa)) << IsaName(isa);
    if (status.ok()) {
      EXPECT_EQ(ActiveIsa(), isa);
    }
  }
}

}  // namespace
}  // namespace animat
