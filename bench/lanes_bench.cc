// Spring forces of eight animats at once, one animat per AVX-512 lane,
// against one animat at a time (docs/benchmarks.md, "Where it stands").
//
// Each lane runs exactly the scalar sequence of operations of its own
// animat, so its forces keep the scalar bits; the cost is that every
// position, velocity and force of a lane is a gather or a scatter, since
// the animats' springs join different nodes. The workload: the benchmark
// body (bench/data/bench-genome.json: 32 cells, 71 springs) eight times,
// each copy with its nodes relabelled at random and its positions and
// velocities moved a little, so that no two lanes read alike. The force is
// that of docs/model.md §7.2 (elastic and damping along the spring),
// summed at each node in spring order.
//
//   BM_SpringsScalar        one animat after another, as SoftBody does
//   BM_SpringsLanes         eight in the lanes, gathers and ordered scatters
//   BM_SpringsLanesBuffered eight in the lanes, then each lane's forces
//                           added by scalar code in spring order
//   BM_SpringsLanesSameBody eight copies of one body in the lanes (as a
//                           guidance evaluation's trials are: one body,
//                           other stimuli), each with its own positions
//                           and velocities: node i of every lane lies
//                           together, so a spring reads and adds with
//                           plain vector loads and stores, no gathers
//
// Times are per animat. Before timing, every lane's forces are checked bit
// for bit against the scalar code; a mismatch fails the run (exit 1).
// Without AVX-512 on the machine, the lane benchmarks report an error.
#include <benchmark/benchmark.h>
#include <immintrin.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include "common/body/body.h"
#include "common/development/development.h"
#include "common/evaluation/model_config.h"
#include "common/genome/genome_proto.h"
#include "common/grn/network.h"
#include "common/io/proto_file.h"

