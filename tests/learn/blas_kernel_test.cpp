// The BLAS kernel is pinned where the CPU allows it, so a seed gives the same numbers everywhere.
#include "core/blas_kernel.hpp"

#include <gtest/gtest.h>
#include <torch/torch.h>

#include <cstdlib>
#include <string>

TEST(BlasKernel, OpenBlasRunsHaswellsKernelsOnEveryAvx2Machine) {
#if defined(__x86_64__)
  if (!__builtin_cpu_supports("avx2") || !__builtin_cpu_supports("fma")) GTEST_SKIP() << "this CPU has no AVX2 and FMA";
  const char* chosen = std::getenv("OPENBLAS_CORETYPE");
  ASSERT_NE(chosen, nullptr) << "the test program did not pin the kernel";
  ASSERT_NE(std::getenv("ATEN_CPU_CAPABILITY"), nullptr);
  // LibTorch's matrix products go to the OpenBLAS this program loaded (after a first product).
  (void)torch::mm(torch::ones({4, 4}), torch::ones({4, 4}));
  const std::string name = mimic::blas_kernel_name();
  if (std::string(chosen) == "Haswell") {
    EXPECT_EQ(name, "Haswell");
  }
  EXPECT_NE(name, "") << "OpenBLAS is not the BLAS in this program";
#else
  GTEST_SKIP() << "kernels are pinned on x86-64 only";
#endif
}
