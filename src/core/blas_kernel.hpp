#pragma once
// The same numbers on every x86-64 machine. OpenBLAS picks its kernels by CPU when it loads (an
// AVX-512 machine gets SkylakeX's, an AVX2 one Haswell's) and they round differently; a policy
// is a chaotic system, so a seed's run, evaluation or video changed with the machine (a shipped
// walk fell in 2 of 10 trials on AVX-512 kernels and in none on AVX2 ones). Programs call this
// first thing in main.

namespace mimic {

// On a CPU with AVX2 and FMA: caps LibTorch's own vector kernels at AVX2 (ATEN_CPU_CAPABILITY,
// unless set) and, where OPENBLAS_CORETYPE is unset, sets it to Haswell and executes the program
// again from the start with the same arguments, as OpenBLAS reads it only when it loads. Returns
// where it does not re-execute: the variable was set (a user's choice of kernel is kept), another
// CPU, or the re-execution failed.
void pin_blas_kernel(char** argv);

// The kernel the loaded OpenBLAS uses ("Haswell"), or "" where it cannot say.
const char* blas_kernel_name();

}  // namespace mimic