namespace animat {
namespace {

constexpr int kLanes = 8;
constexpr double kStiffness = 10.0;
constexpr double kDamping = 0.5;

struct Animat {
  std::vector<int> a, b;
  std::vector<double> rest;
  std::vector<Vec2> x, v;
};

// The scalar force, as SoftBody computes it.
void ScalarForces(const Animat& m, Vec2* f) {
  for (size_t s = 0; s < m.a.size(); ++s) {
    const int a = m.a[s];
    const int b = m.b[s];
    const Vec2 d = m.x[b] - m.x[a];
    const double l = Length(d);
    const Vec2 u = l > 0.0 ? d / l : Vec2{};
    const double force =
        kStiffness * (l - m.rest[s]) + kDamping * Dot(m.v[b] - m.v[a], u);
    const Vec2 fa = u * force;
    f[a] += fa;
    f[b] -= fa;
  }
}

// Eight animats with the same spring count, lane-interleaved: value of
// node i in lane j at [i * kLanes + j].
struct Batch {
  int springs = 0;
  std::vector<int> ia, ib;   // [s * kLanes + lane]: node * kLanes + lane.
  std::vector<double> rest;  // [s * kLanes + lane]
  std::vector<double> x, y, vx, vy, fx, fy;
  std::vector<double> cx, cy;  // Buffered contributions, per spring.
};

constexpr __mmask8 kAll = 0xff;

// A gather of eight doubles at base[index[j]] (the masked form, whose
// unmasked twin trips GCC 12's -Wmaybe-uninitialized).
__attribute__((target("avx512f"))) inline __m512d Gather(__m256i index,
                                                         const double* base,
                                                         int scale) {
  return _mm512_mask_i32gather_pd(_mm512_setzero_pd(), kAll, index, base,
                                  scale);
}

__attribute__((target("avx512f"))) inline void LaneSpring(const Batch& p, int s,
                                                          __m512d* fx,
                                                          __m512d* fy) {
  const __m512d zero = _mm512_setzero_pd();
  const __m256i ia =
      _mm256_loadu_si256(reinterpret_cast<const __m256i*>(&p.ia[s * kLanes]));
  const __m256i ib =
      _mm256_loadu_si256(reinterpret_cast<const __m256i*>(&p.ib[s * kLanes]));
  const __m512d dx =
      _mm512_sub_pd(Gather(ib, p.x.data(), 8), Gather(ia, p.x.data(), 8));
  const __m512d dy =
      _mm512_sub_pd(Gather(ib, p.y.data(), 8), Gather(ia, p.y.data(), 8));
  const __m512d l = _mm512_maskz_sqrt_pd(
      kAll, _mm512_add_pd(_mm512_mul_pd(dx, dx), _mm512_mul_pd(dy, dy)));
  const __mmask8 positive = _mm512_cmp_pd_mask(l, zero, _CMP_GT_OQ);
  const __m512d ux = _mm512_maskz_div_pd(positive, dx, l);
  const __m512d uy = _mm512_maskz_div_pd(positive, dy, l);
  const __m512d elastic =
      _mm512_mul_pd(_mm512_set1_pd(kStiffness),
                    _mm512_sub_pd(l, _mm512_loadu_pd(&p.rest[s * kLanes])));
  const __m512d dvx =
      _mm512_sub_pd(Gather(ib, p.vx.data(), 8), Gather(ia, p.vx.data(), 8));
  const __m512d dvy =
      _mm512_sub_pd(Gather(ib, p.vy.data(), 8), Gather(ia, p.vy.data(), 8));
  const __m512d dot =
      _mm512_add_pd(_mm512_mul_pd(dvx, ux), _mm512_mul_pd(dvy, uy));
  const __m512d force =
      _mm512_add_pd(elastic, _mm512_mul_pd(_mm512_set1_pd(kDamping), dot));
  *fx = _mm512_mul_pd(ux, force);
  *fy = _mm512_mul_pd(uy, force);
}

// Gathers, then an ordered scatter: spring s's forces reach its nodes
// before spring s + 1's (a lane's two nodes differ, and lanes never share
// a node, so one scatter has no conflicts).
__attribute__((target("avx512f"))) void LaneForces(Batch* p) {
  double* fxs = p->fx.data();
  double* fys = p->fy.data();
  for (int s = 0; s < p->springs; ++s) {
    __m512d fx, fy;
    LaneSpring(*p, s, &fx, &fy);
    const __m256i ia = _mm256_loadu_si256(
        reinterpret_cast<const __m256i*>(&p->ia[s * kLanes]));
    const __m256i ib = _mm256_loadu_si256(
        reinterpret_cast<const __m256i*>(&p->ib[s * kLanes]));
    _mm512_i32scatter_pd(fxs, ia, _mm512_add_pd(Gather(ia, fxs, 8), fx), 8);
    _mm512_i32scatter_pd(fys, ia, _mm512_add_pd(Gather(ia, fys, 8), fy), 8);
    _mm512_i32scatter_pd(fxs, ib, _mm512_sub_pd(Gather(ib, fxs, 8), fx), 8);
    _mm512_i32scatter_pd(fys, ib, _mm512_sub_pd(Gather(ib, fys, 8), fy), 8);
  }
}

// The lanes' contributions stored per spring, then added by scalar code.
__attribute__((target("avx512f"))) void LaneForcesBuffered(Batch* p) {
  for (int s = 0; s < p->springs; ++s) {
    __m512d fx, fy;
    LaneSpring(*p, s, &fx, &fy);
    _mm512_storeu_pd(&p->cx[s * kLanes], fx);
    _mm512_storeu_pd(&p->cy[s * kLanes], fy);
  }
  for (int s = 0; s < p->springs; ++s) {
    for (int lane = 0; lane < kLanes; ++lane) {
      const int k = s * kLanes + lane;
      p->fx[p->ia[k]] += p->cx[k];
      p->fy[p->ia[k]] += p->cy[k];
      p->fx[p->ib[k]] -= p->cx[k];
      p->fy[p->ib[k]] -= p->cy[k];
    }
  }
}

// One body in every lane: spring s joins the same nodes in each, so a
// node's value in the eight lanes is one vector load from lane 0's index
// on, and one vector addition per node and coordinate keeps every lane's
// order.
__attribute__((target("avx512f"))) void LaneForcesSameBody(Batch* p) {
  const __m512d zero = _mm512_setzero_pd();
  const __m512d stiffness = _mm512_set1_pd(kStiffness);
  const __m512d damping = _mm512_set1_pd(kDamping);
  const double* x = p->x.data();
  const double* y = p->y.data();
  const double* vx = p->vx.data();
  const double* vy = p->vy.data();
  double* fxs = p->fx.data();
  double* fys = p->fy.data();
  for (int s = 0; s < p->springs; ++s) {
    const int a = p->ia[s * kLanes];  // Lane 0's: node * kLanes.
    const int b = p->ib[s * kLanes];
    const __m512d dx =
        _mm512_sub_pd(_mm512_loadu_pd(x + b), _mm512_loadu_pd(x + a));
    const __m512d dy =
        _mm512_sub_pd(_mm512_loadu_pd(y + b), _mm512_loadu_pd(y + a));
    const __m512d l = _mm512_maskz_sqrt_pd(
        kAll, _mm512_add_pd(_mm512_mul_pd(dx, dx), _mm512_mul_pd(dy, dy)));
    const __mmask8 positive = _mm512_cmp_pd_mask(l, zero, _CMP_GT_OQ);
    const __m512d ux = _mm512_maskz_div_pd(positive, dx, l);
    const __m512d uy = _mm512_maskz_div_pd(positive, dy, l);
    const __m512d elastic = _mm512_mul_pd(
        stiffness, _mm512_sub_pd(l, _mm512_loadu_pd(&p->rest[s * kLanes])));
    const __m512d dvx =
        _mm512_sub_pd(_mm512_loadu_pd(vx + b), _mm512_loadu_pd(vx + a));
    const __m512d dvy =
        _mm512_sub_pd(_mm512_loadu_pd(vy + b), _mm512_loadu_pd(vy + a));
    const __m512d dot =
        _mm512_add_pd(_mm512_mul_pd(dvx, ux), _mm512_mul_pd(dvy, uy));
    const __m512d force = _mm512_add_pd(elastic, _mm512_mul_pd(damping, dot));
    const __m512d fx = _mm512_mul_pd(ux, force);
    const __m512d fy = _mm512_mul_pd(uy, force);
    _mm512_storeu_pd(fxs + a, _mm512_add_pd(_mm512_loadu_pd(fxs + a), fx));
    _mm512_storeu_pd(fys + a, _mm512_add_pd(_mm512_loadu_pd(fys + a), fy));
    _mm512_storeu_pd(fxs + b, _mm512_sub_pd(_mm512_loadu_pd(fxs + b), fx));
    _mm512_storeu_pd(fys + b, _mm512_sub_pd(_mm512_loadu_pd(fys + b), fy));
  }
}

Body BenchBody() {
  const std::string path =
      std::string(ANIMAT_BENCH_DATA_DIR) + "/bench-genome.json";
  v1::Genome message;
  const Status status = ReadProtoFile(path, &message);
  Result<Genome> genome =
      status.ok() ? GenomeFromProto(message) : Result<Genome>(status);
  if (!genome.ok()) {
    std::fprintf(stderr, "%s\n", genome.status().ToString().c_str());
    std::exit(1);
  }
  const ModelConfig config;
  const Network network = Network::Build(*genome, config.grn);
  DevelopmentT<double> development(network, config.grn, config.development,
                                   config.signals);
  development.Run();
  return *BuildBody(development.embryo().position, development.embryo().radius);
}

struct Workload {
  std::vector<Animat> animats;
  Batch batch;

