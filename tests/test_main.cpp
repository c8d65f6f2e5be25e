// The test programs' main: the same BLAS kernel as the `mimic` command (core/blas_kernel.hpp),
// so that tests see the numbers users do on any machine.
#include <gtest/gtest.h>

#include "core/blas_kernel.hpp"

// LeakSanitizer (the asan preset): Mesa's EGL/GL stack (software rasteriser), loaded by the
// rendering tests, keeps allocations until the process exits. Not ours to fix.
extern "C" const char* __lsan_default_suppressions();
extern "C" const char* __lsan_default_suppressions() {
  return "leak:swrast_dri.so\nleak:kms_swrast_dri.so\nleak:libgallium\nleak:libEGL_mesa.so\nleak:libglapi.so\nleak:libLLVM\n";
}
extern "C" const char* __lsan_default_options();
extern "C" const char* __lsan_default_options() { return "print_suppressions=0"; }

int main(int argc, char** argv) {
  mimic::pin_blas_kernel(argv);
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
