#include <deal.II/base/exceptions.h>
#include <deal.II/base/timer.h>
#include <deal.II/lac/solver_cg.h>

#include <fem/trilinos_solver.h>

#include <sstream>

namespace dualcontact
{
  namespace fem
  {
    TrilinosSolver::TrilinosSolver(const Parameters &parameters,
                                   const MPI_Comm    communicator)
        : parameters_(parameters)
        , communicator_(communicator)
    {
      AssertThrow(parameters.cg_tolerance > 0 && parameters.cg_tolerance < 1,
                  dealii::ExcMessage(
                    "The CG tolerance must lie in (0, 1) (`set CG tolerance' "
                    "in `subsection Stiffness solver')."));
      AssertThrow(parameters.cg_max_iterations > 0,
                  dealii::ExcMessage(
                    "The CG iteration limit must be positive (`set CG max "
                    "iterations' in `subsection Stiffness solver')."));
    }


    TrilinosSolver::~TrilinosSolver() = default;


    void
    TrilinosSolver::set_locally_owned_rows(const dealii::IndexSet &rows)
    {
      requested_rows_ = rows;
    }


    void
    TrilinosSolver::set_block_size(const unsigned int block_size)
    {
      Assert(block_size > 0, dealii::ExcInternalError());
      block_size_ = block_size;
    }


    void
    TrilinosSolver::initialize(const dealii::SparseMatrix<double> &matrix)
    {
      dealii::Timer      timer;
      const unsigned int n = matrix.m();
      dealii::IndexSet   rows(n);
      if (requested_rows_.size() == n)
        rows = requested_rows_;
      else
      {
        const unsigned int n_ranks =
          dealii::Utilities::MPI::n_mpi_processes(communicator_);
        const unsigned int rank =
          dealii::Utilities::MPI::this_mpi_process(communicator_);
        // contiguous, even split in whole blocks (nodes)
        const unsigned int n_blocks =
          n % block_size_ == 0 ? n / block_size_ : n;
        const unsigned int size = n_blocks == n ? 1 : block_size_;
        rows.add_range(static_cast<dealii::types::global_dof_index>(
                         (n_blocks * static_cast<unsigned long>(rank)) /
                         n_ranks * size),
                       static_cast<dealii::types::global_dof_index>(
                         (n_blocks * static_cast<unsigned long>(rank + 1)) /
                         n_ranks * size));
      }
      AssertThrow(rows.is_contiguous(),
                  dealii::ExcMessage("TrilinosSolver: the rows of a process "
                                     "must be a contiguous range."));
      // drop tolerance 0: keep every stored nonzero, drop explicit zeros
      own_matrix_.reinit(rows, rows, matrix, communicator_, 0.);
      setup(own_matrix_);
      statistics_.setup_time = timer.wall_time();
    }


    void
    TrilinosSolver::initialize(
      const dealii::TrilinosWrappers::SparseMatrix &matrix)
    {
      dealii::Timer timer;
      setup(matrix);
      statistics_.setup_time = timer.wall_time();
    }