  // `same_body`: every lane keeps the body's own node labels (guidance's
  // trials); otherwise lanes after the first relabel them at random.
  explicit Workload(bool same_body = false) {
    const Body body = BenchBody();
    const int n = body.nodes();
    std::mt19937_64 rng(5);
    std::uniform_real_distribution<double> jitter(-0.2, 0.2);
    for (int lane = 0; lane < kLanes; ++lane) {
      std::vector<int> label(n);
      for (int i = 0; i < n; ++i) label[i] = i;
      if (lane > 0 && !same_body) {
        std::shuffle(label.begin(), label.end(), rng);
      }
      Animat m;
      m.x.resize(n);
      m.v.resize(n);
      for (int i = 0; i < n; ++i) {
        m.x[label[i]] = body.position[i] + Vec2{jitter(rng), jitter(rng)};
        m.v[label[i]] = {jitter(rng), jitter(rng)};
      }
      for (const Spring& spring : body.springs) {
        m.a.push_back(label[spring.a]);
        m.b.push_back(label[spring.b]);
        m.rest.push_back(0.9 * spring.rest_length);
      }
      animats.push_back(std::move(m));
    }
    Batch& p = batch;
    p.springs = static_cast<int>(body.springs.size());
    const size_t values = static_cast<size_t>(n) * kLanes;
    for (auto* v : {&p.x, &p.y, &p.vx, &p.vy, &p.fx, &p.fy}) v->resize(values);
    p.cx.resize(static_cast<size_t>(p.springs) * kLanes);
    p.cy.resize(p.cx.size());
    for (int s = 0; s < p.springs; ++s) {
      for (int lane = 0; lane < kLanes; ++lane) {
        const Animat& m = animats[lane];
        p.ia.push_back(m.a[s] * kLanes + lane);
        p.ib.push_back(m.b[s] * kLanes + lane);
        p.rest.push_back(m.rest[s]);
      }
    }
    for (int lane = 0; lane < kLanes; ++lane) {
      for (int i = 0; i < n; ++i) {
        p.x[i * kLanes + lane] = animats[lane].x[i].x;
        p.y[i * kLanes + lane] = animats[lane].x[i].y;
        p.vx[i * kLanes + lane] = animats[lane].v[i].x;
        p.vy[i * kLanes + lane] = animats[lane].v[i].y;
      }
    }
  }

