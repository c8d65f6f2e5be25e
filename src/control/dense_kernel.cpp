#include "control/dense_kernel.hpp"

#include <Eigen/Core>
#include <cmath>
#include <cstddef>

#if defined(__x86_64__)
#include <immintrin.h>
#endif

namespace mimic {

namespace {

using RowMajor = Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

void dense_eigen(const float* x, int n, int in, const float* w, const float* b, int out, float* y) {
  const Eigen::Map<const RowMajor> X(x, n, in), W(w, in, out);
  const Eigen::Map<const Eigen::RowVectorXf> B(b, out);
  Eigen::Map<RowMajor> Y(y, n, out);
  Y.noalias() = X * W;
  Y.rowwise() += B;
}

void dense_one_eigen(const float* x, int in, const float* w, const float* b, int out, float* y) {
  const Eigen::Map<const RowMajor> W(w, out, in);
  Eigen::Map<Eigen::VectorXf> Y(y, out);
  Y.noalias() = W * Eigen::Map<const Eigen::VectorXf>(x, in);
  Y += Eigen::Map<const Eigen::VectorXf>(b, out);
}

#if defined(__x86_64__)

__attribute__((target("avx2,fma"))) inline float horizontal_sum(__m256 v) {
  const __m128 s = _mm_add_ps(_mm256_castps256_ps128(v), _mm256_extractf128_ps(v, 1));
  const __m128 t = _mm_add_ps(s, _mm_movehl_ps(s, s));
  return _mm_cvtss_f32(_mm_add_ss(t, _mm_shuffle_ps(t, t, 1)));
}

// Four outputs at a time, each a dot product over its contiguous weight row, 16 inputs a step in
// two accumulators per output (eight chains in flight), the tail one input at a time.
__attribute__((target("avx2,fma"))) void dot_rows(const float* x, int in, const float* w, const float* b, int out, float* y) {
  const std::ptrdiff_t ld = in;
  int j = 0;
  for (; j + 4 <= out; j += 4) {
    const float *w0 = w + j * ld, *w1 = w0 + ld, *w2 = w1 + ld, *w3 = w2 + ld;
    __m256 a0 = _mm256_setzero_ps(), a1 = a0, a2 = a0, a3 = a0, c0 = a0, c1 = a0, c2 = a0, c3 = a0;
    int k = 0;
    for (; k + 16 <= in; k += 16) {
      const __m256 x0 = _mm256_loadu_ps(x + k), x1 = _mm256_loadu_ps(x + k + 8);
      a0 = _mm256_fmadd_ps(_mm256_loadu_ps(w0 + k), x0, a0), c0 = _mm256_fmadd_ps(_mm256_loadu_ps(w0 + k + 8), x1, c0);
      a1 = _mm256_fmadd_ps(_mm256_loadu_ps(w1 + k), x0, a1), c1 = _mm256_fmadd_ps(_mm256_loadu_ps(w1 + k + 8), x1, c1);
      a2 = _mm256_fmadd_ps(_mm256_loadu_ps(w2 + k), x0, a2), c2 = _mm256_fmadd_ps(_mm256_loadu_ps(w2 + k + 8), x1, c2);
      a3 = _mm256_fmadd_ps(_mm256_loadu_ps(w3 + k), x0, a3), c3 = _mm256_fmadd_ps(_mm256_loadu_ps(w3 + k + 8), x1, c3);
    }
    float s0 = horizontal_sum(_mm256_add_ps(a0, c0)), s1 = horizontal_sum(_mm256_add_ps(a1, c1));
    float s2 = horizontal_sum(_mm256_add_ps(a2, c2)), s3 = horizontal_sum(_mm256_add_ps(a3, c3));
    for (; k < in; ++k) s0 = std::fma(w0[k], x[k], s0), s1 = std::fma(w1[k], x[k], s1), s2 = std::fma(w2[k], x[k], s2), s3 = std::fma(w3[k], x[k], s3);
    y[j] = s0 + b[j], y[j + 1] = s1 + b[j + 1], y[j + 2] = s2 + b[j + 2], y[j + 3] = s3 + b[j + 3];
  }
  for (; j < out; ++j) {
    const float* wj = w + j * ld;
    __m256 a = _mm256_setzero_ps();
    int k = 0;
    for (; k + 8 <= in; k += 8) a = _mm256_fmadd_ps(_mm256_loadu_ps(wj + k), _mm256_loadu_ps(x + k), a);
    float s = horizontal_sum(a);
    for (; k < in; ++k) s = std::fma(wj[k], x[k], s);
    y[j] = s + b[j];
  }
}

// One row of x: `out` outputs in blocks of 32 (four vectors), then 8, then one at a time; for
// each input k the row's value is broadcast and multiplied into the weights' row k (`ldw` apart).
__attribute__((target("avx2,fma"))) void one_row(const float* x, int in, const float* w, std::ptrdiff_t ldw, const float* b, int out, float* y) {
  int j = 0;
  for (; j + 32 <= out; j += 32) {
    __m256 a0 = _mm256_loadu_ps(b + j), a1 = _mm256_loadu_ps(b + j + 8), a2 = _mm256_loadu_ps(b + j + 16), a3 = _mm256_loadu_ps(b + j + 24);
    const float* wk = w + j;
    for (int k = 0; k < in; ++k, wk += ldw) {
      const __m256 xk = _mm256_broadcast_ss(x + k);
      a0 = _mm256_fmadd_ps(xk, _mm256_loadu_ps(wk), a0);
      a1 = _mm256_fmadd_ps(xk, _mm256_loadu_ps(wk + 8), a1);
      a2 = _mm256_fmadd_ps(xk, _mm256_loadu_ps(wk + 16), a2);
      a3 = _mm256_fmadd_ps(xk, _mm256_loadu_ps(wk + 24), a3);
    }
    _mm256_storeu_ps(y + j, a0), _mm256_storeu_ps(y + j + 8, a1), _mm256_storeu_ps(y + j + 16, a2), _mm256_storeu_ps(y + j + 24, a3);
  }
  for (; j + 8 <= out; j += 8) {
    __m256 a = _mm256_loadu_ps(b + j);
    const float* wk = w + j;
    for (int k = 0; k < in; ++k, wk += ldw) a = _mm256_fmadd_ps(_mm256_broadcast_ss(x + k), _mm256_loadu_ps(wk), a);
    _mm256_storeu_ps(y + j, a);
  }
  for (; j < out; ++j) {
    float s = b[j];
    for (int k = 0; k < in; ++k) s = std::fma(x[k], w[k * ldw + j], s);
    y[j] = s;
  }
}

// R rows of x (4 or 6) by sixteen outputs (two vectors per row, 2R accumulators): each weight
// loaded serves R rows. Written out by hand: GCC keeps these in registers only when unrolled.
template <int R>
__attribute__((target("avx2,fma"))) void block_16(const float* x, std::ptrdiff_t xs, int in, const float* w, std::ptrdiff_t ldw, const float* b,
                                                  float* y, std::ptrdiff_t ys) {
  static_assert(R == 4 || R == 6);
  const __m256 b0 = _mm256_loadu_ps(b), b1 = _mm256_loadu_ps(b + 8);
  __m256 a00 = b0, a01 = b1, a10 = b0, a11 = b1, a20 = b0, a21 = b1, a30 = b0, a31 = b1, a40 = b0, a41 = b1, a50 = b0, a51 = b1;
  const float* wk = w;
  for (int k = 0; k < in; ++k, wk += ldw) {
    const __m256 w0 = _mm256_loadu_ps(wk), w1 = _mm256_loadu_ps(wk + 8);
    __m256 xk = _mm256_broadcast_ss(x + k);
    a00 = _mm256_fmadd_ps(xk, w0, a00), a01 = _mm256_fmadd_ps(xk, w1, a01);
    xk = _mm256_broadcast_ss(x + xs + k);
    a10 = _mm256_fmadd_ps(xk, w0, a10), a11 = _mm256_fmadd_ps(xk, w1, a11);
    xk = _mm256_broadcast_ss(x + 2 * xs + k);
    a20 = _mm256_fmadd_ps(xk, w0, a20), a21 = _mm256_fmadd_ps(xk, w1, a21);
    xk = _mm256_broadcast_ss(x + 3 * xs + k);
    a30 = _mm256_fmadd_ps(xk, w0, a30), a31 = _mm256_fmadd_ps(xk, w1, a31);
    if constexpr (R == 6) {
      xk = _mm256_broadcast_ss(x + 4 * xs + k);
      a40 = _mm256_fmadd_ps(xk, w0, a40), a41 = _mm256_fmadd_ps(xk, w1, a41);
      xk = _mm256_broadcast_ss(x + 5 * xs + k);
      a50 = _mm256_fmadd_ps(xk, w0, a50), a51 = _mm256_fmadd_ps(xk, w1, a51);
    }
  }
  _mm256_storeu_ps(y, a00), _mm256_storeu_ps(y + 8, a01);
  _mm256_storeu_ps(y + ys, a10), _mm256_storeu_ps(y + ys + 8, a11);
  _mm256_storeu_ps(y + 2 * ys, a20), _mm256_storeu_ps(y + 2 * ys + 8, a21);
  _mm256_storeu_ps(y + 3 * ys, a30), _mm256_storeu_ps(y + 3 * ys + 8, a31);
  if constexpr (R == 6) {
    _mm256_storeu_ps(y + 4 * ys, a40), _mm256_storeu_ps(y + 4 * ys + 8, a41);
    _mm256_storeu_ps(y + 5 * ys, a50), _mm256_storeu_ps(y + 5 * ys + 8, a51);
  }
}

// A batch: sixteen outputs at a time over the rows in blocks of six (then four), so that those
// outputs' weights (in x 16 values) stay in the cache while the whole batch passes; the outputs
// past the last sixteen, and the rows past the blocks, by one_row.
__attribute__((target("avx2,fma"))) void dense_avx2(const float* x, int n, int in, const float* w, const float* b, int out, float* y) {
  const std::ptrdiff_t xs = in, ys = out;
  const int rows6 = n - n % 6, rows4 = rows6 + (n - rows6) / 4 * 4, cols16 = out - out % 16;
  for (int j = 0; j < cols16; j += 16) {
    for (int i = 0; i < rows6; i += 6) block_16<6>(x + i * xs, xs, in, w + j, ys, b + j, y + i * ys + j, ys);
    for (int i = rows6; i < rows4; i += 4) block_16<4>(x + i * xs, xs, in, w + j, ys, b + j, y + i * ys + j, ys);
  }
  if (cols16 < out)
    for (int i = 0; i < rows4; ++i) one_row(x + i * xs, in, w + cols16, ys, b + cols16, out - cols16, y + i * ys + cols16);
  for (int i = rows4; i < n; ++i) one_row(x + i * xs, in, w, ys, b, out, y + i * ys);
}

bool has_avx2_fma() {
  static const bool yes = __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
  return yes;
}

#else

bool has_avx2_fma() { return false; }

#endif

}  // namespace

void dense_forward(const float* x, int n, int in, const float* w, const float* b, int out, float* y) {
#if defined(__x86_64__)
  if (has_avx2_fma()) return dense_avx2(x, n, in, w, b, out, y);
#endif
  dense_eigen(x, n, in, w, b, out, y);
}

void dense_forward_one(const float* x, int in, const float* w_out_in, const float* b, int out, float* y) {
#if defined(__x86_64__)
  if (has_avx2_fma()) return dot_rows(x, in, w_out_in, b, out, y);
#endif
  dense_one_eigen(x, in, w_out_in, b, out, y);
}

void dense_forward_one_portable(const float* x, int in, const float* w_out_in, const float* b, int out, float* y) {
  dense_one_eigen(x, in, w_out_in, b, out, y);
}

void dense_forward_portable(const float* x, int n, int in, const float* w, const float* b, int out, float* y) {
  dense_eigen(x, n, in, w, b, out, y);
}

const char* dense_kernel_name() { return has_avx2_fma() ? "avx2-fma" : "eigen"; }

}  // namespace mimic
