// Separable convolution helpers for FLIP (private to the flip room). Images are planar float rows;
// borders replicate the edge pixel (as the FLIP paper's reference evaluation does).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstring>
#include <cstdint>
#include <utility>
#include <vector>

// The FLIP engine is compiled for the baseline ISA and for x86-64-v3 (AVX2 + FMA) and x86-64-v4
// (AVX-512), chosen at run time, so portable binaries still run fast on current CPUs.
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#define FGB_X86_DISPATCH 1
#else
#define FGB_X86_DISPATCH 0
#endif

// Forces inlining, so that a helper is compiled for the instruction set of the function it is used in
// (the FLIP engine is instantiated once per ISA level with target attributes).
#if defined(__GNUC__)
#define FGB_INLINE inline __attribute__((always_inline))
#define FGB_LAMBDA_INLINE __attribute__((always_inline))
#else
#define FGB_INLINE inline
#define FGB_LAMBDA_INLINE
#endif

namespace fgb::harness::flip_detail {

// A 1D kernel on [-radius, radius]: taps[i] multiplies the sample at offset i - radius.
// symmetry +1 (even: Gaussians, second derivatives) or -1 (odd: first derivatives); 0 for anything
// else.
struct Kernel {
  int radius = 0;
  int symmetry = 0;
  std::vector<float> taps;
};

// Samples of f(i) for i in [-radius, radius].
template <typename F>
Kernel sampleKernel(int radius, F f) {
  Kernel k;
  k.radius = radius;
  k.taps.resize(static_cast<std::size_t>(2 * radius + 1));
  for (int i = -radius; i <= radius; ++i) k.taps[static_cast<std::size_t>(i + radius)] = static_cast<float>(f(static_cast<double>(i)));
  return k;
}

double sumOf(const Kernel& k);
void scale(Kernel& k, double factor);
// Positive taps scaled to sum to 1 and negative taps to sum to -1 (FLIP's feature kernels).
void normalizeSignedParts(Kernel& k);
// Sets k.symmetry from the taps (exact comparison: kernels are sampled from even/odd functions).
void detectSymmetry(Kernel& k);
// Drops outer taps below `relative` times the largest one: a Gaussian's far tail is below float
// precision of the sum, and computing it only costs time.
void trimNegligibleTaps(Kernel& k, double relative);

// A symmetric (even) or antisymmetric (odd) kernel folded around its centre:
//   out[x] = centre * in[x] + sum_{i=1..radius} side[i] * (in[x + i] +- in[x - i])
// (+ for even kernels, - for odd ones, whose centre tap is 0). Folding halves the multiplications
// and lets kernels that read the same input share its loads.
struct FoldedKernel {
  int radius = 0;
  bool odd = false;
  float centre = 0.0f;
  std::vector<float> side;  // side[0] unused; side[i] = taps[radius + i]
};

// Throws std::logic_error for a kernel that is neither even nor odd.
FoldedKernel fold(const Kernel& k);
// The same kernel with zero taps appended up to `radius` (adding 0 * x changes no sum, so the
// result is identical): lets kernels of different reach share one pass over their input.
FoldedKernel padTo(FoldedKernel k, int radius);

// ---- Vector primitives ------------------------------------------------------------------------
// L floats: 16 for AVX-512, 8 for AVX2, 4 for SSE2 (each ISA's own width, so every vector operation
// is one instruction; wider generic vectors made GCC go through memory on the narrower ISAs).
template <int L>
struct VecTraits;
template <>
struct VecTraits<16> {
  typedef float V __attribute__((vector_size(64)));
  typedef float Unaligned __attribute__((vector_size(64), aligned(4), may_alias));
};
template <>
struct VecTraits<8> {
  typedef float V __attribute__((vector_size(32)));
  typedef float Unaligned __attribute__((vector_size(32), aligned(4), may_alias));
};
template <>
struct VecTraits<4> {
  typedef float V __attribute__((vector_size(16)));
  typedef float Unaligned __attribute__((vector_size(16), aligned(4), may_alias));
};
// Row lengths are padded to a multiple of the widest vector.
inline constexpr int kMaxVecLanes = 16;

// Unaligned views of float arrays as vectors (references, so no vector crosses a call boundary).
template <int L>
FGB_INLINE const typename VecTraits<L>::Unaligned& vecAt(const float* p) {
  return *reinterpret_cast<const typename VecTraits<L>::Unaligned*>(p);
}
template <int L>
FGB_INLINE typename VecTraits<L>::Unaligned& vecAt(float* p) {
  return *reinterpret_cast<typename VecTraits<L>::Unaligned*>(p);
}

// The convolutions below compute n outputs (n a multiple of L), NV vectors at a time with
// the accumulators in registers (then single vectors for what is left). Tap j of a kernel of radius
// r reads base + offsets[j] + x (j = 0..2r, centre j = r): for a horizontal pass the offsets are
// 0, 1, 2, ... along one padded row; for a vertical pass they are the (clamped) rows of a plane.
// Runs step.template operator()<NV>(x) over [0, n) in blocks of NV vectors, then of one vector.
template <int L, int NV, typename Step>
FGB_INLINE void forVectorBlocks(int n, const Step& step) {
  int x = 0;
  for (; x + NV * L <= n; x += NV * L) step.template operator()<NV>(x);
  if constexpr (NV > 1) {
    for (; x < n; x += L) step.template operator()<1>(x);
  }
}

// One kernel, one output.
template <int L, int NV>
FGB_INLINE void convolve1(const float* base, const std::ptrdiff_t* offsets, const FoldedKernel& k, float* out, int n) {
  using Vec = typename VecTraits<L>::V;
  const int r = k.radius;
  const float* centre = base + offsets[r];
  const float* side = k.side.data();
  const float c = k.centre;
  const bool odd = k.odd;
  forVectorBlocks<L, NV>(n, [&]<int N>(int x) FGB_LAMBDA_INLINE {
    Vec acc[N];
    _Pragma("GCC unroll 8") for (int v = 0; v < N; ++v) acc[v] = odd ? Vec{} : vecAt<L>(centre + x + v * L) * c;
    for (int i = 1; i <= r; ++i) {
      const float* after = base + offsets[r + i] + x;
      const float* before = base + offsets[r - i] + x;
      const float w = side[i];
      if (odd) {
        _Pragma("GCC unroll 8") for (int v = 0; v < N; ++v) acc[v] += w * (vecAt<L>(after + v * L) - vecAt<L>(before + v * L));
      } else {
        _Pragma("GCC unroll 8") for (int v = 0; v < N; ++v) acc[v] += w * (vecAt<L>(after + v * L) + vecAt<L>(before + v * L));
      }
    }
    _Pragma("GCC unroll 8") for (int v = 0; v < N; ++v) vecAt<L>(out + x + v * L) = acc[v];
  });
}

// Two even kernels of the same radius over one input, two outputs (shared loads).
template <int L, int NV>
FGB_INLINE void convolve2(const float* base, const std::ptrdiff_t* offsets, const FoldedKernel& k1, const FoldedKernel& k2,
                          float* out1, float* out2, int n) {
  using Vec = typename VecTraits<L>::V;
  const int r = k1.radius;
  const float* centre = base + offsets[r];
  const float* side1 = k1.side.data();
  const float* side2 = k2.side.data();
  const float c1 = k1.centre, c2 = k2.centre;
  forVectorBlocks<L, NV>(n, [&]<int N>(int x) FGB_LAMBDA_INLINE {
    Vec a1[N], a2[N];
    _Pragma("GCC unroll 8") for (int v = 0; v < N; ++v) {
      const Vec c = vecAt<L>(centre + x + v * L);
      a1[v] = c * c1;
      a2[v] = c * c2;
    }
    for (int i = 1; i <= r; ++i) {
      const float* after = base + offsets[r + i] + x;
      const float* before = base + offsets[r - i] + x;
      const float w1 = side1[i], w2 = side2[i];
      _Pragma("GCC unroll 8") for (int v = 0; v < N; ++v) {
        const Vec sum = vecAt<L>(after + v * L) + vecAt<L>(before + v * L);
        a1[v] += w1 * sum;
        a2[v] += w2 * sum;
      }
    }
    _Pragma("GCC unroll 8") for (int v = 0; v < N; ++v) {
      vecAt<L>(out1 + x + v * L) = a1[v];
      vecAt<L>(out2 + x + v * L) = a2[v];
    }
  });
}

// FLIP's three feature kernels over one input: Gaussian g (even), edge e (odd), point p (even), and
// a fourth even kernel c (the achromatic CSF, zero-padded to their radius), all of one radius.
template <int L, int NV>
FGB_INLINE void convolveFeatures(const float* base, const std::ptrdiff_t* offsets, const FoldedKernel& g, const FoldedKernel& e,
                                 const FoldedKernel& p, const FoldedKernel& c, float* outG, float* outE, float* outP, float* outC,
                                 int n) {
  using Vec = typename VecTraits<L>::V;
  const int r = g.radius;
  const float* centre = base + offsets[r];
  const float* sideG = g.side.data();
  const float* sideE = e.side.data();
  const float* sideP = p.side.data();
  const float* sideC = c.side.data();
  const float cg = g.centre, cp = p.centre, cc = c.centre;
  forVectorBlocks<L, NV>(n, [&]<int N>(int x) FGB_LAMBDA_INLINE {
    Vec ag[N], ae[N], ap[N], ac[N];
    _Pragma("GCC unroll 8") for (int v = 0; v < N; ++v) {
      const Vec mid = vecAt<L>(centre + x + v * L);
      ag[v] = mid * cg;
      ae[v] = Vec{};
      ap[v] = mid * cp;
      ac[v] = mid * cc;
    }
    for (int i = 1; i <= r; ++i) {
      const float* after = base + offsets[r + i] + x;
      const float* before = base + offsets[r - i] + x;
      const float wg = sideG[i], we = sideE[i], wp = sideP[i], wc = sideC[i];
      _Pragma("GCC unroll 8") for (int v = 0; v < N; ++v) {
        const Vec a = vecAt<L>(after + v * L), b = vecAt<L>(before + v * L);
        const Vec sum = a + b;
        ag[v] += wg * sum;
        ae[v] += we * (a - b);
        ap[v] += wp * sum;
        ac[v] += wc * sum;
      }
    }
    _Pragma("GCC unroll 8") for (int v = 0; v < N; ++v) {
      vecAt<L>(outG + x + v * L) = ag[v];
      vecAt<L>(outE + x + v * L) = ae[v];
      vecAt<L>(outP + x + v * L) = ap[v];
      vecAt<L>(outC + x + v * L) = ac[v];
    }
  });
}

// K kernels of one radius r over one input plane, for Q consecutive output rows y .. y + Q - 1 at
// once (a vertical pass): out[q * K + k] = kernel k at row y + q. offsets[d + r] is input row y + d
// for d in [-r, r + Q - 1]. The rows the Q windows share are loaded once: each step i of the folded
// kernel loads the two rows entering the windows (y + Q - 1 + i + 1 above, y - i - 1 below) and
// reuses the other 2Q - 2 from registers, about 2r / Q + 1 loads per output row instead of 2r + 1.
// The registers holding the windows are used round-robin (steps unrolled by Q), so nothing moves
// between them. Kernel k is odd when bit k of OddMask is set.
template <int L, int NV, int Q, int K, unsigned OddMask>
FGB_INLINE void convolveRows(const float* base, const std::ptrdiff_t* offsets, const FoldedKernel* const* kernels, float* const* out,
                             int n) {
  using Vec = typename VecTraits<L>::V;
  const int r = kernels[0]->radius;
  const float* sides[K];
  float centres[K];
  for (int k = 0; k < K; ++k) {
    sides[k] = kernels[k]->side.data();
    centres[k] = kernels[k]->centre;
  }
  constexpr auto odd = [](int k) { return ((OddMask >> k) & 1u) != 0; };
  constexpr auto mod = [](int a) { return ((a % Q) + Q) % Q; };
  const std::ptrdiff_t* window = offsets + r;  // window[d]: input row y + d
  forVectorBlocks<L, NV>(n, [&]<int N>(int x) FGB_LAMBDA_INLINE {
    Vec acc[Q][K][N];
    // At step i, above[m] holds the input row y + d with d = i .. i + Q - 1, d = m (mod Q), and
    // below[m] the row y + d with d = -i .. Q - 1 - i, d = m (mod Q): output row y + q reads
    // above[(q + i) % Q] and below[(q - i) % Q].
    Vec above[Q][N], below[Q][N];
    _Pragma("GCC unroll 8") for (int v = 0; v < N; ++v) {
      Vec rows[Q + 2];  // input rows y - 1 .. y + Q
      _Pragma("GCC unroll 8") for (int d = -1; d <= Q; ++d) rows[d + 1] = vecAt<L>(base + window[d] + x + v * L);
      _Pragma("GCC unroll 8") for (int q = 0; q < Q; ++q) {
        _Pragma("GCC unroll 4") for (int k = 0; k < K; ++k) acc[q][k][v] = odd(k) ? Vec{} : rows[q + 1] * centres[k];
        above[mod(q + 1)][v] = rows[q + 2];  // step 1: rows y + 1 .. y + Q
        below[mod(q - 1)][v] = rows[q];      // step 1: rows y - 1 .. y + Q - 2
      }
    }
    // Step i (residue J = i mod Q, known at compile time), then the rows of step i + 1 come in.
    auto step = [&]<int J>(int i) FGB_LAMBDA_INLINE {
      float w[K];
      _Pragma("GCC unroll 4") for (int k = 0; k < K; ++k) w[k] = sides[k][i];
      _Pragma("GCC unroll 8") for (int v = 0; v < N; ++v) {
        _Pragma("GCC unroll 8") for (int q = 0; q < Q; ++q) {
          const Vec& a = above[mod(q + J)][v];
          const Vec& b = below[mod(q - J)][v];
          const Vec sum = a + b;
          Vec difference{};
          if constexpr (OddMask != 0) difference = a - b;
          _Pragma("GCC unroll 4") for (int k = 0; k < K; ++k) acc[q][k][v] += w[k] * (odd(k) ? difference : sum);
        }
      }
      if (i == r) return;
      // Row y + i leaves the top window for row y + Q + i; row y + Q - 1 - i leaves the bottom one
      // for row y - i - 1.
      const float* nextAbove = base + window[Q + i] + x;
      const float* nextBelow = base + window[-i - 1] + x;
      _Pragma("GCC unroll 8") for (int v = 0; v < N; ++v) {
        above[mod(J)][v] = vecAt<L>(nextAbove + v * L);
        below[mod(-J - 1)][v] = vecAt<L>(nextBelow + v * L);
      }
    };
    int i = 1;
    for (; i + Q - 1 <= r; i += Q) {
      [&]<int... J>(std::integer_sequence<int, J...>) FGB_LAMBDA_INLINE { (step.template operator()<J + 1>(i + J), ...); }
      (std::make_integer_sequence<int, Q>{});
    }
    [&]<int... J>(std::integer_sequence<int, J...>) FGB_LAMBDA_INLINE {
      ((i + J <= r ? step.template operator()<J + 1>(i + J) : void()), ...);
    }
    (std::make_integer_sequence<int, Q - 1>{});
    _Pragma("GCC unroll 8") for (int v = 0; v < N; ++v) {
      _Pragma("GCC unroll 8") for (int q = 0; q < Q; ++q) {
        _Pragma("GCC unroll 4") for (int k = 0; k < K; ++k) vecAt<L>(out[q * K + k] + x + v * L) = acc[q][k][v];
      }
    }
  });
}

// 2^x and x^e for the per-pixel loops: polynomial forms that vectorise (libm's powf does not and
// was a sixth of FLIP's time). Relative error below 1e-6, far under what FLIP's outputs resolve.
FGB_INLINE float fastExp2(float x) {
  // 2^x = 2^n * 2^f with n = round(x), f in [-0.5, 0.5]; 2^f = e^(f ln 2) by its Taylor series to
  // degree 7 (remainder < 1e-8).
  const float clamped = std::clamp(x, -126.0f, 127.0f);
  // n = round(clamped) by the 1.5 * 2^23 trick: the sum's low mantissa bits are the integer. No
  // floor() (no SSE2 instruction: a libm call kept the baseline build's loops from vectorising) and
  // no float-to-int conversion (which GCC will not execute speculatively, so callers that select
  // the result stayed branches on AVX2/AVX-512).
  constexpr float kRound = 12582912.0f;
  const float shifted = clamped + kRound;
  const float n = shifted - kRound;
  int32_t shiftedBits, roundBits;
  std::memcpy(&shiftedBits, &shifted, sizeof shiftedBits);
  std::memcpy(&roundBits, &kRound, sizeof roundBits);
  const int32_t exponent = shiftedBits - roundBits;
  const float t = (clamped - n) * 0.69314718f;
  float p = 1.0f / 5040.0f;
  p = p * t + 1.0f / 720.0f;
  p = p * t + 1.0f / 120.0f;
  p = p * t + 1.0f / 24.0f;
  p = p * t + 1.0f / 6.0f;
  p = p * t + 0.5f;
  p = p * t + 1.0f;
  p = p * t + 1.0f;
  const auto exponentBits = static_cast<uint32_t>(exponent + 127) << 23;
  float scaleBy;
  std::memcpy(&scaleBy, &exponentBits, sizeof scaleBy);
  return p * scaleBy;
}

FGB_INLINE float fastLog2(float x) {
  // x = m * 2^e with m in [sqrt(1/2), sqrt(2)); ln m = 2 atanh(s), s = (m-1)/(m+1), |s| < 0.172,
  // by its series to s^9 (remainder < 1e-9).
  uint32_t bits;
  std::memcpy(&bits, &x, sizeof bits);
  int32_t e = static_cast<int32_t>((bits >> 23) & 0xffu) - 127;
  uint32_t mantissaBits = (bits & 0x7fffffu) | 0x3f800000u;  // m in [1, 2)
  float m;
  std::memcpy(&m, &mantissaBits, sizeof m);
  const bool upper = m > 1.41421356f;  // a select, not a branch: keeps the callers' loops vectorisable
  m = upper ? m * 0.5f : m;
  e += upper ? 1 : 0;
  const float s = (m - 1.0f) / (m + 1.0f);
  const float s2 = s * s;
  float series = 1.0f / 9.0f;
  series = series * s2 + 1.0f / 7.0f;
  series = series * s2 + 1.0f / 5.0f;
  series = series * s2 + 1.0f / 3.0f;
  series = series * s2 + 1.0f;
  return static_cast<float>(e) + 2.0f * s * series * 1.44269504f;  // ln -> log2
}

// Cube root for the L*a*b* transform (relative error < 3e-7, as libm's cbrtf rounded to float):
// a bit-trick estimate r of x^(-1/3) within 4%, two third-order steps r *= 1 + e/3 + 2e^2/9 with
// e = 1 - x r^3 (the series of (1 - e)^(-1/3); no division), then x r^2. Branch-free so the loops
// vectorise. Inputs <= 0 give a small positive number, which the caller never selects (L*a*b*
// uses the linear segment there).
FGB_INLINE float fastCbrt(float x) {
  const float v = std::max(x, 1e-30f);
  int32_t bits;
  std::memcpy(&bits, &v, sizeof bits);
  // 2^(-e/3): the exponent field divided by 3 (in float: an estimate needs no exact division).
  const auto third = static_cast<int32_t>(static_cast<float>(bits) * (1.0f / 3.0f));
  const int32_t estimateBits = 0x54a2fa8c - third;
  float r;
  std::memcpy(&r, &estimateBits, sizeof r);
  for (int i = 0; i < 2; ++i) {
    const float e = 1.0f - v * (r * r * r);
    r += r * (e * (e * (2.0f / 9.0f) + 1.0f / 3.0f));
  }
  return v * r * r;
}

// x > 0 only; 0 otherwise.
FGB_INLINE float fastPow(float x, float e) {
  const float power = fastExp2(e * fastLog2(x));  // computed either way: the loops stay branch-free
  return x > 0.0f ? power : 0.0f;
}

}  // namespace fgb::harness::flip_detail
