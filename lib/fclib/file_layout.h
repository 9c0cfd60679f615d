#pragma once

#include <fclib/fclib_file.h>

#include <cstdint>
#include <string>

namespace dualcontact
{
  namespace fclib
  {
    /**
     * The sizes an FCLIB file declares, checked against what it holds,
     * before libfclib reads it.
     *
     * libfclib allocates every array from the header of its matrix (m, n,
     * nz, nzmax) and then reads the whole data set into it: a data set
     * longer than its header says overflows the heap, a shorter one leaves
     * the tail undefined, and a header of 10^9 entries allocates before
     * anything is read.  The constructor reads only the headers and the
     * extents (not the data), and refuses, naming the file and the data
     * set, anything that does not fit together:
     *  - every matrix: m, n >= 0, 0 <= nzmax; triplets (nz >= 0): p, i, x
     *    each of nz entries, nz <= nzmax; compressed columns (nz = -1) or
     *    rows (nz = -2): p of n + 1 or m + 1 entries, i and x of nzmax;
     *  - local: W square; q of its order, mu of one per contact; global:
     *    M square, H with as many rows as M, f of M's order, w of H's
     *    columns, mu of one per contact;
     *  - equality constraints (local V, R, s; global G, b) are refused:
     *    not supported;
     *  - /solution/r, if present, of one entry per contact unknown;
     *  - every data set stored inside the file (a file cut short after
     *    its header would make HDF5 read past its end).
     * The values of the compressed pointers are checked where they are
     * used (check_compressed_pointers()).
     */
    class FileLayout
    {
    public:
      /** Reads and checks the layout of the problem in @p path. */
      FileLayout(const std::string &path, const Form form);

      /**
       * The number of contact unknowns: W's order (local) or H's columns
       * (global).
       */
      std::uint64_t
      contact_size() const;

      /** Whether the file has /solution/r (checked to be of contact_size()). */
      bool
      has_solution() const;

    private:
      std::uint64_t contact_size_ = 0;
      bool          has_solution_ = false;
    };


    /**
     * Checks the pointers of a compressed matrix (@p n_pointers entries
     * of @p p) before they index i and x: p[0] = 0, non-decreasing, the last
     * one at most @p nzmax.  @p what names the matrix in the message.
     */
    void
    check_compressed_pointers(const int         *p,
                              const std::int64_t n_pointers,
                              const std::int64_t nzmax,
                              const std::string &what);
  } // namespace fclib
} // namespace dualcontact
