#include <driver/run_log.h>

#include <iomanip>
#include <sstream>

namespace dualcontact
{
  namespace driver
  {
    RunLog::RunLog(dealii::ConditionalOStream &console, io::ConsoleLog *log)
        : console_(console)
        , log_(log)
    {
    }


    void
    RunLog::set_parameters(const OutputParameters &output)
    {
      const std::string &verbosity = output.verbosity;
      progress_interval_           = output.progress_interval;
      verbosity_                   = verbosity == "quiet" ? Verbosity::quiet :
                                     verbosity == "detailed" ? Verbosity::detailed :
                                                               Verbosity::normal;
      if (log_ != nullptr)
        log_->show_on_terminal(verbosity_ != Verbosity::quiet);
    }


    void
    RunLog::start_phase(const std::string &name)
    {
      close_open_line();
      std::ostringstream line;
      line << "  " << std::left << std::setw(16) << name;
      console_ << line.str() << std::flush;
      line_open_ = true;
    }


    void
    RunLog::end_phase(const std::string &name, const double seconds)
    {
      std::ostringstream line;
      if (!line_open_)
        line << "  " << std::left << std::setw(16) << name;
      line << std::right << std::fixed << std::setprecision(3) << std::setw(9)
           << seconds << " s";
      console_ << line.str() << std::endl;
      line_open_ = false;
    }


    void
    RunLog::close_open_line() const
    {
      if (line_open_)
        console_ << "started" << std::endl;
      line_open_ = false;
    }


    void
    RunLog::progress(const std::string &line) const
    {
      close_open_line();
      console_ << "      " << line << std::endl;
    }


    qp::ProgressMonitor
    RunLog::qp_monitor() const
    {
      qp::ProgressMonitor monitor;
      monitor.interval       = progress_interval_;
      const bool every_start = verbosity_ == Verbosity::detailed;
      monitor.report = [this, every_start](const qp::ProgressReport &report)
      {
        if (report.first && !every_start)
          return;
        std::ostringstream line;
        line << std::setprecision(3) << "QP " << report.solver << ": iteration "
             << report.iterations << ", criterion " << report.criterion
             << " (tolerance " << report.tolerance << ")";
        if (report.n_blocks >= 0)
          line << ", active " << report.n_active << " of " << report.n_blocks
               << " blocks";
        line << ", " << report.n_hessian_products << " Hessian products, "
             << std::fixed << std::setprecision(1) << report.elapsed << " s";
        progress(line.str());
      };
      return monitor;
    }


    std::function<void(const std::string &)>
    RunLog::monitor() const
    {
      return [this](const std::string &line) { progress(line); };
    }


    void
    RunLog::coulomb_iterate(const unsigned int iterate,
                            const double       change,
                            const double       tolerance,
                            const unsigned int qp_iterations,
                            const double       elapsed)
    {
      if (iterate == 1)
        next_coulomb_line_ = 0.;
      if (verbosity_ != Verbosity::detailed && elapsed < next_coulomb_line_)
        return;
      std::ostringstream line;
      line << std::setprecision(3) << "Coulomb iterate " << iterate
           << ": change of psi " << change << " (tolerance " << tolerance
           << "), " << qp_iterations << " QP iterations, " << std::fixed
           << std::setprecision(1) << elapsed << " s";
      progress(line.str());
      next_coulomb_line_ = elapsed + progress_interval_;
    }


    void
    RunLog::record(const std::string &text)
    {
      if (log_ != nullptr)
        log_->add_to_record(text);
    }


    std::string
    RunLog::text() const
    {
      return log_ != nullptr ? log_->text() : std::string();
    }
  } // namespace driver
} // namespace dualcontact
