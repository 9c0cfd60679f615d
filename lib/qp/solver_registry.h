/**
 * @file solver_registry.h
 * The table of QP solvers: name, one-line description, the constraint sets a
 * solver accepts, how to create it for either vector type, and its own
 * parameters (their subsection of `QP solver` and the hooks that declare,
 * read and check them).  Everything
 * that lists solvers reads this table: the pattern and documentation of
 * `Solver` in `subsection QP solver`, the solvers' own subsections, the
 * checks of `Auto/Chain for ...`, qpsolve's `--solver` choices, fclibsolve's
 * `--solver` list and create().
 */
#ifndef dualcontact_qp_solver_registry_h
#define dualcontact_qp_solver_registry_h

#include <deal.II/lac/trilinos_vector.h>
#include <deal.II/lac/vector.h>

#include <qp/solver_base.h>

#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace dualcontact
{
  namespace qp
  {
    /// The constraint sets a solver accepts.
    enum class AcceptedSets
    {
      /// bounds and boxes only (mprgp)
      bounds_and_boxes,
      /// every separable block: bound, box, disc, ellipse, cone
      any_separable
    };


    /**
     * One solver of the registry.  A solver for problems with equality
     * constraints is not an entry: make_solver() wraps SMALSE-M around the
     * entry the parameters name.
     */
    struct SolverEntry
    {
      template <typename VectorType>
      using Creator = std::function<std::unique_ptr<SolverBase<VectorType>>(
        const SolverParameters &)>;

      /// the value of `Solver` ("mprgp", ...)
      std::string name;
      /// one phrase for the parameter documentation and --help
      std::string  description;
      AcceptedSets accepted_sets = AcceptedSets::any_separable;
      /// whether an `Auto/Chain for ...` parameter may name it (false for the
      /// chain itself, which creates the solvers of a chain)
      bool chainable = true;

      Creator<dealii::Vector<double>>                create_serial;
      Creator<dealii::TrilinosWrappers::MPI::Vector> create_distributed;

      /// The solver's own parameters (empty / unset: it has none, it uses
      /// only the shared ones of `subsection QP solver`): the subsection
      /// of `QP solver` they live in, and the hooks that declare them
      /// there, read them into their member of SolverParameters and check
      /// them.  SolverParameters enters and leaves the subsection around
      /// the first two.  Set by solver_entry() from a member of
      /// SolverParameters.
      std::string                                     parameter_subsection;
      std::function<void(dealii::ParameterHandler &)> declare_parameters;
      std::function<void(const dealii::ParameterHandler &, SolverParameters &)>
                                                    parse_parameters;
      std::function<void(const SolverParameters &)> check_parameters;

      /// the creator for @p VectorType
      template <typename VectorType>
      const Creator<VectorType> &
      creator() const;
    };


    // the two creators (solver_registry.cc)
    template <>
    const SolverEntry::Creator<dealii::Vector<double>> &
    SolverEntry::creator<dealii::Vector<double>>() const;
    template <>
    const SolverEntry::Creator<dealii::TrilinosWrappers::MPI::Vector> &
    SolverEntry::creator<dealii::TrilinosWrappers::MPI::Vector>() const;


    /**
     * The registered solvers, in registration order (the order of the
     * documentation and of the `Solver` pattern).
     *
     * Why one registration function (register_builtin_solvers() in
     * solver_registry.cc) and not a static registrar object in every
     * solver's file: the modules are static libraries, and the linker drops
     * an object file nothing refers to, together with its registrar, so a
     * solver would vanish from the programs that create it by name only.
     * A program or test adds its own solver with add() before parsing
     * parameters.
     */
    class SolverRegistry
    {
    public:
      /// The registry of the process, with the built-in solvers.
      static SolverRegistry &
      instance();

      /// Add @p entry; throws if its name is taken or contains '|', ',' or
      /// a space, or its parameter subsection is another entry's.  Add a
      /// solver with own parameters before SolverParameters declares them.
      void
      add(SolverEntry entry);

      /// The entry called @p name, or nullptr.
      const SolverEntry *
      find(const std::string &name) const;

      /// The names, in registration order.
      std::vector<std::string>
      names() const;

      /// The entries, in registration order (SolverParameters declares,
      /// reads and checks the solvers' own parameters through them).
      const std::vector<SolverEntry> &
      entries() const;

      /// The names the `Auto/Chain for ...` parameters may hold, for @p general
      /// (some block a disc, ellipse or cone) or bounds-only problems.
      std::vector<std::string>
      chainable_names(bool general) const;

      /// "name: description; name: description; ..." for the parameter
      /// documentation.
      std::string
      descriptions() const;

    private:
      SolverRegistry() = default;
      std::vector<SolverEntry> entries_;
    };


    /**
     * The entry of solver class @p Solver (a class template on the vector
     * type whose constructor takes SolverParameters) as @p name, accepting
     * @p sets, described by @p description; @p chainable: whether an
     * `Auto/Chain for ...` parameter may name it.  No own parameters.
     */
    template <template <typename> class Solver>
    SolverEntry
    solver_entry(const std::string &name,
                 const AcceptedSets sets,
                 const std::string &description,
                 const bool         chainable = true)
    {
      SolverEntry entry;
      entry.name          = name;
      entry.description   = description;
      entry.accepted_sets = sets;
      entry.chainable     = chainable;
      entry.create_serial = [](const SolverParameters &p)
        -> std::unique_ptr<SolverBase<dealii::Vector<double>>>
      { return std::make_unique<Solver<dealii::Vector<double>>>(p); };
      entry.create_distributed = [](const SolverParameters &p)
        -> std::unique_ptr<SolverBase<dealii::TrilinosWrappers::MPI::Vector>> {
        return std::make_unique<Solver<dealii::TrilinosWrappers::MPI::Vector>>(
          p);
      };
      return entry;
    }


    /**
     * The entry of solver class @p Solver as solver_entry() above, with own
     * parameters: the member @p own of SolverParameters, a struct with a
     * `subsection` name, `declare_parameters(prm)`, `parse_parameters(prm)`
     * and `check()` (e.g. SPGQPParameters, solver_parameters.h).
     */
    template <template <typename> class Solver, typename Own>
    SolverEntry
    solver_entry(const std::string &name,
                 const AcceptedSets sets,
                 const std::string &description,
                 Own SolverParameters::*own,
                 const bool             chainable = true)
    {
      SolverEntry entry =
        solver_entry<Solver>(name, sets, description, chainable);
      entry.parameter_subsection = Own::subsection;
      entry.declare_parameters   = [](dealii::ParameterHandler &prm)
      { Own::declare_parameters(prm); };
      entry.parse_parameters =
        [own](const dealii::ParameterHandler &prm, SolverParameters &p)
      { (p.*own).parse_parameters(prm); };
      entry.check_parameters = [own](const SolverParameters &p)
      { (p.*own).check(); };
      return entry;
    }


    /// @p names separated by '|' (a Patterns::Selection, a --solver list).
    std::string
    join_names(const std::vector<std::string> &names);


    /**
     * Registers solver class @p Class as @p key (solver_entry()): used in
     * register_builtin_solvers(); a program adds its own solvers the same
     * way.
     */
#define DUALCONTACT_QP_REGISTER_SOLVER(registry, Class, key, sets, text) \
  (registry).add(::dualcontact::qp::solver_entry<Class>(key, sets, text))

    /**
     * Registers solver class @p Class as @p key with its own parameters,
     * the member @p own of SolverParameters (declared in their subsection
     * of `QP solver`, read and checked through the entry).
     */
#define DUALCONTACT_QP_REGISTER_SOLVER_WITH_PARAMETERS(  \
  registry, Class, key, sets, text, own)                 \
  (registry).add(::dualcontact::qp::solver_entry<Class>( \
    key, sets, text, &::dualcontact::qp::SolverParameters::own))
  } // namespace qp
} // namespace dualcontact

#endif
