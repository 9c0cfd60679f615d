/**
 * @file blas_kernels.h
 * Which kernels OpenBLAS runs, and the choice of the fast ones on CPUs it
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
     * The name of the kernel set OpenBLAS runs ("Haswell", "SkylakeX",
     * "Prescott", ...), or "" if the BLAS in use is not OpenBLAS.
     */
    std::string
    blas_core_name();

    /**
     * OpenBLAS picks its kernels from the CPU model when it is loaded.  On
     * a model it does not know (the generic "Intel(R) Xeon(R) Processor" of
     * virtual machines) it falls back to its Prescott (SSE3) kernels, even
     * when the CPU has AVX2 or AVX-512: on this project's machines a dsymv
     * of order 207 (the Delassus product of the Hertz L3 export) then takes
     * 7.2 us instead of 4.1-4.6 us, and a dgemm of order 600 (the
     * supernodal sparse Cholesky factorization) runs at 16 GFlop/s instead
     * of 40 (Haswell kernels) or 71-74 (SkylakeX kernels); see
     * scripts/bench_blas_kernels and lib/util/README.md.
     *
     * This function mends that: if OpenBLAS runs the Prescott kernels and
     * OPENBLAS_CORETYPE is not set, it sets OPENBLAS_CORETYPE to SkylakeX
     * on a CPU with AVX-512 F, CD, BW, DQ and VL, else to Haswell on a CPU
     * with AVX2 and FMA, and has OpenBLAS choose its kernels again
     * (gotoblas_dynamic_quit / gotoblas_dynamic_init, looked up at run
     * time).  A CPU that OpenBLAS recognises keeps OpenBLAS' choice; a user
     * who sets OPENBLAS_CORETYPE (to any value, e.g. Prescott) keeps that.
     * (Setting the variable before main() does not work: glibc's own
     * initialisation resets the environment after an executable's
     * pre-initialisation, and OpenBLAS reads it in its constructor.)
     *
     * Call it first in main(), before any BLAS call, thread or MPI start.
     * Returns what it did: "" if nothing, else e.g.
     * "OPENBLAS_CORETYPE=SkylakeX (OpenBLAS chose Prescott)".
     */
    std::string
    blas_kernel_choice();

    /**
     * What the first blas_kernel_choice() of this process did: its return
     * value, or "OpenBLAS' own choice" if it changed nothing (also when
     * OPENBLAS_CORETYPE was set by the user: "OPENBLAS_CORETYPE=X set by
     * the user").  For the records (statistics.json).
     */
    std::string
    blas_kernel_report();

    /**
     * The number of threads OpenBLAS uses (openblas_get_num_threads), or 0
     * if the BLAS is not OpenBLAS.
     */
    int
    blas_threads();

    /**
     * Have OpenBLAS use @p n threads (openblas_set_num_threads; nothing for
     * another BLAS).  Under MPI every process runs its own BLAS: the
     * programs set one thread per process, so that N processes do not start
     * N times the cores' threads.
     */
    void
    set_blas_threads(const int n);

    /**
     * What `Stiffness solver / BLAS threads = automatic` gives OpenBLAS:
     * the number of threads (0: leave OpenBLAS as it is) and why.
     */
    struct BlasThreadChoice
    {
      int         threads = 0;
      std::string reason;
    };

    /**
     * One thread per process under MPI (@p n_processes > 1); the user's
     * OPENBLAS_NUM_THREADS or OMP_NUM_THREADS where set (threads 0);
     * otherwise the cores of this process' CPU set that the load average
     * leaves idle, rounded, at least one.  Why not simply every core:
     * OpenBLAS' threads wait for work by spinning, so on cores that other
     * processes keep busy they take the time slices of the thread that has
     * the work.  Measured on 2 cores (inputs/hertz_3d.prm, 26,127 dofs):
     * idle, 1.33 s with one thread, 1.23 s with two; beside two busy
     * processes 1.63 s with one, 21.9 s with two (factorization 0.6 ->
     * 12.5 s, QP 0.002 -> 0.93 s); lib/util/README.md.
     */
    BlasThreadChoice
    automatic_blas_threads(const unsigned int n_processes);

    /** Gives OpenBLAS @p choice's threads (nothing when they are 0). */
    void
    use_blas_threads(const BlasThreadChoice &choice);
  } // namespace util
} // namespace dualcontact

#endif
