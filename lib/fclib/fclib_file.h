#pragma once

#include <deal.II/base/exceptions.h>
#include <deal.II/lac/vector.h>

#include <fclib/global_problem.h>
#include <fclib/local_problem.h>

#include <string>

namespace dualcontact
{
  namespace fclib
  {
    /**
     * Reading and writing FCLIB files (HDF5) through Debian's libfclib.
     *
     * Index conventions of the files (measured on the distributed ones, see
     * tests/fclib/data/README.md): in triplet storage `i` holds the row and
     * `p` the column index (libfclib's header says the opposite); a
     * symmetric M may be stored as its upper triangle only.  Matrices are
     * written in compressed columns (p = column pointers, i = row indices),
     * which is unambiguous.
     *
     * libfclib ends the process when asked for a group that is not in the
     * file, so the form of a file is looked up first (form_of()), and every
     * reader checks it.
     */
    enum class Form
    {
      local,
      global
    };

    /** "local" / "global". */
    std::string
    to_string(const Form form);

    /**
     * Whether @p path holds a local or a global problem; throws (naming the
     * file) if it does not exist, is not HDF5, or holds neither.
     */
    Form
    form_of(const std::string &path);

    /** @p storage: how W is kept for the products (DelassusOperator). */
    LocalProblem
    read_local(const std::string &path,
               const Storage      storage = Storage::automatic);

    GlobalProblem
    read_global(const std::string &path);

    /** The local form of either kind of file (a global one is reduced). */
    LocalProblem
    read_as_local(const std::string &path,
                  const Storage      storage = Storage::automatic);

    /**
     * Write @p problem to @p path (replacing the file), and, if @p r is not
     * empty, the solution r and u = W r + q into /solution.
     */
    void
    write_local(const std::string            &path,
                const LocalProblem           &problem,
                const dealii::Vector<double> &r           = {},
                const std::string            &description = "");

    /**
     * Write @p problem to @p path (replacing the file), and, if @p r is not
     * empty, the solution v = M^-1(H r + f), u = H'v + w and r.
     */
    void
    write_global(const std::string            &path,
                 const GlobalProblem          &problem,
                 const dealii::Vector<double> &r           = {},
                 const std::string            &description = "");

    /**
     * The text of an ExcMessage (print_info() without deal.II's frame), for
     * messages that wrap another one.
     */
    std::string
    exception_message(const dealii::ExceptionBase &e);

    /** The r stored in /solution, empty if the file has none. */
    dealii::Vector<double>
    read_solution_r(const std::string &path);
  } // namespace fclib
} // namespace dualcontact
