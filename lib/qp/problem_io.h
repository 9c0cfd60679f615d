/**
 * @file problem_io.h
 * Reading and writing a QP as files: the PROBLEM.json format of `qpsolve`,
 * Matrix Market matrices and plain vectors.
 *
 * Why a file format at all: the QP library must be usable and testable
 * without any mesh (design.md, "qpsolve"), and problems exported from a
 * contact run, or generated (membrane benchmark), must be solvable by every
 * solver from the command line.  The readers are written for size: a Hessian
 * with 10^6 rows and 5*10^6 non-zeros is read in a few seconds (the whole
 * file is read at once and parsed with std::from_chars; the sparsity pattern
 * is built row by row from a counting sort, never through a dynamic
 * pattern).
 *
 * Every error message names the file and, where there is one, the line or
 * the JSON field, because the user has to find the mistake in a file that
 * may have millions of lines.
 */
#ifndef dualcontact_qp_problem_io_h
#define dualcontact_qp_problem_io_h

#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/sparsity_pattern.h>
#include <deal.II/lac/vector.h>

#include <memory>
#include <string>
#include <vector>

namespace dualcontact
{
  namespace qp
  {
    /**
     * A QP as read from (or to be written to) files:
     * minimize 1/2 x'Ax - b'x over x in a separable set, optionally Bx = c.
     *
     * The constraint blocks are kept as plain data (type name and per-block
     * values) rather than as a SeparableSet: reading files must not depend
     * on how the solver library represents sets, and the same data is
     * written back by write_problem().
     *
     * Not copyable or movable: the matrices refer to their sparsity
     * patterns (deal.II SmartPointer), so the object lives behind a
     * std::unique_ptr.
     */
    struct ProblemData
    {
      /**
       * One entry of the "constraints" array.  Values are expanded to one
       * per unknown (bound, box) or per block (disc radius, cone mu,
       * ellipse rotation), two per block for ellipse axes.
       */
      struct ConstraintBlock
      {
        /// "bound", "box", "disc", "ellipse" or "cone"
        std::string type;
        /// first unknown of the first block
        unsigned int first = 0;
        /// unknowns for bound/box, blocks for disc/ellipse/cone
        unsigned int count = 0;
        /// bound, box: per unknown
        std::vector<double> lower;
        /// box: per unknown
        std::vector<double> upper;
        /// disc: per block
        std::vector<double> radius;
        /// ellipse: two semi-axes per block, along the block's two unknowns
        std::vector<double> axes;
        /// ellipse: rotation angle (radians) per block; empty = none
        std::vector<double> rotation;
        /// cone: friction coefficient per block
        std::vector<double> mu;

        /// unknowns per block of this type (1, 1, 2, 2, 3)
        unsigned int
        block_size() const;
        /// number of unknowns covered (64-bit: count * 3 of a cone block
        /// may exceed 2^32 in a hostile file; the reader checks it
        /// against the problem size)
        std::size_t
        n_unknowns() const;
      };

      ProblemData()                    = default;
      ProblemData(const ProblemData &) = delete;
      ProblemData &
      operator=(const ProblemData &) = delete;

      /// number of unknowns
      unsigned int
      size() const;

      dealii::SparsityPattern      hessian_pattern;
      dealii::SparseMatrix<double> hessian;
      dealii::Vector<double>       rhs;
      /// empty if no initial guess was given
      dealii::Vector<double> x0;

      std::vector<ConstraintBlock> constraints;

      /// equality constraints Bx = c (has_equality() tells if present)
      dealii::SparsityPattern      equality_pattern;
      dealii::SparseMatrix<double> equality_matrix;
      dealii::Vector<double>       equality_rhs;

      bool
      has_equality() const;

      /// file names the problem was read from (for messages)
      std::string source;
    };


    /**
     * Read a Matrix Market file ("coordinate real|integer general|symmetric")
     * into @p pattern and @p matrix.  Symmetric files may give either
     * triangle; the other one is mirrored.  Duplicate entries are summed
     * (as most readers do).  Throws ExcMessage naming the file and the line
     * on any error.
     */
    void
    read_matrix_market(const std::string            &filename,
                       dealii::SparsityPattern      &pattern,
                       dealii::SparseMatrix<double> &matrix);

    /**
     * Write @p matrix in Matrix Market coordinate format; with
     * @p symmetric only the lower triangle is written (the matrix is
     * assumed symmetric, not checked).
     */
    void
    write_matrix_market(const std::string                  &filename,
                        const dealii::SparseMatrix<double> &matrix,
                        const bool                          symmetric);

    /**
     * Read a vector stored as one number per line.  Blank lines and lines
     * starting with '%' or '#' are skipped.  If @p expected_size is not
     * -1, the number of values must match it; @p what names the quantity in
     * the message ("rhs", "constraints[2].lower").
     */
    std::vector<double>
    read_vector_file(const std::string &filename,
                     const long         expected_size = -1,
                     const std::string &what          = "");

    /// Write one number per line, with full precision.
    void
    write_vector_file(const std::string         &filename,
                      const std::vector<double> &values);

    /// As above, for a deal.II vector.
    void
    write_vector_file(const std::string            &filename,
                      const dealii::Vector<double> &values);

    /**
     * Read PROBLEM.json (format: issue 3 and lib/qp/README.md).  File names
     * inside are relative to the directory of @p json_filename.  Validates
     * everything that can be validated without solving: unknown keys,
     * types, sizes, block ranges inside [0, n) and not overlapping, lower <=
     * upper, positive radii and axes, non-negative mu, the shapes of B and c.
     */
    std::unique_ptr<ProblemData>
    read_problem(const std::string &json_filename);

    /**
     * The text of a deal.II ExcMessage without the banner, file/line and
     * stack trace, with deal.II's line wrapping undone: what a command-line
     * tool shows its user.  Other exceptions: what().
     */
    std::string
    plain_message(const std::exception &exception);

    /**
     * Write @p problem as @p directory/@p name.json with the matrices and
     * vectors beside it (@p name_A.mtx, @p name_b.txt, ...).  The Hessian is
     * written as symmetric.  Returns the path of the JSON file.
     */
    std::string
    write_problem(const ProblemData &problem,
                  const std::string &directory,
                  const std::string &name);
  } // namespace qp
} // namespace dualcontact

#endif
