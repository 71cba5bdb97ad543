#include "analysis/spectrum.h"

#include <unsupported/Eigen/FFT>

#include <algorithm>
#include <cmath>
#include <complex>
#include <numbers>

#include "common/base/fast_math.h"

namespace animat::analysis {
namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;

// e^{−2πi·t} for t in cycles; only the fraction of t matters, so it is
// taken first (SinCos is accurate for small arguments).
std::complex<double> Twiddle(double cycles) {
  const double fraction = cycles - std::floor(cycles);
  double s = 0;
  double c = 0;
  SinCos(kTwoPi * fraction, &s, &c);
  return {c, -s};
}

std::vector<double> HannWindow(size_t n) {
  std::vector<double> w(n, 1.0);
  if (n < 2) return w;
  for (size_t k = 0; k < n; ++k) {
    const double c = Twiddle(static_cast<double>(k) / (n - 1)).real();
    w[k] = 0.5 - 0.5 * c;
  }
  return w;
}

// w_k·(s_k − m), m the window-weighted mean, so the zero frequency is
// removed exactly.
std::vector<double> Windowed(std::span<const double> s,
                             const std::vector<double>& w, double w_sum) {
  double mean = 0;
  for (size_t k = 0; k < s.size(); ++k) mean += w[k] * s[k];
  mean /= w_sum;
  std::vector<double> d(s.size());
  for (size_t k = 0; k < s.size(); ++k) d[k] = w[k] * (s[k] - mean);
  return d;
}

double Sum(const std::vector<double>& v) {
  double sum = 0;
  for (double x : v) sum += x;
  return sum;
}

std::complex<double> Transform(const std::vector<double>& d,
                               const std::vector<std::complex<double>>& e) {
  std::complex<double> x;
  for (size_t k = 0; k < d.size(); ++k) x += d[k] * e[k];
  return x;
}

std::vector<std::complex<double>> Basis(size_t n, double frequency) {
  std::vector<std::complex<double>> e(n);
  for (size_t k = 0; k < n; ++k) e[k] = Twiddle(frequency * k);
  return e;
}

Component FromTransform(std::complex<double> x, double w_sum) {
  Component c;
  c.amplitude = 2.0 * std::abs(x) / w_sum;
  if (c.amplitude > 0) c.phase = WrapAngle(-std::arg(x));
  return c;
}

}  // namespace

double WrapAngle(double radians) {
  double r = std::remainder(radians, kTwoPi);  // In [−π, π].
  if (r <= -std::numbers::pi) r += kTwoPi;
  return r;
}

Component ComponentAt(std::span<const double> signal, double frequency) {
  if (signal.size() < 2) return {};
  const std::vector<double> w = HannWindow(signal.size());
  const double w_sum = Sum(w);
  return FromTransform(
      Transform(Windowed(signal, w, w_sum), Basis(signal.size(), frequency)),
      w_sum);
}

namespace {

// The windowed signals' summed power spectrum, each zero-padded to `size`
// points (a power of two): size / 2 + 1 values.
std::vector<double> SummedPowerSpectrum(
    const std::vector<std::vector<double>>& windowed, size_t size) {
  std::vector<double> power(size / 2 + 1, 0.0);
  Eigen::FFT<double> fft;
  fft.SetFlag(Eigen::FFT<double>::HalfSpectrum);  // size / 2 + 1 values.
  std::vector<double> padded(size, 0.0);
  std::vector<std::complex<double>> spectrum;
  for (const std::vector<double>& d : windowed) {
    std::copy(d.begin(), d.end(), padded.begin());
    fft.fwd(spectrum, padded);
    for (size_t j = 0; j < power.size(); ++j) {
      power[j] += std::norm(spectrum[j]);
    }
  }
  return power;
}

// The frequency in [lo, hi] where `power` peaks, by golden-section search
// (200 iterations at most, to a relative width of 1e-9).
template <typename Power>
double GoldenSectionPeak(double lo, double hi, Power power) {
  const double ratio = (std::sqrt(5.0) - 1.0) / 2.0;
  double a = hi - ratio * (hi - lo);
  double b = lo + ratio * (hi - lo);
  double pa = power(a);
  double pb = power(b);
  for (int iteration = 0; iteration < 200 && hi - lo > 1e-9 * hi; ++iteration) {
    if (pa >= pb) {
      hi = b;
      b = a;
      pb = pa;
      a = hi - ratio * (hi - lo);
      pa = power(a);
    } else {
      lo = a;
      a = b;
      pa = pb;
      b = lo + ratio * (hi - lo);
      pb = power(b);
    }
  }
  return (lo + hi) / 2;
}

}  // namespace

std::optional<DominantFrequency> FindDominantFrequency(
    const std::vector<std::vector<double>>& signals, double min_frequency) {
  if (signals.empty() || min_frequency > 0.5) return std::nullopt;
  const size_t n = signals[0].size();
  if (n < 4) return std::nullopt;
  const std::vector<double> w = HannWindow(n);
  const double w_sum = Sum(w);
  bool constant = true;
  for (const std::vector<double>& s : signals) {
    if (s.size() != n) return std::nullopt;
    for (double x : s) constant = constant && x == s[0];
  }
  if (constant) return std::nullopt;
  std::vector<std::vector<double>> windowed;
  double variance = 0;
  for (const std::vector<double>& s : signals) {
    windowed.push_back(Windowed(s, w, w_sum));
    double mean = 0;
    for (double x : s) mean += x;
    mean /= n;
    for (double x : s) variance += (x - mean) * (x - mean) / n;
  }
  if (!(variance > 0)) return std::nullopt;

  // Coarse: the summed power spectrum, zero-padded to >= 4n points. The
  // length is a power of two: Eigen's FFT (kissfft) takes any length, but
  // a prime factor p costs n·p (docs/analysis.md, "Dominant period").
  size_t size = 1;
  while (size < 4 * n) size <<= 1;
  const std::vector<double> power = SummedPowerSpectrum(windowed, size);
  size_t first = static_cast<size_t>(std::ceil(min_frequency * size));
  if (first < 1) first = 1;
  if (first >= power.size()) first = power.size() - 1;
  size_t best = first;
  for (size_t j = first; j < power.size(); ++j) {
    if (power[j] > power[best]) best = j;
  }

  // Fine: golden-section search for the peak between the neighbours.
  auto summed_power = [&](double f) {
    const std::vector<std::complex<double>> e = Basis(n, f);
    double p = 0;
    for (const std::vector<double>& d : windowed) {
      p += std::norm(Transform(d, e));
    }
    return p;
  };
  double lo = std::max(min_frequency, static_cast<double>(best - 1) / size);
  double hi = std::min(0.5, static_cast<double>(best + 1) / size);
  if (lo > hi) lo = hi;
  DominantFrequency result;
  result.frequency = GoldenSectionPeak(lo, hi, summed_power);
  const std::vector<std::complex<double>> e = Basis(n, result.frequency);
  double explained = 0;
  for (const std::vector<double>& d : windowed) {
    const double amplitude = FromTransform(Transform(d, e), w_sum).amplitude;
    explained += amplitude * amplitude / 2;
  }
  result.periodic_fraction = std::min(1.0, explained / variance);
  return result;
}

}  // namespace animat::analysis
