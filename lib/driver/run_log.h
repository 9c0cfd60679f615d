#pragma once

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/parameter_handler.h>

#include <driver/output_parameters.h>

#include <io/console_log.h>
#include <qp/solver_progress.h>

#include <functional>
#include <string>

namespace dualcontact
{
  namespace driver
  {
    /** `Output/Verbosity': what the console shows. */
    enum class Verbosity
    {
      quiet,
      normal,
      detailed
    };

    /**
     * The console of a run (process 0): phase lines, progress lines during
     * long phases, and the record that becomes log.txt.
     *
     * A phase prints its name when it starts and its wall time on the same
     * line when it ends ("  Factorization       0.130 s"); if progress lines
     * come in between, the start line ends with "started" and the time gets
     * a line of its own.  Progress comes from the QP solvers
     * (qp_monitor(): iteration, criterion against tolerance, active set,
     * Hessian products, time), from the direct stiffness solvers
     * (monitor(): the factorization's size and time estimate before it, its
     * time after) and from the Coulomb fixed point (coulomb_iterate()).
     *
     * Verbosity (subsection `Output'): quiet switches the terminal off (the
     * record still gets the normal lines), detailed adds a progress line at
     * the start of every QP solve and after every Coulomb iterate.
     */
    class RunLog
    {
    public:
      /**
       * @p console prints on process 0; @p log, if not null, is the stream
       * behind it (whose text becomes log.txt, and whose terminal a quiet
       * run switches off).
       */
      RunLog(dealii::ConditionalOStream &console, io::ConsoleLog *log);

      /** Take `Verbosity' and `Progress interval' of subsection `Output'. */
      void
      set_parameters(const OutputParameters &output);

      Verbosity
      verbosity() const
      {
        return verbosity_;
      }

      /** "  Name" (padded), left open for the time. */
      void
      start_phase(const std::string &name);

      /** The time of the phase started last, on its line if still open. */
      void
      end_phase(const std::string &name, const double seconds);

      /** A progress line (indented), closing an open phase line first. */
      void
      progress(const std::string &line) const;

      /** A QP progress hook that prints through progress(). */
      qp::ProgressMonitor
      qp_monitor() const;

      /** A stiffness solver's monitor that prints through progress(). */
      std::function<void(const std::string &)>
      monitor() const;

      /**
       * A line on Coulomb iterate @p iterate (1-based) with the relative
       * change of psi against @p tolerance, the QP's iterations and the
       * time @p elapsed since the QP phase started: every iterate when
       * detailed, else at most one per progress interval.
       */
      void
      coulomb_iterate(const unsigned int iterate,
                      const double       change,
                      const double       tolerance,
                      const unsigned int qp_iterations,
                      const double       elapsed);

      /** Add @p text to the record only (an error printed on stderr). */
      void
      record(const std::string &text);

      /** Everything the console showed (and, quiet, would have shown). */
      std::string
      text() const;

    private:
      /** End an open phase line with "started". */
      void
      close_open_line() const;

      dealii::ConditionalOStream &console_;
      io::ConsoleLog             *log_;
      Verbosity                   verbosity_         = Verbosity::normal;
      double                      progress_interval_ = 5.;
      mutable bool                line_open_         = false;
      double                      next_coulomb_line_ = 0.;
    };
  } // namespace driver
} // namespace dualcontact