  void ClearForces() {
    std::fill(batch.fx.begin(), batch.fx.end(), 0.0);
    std::fill(batch.fy.begin(), batch.fy.end(), 0.0);
  }

  // Every lane's forces against the scalar code's, bit for bit.
  bool LanesMatchScalar() const {
    for (int lane = 0; lane < kLanes; ++lane) {
      const Animat& m = animats[lane];
      std::vector<Vec2> f(m.x.size());
      ScalarForces(m, f.data());
      for (size_t i = 0; i < f.size(); ++i) {
        const double got[2] = {batch.fx[i * kLanes + lane],
                               batch.fy[i * kLanes + lane]};
        if (std::memcmp(got, &f[i], sizeof got) != 0) return false;
      }
    }
    return true;
  }
};

bool HasAvx512() { return __builtin_cpu_supports("avx512f"); }

void BM_SpringsScalar(benchmark::State& state) {
  Workload w;
  std::vector<Vec2> f(w.animats[0].x.size());
  for (auto _ : state) {
    for (const Animat& m : w.animats) {
      std::fill(f.begin(), f.end(), Vec2{});
      ScalarForces(m, f.data());
      benchmark::DoNotOptimize(f.data());
      benchmark::ClobberMemory();
    }
  }
  state.SetItemsProcessed(state.iterations() * kLanes);
  state.counters["ns_per_animat"] = benchmark::Counter(
      static_cast<double>(state.iterations()) * kLanes,
      benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}
BENCHMARK(BM_SpringsScalar);

template <void (*kForces)(Batch*), bool kSameBody = false>
void BM_Lanes(benchmark::State& state) {
  if (!HasAvx512()) {
    state.SkipWithError("this machine has no AVX-512");
    return;
  }
  Workload w(kSameBody);
  w.ClearForces();
  kForces(&w.batch);
  if (!w.LanesMatchScalar()) {
    std::fprintf(stderr,
                 "lanes_bench: a lane's forces differ from the "
                 "scalar code's bits\n");
    std::exit(1);
  }
  for (auto _ : state) {
    w.ClearForces();
    kForces(&w.batch);
    benchmark::DoNotOptimize(w.batch.fx.data());
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations() * kLanes);
  state.counters["ns_per_animat"] = benchmark::Counter(
      static_cast<double>(state.iterations()) * kLanes,
      benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

void BM_SpringsLanes(benchmark::State& state) { BM_Lanes<LaneForces>(state); }
BENCHMARK(BM_SpringsLanes);
void BM_SpringsLanesBuffered(benchmark::State& state) {
  BM_Lanes<LaneForcesBuffered>(state);
}
BENCHMARK(BM_SpringsLanesBuffered);
void BM_SpringsLanesSameBody(benchmark::State& state) {
  BM_Lanes<LaneForcesSameBody, /*kSameBody=*/true>(state);
}
BENCHMARK(BM_SpringsLanesSameBody);

}  // namespace
}  // namespace animat