    void
    TrilinosSolver::setup(const dealii::TrilinosWrappers::SparseMatrix &matrix)
    {
      statistics_ = Statistics();
      matrix_     = &matrix;
      owned_rows_ = matrix.locally_owned_range_indices();
      AssertThrow(owned_rows_.is_contiguous(),
                  dealii::ExcMessage("TrilinosSolver: the rows of a process "
                                     "must be a contiguous range."));
      const int first =
        owned_rows_.n_elements() > 0 ? owned_rows_.nth_index_in_set(0) : 0;
      const int count = owned_rows_.n_elements();
      offsets_ = dealii::Utilities::MPI::all_gather(communicator_, first);
      counts_  = dealii::Utilities::MPI::all_gather(communicator_, count);
      work_x_.reinit(owned_rows_, communicator_);
      work_b_.reinit(owned_rows_, communicator_);

      direct_.reset();
      amg_.reset();
      if (parameters_.method == Method::mumps)
      {
        direct_ = std::make_unique<dealii::TrilinosWrappers::SolverDirect>(
          direct_control_,
          dealii::TrilinosWrappers::SolverDirect::AdditionalData(
            false, "Amesos_Mumps"));
        direct_->initialize(matrix);
      }
      else
      {
        dealii::TrilinosWrappers::PreconditionAMG::AdditionalData data;
        data.elliptic              = true;
        data.aggregation_threshold = parameters_.aggregation_threshold;
        data.smoother_sweeps       = parameters_.smoother_sweeps;
        data.smoother_type         = "Chebyshev";
        data.coarse_type           = "Amesos-KLU";
        const unsigned int n       = matrix.m();
        if (block_size_ > 1 && n % block_size_ == 0)
        {
          // the translations: one mask per component, the rows of each
          // node numbered consecutively
          data.constant_modes.assign(block_size_,
                                     std::vector<bool>(owned_rows_.n_elements(),
                                                       false));
          unsigned int k = 0;
          for (const auto row : owned_rows_)
            data.constant_modes[row % block_size_][k++] = true;
        }
        amg_ = std::make_unique<dealii::TrilinosWrappers::PreconditionAMG>();
        amg_->initialize(matrix, data);
      }
    }


    void
    TrilinosSolver::solve(dealii::TrilinosWrappers::MPI::Vector       &x,
                          const dealii::TrilinosWrappers::MPI::Vector &b) const
    {
      Assert(matrix_ != nullptr, dealii::ExcMessage("Not initialized."));
      dealii::Timer timer;
      if (direct_)
        direct_->solve(x, b);
      else
      {
        x                   = 0;
        const double norm_b = b.l2_norm();
        if (norm_b > 0)
        {
          dealii::SolverControl control(parameters_.cg_max_iterations,
                                        parameters_.cg_tolerance * norm_b,
                                        false,
                                        false);
          dealii::SolverCG<dealii::TrilinosWrappers::MPI::Vector> cg(control);
          try
          {
            cg.solve(*matrix_, x, b, *amg_);
          }
          catch (const dealii::SolverControl::NoConvergence &failure)
          {
            std::ostringstream message;
            message << "AMG-preconditioned CG did not converge in "
                    << failure.last_step << " iterations: relative residual "
                    << failure.last_residual / norm_b << " > tolerance "
                    << parameters_.cg_tolerance
                    << " (`set CG tolerance' and `set CG max iterations' in "
                       "`subsection Stiffness solver'; or `set Solver = "
                       "mumps').";
            AssertThrow(false, dealii::ExcMessage(message.str()));
          }
          statistics_.iterations = control.last_step();
        }
      }
      statistics_.solve_time += timer.wall_time();
      ++statistics_.n_solves;
    }


    void
    TrilinosSolver::solve(dealii::Vector<double>       &x,
                          const dealii::Vector<double> &b) const
    {
      Assert(matrix_ != nullptr, dealii::ExcMessage("Not initialized."));
      Assert(b.size() == matrix_->m(),
             dealii::ExcDimensionMismatch(b.size(), matrix_->m()));
      unsigned int k = 0;
      for (const auto row : owned_rows_)
        work_b_.begin()[k++] = b(row);
      work_b_.compress(dealii::VectorOperation::insert);
      solve(work_x_, work_b_);
      x.reinit(b.size(), true);
      // every process's contiguous range into the whole vector
      const int ierr = MPI_Allgatherv(
        work_x_.begin(),
        counts_[dealii::Utilities::MPI::this_mpi_process(communicator_)],
        MPI_DOUBLE,
        x.begin(),
        counts_.data(),
        offsets_.data(),
        MPI_DOUBLE,
        communicator_);
      AssertThrowMPI(ierr);
    }


    bool
    TrilinosSolver::is_distributed() const
    {
      return true;
    }


    std::string
    TrilinosSolver::name() const
    {
      return parameters_.method == Method::mumps ? "mumps" : "amg";
    }


    const dealii::IndexSet &
    TrilinosSolver::locally_owned_rows() const
    {
      return owned_rows_;
    }
  } // namespace fem
} // namespace dualcontact
