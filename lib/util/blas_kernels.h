/**
 * @file blas_kernels.h
 * Which kernels OpenBLAS runs, and the switch to the fast ones on CPUs it
 * does not recognise.
 */
#ifndef dualcontact_util_blas_kernels_h
#define dualcontact_util_blas_kernels_h

#include <string>

namespace dualcontact
{
  namespace util
  {
    /**
     * The name of the kernel set OpenBLAS chose when it was loaded
     * ("Haswell", "SkylakeX", "Prescott", ...), or "" if the BLAS in use is
     * not OpenBLAS.
     */
    std::string
    blas_core_name();

    /**
     * OpenBLAS picks its kernels from the CPU model when it is loaded.  On
     * a model it does not know (the generic "Intel(R) Xeon(R) Processor" of
     * virtual machines) it falls back to the Prescott (SSE3) kernels, even
     * when the CPU has AVX2 and FMA: on this project's machines a dsymv of
     * order 207 then takes 13.6 us instead of 3.9 us with the Haswell
     * kernels, and the sparse factorizations (CHOLMOD, UMFPACK) and the
     * dense Delassus products of the FCLIB solver are slowed alike.
     *
     * If OpenBLAS runs the Prescott kernels, the CPU has AVX2 and FMA, and
     * OPENBLAS_CORETYPE is not set, this sets OPENBLAS_CORETYPE=Haswell and
     * executes the program again with the same arguments (OpenBLAS reads
     * the variable only when it is loaded); otherwise, or if the exec
     * fails, it returns and nothing changes.  Setting OPENBLAS_CORETYPE
     * (to any value, e.g. Prescott) keeps the user's choice.  Call it
     * first in main(), before MPI, threads or output start.
     */
    void
    use_fast_blas_kernels(char **argv);
  } // namespace util
} // namespace dualcontact

#endif
