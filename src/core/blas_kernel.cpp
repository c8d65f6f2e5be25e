#include "core/blas_kernel.hpp"

#include <dlfcn.h>
#include <unistd.h>

#include <cstdlib>

namespace mimic {

void pin_blas_kernel(char** argv) {
#if defined(__x86_64__)
  if (!__builtin_cpu_supports("avx2") || !__builtin_cpu_supports("fma")) return;
  // LibTorch reads its variable at its first operation: setting it now is soon enough.
  if (std::getenv("ATEN_CPU_CAPABILITY") == nullptr) setenv("ATEN_CPU_CAPABILITY", "avx2", 1);
  if (std::getenv("OPENBLAS_CORETYPE") != nullptr) return;
  setenv("OPENBLAS_CORETYPE", "Haswell", 1);
  execv("/proc/self/exe", argv);
  // Not re-executed: this process keeps the kernel OpenBLAS chose.
#else
  (void)argv;
#endif
}

const char* blas_kernel_name() {
  using CoreName = char* (*)();
  if (auto* f = reinterpret_cast<CoreName>(dlsym(RTLD_DEFAULT, "openblas_get_corename"))) return f();
  return "";
}

}  // namespace mimic
