// Frequency analysis of evenly sampled real signals: the dominant
// frequency of a set of signals, and the amplitude and phase of each at a
// given frequency.
//
// Frequencies are in cycles per sample; a signal's component at frequency
// f is the A and φ of the best fit s_k ≈ m + A·cos(2π·f·k − φ), k = 0 the
// first sample, estimated with a Hann window (which keeps a strong
// component from leaking into its neighbours). Trigonometry uses the
// project's SinCos, so results are the same bits on every machine of one
// architecture; the one exception is the coarse search of
// FindDominantFrequency (below). Pure functions; thread-safe.
#ifndef ANIMAT_ANALYSIS_SPECTRUM_H_
#define ANIMAT_ANALYSIS_SPECTRUM_H_

#include <optional>
#include <span>
#include <vector>

namespace animat::analysis {

struct Component {
  double amplitude = 0;  // A >= 0, in the signal's units.
  double phase = 0;      // φ in (−π, π] (radians); 0 when A = 0.
};

// The component of `signal` at `frequency` (in (0, 0.5]). A signal of
// fewer than 2 samples has amplitude 0.
Component ComponentAt(std::span<const double> signal, double frequency);

struct DominantFrequency {
  double frequency = 0;  // Cycles per sample, in [min_frequency, 0.5].
  // The share of the signals' summed variance that the components at
  // `frequency` explain (Σ A²/2 over Σ variance), in [0, 1]: 1 for pure
  // sinusoids, near 0 for noise.
  double periodic_fraction = 0;
};

// The frequency at or above `min_frequency` where the summed power of the
// Hann-windowed signals peaks: found on a grid four times finer than the
// signals' own resolution, then refined to ~1e-9 relative by golden-section
// search. The grid's spectrum is Eigen's FFT, whose twiddle factors come
// from the C library's sin and cos: it only picks the grid point to refine
// around, so results differ between machines only if two grid points'
// powers agree to within rounding. Every signal must have the same length
// n >= 4. nullopt when every signal is constant (all its values equal), or
// n < 4, or min_frequency > 0.5.
std::optional<DominantFrequency> FindDominantFrequency(
    const std::vector<std::vector<double>>& signals, double min_frequency);

// Wraps an angle into (−π, π].
double WrapAngle(double radians);

}  // namespace animat::analysis

#endif  // ANIMAT_ANALYSIS_SPECTRUM_H_
