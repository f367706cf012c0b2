// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#pragma once
// The dense kernels of CHOLMOD's supernodal factor, the engine's own.
//
// CHOLMOD calls six BLAS and LAPACK routines (dgemm, dsyrk, dtrsm, dpotrf for
// the factor; dtrsv, dgemv for a solve with one right-hand side). Left to the
// system's BLAS, the factor's bits depend on the machine: OpenBLAS picks its
// kernels by CPU at load time (OPENBLAS_CORETYPE), each kernel sums in its
// own order, and another machine may have another BLAS installed altogether.
// portable_blas.cpp defines these six routines under their Fortran names in
// the engine itself. The program that links the engine then exports them
// (CHOLMOD's shared library refers to them), and the dynamic linker binds
// CHOLMOD's calls to them before any BLAS library: one code, compiled with
// the engine's flags (x86-64 baseline, no FMA contraction), summing in one
// fixed order that depends on no run-time figure (no cache size, no thread
// count), so the factor is the same to the bit on every x86-64 machine.
//
// The routines follow the reference BLAS's definitions for every argument
// combination (any op, side, triangle; any stride); the combinations the
// factor spends its time in (C −= A·Bᵀ, the lower rank-k update, the solve
// X·L⁻ᵀ and the lower Cholesky factor) are blocked around one 4 × 4 product
// kernel whose sums run over k in order.
namespace dda {

// True when the process's BLAS and LAPACK symbols that CHOLMOD calls resolve
// to the engine's own (checked once: CholmodFactor refuses to run otherwise,
// rather than give machine-dependent results).
bool portable_blas_bound();

}  // namespace dda
