#include <deal.II/base/exceptions.h>

#include <qp/apgd.h>
#include <qp/mpgp.h>
#include <qp/mpgp_bb.h>
#include <qp/mprgp.h>
#include <qp/mwpgp.h>
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
       * Adding a solver: its class, one line here.
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
        DUALCONTACT_QP_REGISTER_SOLVER(
          registry,
          MPGPBB,
          "mpgp-bb",
          any,
          "MPGP with Barzilai-Borwein projection steps under a non-monotone "
          "safeguard (thesis 2.4.2), any separable set");
        DUALCONTACT_QP_REGISTER_SOLVER(
          registry,
          MwPGP,
          "mwpgp",
          any,
          "MPGP with the weak proportioning test (thesis 2.4.3), any "
          "separable set");
        DUALCONTACT_QP_REGISTER_SOLVER(
          registry,
          SPGQP,
          "spg-qp",
          any,
          "spectral projected gradient (thesis 2.1.4, algorithm 4)");
        DUALCONTACT_QP_REGISTER_SOLVER(
          registry,
          PBBf,
          "pbbf",
          any,
          "projected Barzilai-Borwein with fall-back (thesis 2.2, "
          "algorithm 5)");
        DUALCONTACT_QP_REGISTER_SOLVER(
          registry,
          APGD,
          "apgd",
          any,
          "Nesterov's accelerated projected gradient descent (thesis 2.3, "
          "algorithm 6)");
        // SolverChain's second constructor argument (the SMALSE-M settings)
        // keeps its default here; make_solver() passes the caller's.  Not
        // chainable: the chain creates the solvers of a chain.
        registry.add(solver_entry<SolverChain>(
          "auto",
          any,
          "chosen by the constraint types, with fall-back to the next "
          "solver of `Auto chain for bounds' / `Auto chain for general "
          "sets' when one does not converge (SMALSE-M around each with "
          "equality constraints)",
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
      entries.push_back(std::move(entry));
    }


    const SolverEntry *
    SolverRegistry::find(const std::string &name) const
    {
      for (const SolverEntry &entry : entries)
        if (entry.name == name)
          return &entry;
      return nullptr;
    }


    std::vector<std::string>
    SolverRegistry::names() const
    {
      std::vector<std::string> result;
      for (const SolverEntry &entry : entries)
        result.push_back(entry.name);
      return result;
    }


    std::vector<std::string>
    SolverRegistry::chainable_names(const bool general) const
    {
      std::vector<std::string> result;
      for (const SolverEntry &entry : entries)
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
      for (const SolverEntry &entry : entries)
        text +=
          (text.empty() ? "" : "; ") + entry.name + ": " + entry.description;
      return text;
    }
  } // namespace qp
} // namespace dualcontact
