/**
 * @file solver_registry.h
 * The table of QP solvers: name, one-line description, the constraint sets a
 * solver accepts, and how to create it for either vector type.  Everything
 * that lists solvers reads this table: the pattern and documentation of
 * `Solver` in `subsection QP solver`, the checks of the `Auto chain ...`
 * parameters, qpsolve's `--solver` choices, fclibsolve's `--solver` list
 * and create().
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
      /// whether an `Auto chain ...` parameter may name it (false for the
      /// chain itself)
      bool chainable = true;

      Creator<dealii::Vector<double>>                create_serial;
      Creator<dealii::TrilinosWrappers::MPI::Vector> create_distributed;

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

      /// Add @p entry; throws if its name is taken or contains '|' or ','.
      void
      add(SolverEntry entry);

      /// The entry called @p name, or nullptr.
      const SolverEntry *
      find(const std::string &name) const;

      /// The names, in registration order.
      std::vector<std::string>
      names() const;

      /// The names the `Auto chain ...` parameters may hold, for @p general
      /// (some block a disc, ellipse or cone) or bounds-only problems.
      std::vector<std::string>
      chainable_names(bool general) const;

      /// "name: description; name: description; ..." for the parameter
      /// documentation.
      std::string
      descriptions() const;

    private:
      SolverRegistry() = default;
      std::vector<SolverEntry> entries;
    };


    /**
     * Registers solver class @p Class (a class template on the vector type
     * whose constructor takes SolverParameters) as @p key, accepting
     * @p sets, described by @p text.  Used in
     * register_builtin_solvers(); a program adds its own solvers the same
     * way.
     */
#define DUALCONTACT_QP_REGISTER_SOLVER(registry, Class, key, sets, text)      \
  do                                                                          \
  {                                                                           \
    ::dualcontact::qp::SolverEntry entry_;                                    \
    entry_.name          = key;                                               \
    entry_.description   = text;                                              \
    entry_.accepted_sets = sets;                                              \
    entry_.create_serial = [](const ::dualcontact::qp::SolverParameters &p)   \
      -> std::unique_ptr<                                                     \
        ::dualcontact::qp::SolverBase<dealii::Vector<double>>>                \
    { return std::make_unique<Class<dealii::Vector<double>>>(p); };           \
    entry_.create_distributed =                                               \
      [](const ::dualcontact::qp::SolverParameters &p)                        \
      -> std::unique_ptr<                                                     \
        ::dualcontact::qp::SolverBase<dealii::TrilinosWrappers::MPI::Vector>> \
    {                                                                         \
      return std::make_unique<Class<dealii::TrilinosWrappers::MPI::Vector>>(  \
        p);                                                                   \
    };                                                                        \
    (registry).add(std::move(entry_));                                        \
  } while (false)
  } // namespace qp
} // namespace dualcontact

#endif
