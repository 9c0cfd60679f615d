#include <deal.II/base/exceptions.h>

#include <qp/active_set_solver.h>
#include <qp/apgd.h>
#include <qp/cgc_solver.h>
#include <qp/pbbf.h>
#include <qp/solver_chain.h>
#include <qp/solver_registry.h>
#include <qp/spg_qp.h>

namespace dualcontact
{
  namespace qp
  {
    template <>
    const SolverEntry::Creator<dealii::Vector<double>> &
    SolverEntry::creator<dealii::Vector<double>>() const
    {
      return create_serial;
    }


    template <>
    const SolverEntry::Creator<dealii::TrilinosWrappers::MPI::Vector> &
    SolverEntry::creator<dealii::TrilinosWrappers::MPI::Vector>() const
    {
      return create_distributed;
    }


    namespace
    {
      /**
       * The solvers of the library, in the order of the thesis' chapter 2
       * (active-set, then spectral gradient), and the fall-back chain.
       * Adding a solver: its class, one line here (with its own
       * parameters: their struct, a member of SolverParameters, and
       * DUALCONTACT_QP_REGISTER_SOLVER_WITH_PARAMETERS).
       */
      void
      register_builtin_solvers(SolverRegistry &registry)
      {
        constexpr AcceptedSets bounds = AcceptedSets::bounds_and_boxes;
        constexpr AcceptedSets any    = AcceptedSets::any_separable;
        DUALCONTACT_QP_REGISTER_SOLVER(
          registry,
          MPRGP,
          "mprgp",
          bounds,
          "MPRGP (thesis 2.4.4) with the solvability test of MPRGPS "
          "(2.4.5), bound and box constraints only");
        DUALCONTACT_QP_REGISTER_SOLVER(
          registry,
          MPGP,
          "mpgp",
          any,
          "MPGP (thesis 2.4.1, algorithm 7), any separable set");
        DUALCONTACT_QP_REGISTER_SOLVER_WITH_PARAMETERS(
          registry,
          MPGPBB,
          "mpgp-bb",
          any,
          "MPGP with Barzilai-Borwein projection steps under a non-monotone "
          "safeguard (thesis 2.4.2), any separable set",
          mpgp_bb);
        DUALCONTACT_QP_REGISTER_SOLVER_WITH_PARAMETERS(
          registry,
          MwPGP,
          "mwpgp",
          any,
          "MPGP with the weak proportioning test (thesis 2.4.3), any "
          "separable set",
          mwpgp);
        DUALCONTACT_QP_REGISTER_SOLVER_WITH_PARAMETERS(
          registry,
          SPGQP,
          "spg-qp",
          any,
          "spectral projected gradient (thesis 2.1.4, algorithm 4)",
          spg);
        DUALCONTACT_QP_REGISTER_SOLVER_WITH_PARAMETERS(
          registry,
          PBBf,
          "pbbf",
          any,
          "projected Barzilai-Borwein with fall-back (thesis 2.2, "
          "algorithm 5)",
          pbbf);
        DUALCONTACT_QP_REGISTER_SOLVER_WITH_PARAMETERS(
          registry,
          APGD,
          "apgd",
          any,
          "Nesterov's accelerated projected gradient descent (thesis 2.3, "
          "algorithm 6)",
          apgd);
        registry.add(cgc_solver_entry());
        // SolverChain's second constructor argument (the SMALSE-M settings)
        // keeps its default here; make_solver() passes the caller's.  Not
        // chainable: the chain creates the solvers of a chain.
        registry.add(solver_entry<SolverChain>(
          "auto",
          any,
          "chosen by the constraint types, with fall-back to the next "
          "solver of `Auto/Chain for bounds' / `Auto/Chain for general "
          "sets' when one does not converge (SMALSE-M around each with "
          "equality constraints)",
          &SolverParameters::auto_chain,
          false));
      }
    } // namespace


    SolverRegistry &
    SolverRegistry::instance()
    {
      static SolverRegistry registry = []()
      {
        SolverRegistry r;
        register_builtin_solvers(r);
        return r;
      }();
      return registry;
    }


    void
    SolverRegistry::add(SolverEntry entry)
    {
      AssertThrow(!entry.name.empty() &&
                    entry.name.find_first_of("|, ") == std::string::npos,
                  dealii::ExcMessage("QP solver name '" + entry.name +
                                     "': must be non-empty, without '|', ',' "
                                     "or spaces."));
      AssertThrow(find(entry.name) == nullptr,
                  dealii::ExcMessage("QP solver name '" + entry.name +
                                     "' is registered twice."));
      Assert(entry.create_serial && entry.create_distributed,
             dealii::ExcInternalError());
      for (const SolverEntry &other : entries_)
        AssertThrow(entry.parameter_subsection.empty() ||
                      entry.parameter_subsection != other.parameter_subsection,
                    dealii::ExcMessage("QP solver '" + entry.name +
                                       "': its parameter subsection `" +
                                       entry.parameter_subsection +
                                       "' is solver '" + other.name + "''s."));
      Assert(entry.parameter_subsection.empty() ==
               !(entry.declare_parameters && entry.parse_parameters &&
                 entry.check_parameters),
             dealii::ExcInternalError());
      entries_.push_back(std::move(entry));
    }


    const SolverEntry *
    SolverRegistry::find(const std::string &name) const
    {
      for (const SolverEntry &entry : entries_)
        if (entry.name == name)
          return &entry;
      return nullptr;
    }


    std::vector<std::string>
    SolverRegistry::names() const
    {
      std::vector<std::string> result;
      for (const SolverEntry &entry : entries_)
        result.push_back(entry.name);
      return result;
    }


    const std::vector<SolverEntry> &
    SolverRegistry::entries() const
    {
      return entries_;
    }


    std::vector<std::string>
    SolverRegistry::chainable_names(const bool general) const
    {
      std::vector<std::string> result;
      for (const SolverEntry &entry : entries_)
        if (entry.chainable &&
            (!general || entry.accepted_sets == AcceptedSets::any_separable))
          result.push_back(entry.name);
      return result;
    }


    std::string
    join_names(const std::vector<std::string> &names)
    {
      std::string text;
      for (const std::string &name : names)
        text += (text.empty() ? "" : "|") + name;
      return text;
    }


    std::string
    SolverRegistry::descriptions() const
    {
      std::string text;
      for (const SolverEntry &entry : entries_)
        text +=
          (text.empty() ? "" : "; ") + entry.name + ": " + entry.description;
      return text;
    }
  } // namespace qp
} // namespace dualcontact
