#pragma once
// The runtime's one numeric kernel: a dense layer over a batch, y = x W + b, in float32, with the
// weights stored input-major (W is [in, out], the transpose of LibTorch's [out, in]), so that
// eight outputs load as one vector. On x86-64 CPUs with AVX2 and FMA (checked when the program
// runs) a register-blocked kernel of its own; elsewhere Eigen's product. They differ in
// summation order only.
namespace mimic {

// x [n, in], w [in, out], b [out], y [n, out], all row-major and contiguous; y must not alias x.
void dense_forward(const float* x, int n, int in, const float* w, const float* b, int out, float* y);
// One row (batch 1) with the weights output-major, LibTorch's [out, in]: each output a dot
// product over a contiguous row, so that the weights stream through once (what bounds batch 1).
void dense_forward_one(const float* x, int in, const float* w_out_in, const float* b, int out, float* y);
// The portable path alone (Eigen), whatever the CPU: what other CPUs run, for tests.
void dense_forward_portable(const float* x, int n, int in, const float* w, const float* b, int out, float* y);
void dense_forward_one_portable(const float* x, int in, const float* w_out_in, const float* b, int out, float* y);

// Which kernel dense_forward uses on this CPU ("avx2-fma" or "eigen").
const char* dense_kernel_name();

}  // namespace mimic
